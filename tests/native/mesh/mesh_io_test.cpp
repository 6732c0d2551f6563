#include "helpers.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/mesh/mesh.h"
#include "liftremesh/mesh/mesh_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>


using namespace liftremesh;
namespace fs = std::filesystem;

namespace {

//! Each test gets its own empty directory, removed afterwards.
class MeshIo : public ::testing::Test {
protected:
    std::string path(const std::string& name) const { return (dir_ / name).string(); }

    std::string write_file(const std::string& name, const std::string& content) const {
        const std::string p = path(name);
        std::ofstream(p, std::ios::binary) << content;
        return p;
    }

    const test::TestDir scratch_{"liftremesh_io_"};
    const fs::path& dir_ = scratch_.path();
};

//! ASCII STL text of every triangle of `mesh`, with `eol` line endings.
std::string ascii_stl(const Mesh& mesh, const std::string& eol = "\n") {
    std::string s = "solid test" + eol;
    char line[200];
    for (Eigen::Index f = 0; f < mesh.triangles.rows(); ++f) {
        s += "  facet normal 0 0 0" + eol + "    outer loop" + eol;
        for (int j = 0; j < 3; ++j) {
            const auto p = mesh.points.row(mesh.triangles(f, j));
            std::snprintf(line, sizeof line, "      vertex %.17g %.17g %.17g", p(0), p(1), p(2));
            s += line + eol;
        }
        s += "    endloop" + eol + "  endfacet" + eol;
    }
    return s + "endsolid test" + eol;
}

//! Expects read_mesh(p) to throw InvalidInput whose message names the file and contains `problem`.
void expect_invalid(const std::string& p, const std::string& problem) {
    try {
        read_mesh(p);
        ADD_FAILURE() << "no exception reading " << p;
    } catch (const InvalidInput& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(fs::path(p).filename().string()), std::string::npos) << what;
        EXPECT_NE(what.find(problem), std::string::npos) << "expected '" << problem << "' in: " << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << "message is not one line: " << what;
    }
}

} // namespace

TEST_F(MeshIo, ObjAndOffRoundTripIsExact) {
    for (const Mesh& original : {test::make_torus(1.0, 0.3, 24, 12), test::make_icosphere(2, 1.7)}) {
        for (const std::string name : {"mesh.obj", "mesh.off", "MESH.OBJ", "Mesh.Off"}) {
            write_mesh(path(name), original);
            const Mesh back = read_mesh(path(name));
            EXPECT_EQ(back.points.rows(), original.points.rows()) << name;
            EXPECT_EQ(back.triangles.rows(), original.triangles.rows()) << name;
            EXPECT_EQ(euler_characteristic(back), euler_characteristic(original)) << name;
            // Shortest round-trip decimal: every coordinate comes back bit for bit.
            EXPECT_TRUE(back.points == original.points) << name;
            EXPECT_TRUE(back.triangles == original.triangles) << name;
        }
    }
}

TEST_F(MeshIo, BinaryStlRoundTripKeepsTopologyAndFloatCoordinates) {
    for (const Mesh& original : {test::make_torus(2.0, 0.5, 30, 10), test::make_icosphere(3, 10.0)}) {
        for (const std::string name : {"mesh.stl", "MESH.STL"}) {
            write_mesh(path(name), original);
            EXPECT_EQ(fs::file_size(path(name)), 84u + 50u * original.triangles.rows());
            const Mesh back = read_mesh(path(name));
            ASSERT_EQ(back.points.rows(), original.points.rows());
            ASSERT_EQ(back.triangles.rows(), original.triangles.rows());
            EXPECT_EQ(euler_characteristic(back), euler_characteristic(original));
            // STL stores corners per triangle: vertex order may change, triangle order does not.
            double worst = 0.0;
            for (Eigen::Index f = 0; f < original.triangles.rows(); ++f)
                for (int j = 0; j < 3; ++j)
                    worst = std::max(
                        worst, (back.points.row(back.triangles(f, j)) - original.points.row(original.triangles(f, j)))
                                   .cwiseAbs()
                                   .maxCoeff());
            EXPECT_LT(worst, 1e-6 * original.points.cwiseAbs().maxCoeff()); // float32 precision
        }
    }
}

