// Agreement of the three geodesic solvers on one TOSCA shape per class (label `tosca`; skipped
// without the data). Each shape is preprocessed (unit area), 1,000 farthest-point sources are
// drawn, and the mean relative difference of dijkstra and heat against fast_marching (and of
// dijkstra against heat) is printed with the wall time of each solver.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "core/mesh_io.h"
#include "stages/geodesics/dijkstra.h"
#include "stages/geodesics/fast_marching.h"
#include "stages/geodesics/heat.h"
#include "stages/preprocess/standard.h"
#include "stages/sampling/farthest_point.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

double ReportValue(const Report& report, const std::string& key) {
  for (const auto& [k, v] : report) {
    if (k == key) return v;
  }
  return -1;
}

// Mean of |a - b| / b over entries with b > min_dist (relative error is ill-conditioned near
// each source).
double MeanRelativeDifference(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                              double min_dist) {
  double sum = 0.0;
  long count = 0;
  for (int j = 0; j < b.cols(); ++j) {
    for (int i = 0; i < b.rows(); ++i) {
      if (b(i, j) > min_dist && std::isfinite(b(i, j))) {
        sum += std::abs(a(i, j) - b(i, j)) / b(i, j);
        ++count;
      }
    }
  }
  return sum / count;
}

template <typename Fn>
double Seconds(Fn&& fn) {
  const auto start = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

TEST(GeodesicsTosca, SolversAgreeOnOneShapePerClass) {
  const std::string root = testing::DataRoot();
  if (root.empty()) GTEST_SKIP() << "no benchmark data (set SYMEMBED_DATA)";
  const std::string dir = root + "/tosca_iso_5k/shapes/";
  const std::vector<std::string> shapes = {"cat0",     "centaur0",   "david0", "dog0",
                                           "horse0",   "michael0",   "victoria10", "wolf0"};
  std::printf("%-11s %5s %7s %8s | %9s %9s %9s | %7s %7s %7s\n", "shape", "#V", "flipped",
              "boundary", "dijk/fmm", "heat/fmm", "dijk/heat", "t_dijk", "t_fmm", "t_heat");
  for (const std::string& name : shapes) {
    const std::string path = dir + name + ".off";
    if (!std::filesystem::exists(path)) {
      ADD_FAILURE() << "missing " << path;
      continue;
    }
    const PreprocessResult pre = StandardPreprocess(LoadSurface(path));
    const Surface& s = pre.surface;
    const std::vector<int> sources = FarthestPointSampling(s, {1000, 1}).samples;
    Eigen::MatrixXd Dd, Df, Dh;
    const double td = Seconds([&] { Dd = DijkstraDistances(s, sources); });
    const double tf = Seconds([&] { Df = FastMarchingDistances(s, sources); });
    const double th = Seconds([&] { Dh = HeatDistances(s, sources); });
    // Unit total area: 0.05 is 5% of the shape's scale.
    const double dijk_fmm = MeanRelativeDifference(Dd, Df, 0.05);
    const double heat_fmm = MeanRelativeDifference(Dh, Df, 0.05);
    const double dijk_heat = MeanRelativeDifference(Dd, Dh, 0.05);
    std::printf("%-11s %5d %7.0f %8.0f | %9.4f %9.4f %9.4f | %6.2fs %6.2fs %6.2fs\n",
                name.c_str(), s.NumVertices(), ReportValue(pre.report, "flipped_faces"),
                ReportValue(pre.report, "boundary_edges"), dijk_fmm, heat_fmm, dijk_heat, td, tf,
                th);
    std::fflush(stdout);
    // Loose agreement: dijkstra's edge-path bias is ~5-8%; heat and fast marching are both
    // first order and should agree within a few percent.
    EXPECT_LT(dijk_fmm, 0.12) << name;
    EXPECT_LT(heat_fmm, 0.05) << name;
    EXPECT_TRUE(std::isfinite(Dh.maxCoeff())) << name;
    EXPECT_TRUE(std::isfinite(Df.maxCoeff())) << name;
  }
}

}  // namespace
}  // namespace symembed
