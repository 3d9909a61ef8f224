// Geodesic solvers against analytic distances (plane, sphere) and metric invariants. Every
// registered solver runs through the same tests with its own tolerances.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

#include "core/primitives.h"
#include "eval/synthetic/variations.h"
#include "registry/registry.h"
#include "stages/geodesics/dijkstra.h"
#include "stages/geodesics/fast_marching.h"
#include "stages/geodesics/heat.h"

namespace symembed {
namespace {

struct SolverCase {
  std::string name;
  double grid_mean_rel;    // mean relative error on the flat grid
  double grid_max_rel;     // max relative error (vertices at least 0.2 from the source)
  double sphere_mean_rel;  // mean relative error on the level-4 icosphere
  bool converges;          // error decreases under refinement
  double symmetry_mean_rel;  // mean |d(i,j) - d(j,i)| / mean distance
  double symmetry_max_rel;   // max |d(i,j) - d(j,i)| / mean distance; triangle inequality slack
};

void PrintTo(const SolverCase& c, std::ostream* os) { *os << c.name; }

// Tolerances per solver. Dijkstra: a shortest path made of axis and diagonal grid steps is at
// most 1 / cos(22.5 deg) = 1.0824 times the straight line (worst at 22.5 deg), and this bias
// does not shrink under refinement; on the icosphere it is ~8.5% on average. fast_marching and
// heat are first order; measured errors are about half the bounds. The heat method is not
// symmetric by construction (each source has its own smoothed cone tip), and the box's 4:1
// triangles make that visible (~2% mean asymmetry).
const SolverCase kCases[] = {
    {"dijkstra", 0.06, 0.0825, 0.10, false, 1e-12, 1e-12},
    {"fast_marching", 0.02, 0.04, 0.025, true, 0.01, 0.08},
    {"heat", 0.02, 0.04, 0.02, true, 0.03, 0.10},
};

std::unique_ptr<GeodesicSolver> MakeSolver(const std::string& name, const Surface& s,
                                           const std::string& extra = "") {
  Registry registry;
  RegisterBuiltinStages(registry);
  auto stage = registry.CreateAs<GeodesicsStage>(
      "geodesics", YAML::Load("{type: " + name + extra + "}"), "test.yaml", "pipeline.geodesics");
  return stage->Prepare(s);
}

// Mean and max relative error of row 0 of D against `exact`, over vertices farther than
// `min_dist` from the source (close to the source the relative error is ill-conditioned).
std::pair<double, double> RelativeErrors(const Eigen::RowVectorXd& d,
                                         const Eigen::VectorXd& exact, double min_dist) {
  double sum = 0.0, max = 0.0;
  int count = 0;
  for (int v = 0; v < exact.size(); ++v) {
    if (exact(v) < min_dist) continue;
    const double rel = std::abs(d(v) - exact(v)) / exact(v);
    sum += rel;
    max = std::max(max, rel);
    ++count;
  }
  return {sum / count, max};
}

class GeodesicsTest : public ::testing::TestWithParam<SolverCase> {};

TEST_P(GeodesicsTest, FlatGridMatchesEuclidean) {
  const SolverCase& c = GetParam();
  const Surface grid = GridMesh(41, 41);
  const int center = 20 * 41 + 20;
  const auto solver = MakeSolver(c.name, grid);
  const Eigen::MatrixXd D = solver->Distances({center, 0});
  for (int row = 0; row < 2; ++row) {
    const int source = row == 0 ? center : 0;
    Eigen::VectorXd exact(grid.NumVertices());
    for (int v = 0; v < grid.NumVertices(); ++v) {
      exact(v) = (grid.V.row(v) - grid.V.row(source)).norm();
    }
    EXPECT_NEAR(D(row, source), 0.0, 1e-9);
    const auto [mean, max] = RelativeErrors(D.row(row), exact, 0.2);
    RecordProperty(c.name + "_grid_mean_rel_" + std::to_string(row), std::to_string(mean));
    std::printf("%s grid source %d: mean rel %.4f max rel %.4f\n", c.name.c_str(), source, mean,
                max);
    EXPECT_LT(mean, c.grid_mean_rel);
    EXPECT_LT(max, c.grid_max_rel);
  }
}

// The angle between the directions of a and b from the origin: their great-circle distance on
// the unit sphere.
double GreatCircleAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d p = a.normalized(), q = b.normalized();
  return std::atan2(p.cross(q).norm(), p.dot(q));
}

TEST_P(GeodesicsTest, SphereMatchesGreatCircleAndConverges) {
  const SolverCase& c = GetParam();
  const double radius = 2.0;
  double errors[2];
  for (int level : {3, 4}) {
    const Surface sphere = Icosphere(level, radius);
    const auto solver = MakeSolver(c.name, sphere);
    const Eigen::MatrixXd D = solver->Distances({0});
    Eigen::VectorXd exact(sphere.NumVertices());
    for (int v = 0; v < sphere.NumVertices(); ++v) {
      exact(v) = radius * GreatCircleAngle(sphere.V.row(0), sphere.V.row(v));
    }
    const auto [mean, max] = RelativeErrors(D.row(0), exact, 0.2 * radius);
    std::printf("%s icosphere level %d (%d vertices): mean rel %.4f max rel %.4f\n",
                c.name.c_str(), level, sphere.NumVertices(), mean, max);
    errors[level - 3] = mean;
  }
  EXPECT_LT(errors[1], c.sphere_mean_rel);
  if (c.converges) {
    EXPECT_LT(errors[1], errors[0]);
  }
}

TEST_P(GeodesicsTest, SymmetricAndTriangleInequality) {
  const SolverCase& c = GetParam();
  const Surface box = BoxMesh(12, 1.0, 2.0, 0.5);
  std::mt19937 rng(7);
  std::vector<int> sources(40);
  for (int& s : sources) s = std::uniform_int_distribution<int>(0, box.NumVertices() - 1)(rng);
  const auto solver = MakeSolver(c.name, box);
  const Eigen::MatrixXd D = solver->Distances(sources);
  // The box's sharp edges and corners are where first-order solvers err most.
  double mean = 0.0, mean_asym = 0.0, max_asym = 0.0;
  for (size_t i = 0; i < sources.size(); ++i) {
    for (size_t j = 0; j < sources.size(); ++j) {
      const double asym = std::abs(D(i, sources[j]) - D(j, sources[i]));
      mean += D(i, sources[j]);
      mean_asym += asym;
      max_asym = std::max(max_asym, asym);
    }
  }
  std::printf("%s box: asymmetry / mean distance: mean %.4f max %.4f\n", c.name.c_str(),
              mean_asym / mean, max_asym * sources.size() * sources.size() / mean);
  mean /= sources.size() * sources.size();
  EXPECT_LE(mean_asym / (mean * sources.size() * sources.size()), c.symmetry_mean_rel);
  EXPECT_LE(max_asym / mean, c.symmetry_max_rel);
  // d(a, c) <= d(a, b) + d(b, c), with slack for the symmetry error of approximate solvers.
  for (int t = 0; t < 2000; ++t) {
    const int a = std::uniform_int_distribution<int>(0, sources.size() - 1)(rng);
    const int b = std::uniform_int_distribution<int>(0, sources.size() - 1)(rng);
    const int v = std::uniform_int_distribution<int>(0, box.NumVertices() - 1)(rng);
    EXPECT_LE(D(a, v), D(a, sources[b]) + D(b, v) + c.symmetry_max_rel * mean + 1e-12);
  }
}

TEST_P(GeodesicsTest, ThreadCountAndPrecisionDoNotChangeResults) {
  const SolverCase& c = GetParam();
  const Surface sphere = Icosphere(3);
  const std::vector<int> sources = {0, 5, 17, 100, 333};
  const Eigen::MatrixXd one = MakeSolver(c.name, sphere, ", threads: 1")->Distances(sources);
  const Eigen::MatrixXd two = MakeSolver(c.name, sphere, ", threads: 2")->Distances(sources);
  EXPECT_EQ((one - two).cwiseAbs().maxCoeff(), 0.0);
  const Eigen::MatrixXd single =
      MakeSolver(c.name, sphere, ", precision: float")->Distances(sources);
  // float carries ~7 significant digits; accumulated rounding stays well below 1e-4.
  EXPECT_LT((one - single).cwiseAbs().maxCoeff(), 1e-4);
}

TEST_P(GeodesicsTest, RejectsBadSources) {
  const auto solver = MakeSolver(GetParam().name, Icosphere(1));
  EXPECT_THROW(solver->Distances({-1}), InvalidInputError);
  EXPECT_THROW(solver->Distances({42}), InvalidInputError);
  EXPECT_EQ(solver->Distances({}).rows(), 0);
}

INSTANTIATE_TEST_SUITE_P(Solvers, GeodesicsTest, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return info.param.name; });

