// Small meshes built in code for the tests, and access to ../shared/meshes.
#pragma once

#include "liftremesh/cvt/rvd.h"
#include "liftremesh/mesh/mesh.h"
#include "liftremesh/params.h"
#include "liftremesh/spatial/reference.h"

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

namespace liftremesh::test {

using liftremesh::make_mesh; // the core's (mesh.h), as test::make_mesh in the tests

//! Unit icosphere (radius r), outward oriented: 12 vertices at level 0, x4 faces per level.
inline Mesh make_icosphere(int levels, double r = 1.0) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Eigen::Vector3d> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                      {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<std::array<int32_t, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (auto& x : p) x.normalize();
    for (int l = 0; l < levels; ++l) {
        std::map<std::pair<int32_t, int32_t>, int32_t> mid;
        auto midpoint = [&](int32_t a, int32_t b) {
            auto key = std::make_pair(std::min(a, b), std::max(a, b));
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            p.push_back((p[a] + p[b]).normalized());
            return mid[key] = static_cast<int32_t>(p.size() - 1);
        };
        std::vector<std::array<int32_t, 3>> g;
        for (auto& tri : f) {
            const int32_t a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
            g.push_back({tri[0], a, c});
            g.push_back({tri[1], b, a});
            g.push_back({tri[2], c, b});
            g.push_back({a, b, c});
        }
        f = std::move(g);
    }
    for (auto& x : p) x *= r;
    return make_mesh(p, f);
}

//! Torus with major radius R, minor radius r, n x m quads split in two, outward oriented.
inline Mesh make_torus(double R, double r, int n, int m) {
    std::vector<Eigen::Vector3d> p;
    std::vector<std::array<int32_t, 3>> f;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) {
            const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
            p.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
        }
    auto id = [&](int i, int j) { return static_cast<int32_t>(((i + n) % n) * m + (j + m) % m); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < m; ++j) {
            f.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            f.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return make_mesh(p, f);
}

//! Axis-aligned cube [-s, s]^3, each face an n x n grid split into triangles, outward oriented.
inline Mesh make_cube(double s, int n) {
    std::vector<Eigen::Vector3d> p;
    std::vector<std::array<int32_t, 3>> f;
    std::map<std::array<long, 3>, int32_t> index;
    auto vertex = [&](const Eigen::Vector3d& x) {
        std::array<long, 3> key = {std::lround(x.x() * 1e6), std::lround(x.y() * 1e6), std::lround(x.z() * 1e6)};
        auto it = index.find(key);
        if (it != index.end()) return it->second;
        p.push_back(x);
        return index[key] = static_cast<int32_t>(p.size() - 1);
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int side = -1; side <= 1; side += 2) {
            Eigen::Vector3d normal = Eigen::Vector3d::Zero();
            normal[axis] = side;
            Eigen::Vector3d u = Eigen::Vector3d::Zero(), v;
            u[(axis + 1) % 3] = 1;
            v = normal.cross(u);
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    auto at = [&](int a, int b) {
                        return vertex(s * (normal + u * (-1 + 2.0 * a / n) + v * (-1 + 2.0 * b / n)));
                    };
                    const int32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
                    f.push_back({a, b, c});
                    f.push_back({a, c, d});
                }
        }
    return make_mesh(p, f);
}

//! The two meshes as one: a's points and triangles, then b's, its indices shifted past a's points.
inline Mesh joined(const Mesh& a, const Mesh& b) {
    Mesh both = a;
    liftremesh::append(both, b);
    return both;
}

//! `mesh` with every triangle turned (corners 1 and 2 swapped): a closed one faces inward.
inline Mesh turned(Mesh mesh) {
    mesh.triangles.col(1).swap(mesh.triangles.col(2));
    return mesh;
}

