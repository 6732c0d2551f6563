// The liftremesh command-line tool, run as a user would: exit codes, one-line errors, outputs.
#include "liftremesh/mesh/mesh_io.h"
#include "liftremesh/params.h"
#include "helpers.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace liftremesh;
namespace fs = std::filesystem;

namespace {

struct CliRun {
    int exit_code;
    std::string out, err;
};

class Cli : public ::testing::Test {
protected:
    const test::TestDir scratch{"liftremesh_cli_"};
    const fs::path dir = scratch.path();

    static std::string slurp(const fs::path& p) {
        std::ifstream in(p);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }
    CliRun run(const std::string& args) const {
        const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
        const std::string command = std::string(LIFTREMESH_CLI) + " " + args + " >" + out.string() + " 2>" + err.string();
        const int status = std::system(command.c_str());
        return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
    }
    std::string sphere_off() const {
        const fs::path p = dir / "sphere.off";
        write_mesh(p.string(), test::make_icosphere(2));
        return p.string();
    }
    static long lines(const std::string& s) { return std::count(s.begin(), s.end(), '\n'); }
    static std::string text_of(double v) {
        std::ostringstream s;
        s << v;
        return s.str();
    }
};

} // namespace

TEST_F(Cli, RemeshesAndWritesAReport) {
    const std::string in = sphere_off(), out = (dir / "out.obj").string(), report = (dir / "r.json").string();
    const CliRun r = run(in + " " + out + " --vertices 300 --iterations 30 --report " + report + " --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << "--quiet printed: " << r.err;
    const Mesh m = read_mesh(out);
    EXPECT_EQ(euler_characteristic(m), 2);
    const std::string json = slurp(report);
    for (const char* key : {"\"kappa_min\"", "\"kappa_mean\"", "\"kappa_histogram\"", "\"min_angle_deg\"",
                            "\"hausdorff_relative\"", "\"boundary_edges\"", "\"nonmanifold_edges\"",
                            "\"euler_characteristic\"", "\"timings\"", "\"optimize\""})
        EXPECT_NE(json.find(key), std::string::npos) << key;
}

TEST_F(Cli, ProgressGoesToStderr) {
    const CliRun r = run(sphere_off() + " " + (dir / "o.stl").string() + " --vertices 200 --iterations 20");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.out.empty());
    EXPECT_NE(r.err.find("optimize"), std::string::npos);
}

TEST_F(Cli, HelpDocumentsEveryOptionWithItsDefault) {
    const CliRun r = run("--help");
    EXPECT_EQ(r.exit_code, 0);
    for (const ParameterInfo& p : parameter_table()) {
        std::string flag = "--" + p.name;
        std::replace(flag.begin(), flag.end(), '_', '-');
        EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
        EXPECT_NE(r.out.find("[" + p.default_text + "]"), std::string::npos) << p.name;
    }
    for (const char* flag : {"--report", "--quiet", "--help"}) EXPECT_NE(r.out.find(flag), std::string::npos) << flag;
}

// Every row of the table is an option, parsed with the row's range: a value just outside it is
// refused before any work, in one line naming the option and the value.
TEST_F(Cli, EveryParameterIsAnOptionCheckedAgainstItsRange) {
    const std::string in = sphere_off(), out = (dir / "o.stl").string();
    for (const ParameterInfo& p : parameter_table()) {
        std::string flag = "--" + p.name;
        std::replace(flag.begin(), flag.end(), '_', '-');
        std::string bad = "maybe"; // a Choice's or a Flag's unknown word
        if (p.kind == ParameterKind::Integer) bad = std::to_string(static_cast<long long>(p.min) - 1);
        if (p.kind == ParameterKind::Real) bad = p.min_open ? text_of(p.min) : "-1e300";
        const CliRun r = run(in + " " + out + " " + flag + " " + bad);
        EXPECT_EQ(r.exit_code, 2) << flag << " " << bad << "\n" << r.err;
        EXPECT_EQ(lines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(p.kind == ParameterKind::Choice ? p.name : flag), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("'" + bad + "'"), std::string::npos) << r.err;
    }
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(Cli, BadInputIsOneLineOnStderrAndExitCode2) {
    const std::string in = sphere_off(), out = (dir / "o.stl").string();
    const fs::path garbage = dir / "garbage.stl";
    std::ofstream(garbage) << "this is not\na mesh at all\n";
    const fs::path folder = dir / "folder.stl"; // a directory with a mesh's name
    fs::create_directories(folder);
    Mesh far = test::make_icosphere(2); // a corrupt coordinate: one vertex 1e25 away
    far.points(5, 2) = 1e25;
    const fs::path far_off = dir / "far.off";
    write_mesh(far_off.string(), far);
    const std::vector<std::pair<std::string, std::string>> cases = {
        {(dir / "missing.stl").string() + " " + out, "missing.stl"},
        {garbage.string() + " " + out, "garbage.stl"},
        {in + " " + (dir / "o.ply").string(), ".ply"},
        {in + " " + out + " --frobnicate 3", "--frobnicate"},
        {in + " " + out + " --vertices many", "--vertices"},
        {in + " " + out + " --sigma 0.5", "sigma"},
        {in + " " + out + " --mode sideways", "sideways"},
        {in + " " + out + " --vertices 100 --edge-length 0.1", "--edge-length"},
        {in + " " + out + " --eta -1", "eta"},
        {in, "input and an output"},
        // Refused before the work (no stage is printed), not after it.
        {in + " " + (dir / "no_such_dir" / "o.stl").string(), "no_such_dir"},
        {in + " " + out + " --report " + (dir / "no_such_dir" / "r.json").string(), "no_such_dir"},
        {in + " " + folder.string(), "is a directory"},
        // Refused in the prepare stage, whose progress line --quiet leaves out.
        {far_off.string() + " " + out + " --quiet", "far from the rest"},
    };
    for (const auto& [args, named] : cases) {
        const CliRun r = run(args);
        EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
        EXPECT_EQ(lines(r.err), 1) << args << "\n" << r.err;
        EXPECT_NE(r.err.find(named), std::string::npos) << args << "\n" << r.err;
    }
    EXPECT_FALSE(fs::exists(out)); // nothing is written when the run fails
}

TEST_F(Cli, WarnsWhenTheSizeIsTooCoarseForTheShape) {
    // A thin torus (tube radius 0.05) at 60 vertices cannot keep its topology: the mesh is still
    // written, and stderr says why it is not a copy of the input, even with --quiet.
    const fs::path in = dir / "torus.off", out = dir / "out.off";
    write_mesh(in.string(), test::make_torus(1.0, 0.05, 48, 12));
    const CliRun r = run(in.string() + " " + out.string() + " --vertices 60 --iterations 20 --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(out));
    EXPECT_EQ(r.err.rfind("liftremesh: warning: the result's topology differs from the source's", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("ask for more vertices"), std::string::npos) << r.err;
}