// The ratio of the solver's distance to the great circle's along the remeshing's direction over
// the same ratio across it, less 1, from sources whose tangent plane holds the direction.
double DirectionalBias(const std::string& solver_name, const Surface& sphere,
                       const Eigen::Vector3d& direction) {
  std::vector<int> sources;
  for (const Eigen::RowVector3d& at : {Eigen::RowVector3d(0, 0, 1), Eigen::RowVector3d(0, 0, -1),
                                       Eigen::RowVector3d(0, 1, 0), Eigen::RowVector3d(0, -1, 0)}) {
    Eigen::Index nearest = 0;
    (sphere.V.rowwise() - at).rowwise().squaredNorm().minCoeff(&nearest);
    sources.push_back(static_cast<int>(nearest));
  }
  const Eigen::MatrixXd D = MakeSolver(solver_name, sphere)->Distances(sources);
  double along = 0.0, across = 0.0;
  int n_along = 0, n_across = 0;
  for (size_t i = 0; i < sources.size(); ++i) {
    const Eigen::Vector3d p0 = sphere.V.row(sources[i]).normalized();
    for (int v = 0; v < sphere.NumVertices(); ++v) {
      const Eigen::Vector3d p = sphere.V.row(v).normalized();
      const double exact = GreatCircleAngle(p0, p);
      if (exact < 0.3 || exact > 1.2) continue;
      const double cosine = std::abs((p - p.dot(p0) * p0).normalized().dot(direction));
      if (cosine > 0.9) {
        along += D(i, v) / exact;
        ++n_along;
      } else if (cosine < 0.3) {
        across += D(i, v) / exact;
        ++n_across;
      }
    }
  }
  return (along / n_along) / (across / n_across) - 1.0;
}