//! The defects of a careless STL export (carelessly_exported): which, and how many.
struct CarelessExport {
    int turn_every = 3;           //!< every k-th facet turned (0: each with probability 1/3, seeded)
    int repeats = 10;             //!< facets written twice, right after themselves: every other one
                                  //!< the second time the other way round
    int zero_area = 3;            //!< zero-area facets added: over a side (a, b) of a random facet, (a, b, m)
                                  //!< with a new vertex m at the side's midpoint, or (a, b, b)
    std::uint64_t seed = 1;       //!< which facets repeat, carry the zero-area ones (and turn, if random)
    long turned = 0;              //!< out: facets turned (of the originals)
};

//! `mesh` as a careless STL export writes it (CarelessExport, seeded): facets turned, repeated
//! (some reversed) and zero-area facets added. The originals keep their order and come first in
//! each repeat, so that a cleaning that keeps the first listed of each facet gives back `mesh`'s
//! facets (their corners maybe rotated) with `what.turned` of them turned back.
inline Mesh carelessly_exported(const Mesh& mesh, CarelessExport& what) {
    std::mt19937_64 rng(what.seed);
    const long n = static_cast<long>(mesh.triangles.rows());
    std::vector<Eigen::Vector3d> points;
    for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) points.push_back(mesh.points.row(i).transpose());
    std::vector<std::array<int32_t, 3>> facets;
    std::vector<long> order(static_cast<size_t>(n));
    std::iota(order.begin(), order.end(), 0L);
    std::shuffle(order.begin(), order.end(), rng);
    const std::vector<long> repeated(order.begin(), order.begin() + std::min<long>(what.repeats, n));
    std::shuffle(order.begin(), order.end(), rng);
    const std::vector<long> carriers(order.begin(), order.begin() + std::min<long>(what.zero_area, n));
    std::bernoulli_distribution third(1.0 / 3.0);
    what.turned = 0;
    for (long f = 0; f < n; ++f) {
        std::array<int32_t, 3> t = {mesh.triangles(f, 0), mesh.triangles(f, 1), mesh.triangles(f, 2)};
        if (what.turn_every > 0 ? f % what.turn_every == 0 : third(rng)) {
            std::swap(t[1], t[2]);
            ++what.turned;
        }
        facets.push_back(t);
        const auto r = std::find(repeated.begin(), repeated.end(), f);
        if (r != repeated.end()) facets.push_back((r - repeated.begin()) % 2 ? std::array<int32_t, 3>{t[0], t[2], t[1]} : t);
        const auto z = std::find(carriers.begin(), carriers.end(), f);
        if (z != carriers.end()) {
            if ((z - carriers.begin()) % 2 == 0) {
                points.push_back(0.5 * (points[t[0]] + points[t[1]]));
                facets.push_back({t[0], t[1], static_cast<int32_t>(points.size() - 1)});
            } else {
                facets.push_back({t[0], t[1], t[1]});
            }
        }
    }
    return make_mesh(points, facets);
}

//! The box [lo, hi], each face an n x n grid split into triangles, outward oriented.
inline Mesh make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int n) {
    Mesh box = make_cube(0.5, n);
    for (int k = 0; k < 3; ++k) box.points.col(k) = box.points.col(k).array() * (hi[k] - lo[k]) + 0.5 * (hi[k] + lo[k]);
    return box;
}

//! Two icospheres of radius 1 touching at one vertex: the second is the first reflected through
//! its vertex 0, the two vertex lists welded there (chi 3, that vertex non-manifold).
inline Mesh make_touching_spheres(int levels) {
    const Mesh a = make_icosphere(levels);
    Mesh b = a;
    b.points = (-a.points).rowwise() + 2.0 * a.points.row(0);
    Mesh glued = joined(a, b);
    // b's vertex 0 is a's vertex 0: refer to a's.
    for (Eigen::Index f = a.triangles.rows(); f < glued.triangles.rows(); ++f)
        for (int j = 0; j < 3; ++j)
            if (glued.triangles(f, j) == a.points.rows()) glued.triangles(f, j) = 0;
    return glued;
}

