#include "liftremesh/exceptions.h"
#include "liftremesh/params.h"

#include <gtest/gtest.h>

#include <map>
#include <sstream>

using namespace liftremesh;

namespace {
std::string text(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}
} // namespace

// parameter_table() feeds --help and the bindings: its defaults must be the struct's.
TEST(Params, TableDefaultsAreTheStructDefaults) {
    std::map<std::string, std::string> table;
    for (const ParameterInfo& p : parameter_table()) table[p.name] = p.default_text;
    const RemeshParams iso = RemeshParams::for_mode(Mode::Isotropic);
    const RemeshParams aniso = RemeshParams::for_mode(Mode::Anisotropic);
    EXPECT_EQ(table.at("vertices"), std::to_string(iso.target_vertices));
    EXPECT_EQ(table.at("sigma"), text(iso.sigma));
    EXPECT_EQ(table.at("eta"), text(iso.eta));
    EXPECT_EQ(table.at("iterations"), std::to_string(iso.iterations));
    EXPECT_EQ(table.at("seed"), std::to_string(iso.seed));
    EXPECT_EQ(table.at("threads"), std::to_string(iso.threads));
    EXPECT_EQ(table.at("mode"), to_string(RemeshParams().mode));
    EXPECT_EQ(table.at("delta"), text(iso.delta) + " (isotropic), " + text(aniso.delta) + " (anisotropic)");
    EXPECT_EQ(table.at("nu"), text(iso.nu) + " (isotropic), " + text(aniso.nu) + " (anisotropic)");
    // Section 6.1.
    EXPECT_EQ(iso.sigma, 5.0);
    EXPECT_EQ(iso.nu, 0.01);
    EXPECT_EQ(iso.delta, 0.4);
    EXPECT_EQ(aniso.nu, 0.05);
    EXPECT_EQ(aniso.delta, 0.0);
}

TEST(Params, ValidateNamesTheFieldAndTheRange) {
    RemeshParams p;
    p.delta = 3.0;
    try {
        p.validate();
        FAIL() << "delta = 3 accepted";
    } catch (const InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("delta = 3"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("[0, 2]"), std::string::npos) << e.what();
    }
    EXPECT_THROW(parse_mode("sideways"), InvalidInput);
    EXPECT_NO_THROW(RemeshParams().validate());
}

TEST(Params, VertexCountIsBoundedBothWays) {
    RemeshParams p;
    for (int bad : {3, kMaxVertices + 1}) {
        p.target_vertices = bad;
        try {
            p.validate();
            FAIL() << "vertices = " << bad << " accepted";
        } catch (const InvalidInput& e) {
            EXPECT_NE(std::string(e.what()).find("vertices = " + std::to_string(bad)), std::string::npos) << e.what();
        }
    }
    p.target_vertices = kMaxVertices;
    EXPECT_NO_THROW(p.validate());
}
