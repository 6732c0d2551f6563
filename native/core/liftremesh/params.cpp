#include "liftremesh/params.h"

#include "liftremesh/exceptions.h"

#include <cmath>
#include <sstream>

namespace liftremesh {

const char* to_string(Mode mode) { return mode == Mode::Isotropic ? "isotropic" : "anisotropic"; }

Mode parse_mode(const std::string& text) {
    if (text == "isotropic") return Mode::Isotropic;
    if (text == "anisotropic") return Mode::Anisotropic;
    throw InvalidInput("mode '" + text + "' is not known: expected 'isotropic' or 'anisotropic'");
}

RemeshParams RemeshParams::for_mode(Mode mode) {
    RemeshParams p;
    p.mode = mode;
    if (mode == Mode::Anisotropic) { // Section 6.1
        p.nu = 0.05;
        p.delta = 0.0;
    }
    return p;
}

namespace {
template <typename T>
void require(bool ok, const char* field, T value, const char* expected) {
    if (ok) return;
    std::ostringstream s;
    s << field << " = " << value << " is out of range: expected " << expected;
    throw InvalidInput(s.str());
}
} // namespace

void RemeshParams::validate() const {
    require((target_vertices >= 4 && target_vertices <= kMaxVertices) || target_edge_length > 0.0, "vertices",
            target_vertices, ("an integer in [4, " + std::to_string(kMaxVertices) + "]").c_str());
    require(std::isfinite(target_edge_length) && target_edge_length >= 0.0, "edge_length", target_edge_length,
            "a length > 0 (or 0 to use the vertex count)");
    require(std::isfinite(sigma) && sigma >= 1.0 && sigma <= 100.0, "sigma", sigma, "a number in [1, 100]");
    require(std::isfinite(delta) && delta >= 0.0 && delta <= 2.0, "delta", delta, "a number in [0, 2]");
    require(std::isfinite(nu) && nu >= 0.0 && nu <= 1.0, "nu", nu, "a number in [0, 1]");
    require(std::isfinite(eta) && eta > 0.0 && eta <= 0.5, "eta", eta, "a number in (0, 0.5]");
    require(iterations >= 1 && iterations <= 100000, "iterations", iterations, "an integer in [1, 100000]");
    require(threads >= 0 && threads <= 1024, "threads", threads, "an integer in [0, 1024] (0 = all cores)");
}

const std::vector<ParameterInfo>& parameter_table() {
    static const std::vector<ParameterInfo> table = {
        {"vertices", "N", "", "6000", "target number of output vertices (sites), 4 to 20000000"},
        {"edge_length", "H", "h", "unset", "target edge length in input units; replaces --vertices"},
        {"mode", "MODE", "", "isotropic", "isotropic (with local density) or anisotropic; sets nu and delta defaults"},
        {"sigma", "S", "sigma", "5", "feature sensitivity (>= 1): pulls vertices onto sharp edges and corners"},
        {"delta", "D", "delta", "0.4 (isotropic), 0 (anisotropic)", "exponent of the curvature density rho^delta"},
        {"nu", "NU", "nu", "0.01 (isotropic), 0.05 (anisotropic)", "normal lifting scale, in unit-ball units"},
        {"eta", "ETA", "eta", "0.02", "radius of the neighbourhood for vertex normals, in unit-ball units"},
        {"iterations", "K", "", "100", "L-BFGS iterations (last 10%, at least 10, with sigma)"},
        {"seed", "R", "", "1", "seed of the random initial sampling"},
        {"threads", "T", "", "0", "worker threads (0 = all cores); the result does not depend on it"},
    };
    return table;
}

} // namespace liftremesh
