// Untangling: flips, then vertex moves, that take triangles out of each other, and only where they
// keep the surface on the input.
#include "helpers.h"
#include "liftremesh/edit/quality_floors.h"
#include "liftremesh/exceptions.h"
#include "liftremesh/measure/quality.h"
#include "liftremesh/repair/untangle.h"
#include "liftremesh/spatial/aabb_tree.h"
#include "liftremesh/spatial/self_intersection.h"

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <utility>
#include <vector>

using namespace liftremesh;

namespace {

// A quad a, c, b, d (a = origin, b = (1, 1, 0), c = (1, 0, 1), d = (0, 1, 1)), all four of its
// triangles either way equilateral, and a small upright triangle T at x = 0.7 standing in the
// tetrahedron abcd. Split along a-b (the valley: a, b low, c, d high) the quad passes through
// T, where it is at z = x - y = 0.5; split along c-d (the tent) it is at z = x + y = 0.9, above.
const std::vector<Eigen::Vector3d> kPoints = {
    {0, 0, 0}, {1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {0.7, 0.15, 0.3}, {0.7, 0.25, 0.3}, {0.7, 0.2, 0.7}};
const std::array<int32_t, 3> kT = {4, 5, 6};

Mesh valley() { return make_mesh(kPoints, {{0, 1, 2}, {1, 0, 3}, kT}); }
Mesh tent() { return make_mesh(kPoints, {{0, 3, 2}, {3, 1, 2}, kT}); }

std::vector<std::pair<int32_t, int32_t>> crossings(const Mesh& m) { return self_intersecting_pairs(m, AabbTree(m)); }

UntangleParams with_tolerance(double tolerance) {
    UntangleParams p;
    p.tolerance = tolerance;
    return p;
}

// The 1.1M-triangle bunny of `make bench` (the shared bunny, each triangle split twice) at 100000
// vertices: a spot of its base where the input turns by 50 to 90 degrees at five edges around one
// vertex, and the output's 30 triangles there pass through each other in 10 pairs. Coordinates
// relative to (-0.04335, 0.0344, -0.0264), times 10^4; the run's tolerance, likewise.
const std::vector<Eigen::Vector3d> kSpikeInputPoints = {
        {-6.400011, 6.929983, 7.690006}, {0.480004, -1.270014, -3.130006}, {2.969988, 1.430002, 0.620001},
        {8.650013, -4.869986, 1.810008}, {8.220002, -2.785015, -9.545003}, {2.074987, 11.30001, 0.510003},
        {-2.960004, 2.829985, 2.28}, {-1.715012, 4.179992, 4.155004}, {-2.944991, -1.160007, 5.420001},
        {3.364999, 6.519996, -7.530003}, {1.724996, 0.079994, -1.255003}, {4.565008, -3.07, -0.659999},
        {1.140014, -2.959992, 7.890008}, {4.609992, 7.870004, -5.654999}, {-4.680007, 4.879984, 4.985003},
        {-6.392505, 4.934988, 9.260007}, {-4.057511, 5.554988, 5.922505}, {4.350003, -2.027514, -6.337504},
        {-1.24, 0.779985, -0.425003}, {-1.232493, -1.21501, 1.144997}, {1.922502, 2.624991, -5.330004}, {1.1025,
        -0.59501, -2.192504}, {2.522506, -2.170007, -1.895003}, {-4.657488, -1.105003, 9.695005}, {-2.614986,
        -2.004996, 10.930008}, {2.522488, 6.365006, 0.565002}, {0.627488, 2.804997, 2.387502}, {2.347492,
        0.754998, -0.317501}, {3.78999, 4.650003, -2.517499}, {10.47751, -4.727494, -2.632494}, {6.607511,
        -3.969993, 0.575004}, {4.895014, -3.914989, 4.850008}, {6.612512, -5.427485, 6.592508}, {5.792501,
        1.867491, -8.537503}, {6.392505, -2.927508, -5.102501}, {8.435008, -3.827501, -3.867497}, {-2.162512,
        9.114996, 4.100004}, {0.179988, 7.740001, 2.332503}, {3.342489, 9.585007, -2.572498}, {-4.672501,
        2.884988, 6.555003}, {-2.337508, 3.504988, 3.217502}, {-2.952497, 0.834989, 3.850001}, {-0.617504,
        1.454989, 0.512499}, {-4.664994, 0.889993, 8.125004}, {0.004992, 2.129993, 1.45}, {0.810009, -2.115003,
        2.380001}, {-0.902488, -2.06, 6.655005}, {2.544998, 3.299995, -4.392503}, {3.987496, 7.195001,
        -6.592501}, {3.167494, 3.974999, -3.455001}, {2.852511, -3.014996, 3.615004}, {2.857513, -4.472488,
        9.632508}
};
const std::vector<std::array<int32_t, 3>> kSpikeInputTriangles = {
        {1, 18, 21}, {1, 20, 17}, {2, 28, 27}, {3, 32, 31}, {1, 22, 19}, {6, 18, 41}, {6, 14, 40}, {5, 25, 37},
        {13, 28, 38}, {11, 30, 50}, {10, 44, 27}, {10, 47, 21}, {4, 34, 17}, {8, 46, 23}, {6, 41, 39}, {6, 40,
        42}, {13, 48, 49}, {11, 50, 45}, {14, 6, 39}, {18, 6, 42}, {20, 9, 33}, {28, 13, 49}, {22, 11, 45}, {18,
        1, 19}, {14, 0, 16}, {25, 2, 26}, {28, 2, 25}, {29, 3, 30}, {30, 3, 31}, {43, 8, 23}, {44, 7, 26}, {36,
        7, 16}, {47, 9, 20}, {34, 11, 22}, {46, 12, 24}, {41, 8, 43}, {40, 7, 44}, {37, 7, 36}, {48, 9, 47},
        {35, 11, 34}, {50, 12, 46}, {21, 42, 10}, {27, 49, 10}, {31, 51, 12}, {19, 45, 8}, {41, 19, 8}, {40, 16,
        7}, {37, 26, 7}, {38, 25, 5}, {35, 30, 11}, {50, 31, 12}, {27, 26, 2}, {21, 20, 1}, {17, 22, 1}, {42,
        44, 10}, {49, 47, 10}, {45, 46, 8}, {14, 39, 15}, {18, 42, 21}, {20, 33, 17}, {28, 49, 27}, {32, 51,
        31}, {22, 45, 19}, {18, 19, 41}, {14, 16, 40}, {25, 26, 37}, {28, 25, 38}, {29, 30, 35}, {30, 31, 50},
        {44, 26, 27}, {47, 20, 21}, {34, 22, 17}, {46, 24, 23}, {41, 43, 39}, {40, 44, 42}, {48, 47, 49}, {50,
        46, 45}
};
const std::vector<Eigen::Vector3d> kSpikeOutputPoints = {
        {7.417647, 2.818551, -10.18961}, {4.282648, -2.076473, -6.083286}, {1.409369, 1.460886, -4.426219},
        {4.717784, 8.848806, -8.787486}, {0.560752, 9.419109, 2.062043}, {4.231917, 6.385375, -4.208408},
        {-3.066933, 4.295636, 4.385144}, {10.418468, -4.568836, -3.494731}, {4.324963, -3.137161, 0.387222},
        {-5.333642, 2.055678, 8.735754}, {-1.500568, -2.382176, 10.283785}, {2.969988, 1.430002, 0.620001},
        {-2.321639, 0.856031, -1.061929}, {2.346182, 2.113304, -0.030689}, {-2.474104, -0.821373, 3.800295},
        {4.159426, -4.336813, 7.24752}, {9.897762, -5.750066, 4.594726}, {-0.376245, -1.242512, -0.992504},
        {0.480004, -1.270014, -3.130006}, {-0.446176, -1.240266, -0.817931}, {2.746238, 3.897504, 0.592501},
        {-1.232493, -1.21501, 1.144997}, {-4.657488, -1.105003, 9.695005}
};
const std::vector<std::array<int32_t, 3>> kSpikeOutputTriangles = {
        {0, 1, 2}, {8, 18, 1}, {1, 7, 8}, {11, 12, 6}, {2, 17, 11}, {12, 17, 13}, {12, 14, 6}, {12, 13, 21}, {2,
        18, 13}, {2, 5, 3}, {6, 14, 9}, {10, 22, 14}, {14, 15, 10}, {14, 19, 8}, {13, 18, 19}, {15, 8, 16}, {4,
        20, 6}, {5, 20, 4}, {11, 20, 2}, {17, 12, 11}, {17, 2, 13}, {18, 2, 1}, {18, 8, 19}, {19, 14, 13}, {15,
        14, 8}, {20, 11, 6}, {20, 5, 2}, {13, 14, 21}, {14, 12, 21}, {22, 9, 14}
};
constexpr double kSpikeTolerance = 1.22966739;

// The frame of tests/freecad/test_components.py (3 mm members, a 1.8 mm pin hole at each crossing,
// 0.6 mm of material between the corner hole and the outer faces) at 13,000 vertices, seed 2:
// where the corner pin hole's wall meets the outer face x = 0. A vertex of the wall, joined to
// three others of it only, lies on the outer face, inside a triangle of it: its three triangles
// stand across the 0.6 mm of material, a tent whose apex touches that triangle and whose sides
// pass through it. Input and output within 7 and 5 mm of the tent, in the part's millimetres;
// the run's tolerance.
const std::vector<Eigen::Vector3d> kTentInputPoints = {
        {0.0, 0.0, 0.0}, {0.0, 0.0, 12.0}, {0.0, 200.0, 0.0}, {0.0, 200.0, 12.0}, {0.6000000238418579,
        40.900001525878906, 0.0}, {0.6000000238418579, 80.30000305175781, 0.0}, {0.6000000238418579,
        119.69999694824219, 0.0}, {0.6000000238418579, 159.10000610351562, 0.0}, {0.6000000238418579, 198.5,
        0.0}, {0.6000000238418579, 198.5, 12.0}, {0.6306667327880859, 159.3329315185547, 0.0},
        {0.6306667327880859, 198.26705932617188, 0.0}, {0.6306667327880859, 198.26705932617188, 12.0},
        {0.6306667327880859, 198.73294067382812, 0.0}, {0.6306667327880859, 198.73294067382812, 12.0},
        {0.7205771207809448, 159.5500030517578, 0.0}, {0.7205771207809448, 198.0500030517578, 0.0},
        {0.7205771207809448, 198.0500030517578, 12.0}, {0.7205771207809448, 198.9499969482422, 0.0},
        {0.7205771207809448, 198.9499969482422, 12.0}, {0.8636038899421692, 159.73638916015625, 0.0},
        {0.8636038899421692, 197.8636016845703, 0.0}, {0.8636038899421692, 197.8636016845703, 12.0},
        {0.8636038899421692, 199.1363983154297, 0.0}, {0.8636038899421692, 199.1363983154297, 12.0},
        {1.0499999523162842, 159.87942504882812, 0.0}, {1.0499999523162842, 197.7205810546875, 0.0},
        {1.0499999523162842, 197.7205810546875, 12.0}, {1.0499999523162842, 199.2794189453125, 0.0},
        {1.0499999523162842, 199.2794189453125, 12.0}, {1.2670629024505615, 159.96932983398438, 0.0},
        {1.2670629024505615, 197.6306610107422, 0.0}, {1.2670629024505615, 197.6306610107422, 12.0},
        {1.2670629024505615, 199.3693389892578, 0.0}, {1.2670629024505615, 199.3693389892578, 12.0}, {1.5,
        197.60000610351562, 0.0}, {1.5, 197.60000610351562, 12.0}, {1.5, 199.39999389648438, 0.0}, {1.5,
        199.39999389648438, 12.0}, {1.7329370975494385, 197.6306610107422, 0.0}, {1.7329370975494385,
        197.6306610107422, 12.0}, {1.7329370975494385, 199.3693389892578, 0.0}, {1.7329370975494385,
        199.3693389892578, 12.0}, {1.9500000476837158, 197.7205810546875, 0.0}, {1.9500000476837158,
        197.7205810546875, 12.0}, {1.9500000476837158, 199.2794189453125, 0.0}, {1.9500000476837158,
        199.2794189453125, 12.0}, {2.1363961696624756, 197.8636016845703, 0.0}, {2.1363961696624756,
        197.8636016845703, 12.0}, {2.1363961696624756, 199.1363983154297, 0.0}, {2.1363961696624756,
        199.1363983154297, 12.0}, {2.2794227600097656, 198.0500030517578, 0.0}, {2.2794227600097656,
        198.0500030517578, 12.0}, {2.2794227600097656, 198.9499969482422, 0.0}, {2.2794227600097656,
        198.9499969482422, 12.0}, {2.369333267211914, 198.26705932617188, 0.0}, {2.369333267211914,
        198.26705932617188, 12.0}, {2.369333267211914, 198.73294067382812, 0.0}, {2.369333267211914,
        198.73294067382812, 12.0}, {2.4000000953674316, 198.5, 0.0}, {2.4000000953674316, 198.5, 12.0},
        {3.0, 160.60000610351562, 0.0}, {3.0, 197.0, 0.0}, {3.0, 197.0, 12.0}, {37.125, 197.0, 0.0},
        {37.125, 197.0, 12.0}, {37.75566864013672, 198.73294067382812, 0.0}, {37.845577239990234,
        198.9499969482422, 0.0}, {37.98860549926758, 199.1363983154297, 0.0}, {38.17499923706055,
        199.2794189453125, 0.0}, {38.39206314086914, 199.3693389892578, 0.0}, {38.625, 199.39999389648438,
        0.0}, {300.0, 200.0, 0.0}, {300.0, 200.0, 12.0}
};
const std::vector<std::array<int32_t, 3>> kTentInputTriangles = {
        {0, 1, 2}, {2, 1, 3}, {73, 72, 2}, {73, 2, 3}, {21, 26, 20}, {20, 26, 25}, {20, 16, 21}, {15, 16,
        20}, {15, 11, 16}, {10, 11, 15}, {25, 31, 30}, {30, 31, 61}, {26, 31, 25}, {11, 2, 8}, {10, 2, 11},
        {7, 2, 10}, {13, 2, 18}, {8, 2, 13}, {35, 62, 31}, {39, 62, 35}, {43, 62, 39}, {47, 62, 43}, {31,
        62, 61}, {2, 23, 18}, {2, 28, 23}, {47, 51, 62}, {2, 33, 28}, {51, 55, 62}, {55, 59, 62}, {2, 37,
        33}, {59, 57, 62}, {2, 41, 37}, {57, 66, 62}, {62, 66, 64}, {53, 66, 57}, {53, 67, 66}, {53, 68,
        67}, {49, 68, 53}, {45, 68, 49}, {45, 69, 68}, {2, 70, 41}, {45, 70, 69}, {41, 70, 45}, {2, 71, 70},
        {0, 2, 4}, {4, 2, 5}, {5, 2, 6}, {6, 2, 7}, {2, 72, 71}, {61, 62, 63}, {64, 65, 62}, {62, 65, 63},
        {60, 58, 59}, {59, 58, 57}, {57, 54, 53}, {58, 54, 57}, {53, 50, 49}, {54, 50, 53}, {49, 46, 45},
        {45, 46, 41}, {50, 46, 49}, {46, 42, 41}, {41, 38, 37}, {37, 38, 33}, {42, 38, 41}, {33, 34, 28},
        {38, 34, 33}, {34, 29, 28}, {28, 24, 23}, {29, 24, 28}, {23, 19, 18}, {18, 19, 13}, {24, 19, 23},
        {19, 14, 13}, {14, 9, 13}, {13, 9, 8}, {9, 12, 8}, {8, 12, 11}, {12, 17, 11}, {11, 17, 16}, {16, 17,
        21}, {17, 22, 21}, {22, 27, 21}, {21, 27, 26}, {27, 32, 26}, {26, 32, 31}, {32, 36, 31}, {31, 36,
        35}, {36, 40, 35}, {35, 40, 39}, {40, 44, 39}, {39, 44, 43}, {44, 48, 43}, {43, 48, 47}, {48, 52,
        47}, {47, 52, 51}, {52, 56, 51}, {51, 56, 55}, {55, 56, 59}, {56, 60, 59}
};
const std::vector<Eigen::Vector3d> kTentOutputPoints = {
        {0.0, 200.0, 0.0}, {2.2385339546939065, 199.26101650533673, 0.005288311581455041},
        {0.5967622066865204, 198.27269386621384, -0.013394073588407274}, {0.0, 196.91151728918865, 0.0},
        {2.9967834135801183, 200.0, 0.0}, {3.0, 197.0, 0.0}, {1.410637409537392, 195.31957578770985, 0.0},
        {1.5803998478983488, 197.4973602181646, 0.007714717218950895}, {4.703348978236853,
        198.62702094799582, 0.0}, {1.5613363873532364, 199.46729975795745, 2.5377029848964527}, {0.0, 200.0,
        1.6915942453419994}, {2.4650106971318166, 198.30473675319087, 1.6365711122209525},
        {1.2742614279291615, 197.54758693895837, 1.8542232221158814}, {1.6771623328993428,
        197.5478650661589, 3.5392683431367855}, {2.4708402938944403, 198.57025225419682, 4.024041721294562},
        {0.03066844803001345, 199.9574960779998, 2.4559825761686773}, {0.0, 197.0346462847335,
        3.4318569232695295}, {0.0, 200.0, 5.500633396529901}, {2.7085695425107303, 200.0,
        3.451648830974888}, {5.2439069951839485, 200.0, 2.2757766497816427}, {0.5288608877229706,
        198.44191895161433, 3.879103617155501}, {1.4906699747755852, 199.46205449284298, 4.897737167440063},
        {1.5249887477196467, 197.52544834297564, 5.458620330554194}, {0.5345105827515795, 198.4580819961251,
        6.054506415493049}, {2.482481672293545, 198.51119736165026, 6.144419918831892}, {0.0,
        198.45575864459371, 0.0}
};
const std::vector<std::array<int32_t, 3>> kTentOutputTriangles = {
        {0, 1, 2}, {3, 25, 2}, {0, 4, 1}, {5, 6, 7}, {5, 7, 1}, {5, 1, 8}, {6, 3, 7}, {8, 1, 4}, {1, 9, 10},
        {1, 10, 2}, {11, 7, 12}, {11, 1, 7}, {11, 9, 1}, {11, 12, 13}, {11, 13, 14}, {11, 14, 9}, {15, 16,
        17}, {15, 17, 18}, {3, 2, 7}, {7, 2, 12}, {2, 10, 12}, {4, 18, 19}, {9, 20, 10}, {9, 21, 20}, {9,
        14, 21}, {12, 20, 13}, {12, 10, 20}, {13, 20, 22}, {13, 22, 14}, {20, 23, 22}, {20, 21, 23}, {22,
        24, 14}, {21, 14, 24}, {15, 25, 16}, {15, 18, 4}, {4, 0, 15}, {0, 25, 15}, {25, 0, 2}, {25, 3, 16}
};
constexpr double kTentTolerance = 0.45527454997046424;

} // namespace

TEST(Untangle, AFlipTakesAQuadOutOfATriangleItPassesThrough) {
    Mesh m = valley();
    const auto before = crossings(m);
    ASSERT_EQ(before.size(), 1u); // the valley's first triangle and T
    EXPECT_EQ(crossings(tent()).size(), 0u);
    // The input is the tent: the flip puts the quad on it.
    const Mesh input = tent();
    const UntangleStats stats = untangle(m, test::OwnedReference(input), with_tolerance(0.01));
    EXPECT_EQ(stats.flipped, 1);
    EXPECT_TRUE(stats.crossings.empty());
    EXPECT_TRUE(crossings(m).empty());
    EXPECT_EQ(m.triangles.rows(), 3);
    EXPECT_EQ(m.points, valley().points); // no vertex moved or added
    EXPECT_EQ(euler_characteristic(m), euler_characteristic(valley()));
}

TEST(Untangle, NoFlipFoldsATriangleOntoItsNeighbour) {
    // The valley with a neighbour (a, c, e) across its edge c-a, turned back over the tent's
    // (a, d, c) to 8 degrees short of its plane: the flip to the tent, the first tried, would
    // fold (a, d, c) onto it. It is not made; the flip of c-a undoes the crossing instead.
    std::vector<Eigen::Vector3d> points = kPoints;
    const Eigen::Vector3d tent_normal = Eigen::Vector3d(1, 1, -1).normalized();
    const Eigen::Vector3d c = points[2], middle = 0.5 * c;
    const Eigen::Vector3d e = middle + 0.3 * (points[3] - middle) + 0.05 * tent_normal; // off the plane x + y = z
    points.push_back(e);
    Mesh m = make_mesh(points, {{0, 1, 2}, {1, 0, 3}, kT, {0, 2, 7}});
    const Eigen::Vector3d neighbour = c.cross(e).normalized();
    ASSERT_LT(neighbour.dot(tent_normal), std::cos(170.0 * M_PI / 180.0));         // the tent folds onto it
    ASSERT_GT(neighbour.dot(Eigen::Vector3d(1, -1, -1).normalized()), -0.5);      // the valley does not
    ASSERT_EQ(crossings(m).size(), 1u);
    const Mesh input = make_mesh(points, {{0, 3, 2}, {3, 1, 2}, kT, {0, 2, 7}});
    ASSERT_TRUE(crossings(input).empty());
    const UntangleStats stats = untangle(m, test::OwnedReference(input), with_tolerance(0.01));
    EXPECT_TRUE(stats.crossings.empty());
    EXPECT_EQ(measure_quality(m).folded_edges, 0);
    EXPECT_EQ(m.triangles.row(1), Eigen::RowVector3i(1, 0, 3)); // the valley's other half kept
}

TEST(Untangle, NoFlipTakesTheSurfaceOffTheInput) {
    // The input is the valley itself: the tent lies up to 0.5 off it, beyond the tolerance, so
    // the crossing stays; with a tolerance past that distance the flip is made.
    Mesh m = valley();
    const Mesh input = valley();
    const UntangleStats kept = untangle(m, test::OwnedReference(input), with_tolerance(0.05));
    EXPECT_EQ(kept.flipped, 0);
    EXPECT_EQ(kept.crossings.size(), 1u);
    EXPECT_EQ(m.triangles, valley().triangles);
    const UntangleStats flipped = untangle(m, test::OwnedReference(input), with_tolerance(1.0));
    EXPECT_EQ(flipped.flipped, 1);
    EXPECT_TRUE(flipped.crossings.empty());
}

TEST(Untangle, AFlipThatLeavesAsManyCrossingsIsNotMade) {
    // T stretched from z = -0.5 to 1.5: through the valley and through the tent alike.
    std::vector<Eigen::Vector3d> points = kPoints;
    points[4].z() = points[5].z() = -0.5;
    points[6].z() = 1.5;
    Mesh m = make_mesh(points, {{0, 1, 2}, {1, 0, 3}, kT});
    ASSERT_EQ(crossings(m).size(), 1u);
    ASSERT_EQ(crossings(make_mesh(points, {{0, 3, 2}, {3, 1, 2}, kT})).size(), 1u);
    const Mesh input = m;
    const UntangleStats stats = untangle(m, test::OwnedReference(input), with_tolerance(1.0));
    EXPECT_EQ(stats.flipped, 0);
    EXPECT_EQ(m.triangles, input.triangles);
}

TEST(Untangle, LeavesAMeshWithoutCrossingsOrWithoutAFlipThatHelpsAsItIs) {
    Mesh sphere = test::make_icosphere(2);
    const Mesh original = sphere;
    EXPECT_EQ(untangle(sphere, test::OwnedReference(original), with_tolerance(0.01)).flipped, 0);
    EXPECT_EQ(sphere.triangles, original.triangles);
    // Two loose triangles through each other: no edge to flip.
    Mesh pair = make_mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.2, -0.5}, {0.3, 0.2, 0.5}, {0.2, 0.3, 0.5}},
                          {{0, 1, 2}, {3, 4, 5}});
    ASSERT_EQ(crossings(pair).size(), 1u);
    const UntangleStats stats = untangle(pair, test::OwnedReference(pair), with_tolerance(0.01));
    EXPECT_EQ(stats.flipped, 0);
    EXPECT_EQ(stats.moved, 0); // their corners end edges of one triangle: on a border, never moved
    EXPECT_EQ(stats.crossings.size(), 1u);
}