//! Open square [0, s]^2 in the plane z = 0, an n x n grid split into triangles, normal +z.
inline Mesh make_square(double s, int n) {
    std::vector<Eigen::Vector3d> p;
    std::vector<std::array<int32_t, 3>> f;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) p.emplace_back(s * i / n, s * j / n, 0.0);
    auto id = [&](int i, int j) { return static_cast<int32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            f.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            f.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return make_mesh(p, f);
}

//! Two sheets `gap` apart facing each other, as the sides of a slot between two parts of a CAD
//! solid: the square [-1, 1]^2 in z = 0, facing up, and a diamond of radius 1.2 in z = gap,
//! facing down, two triangles each. No vertex of either lies across from the other (the corners
//! of each stand out beyond the other's edges), so a lifting per vertex misses the wall their
//! overlap, an octagon, is.
inline Mesh make_offset_sheets(double gap) {
    Points p(8, 3);
    p << -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0, 1.2, 0, gap, 0, 1.2, gap, -1.2, 0, gap, 0, -1.2, gap;
    Triangles t(4, 3);
    t << 0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6;
    Mesh sheets;
    sheets.points = p;
    sheets.triangles = t;
    return sheets;
}

//! Flat plate [-w/2, w/2] x [-h/2, h/2] (z = 0, normal +z) with a round hole of radius r at the
//! origin, as a shell midsurface: each side cut into pieces of about `edge`, the four corners
//! among the cuts, every cut joined to the hole by `rings` rings of quads split in two. The hole
//! is a polygon with one vertex per cut, at the cut's polar angle.
inline Mesh make_plate_with_hole(double w, double h, double r, double edge, int rings) {
    std::vector<Eigen::Vector2d> outer; // counter-clockwise from (w/2, -h/2)
    auto side = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
        const int n = std::max(1, static_cast<int>(std::lround((b - a).norm() / edge)));
        for (int k = 0; k < n; ++k) outer.push_back(a + (b - a) * (static_cast<double>(k) / n));
    };
    const Eigen::Vector2d c0(w / 2, -h / 2), c1(w / 2, h / 2), c2(-w / 2, h / 2), c3(-w / 2, -h / 2);
    side(c0, c1);
    side(c1, c2);
    side(c2, c3);
    side(c3, c0);
    const int n = static_cast<int>(outer.size());
    std::vector<Eigen::Vector3d> p;
    for (const Eigen::Vector2d& o : outer) {
        const Eigen::Vector2d in = r * o.normalized();
        for (int j = 0; j <= rings; ++j) {
            const Eigen::Vector2d x = in + (o - in) * (static_cast<double>(j) / rings);
            p.emplace_back(x.x(), x.y(), 0.0);
        }
    }
    auto id = [&](int i, int j) { return static_cast<int32_t>((i % n) * (rings + 1) + j); };
    std::vector<std::array<int32_t, 3>> f;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < rings; ++j) {
            f.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
            f.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
        }
    return make_mesh(p, f);
}

//! A prism of height `height` on a convex polygon (counter-clockwise, in the xy plane), its caps
//! fanned from their first vertex, outward oriented.
inline Mesh make_prism(const std::vector<Eigen::Vector2d>& polygon, double height) {
    const int n = static_cast<int>(polygon.size());
    std::vector<Eigen::Vector3d> pts;
    for (double z : {0.0, height})
        for (const Eigen::Vector2d& p : polygon) pts.emplace_back(p.x(), p.y(), z);
    std::vector<std::array<int32_t, 3>> tris;
    for (int i = 1; i + 1 < n; ++i) {
        tris.push_back({0, i + 1, i});             // bottom, facing -z
        tris.push_back({n, n + i, n + i + 1});     // top, facing +z
    }
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        tris.push_back({i, j, j + n});
        tris.push_back({i, j + n, i + n});
    }
    return make_mesh(pts, tris);
}