TEST_F(MeshIo, AsciiStlCubeWeldsToEightVertices) {
    const Mesh cube = test::make_cube(1.0, 1);
    ASSERT_EQ(cube.triangles.rows(), 12);
    for (const std::string eol : {"\n", "\r\n"}) {
        const Mesh m = read_mesh(write_file("cube.stl", ascii_stl(cube, eol)));
        EXPECT_EQ(m.points.rows(), 8);
        EXPECT_EQ(m.triangles.rows(), 12);
        EXPECT_EQ(euler_characteristic(m), 2);
        EXPECT_NEAR(surface_area(m), 24.0, 1e-12);
    }
}

TEST_F(MeshIo, BinaryStlWhoseHeaderStartsWithSolidIsReadAsBinary) {
    const Mesh sphere = test::make_icosphere(1);
    write_mesh(path("a.stl"), sphere);
    std::string bytes;
    {
        std::ifstream in(path("a.stl"), std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    bytes.replace(0, 16, "solid exported  ");
    const Mesh m = read_mesh(write_file("b.stl", bytes));
    EXPECT_EQ(m.points.rows(), sphere.points.rows());
    EXPECT_EQ(m.triangles.rows(), sphere.triangles.rows());
    EXPECT_EQ(euler_characteristic(m), 2);
}

TEST_F(MeshIo, ObjNegativeIndicesSlashesAndPolygons) {
    const std::string text = "# a quad and a triangle\n"
                             "mtllib none.mtl\no quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                             "vt 0 0\nvn 0 0 1\ns off\n"
                             "f -4/1/1 -3/1/1 -2//1 -1\n"
                             "v 2 0 0\n"
                             "f 2 5 3\n"
                             "l 1 2\n";
    const Mesh m = read_mesh(write_file("quad.obj", text));
    EXPECT_EQ(m.points.rows(), 5);
    ASSERT_EQ(m.triangles.rows(), 3);
    EXPECT_EQ(m.triangles.row(0), Eigen::RowVector3i(0, 1, 2));
    EXPECT_EQ(m.triangles.row(1), Eigen::RowVector3i(0, 2, 3));
    EXPECT_EQ(m.triangles.row(2), Eigen::RowVector3i(1, 4, 2));
    EXPECT_EQ(euler_characteristic(m), 1); // a disk
}

TEST_F(MeshIo, OffCommentsCountsOnHeaderLineColoursAndPolygons) {
    const std::string text = "# leading comment\n"
                             "COFF 5 2 0\n"
                             "\n"
                             "0 0 0 255 0 0 255  # colour after the coordinates\n"
                             "1 0 0 255 0 0 255\n"
                             "1 1 0 255 0 0 255\n"
                             "0 1 0 255 0 0 255\n"
                             "9 9 9 0 0 0 255\n" // unreferenced: kept, as OFF lists it
                             "4 0 1 2 3 0.5 0.5 0.5\n"
                             "3 1 0 1\n"; // repeats a vertex: kept, for clean_input to drop and count
    const Mesh m = read_mesh(write_file("quad.off", text));
    EXPECT_EQ(m.points.rows(), 5);
    ASSERT_EQ(m.triangles.rows(), 3);
    EXPECT_EQ(m.triangles.row(2), Eigen::RowVector3i(1, 0, 1));
    EXPECT_EQ(euler_characteristic(Mesh{m.points, m.triangles.topRows(2)}), 1); // the quad, without the repeat
}

TEST_F(MeshIo, WeldExactMergesEqualCoordinatesInFirstOccurrenceOrder) {
    Mesh m = test::make_mesh({{1, 2, 3}, {0.0, 0, 0}, {4, 5, 6}, {-0.0, 0, 0}, {1, 2, 3}, {7, 8, 9}},
                             {{0, 1, 2}, {4, 3, 5}, {0, 4, 1}});
    weld_exact(m);
    ASSERT_EQ(m.points.rows(), 4);
    EXPECT_EQ(m.points.row(0), Eigen::RowVector3d(1, 2, 3));
    EXPECT_EQ(m.points.row(1), Eigen::RowVector3d(0, 0, 0));
    EXPECT_EQ(m.points.row(2), Eigen::RowVector3d(4, 5, 6));
    EXPECT_EQ(m.points.row(3), Eigen::RowVector3d(7, 8, 9));
    ASSERT_EQ(m.triangles.rows(), 3); // renumbered, none dropped
    EXPECT_EQ(m.triangles.row(0), Eigen::RowVector3i(0, 1, 2));
    EXPECT_EQ(m.triangles.row(1), Eigen::RowVector3i(0, 1, 3));
    EXPECT_EQ(m.triangles.row(2), Eigen::RowVector3i(0, 0, 1));

    Mesh bad = test::make_mesh({{0, 0, 0}}, {{0, 0, 1}});
    EXPECT_THROW(weld_exact(bad), InvalidInput);
}

// An STL soup's weld: every corner of every triangle its own point, each vertex repeated by the
// triangles round it, many of them a bit or two apart in one coordinate; and 8192 points all
// different, which fill the weld's table (the smallest power of two of at least twice the
// points) to half. The welded vertices are the first occurrences, in their order, as a search of
// the vertices kept so far gives them.
TEST_F(MeshIo, WeldExactOfASoupIsTheFirstOccurrencesInTheirOrder) {
    std::mt19937 rng(5);
    std::vector<Eigen::RowVector3d> distinct;
    for (int i = 0; i < 700; ++i) { // z a whole number or one or two ulps above it
        double z = i / 21;
        for (int ulp = 0; ulp < i % 3; ++ulp) z = std::nextafter(z, 1e9);
        distinct.emplace_back(std::uniform_int_distribution<int>(0, 9)(rng), i % 7, z);
    }
    std::vector<Eigen::RowVector3d> soup;
    std::vector<Eigen::RowVector3i> triangles;
    for (int f = 0; f < 3000; ++f) {
        Eigen::RowVector3i t;
        for (int j = 0; j < 3; ++j) {
            t[j] = static_cast<int>(soup.size());
            soup.push_back(distinct[std::uniform_int_distribution<size_t>(0, distinct.size() - 1)(rng)]);
        }
        triangles.push_back(t);
    }
    Mesh m;
    m.points.resize(static_cast<Eigen::Index>(soup.size()), 3);
    for (size_t i = 0; i < soup.size(); ++i) m.points.row(static_cast<Eigen::Index>(i)) = soup[i];
    m.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
    for (size_t f = 0; f < triangles.size(); ++f) m.triangles.row(static_cast<Eigen::Index>(f)) = triangles[f];
    std::vector<Eigen::RowVector3d> first; // the reference: a linear search of those kept so far
    std::vector<int> index_of(soup.size());
    for (size_t i = 0; i < soup.size(); ++i) {
        size_t k = 0;
        while (k < first.size() && first[k] != soup[i]) ++k;
        if (k == first.size()) first.push_back(soup[i]);
        index_of[i] = static_cast<int>(k);
    }
    weld_exact(m);
    ASSERT_EQ(m.points.rows(), static_cast<Eigen::Index>(first.size()));
    for (size_t k = 0; k < first.size(); ++k) EXPECT_EQ(m.points.row(static_cast<Eigen::Index>(k)), first[k]);
    for (size_t f = 0; f < triangles.size(); ++f)
        for (int j = 0; j < 3; ++j) EXPECT_EQ(m.triangles(static_cast<Eigen::Index>(f), j), index_of[triangles[f][j]]);

    Mesh apart;
    apart.points = Points::Random(8192, 3);
    apart.points.col(0) = Eigen::VectorXd::LinSpaced(8192, 0.0, 8191.0); // no two alike
    apart.triangles.resize(8190, 3);
    for (int f = 0; f < 8190; ++f) apart.triangles.row(f) = Eigen::RowVector3i(f, f + 1, f + 2);
    const Mesh before = apart;
    weld_exact(apart);
    EXPECT_EQ(apart.points, before.points);
    EXPECT_EQ(apart.triangles, before.triangles);
}

TEST_F(MeshIo, MalformedFilesThrowOneLineMessagesNamingTheFile) {
    expect_invalid(path("missing.stl"), "cannot open");
    expect_invalid(path("missing.stl"), "No such file or directory");
    expect_invalid(write_file("x.ply", "ply\n"), "unsupported extension '.ply' (expected .stl, .obj or .off)");
    expect_invalid(write_file("noext", "OFF\n"), "no file extension");
    expect_invalid(write_file("empty.stl", ""), "empty");
    expect_invalid(write_file("empty.obj", ""), "empty");
    expect_invalid(write_file("empty.off", ""), "empty");

    // STL
    std::string header(80, ' ');
    const std::string twelve("\x0c\x00\x00\x00", 4);
    expect_invalid(write_file("trunc.stl", header + twelve + std::string(416, '\0')),
                   "binary STL truncated (expected 684 bytes, found 500)");
    expect_invalid(write_file("short.stl", std::string(40, '\x01')), "binary STL truncated");
    expect_invalid(write_file("none.stl", "solid x\nendsolid x\n"), "no triangle found");
    expect_invalid(write_file("badvertex.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0\n"),
                   "line 4: expected 3 vertex coordinates");
    expect_invalid(
        write_file("twovertices.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n"),
        "line 6: facet has 2 vertices (expected 3)");
    expect_invalid(write_file("keyword.stl", "solid x\nfacet normal 0 0 1\nbanana\n"), "line 3: unexpected 'banana'");
    expect_invalid(write_file("open.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"),
                   "unexpected end of file");

    // OBJ
    expect_invalid(write_file("v.obj", "v 0 0 0\nv 1 0\n"), "line 2: expected 3 vertex coordinates");
    expect_invalid(write_file("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"),
                   "line 4: vertex index 4 out of range");
    expect_invalid(write_file("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
                   "line 4: vertex index 0 out of range");
    expect_invalid(write_file("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n"), "vertex index -4 out of range");
    expect_invalid(write_file("word.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n"), "line 4: invalid vertex index 'x'");
    expect_invalid(write_file("two.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n"), "line 3: expected at least 3 vertex indices");
    expect_invalid(write_file("nofaces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "no triangle found");
    expect_invalid(write_file("degenerate.obj", "v 0 0 0\nv 1 0 0\nv 0 0 0\nf 1 2 3\n"),
                   "no triangle left after welding");

    // OFF
    expect_invalid(write_file("header.off", "OF\n3 1 0\n"), "line 1: expected the 'OFF' header");
    expect_invalid(write_file("counts.off", "OFF\nthree 1 0\n"), "line 2: expected vertex and face counts");
    expect_invalid(write_file("x.off", "OFF\n# comment\n4 1 0\n0 0 0\n1 0 0\n\n0 1\n0 0 1\n3 0 1 2\n"),
                   "line 7: expected 3 vertex coordinates");
    expect_invalid(write_file("face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
                   "line 6: vertex index '3' out of range (expected 0 to 2)");
    expect_invalid(write_file("short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n"),
                   "line 6: expected 3 vertex indices");
    expect_invalid(write_file("eof.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n"), "unexpected end of file after 2 of 3 vertices");
    expect_invalid(write_file("huge.off", "OFF\n2000000000 1 0\n0 0 0\n"), "unexpected end of file");
    expect_invalid(write_file("4d.off", "4OFF\n3 1 0\n"), "not a 3D OFF");
    expect_invalid(write_file("binary.off", "OFF BINARY\n"), "binary OFF is not supported");
}

TEST_F(MeshIo, NonFiniteCoordinatesAreReadAndLeftToCheckMesh) {
    const Mesh m = read_mesh(write_file("nan.obj", "v nan 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n"));
    ASSERT_EQ(m.triangles.rows(), 1);
    EXPECT_TRUE(std::isnan(m.points(0, 0)));
    EXPECT_TRUE(std::isinf(m.points(2, 1)));
    EXPECT_THROW(check_mesh(m, "input"), InvalidInput);
}

TEST_F(MeshIo, RandomBytesNeverCrash) {
    std::mt19937_64 rng(2024);
    int parsed = 0;
    for (int trial = 0; trial < 300; ++trial) {
        std::string bytes(static_cast<size_t>(rng() % 2000), '\0');
        for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
        // Half the trials look like text of the right kind, to get past the first checks.
        static const char* starts[] = {"solid ", "OFF\n3 1 0\n", "v 0 0 0\n"};
        static const char* names[] = {"r.stl", "r.off", "r.obj"};
        const int kind = trial % 3;
        if (trial % 2 == 0) bytes = starts[kind] + bytes;
        try {
            const Mesh m = read_mesh(write_file(names[kind], bytes));
            ++parsed;
            EXPECT_GT(m.triangles.rows(), 0);
        } catch (const InvalidInput& e) {
            EXPECT_NE(std::string(e.what()).find(names[kind]), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(parsed, 0); // random bytes are never a valid mesh
}

TEST_F(MeshIo, WriteFailuresThrow) {
    const Mesh m = test::make_icosphere(0);
    EXPECT_THROW(write_mesh(path("x.ply"), m), InvalidInput);
    EXPECT_THROW(write_mesh(path("no/such/dir/x.obj"), m), InvalidInput);
    Mesh bad = m;
    bad.triangles(0, 0) = 99;
    EXPECT_THROW(write_mesh(path("bad.off"), bad), InvalidInput);
}