TEST(Untangle, AVertexPushedThroughTheOtherSideIsMovedBackOntoTheInput) {
    // A sphere with one vertex pushed through its centre to 0.3 beyond the far side: its fan
    // passes through the far side, which flips cannot undo (they only lessen it). The vertex
    // goes back onto the input, near the centroid of its neighbours; no other vertex moves.
    const Mesh input = test::make_icosphere(3);
    Mesh m = input;
    const Eigen::Index v = 0;
    const Eigen::Vector3d p = m.points.row(v);
    m.points.row(v) = -1.3 * p;
    ASSERT_FALSE(crossings(m).empty());
    const UntangleStats stats = untangle(m, test::OwnedReference(input), with_tolerance(0.01));
    EXPECT_EQ(stats.moved, 1);
    EXPECT_TRUE(stats.crossings.empty());
    EXPECT_TRUE(crossings(m).empty());
    const Eigen::Vector3d back = m.points.row(v);
    EXPECT_NEAR(back.norm(), 1.0, 0.01);   // on the input (the sphere's flat facets)
    EXPECT_LT((back - p).norm(), 0.1);     // among its neighbours again (edges of about 0.16)
    EXPECT_EQ(euler_characteristic(m), 2); // flips keep the topology
    for (Eigen::Index w = 1; w < m.points.rows(); ++w) EXPECT_EQ(m.points.row(w), input.points.row(w)) << w;
}