// An anisotropic remeshing (edges kept short along one direction, triangles elongated across it)
// stretches edge-graph distances along that direction: on a sphere decimated to 2,000 vertices
// with anisotropy 4 along x, Dijkstra's distances relative to the great circle's are about 40%
// longer along x than across it (measured 0.41), where on an isotropic decimation the two agree
// (0.002). A shape's geodesics, and so its embedding and symmetry plane, then depend on the
// direction of its meshing. Fast marching keeps a few percent of that bias (0.05), the heat
// method with its intrinsic Delaunay Laplacian almost none (0.006).
TEST(Geodesics, AnisotropicMeshingStretchesEdgeGraphDistancesAlongItsDirection) {
  const Surface fine = Icosphere(5);
  std::vector<int> ids(fine.NumVertices());
  std::iota(ids.begin(), ids.end(), 0);
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
  const Surface iso = Remesh(TrackedSurface{fine, ids}, 2000, 3).surface;
  const Surface aniso = Remesh(TrackedSurface{fine, ids}, 2000, 3, 4.0, x).surface;
  for (const SolverCase& c : kCases) {
    EXPECT_LT(std::abs(DirectionalBias(c.name, iso, x)), 0.01) << c.name;
  }
  EXPECT_GT(DirectionalBias("dijkstra", aniso, x), 0.2);
  EXPECT_LT(std::abs(DirectionalBias("fast_marching", aniso, x)), 0.1);
  EXPECT_LT(std::abs(DirectionalBias("heat", aniso, x)), 0.02);
}

TEST(DijkstraGeodesics, ExactOnEdgePaths) {
  // On a grid without shortcuts along an axis, graph distance equals Euclidean distance.
  const Surface grid = GridMesh(11, 3, 1.0, 0.2);
  const Eigen::MatrixXd D = DijkstraDistances(grid, {0});
  for (int i = 0; i < 11; ++i) EXPECT_NEAR(D(0, i), 0.1 * i, 1e-12);
}

}  // namespace
}  // namespace symembed