//! Open tube of radius r around the z axis from z = 0 to z = length: n x m quads split in two,
//! normals pointing out; its two ends are n-gons.
inline Mesh make_open_cylinder(double r, double length, int n, int m) {
    std::vector<Eigen::Vector3d> p;
    std::vector<std::array<int32_t, 3>> f;
    for (int j = 0; j <= m; ++j)
        for (int i = 0; i < n; ++i) {
            const double u = 2 * M_PI * i / n;
            p.emplace_back(r * std::cos(u), r * std::sin(u), length * j / m);
        }
    auto id = [&](int i, int j) { return static_cast<int32_t>(j * n + (i % n)); };
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < n; ++i) {
            f.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            f.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    return make_mesh(p, f);
}

//! n sites near a (lifted) surface: uniform points of random triangles, moved off it by Gaussian
//! noise of standard deviation `noise` in every coordinate (generic positions for the tests).
inline LiftedPoints sites_near(const LiftedSurface& s, int n, double noise, unsigned seed) {
    std::mt19937_64 rng(seed);
    std::uniform_int_distribution<long> pick(0, s.triangles.rows() - 1);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    std::normal_distribution<double> gauss(0.0, noise);
    LiftedPoints v(n, s.dimension());
    for (int k = 0; k < n; ++k) {
        const long f = s.row_of[pick(rng)]; // the triangles as given
        double a = u01(rng), b = u01(rng);
        if (a + b > 1) {
            a = 1 - a;
            b = 1 - b;
        }
        v.row(k) = (1 - a - b) * s.points.row(s.triangles(f, 0)) + a * s.points.row(s.triangles(f, 1)) +
                   b * s.points.row(s.triangles(f, 2));
        for (int j = 0; j < s.dimension(); ++j) v(k, j) += gauss(rng);
    }
    return v;
}

//! The running test's own empty directory in the system's temporary folder, named after
//! `prefix`, the process and the test (a parameterized test's "Name/param" as "Name_param", one
//! directory, not one inside another); removed with the object.
class TestDir {
public:
    explicit TestDir(const std::string& prefix) : path_(std::filesystem::temp_directory_path() / (prefix + unique_name())) {
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TestDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    TestDir(const TestDir&) = delete;
    TestDir& operator=(const TestDir&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    static std::string unique_name() {
        std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        std::replace(name.begin(), name.end(), '/', '_');
        return std::to_string(::getpid()) + "_" + name;
    }
    std::filesystem::path path_;
};

//! A mesh and its tree, to pass where a step takes a Reference to its input.
struct OwnedReference {
    explicit OwnedReference(Mesh m) : mesh(std::move(m)), tree(mesh) {}
    Mesh mesh;
    AabbTree tree;
    operator Reference() const { return {mesh, tree}; }
};

//! Path of a mesh in ../shared/meshes, or "" (and the test is skipped) where it does not exist.
inline std::string shared_mesh(const std::string& name) {
    const std::filesystem::path path = std::filesystem::path(LIFTREMESH_SHARED_MESHES) / name;
    return std::filesystem::exists(path) ? path.string() : std::string();
}

#define LIFTREMESH_REQUIRE_SHARED(var, name)                                                 \
    const std::string var = ::liftremesh::test::shared_mesh(name);                           \
    if (var.empty()) GTEST_SKIP() << "../shared/meshes/" << name << " not found beside the repository"

//! The default parameters but for the vertex count, sigma and the seed.
inline RemeshParams params_with(int vertices, double sigma = RemeshParams{}.sigma, std::uint64_t seed = RemeshParams{}.seed) {
    RemeshParams p;
    p.target_vertices = vertices;
    p.sigma = sigma;
    p.seed = seed;
    return p;
}

//! The four CAD meshes in ../shared/meshes that the acceptance criteria name.
inline const std::vector<const char*> kAcceptanceMeshes = {"gmsh_t13_data.stl", "netgen_hinge.stl", "gmsh_lever.stl",
                                                           "pmp_fandisk.off"};

//! Name of a test instantiated on a mesh file: the file name without its extension.
inline std::string mesh_name(const ::testing::TestParamInfo<const char*>& info) {
    const std::string name = info.param;
    return name.substr(0, name.find('.'));
}

} // namespace liftremesh::test