TEST(Untangle, NoMoveMakesATriangleFaceAgainstTheInput) {
    // The same vertex pushed through, with an input that is the sphere turned inside out: the
    // move back would leave the vertex's fan facing against it, so the crossings stay.
    Mesh input = test::make_icosphere(3);
    input.triangles.col(1).swap(input.triangles.col(2));
    Mesh m = test::make_icosphere(3);
    m.points.row(0) *= -1.3;
    const Mesh pushed = m;
    const UntangleStats stats = untangle(m, test::OwnedReference(input), with_tolerance(0.01));
    EXPECT_EQ(stats.moved, 0);
    EXPECT_FALSE(stats.crossings.empty());
    EXPECT_EQ(m.points, pushed.points);
}

TEST(Untangle, EditsThatKeepTheProjectsFloorAreTriedFirst) {
    // At the spike, a flip down to the last resort's floor undoes a crossing first and leaves a
    // triangle of kappa 0.28, and the moves that follow cannot undo the rest. Tried before it,
    // the edits that keep kappa over 0.3 undo all sixteen pairs (ten crossing, six where a
    // corner touches the other triangle): moves, and one flip where the move would have folded
    // an edge (the patch has two folded edges, and keeps two).
    const test::OwnedReference input(make_mesh(kSpikeInputPoints, kSpikeInputTriangles));
    const Mesh patch = make_mesh(kSpikeOutputPoints, kSpikeOutputTriangles);
    ASSERT_EQ(crossings(patch).size(), 16u);
    ASSERT_GE(measure_quality(patch).kappa_min, kKappaFloor);

    UntangleParams last_resort_only = with_tolerance(kSpikeTolerance);
    last_resort_only.preferred_kappa_floor = last_resort_only.kappa_floor;
    Mesh greedy = patch;
    const UntangleStats greedy_stats = untangle(greedy, input, last_resort_only);
    // (The flips and moves leave crossings, which only a tent's vertex taken out undoes.)
    EXPECT_TRUE(!greedy_stats.crossings.empty() || greedy_stats.removed > 0);
    EXPECT_LT(measure_quality(greedy).kappa_min, kKappaFloor);

    Mesh m = patch;
    const UntangleStats stats = untangle(m, input, with_tolerance(kSpikeTolerance));
    EXPECT_TRUE(stats.crossings.empty());
    EXPECT_TRUE(crossings(m).empty());
    EXPECT_LE(stats.flipped, 1);
    EXPECT_EQ(measure_quality(m).folded_edges, measure_quality(patch).folded_edges);
    EXPECT_GE(measure_quality(m).kappa_min, kKappaFloor);
    EXPECT_EQ(euler_characteristic(m), euler_characteristic(patch));
}