namespace symembed {
namespace {

// A flat grid sheared so that half of its triangles are strongly obtuse; distances stay
// Euclidean.
Surface ShearedGrid() {
  Surface s = GridMesh(41, 41);
  for (int v = 0; v < s.NumVertices(); ++v) s.V(v, 0) += 2.0 * s.V(v, 1);
  return s;
}

TEST(FastMarchingGeodesics, SplittingObtuseAnglesRestoresAccuracy) {
  const Surface s = ShearedGrid();
  const int source = 20 * 41 + 20;
  Eigen::VectorXd exact(s.NumVertices());
  for (int v = 0; v < s.NumVertices(); ++v) exact(v) = (s.V.row(v) - s.V.row(source)).norm();
  FastMarchingOptions split, plain;
  plain.max_unfold_steps = 0;
  const FastMarchingGeodesicSolver with_split(s, split), without(s, plain);
  EXPECT_GT(with_split.obtuse_corners(), s.NumFaces() / 4);
  // Corners whose opposite edge is near the boundary cannot be unfolded far enough.
  EXPECT_GT(with_split.split_corners(), 0.8 * with_split.obtuse_corners());
  const auto [mean_split, max_split] = RelativeErrors(with_split.Distances({source}).row(0),
                                                      exact, 0.2);
  const auto [mean_plain, max_plain] = RelativeErrors(without.Distances({source}).row(0),
                                                      exact, 0.2);
  std::printf("sheared grid: mean rel %.4f (split) vs %.4f (no split); max %.4f vs %.4f\n",
              mean_split, mean_plain, max_split, max_plain);
  EXPECT_LT(mean_split, 0.03);
  EXPECT_LT(mean_split, 0.5 * mean_plain);
}

}  // namespace
}  // namespace symembed

namespace symembed {
namespace {

TEST(HeatGeodesics, BoundaryConditionsOnAnOpenCylinder) {
  // An open cylinder unrolls to a strip: the distance between points on one ring line (z fixed)
  // is R * angle. Each boundary option stays close; the average is the paper's choice.
  const double r = 1.0;
  const Surface cyl = Cylinder(96, 41, r, 4.0);
  const int source = 20 * 96;  // middle ring, angle 0
  for (const char* mode : {"average", "neumann", "dirichlet"}) {
    Registry registry;
    RegisterBuiltinStages(registry);
    auto stage = registry.CreateAs<GeodesicsStage>(
        "geodesics", YAML::Load(std::string("{type: heat, boundary: ") + mode + "}"), "t.yaml",
        "pipeline.geodesics");
    const auto solver = stage->Prepare(cyl);
    EXPECT_TRUE(dynamic_cast<const HeatGeodesicSolver&>(*solver).has_boundary());
    const Eigen::MatrixXd D = solver->Distances({source});
    double sum = 0.0;
    for (int i = 10; i <= 48; ++i) {  // along the ring, angles 37.5 to 180 degrees
      const double exact = r * 2.0 * M_PI * i / 96;
      sum += std::abs(D(0, 20 * 96 + i) - exact) / exact;
    }
    std::printf("heat boundary %s: mean rel error on the ring %.4f\n", mode, sum / 39);
    // Measured 1.8% (neumann) to 3.5% (dirichlet): the boundary, 2 away, bends the level sets.
    EXPECT_LT(sum / 39, 0.045);
  }
}

TEST(HeatGeodesics, UnreachableVerticesAreInfinite) {
  Surface s = Icosphere(2);
  s.V.conservativeResize(s.NumVertices() + 1, 3);
  s.V.row(s.NumVertices() - 1) << 5, 5, 5;
  const Eigen::MatrixXd D = HeatDistances(s, {0});
  EXPECT_TRUE(std::isinf(D(0, s.NumVertices() - 1)));
  EXPECT_TRUE(std::isfinite(D.leftCols(s.NumVertices() - 1).maxCoeff()));
}

}  // namespace
}  // namespace symembed

namespace symembed {
namespace {

TEST(HeatGeodesics, IntrinsicDelaunayFixesObtuseMeshes) {
  // On the sheared grid the extrinsic cotan Laplacian has negative weights; on its intrinsic
  // Delaunay triangulation it does not, and the heat method becomes accurate again.
  Surface s = GridMesh(41, 41);
  for (int v = 0; v < s.NumVertices(); ++v) s.V(v, 0) += 2.0 * s.V(v, 1);
  const int source = 20 * 41 + 20;
  Eigen::VectorXd exact(s.NumVertices());
  for (int v = 0; v < s.NumVertices(); ++v) exact(v) = (s.V.row(v) - s.V.row(source)).norm();
  HeatOptions intrinsic, extrinsic;
  extrinsic.intrinsic_delaunay = false;
  const HeatGeodesicSolver with(s, intrinsic), without(s, extrinsic);
  EXPECT_GT(with.flips(), 0);
  const double err_with = RelativeErrors(with.Distances({source}).row(0), exact, 0.2).first;
  const double err_without = RelativeErrors(without.Distances({source}).row(0), exact, 0.2).first;
  std::printf("heat on sheared grid: mean rel %.4f (intrinsic Delaunay) vs %.4f (extrinsic)\n",
              err_with, err_without);
  EXPECT_LT(err_with, 0.03);
  EXPECT_LT(err_with, err_without);
}

}  // namespace
}  // namespace symembed