TEST(Untangle, ATentOfThreeTrianglesThroughAWallIsTakenOut) {
    // No flip of its edges and no move of its apex onto the input takes the tent out of the
    // outer face's triangle; its apex removed, the triangle of its rim lies on the hole's side.
    const test::OwnedReference input(make_mesh(kTentInputPoints, kTentInputTriangles));
    const Mesh patch = make_mesh(kTentOutputPoints, kTentOutputTriangles);
    ASSERT_EQ(crossings(patch).size(), 7u); // before the flips and moves
    Mesh m = patch;
    const UntangleStats stats = untangle(m, input, with_tolerance(kTentTolerance));
    EXPECT_EQ(stats.removed, 1);
    EXPECT_TRUE(stats.crossings.empty());
    EXPECT_TRUE(crossings(m).empty());
    EXPECT_EQ(m.points.rows(), patch.points.rows() - 1);
    EXPECT_EQ(m.triangles.rows(), patch.triangles.rows() - 2);
    EXPECT_EQ(euler_characteristic(m), euler_characteristic(patch));
    const MeshQuality before = measure_quality(patch), after = measure_quality(m);
    ASSERT_TRUE(before.oriented);
    EXPECT_TRUE(after.oriented); // the rim's triangle faces as the tent did
    EXPECT_EQ(after.folded_edges, before.folded_edges);
    EXPECT_GE(after.kappa_min, std::min(before.kappa_min, kKappaFloor));
}

TEST(Untangle, RefusesABadTolerance) {
    Mesh m = valley();
    const AabbTree input(tent());
    for (double tolerance : {0.0, -1.0, std::numeric_limits<double>::infinity()})
        EXPECT_THROW(untangle(m, {tent(), input}, with_tolerance(tolerance)), InvalidInput) << tolerance;
}
