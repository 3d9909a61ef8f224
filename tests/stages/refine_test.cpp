// Refine stages on a near-isometric pair built in code: an asymmetric bumpy blob and a twisted
// copy with shuffled vertex ids (the shuffle is the ground truth). The blob has no self-isometry,
// so the ground-truth map is the only good one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "core/errors.h"
#include "core/fmap/functional_map.h"
#include "core/fmap/spectral_knn.h"
#include "core/fmap/zoomout.h"
#include "core/spectral.h"
#include "eval/synthetic/synthetic.h"
#include "registry/registry.h"
#include "stages/refine/fmap_icp.h"
#include "tests/stages/refine_test_util.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

using testing::MakePair;
using testing::MeanError;
using testing::Pair;
using testing::PerturbedTruth;

std::unique_ptr<RefineStage> MakeStage(const std::string& yaml) {
  Registry registry;
  RegisterBuiltinStages(registry);
  return registry.CreateAs<RefineStage>("refine", YAML::Load(yaml), "test.yaml", "pipeline.refine");
}

// Shared fixture data: one pair with its bases prepared by the zoomout stage.
class RefineTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    pair_ = new Pair(MakePair(16, 0.1));  // 1538 vertices
    const auto stage = MakeStage("{type: zoomout, k_start: 10, k_end: 60, step: 5}");
    ComputeNeeds(stage->Needs(), &pair_->source);
    ComputeNeeds(stage->Needs(), &pair_->target);
  }
  static void TearDownTestSuite() { delete pair_; }

  // What the tests that call ZoomOut directly run on: the bases (60 eigenpairs) and Euclidean
  // farthest points of the source (400) and of the target (800).
  struct ZoomOutInputs {
    LaplaceBasis s, t;
    std::vector<int> samples, target_samples;
  };
  static ZoomOutInputs SampledInputs() {
    return {LeadingEigenpairs(pair_->source.basis, 60), LeadingEigenpairs(pair_->target.basis, 60),
            EuclideanFarthestPoints(pair_->source.surface.V, 400),
            EuclideanFarthestPoints(pair_->target.surface.V, 800)};
  }

  static Pair* pair_;
};
Pair* RefineTest::pair_ = nullptr;

TEST_F(RefineTest, StagesDeclareTheirBasisAndAShapeKeepsTheLargest) {
  EXPECT_EQ(pair_->source.basis.NumEigenpairs(), 60);
  EXPECT_EQ(pair_->source.basis.NumVertices(), pair_->source.surface.NumVertices());
  const Eigen::MatrixXd before = pair_->source.basis.evecs;
  // A stage needing fewer eigenpairs reuses the shape's basis.
  const ShapeNeeds icp = MakeStage("{type: icp, k: 30}")->Needs();
  EXPECT_EQ(icp.basis, 30);
  EXPECT_TRUE(icp.products.empty());
  ComputeNeeds(icp, &pair_->source);
  EXPECT_EQ(pair_->source.basis.evecs, before);
  // The discrete stage's descriptor products are computed from its own basis.
  const ShapeNeeds discrete = MakeStage("{type: discrete, k_start: 10, k_end: 40}")->Needs();
  EXPECT_EQ(discrete.basis, 40);
  ASSERT_EQ(discrete.products.size(), 1u);
  EXPECT_EQ(discrete.products[0].input, ProductInput::kBasis);
  EXPECT_EQ(discrete.products[0].basis_size, 40);
  EXPECT_EQ(MakeStage("{type: none}")->Needs().basis, 0);
}

TEST_F(RefineTest, FunctionalMapOfTruthIsNearlyOrthogonal) {
  const LaplaceBasis s = LeadingEigenpairs(pair_->source.basis, 30);
  const LaplaceBasis t = LeadingEigenpairs(pair_->target.basis, 30);
  std::vector<int> all(pair_->truth.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  const Eigen::MatrixXd C = FitFunctionalMap(s.evecs, t.evecs, all, pair_->truth, s.mass);
  // A near-isometry with an area-preserving bijection: C^T C ~ I (measured defect 1.5e-4; the
  // twist stretches the surface by a few percent).
  EXPECT_LT(OrthogonalityDefect(C), 0.01);
  // The convention of functional_map.h: rows T(i) of Phi_t C^T are rows i of Phi_s, so the map
  // of C recovers the truth.
  const std::vector<int> map = PointMapFromFunctionalMap(s.evecs, t.evecs, t.mass, C, all);
  EXPECT_LT(MeanError(*pair_, map), 0.003);  // measured 0
}

TEST_F(RefineTest, StepsOnGatheredRowsEqualTheGatheringOnes) {
  // ZoomOut gathers the basis rows once and calls the steps on them; the results must be those
  // of FitFunctionalMap and PointMapFromFunctionalMap bit for bit.
  const ZoomOutInputs in = SampledInputs();
  const int k = 30;
  const std::vector<int> targets = PerturbedTruth(*pair_, 0.5, 2, 7);
  std::vector<int> sample_targets(in.samples.size());
  for (size_t r = 0; r < in.samples.size(); ++r) sample_targets[r] = targets[in.samples[r]];
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(in.s.NumVertices());
  const Eigen::MatrixXd C = FitFunctionalMap(in.s.evecs.leftCols(k), in.t.evecs.leftCols(k),
                                             in.samples, sample_targets, ones);
  const Eigen::MatrixXd source_rows = BasisRows(in.s.evecs, in.samples);
  EXPECT_EQ(
      FitFunctionalMapFromRows(source_rows.leftCols(k), BasisRows(in.t.evecs, sample_targets, k),
                               Eigen::VectorXd::Ones(in.samples.size())),
      C);
  std::vector<double> sq, sq_rows;
  const std::vector<int> map = PointMapFromFunctionalMap(in.s.evecs, in.t.evecs, in.t.mass, C,
                                                         in.samples, &sq, in.target_samples);
  const std::vector<int> matchable = MatchableTargets(in.t.mass, in.target_samples);
  EXPECT_EQ(NearestUnderMap(source_rows.leftCols(k), BasisRows(in.t.evecs, matchable, k), matchable,
                            C, &sq_rows),
            map);
  EXPECT_EQ(sq_rows, sq);
  // Bad ids are named.
  EXPECT_THROW(BasisRows(in.t.evecs, {0, in.t.NumVertices()}), InvalidInputError);
}

TEST_F(RefineTest, ZoomOutFromTruthStaysAtTruth) {
  for (const std::string yaml : {"{type: zoomout, k_start: 10, k_end: 60, step: 5, "
                                 "extra_k_starts: []}",
                                 "{type: zoomout, k_start: 10, k_end: 60, step: 5, "
                                 "sample_count: 400, extra_k_starts: []}"}) {
    const MatchResult r = MakeStage(yaml)->Run({pair_->source, pair_->target}, pair_->truth);
    // Mean edge length / sqrt(area) is 0.029 here; a tenth of it allows a few vertices to move to
    // a neighbour (measured: 0, every vertex stays).
    EXPECT_LT(MeanError(*pair_, r.map), 0.003) << yaml << "\n" << r.status.message;
    EXPECT_NE(r.status.message.find("k 10..60"), std::string::npos) << r.status.message;
  }
}

TEST_F(RefineTest, ZoomOutLowersTheErrorOfANoisyTruth) {
  const std::vector<int> noisy = PerturbedTruth(*pair_, 0.5, 3, 7);
  const double before = MeanError(*pair_, noisy);
  for (const std::string yaml : {"{type: zoomout, k_start: 10, k_end: 60, step: 5}",
                                 "{type: zoomout, k_start: 10, k_end: 60, step: 5, "
                                 "sample_count: 400}"}) {
    const MatchResult r = MakeStage(yaml)->Run({pair_->source, pair_->target}, noisy);
    const double after = MeanError(*pair_, r.map);
    // Strictly lower, and by a wide margin: the perturbation is high-frequency, which the
    // smooth spectral embedding removes (measured 0.031 -> 0.0026 dense, 0.0040 sampled).
    EXPECT_LT(after, 0.25 * before) << yaml << " before " << before << " after " << after;
  }
}

TEST_F(RefineTest, ZoomOutOnSamplesOnlyMapsTheSamplesOntoTheTargetSamples) {
  const auto [s, t, samples, target_samples] = SampledInputs();
  const std::vector<int> noisy = PerturbedTruth(*pair_, 0.5, 3, 7);
  ZoomOutOptions options;
  options.k_start = 10;
  options.k_end = 60;
  const ZoomOutResult dense = ZoomOut(s, t, noisy, samples, options);
  options.dense_result = false;
  const ZoomOutResult sparse = ZoomOut(s, t, noisy, samples, options);
  const ZoomOutResult restricted = ZoomOut(s, t, noisy, samples, options, target_samples);
  const std::set<int> sample_set(samples.begin(), samples.end());
  const std::set<int> target_set(target_samples.begin(), target_samples.end());
  double err_noisy = 0.0, err_restricted = 0.0;
  const Surface& ts = pair_->target.surface;
  for (int i = 0; i < pair_->source.surface.NumVertices(); ++i) {
    if (sample_set.count(i) == 0) {
      // Vertices outside the sample keep the initial map.
      EXPECT_EQ(sparse.map[i], noisy[i]);
      EXPECT_EQ(restricted.map[i], noisy[i]);
      continue;
    }
    // On the samples the sparse result is the dense one.
    EXPECT_EQ(sparse.map[i], dense.map[i]);
    EXPECT_EQ(target_set.count(restricted.map[i]), 1u) << "sample " << i;
    err_noisy += (ts.V.row(noisy[i]) - ts.V.row(pair_->truth[i])).norm();
    err_restricted += (ts.V.row(restricted.map[i]) - ts.V.row(pair_->truth[i])).norm();
  }
  // Restricted to 800 of 1538 target vertices the samples still land near the truth: the
  // error is bounded by the target sample spacing, below that of the noisy map.
  EXPECT_LT(err_restricted, err_noisy);
  std::vector<int> bad = target_samples;
  bad.push_back(ts.NumVertices());
  EXPECT_THROW(ZoomOut(s, t, noisy, samples, options, bad), InvalidInputError);
}

TEST_F(RefineTest, ZoomOutSetupRefinesSeveralMapsAsTheStepsWrittenOutDo) {
  // The steps written out with the functions that gather from the full bases: a functional map
  // of the samples' current matches, then each sample's nearest target sample under it.
  const auto [s, t, samples, target_samples] = SampledInputs();
  ZoomOutOptions options;
  options.k_start = 10;
  options.k_end = 60;
  options.dense_result = false;
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(s.NumVertices());
  const Eigen::MatrixXd gram = WeightedGram(BasisRows(s.evecs, samples, options.k_end),
                                            Eigen::VectorXd::Ones(samples.size()));
  auto written_out = [&](const std::vector<int>& initial) {
    std::vector<int> current(samples.size());
    for (size_t r = 0; r < samples.size(); ++r) current[r] = initial[samples[r]];
    std::vector<double> residuals;
    for (int k = options.k_start; k <= options.k_end; k += options.step) {
      const Eigen::MatrixXd C =
          FitFunctionalMap(s.evecs.leftCols(k), t.evecs.leftCols(k), samples, current, ones, &gram);
      std::vector<double> sq;
      current =
          PointMapFromFunctionalMap(s.evecs, t.evecs, t.mass, C, samples, &sq, target_samples);
      double sum = 0.0;
      for (const double d : sq) sum += d;
      residuals.push_back(sum / sq.size());
    }
    std::vector<int> map = initial;
    for (size_t r = 0; r < samples.size(); ++r) map[samples[r]] = current[r];
    return std::make_pair(map, residuals);
  };
  // One setup for three maps; the second starts from the first's result (its matches are all
  // target samples, whose rows the setup gathered), the third from a map far from the truth.
  const ZoomOutSetup setup(s, t, samples, options, target_samples);
  const std::vector<int> first = PerturbedTruth(*pair_, 0.5, 3, 7);
  const std::vector<int> far = PerturbedTruth(*pair_, 0.9, 10, 3);
  const ZoomOutResult a = setup.Run(first);
  const ZoomOutResult b = setup.Run(a.map);
  const ZoomOutResult c = setup.Run(far);
  for (const auto& [result, initial] :
       {std::make_pair(&a, first), std::make_pair(&b, a.map), std::make_pair(&c, far)}) {
    const auto [map, residuals] = written_out(initial);
    EXPECT_EQ(result->map, map);
    EXPECT_EQ(result->spectral_residual, residuals);
  }
  EXPECT_NE(a.map, c.map);
}

TEST_F(RefineTest, ZoomOutFromSeveralStartsKeepsTheRunWithTheLowestResidual) {
  const auto [s, t, samples, target_samples] = SampledInputs();
  // Coarse noise (up to 8 rings), so that the runs from different starts end apart.
  const std::vector<int> noisy = PerturbedTruth(*pair_, 0.7, 8, 11);
  for (const bool sampled : {false, true}) {
    for (const bool dense_result : {true, false}) {
      if (!sampled && !dense_result) continue;
      SCOPED_TRACE(::testing::Message() << "sampled " << sampled << " dense " << dense_result);
      ZoomOutOptions options;
      options.k_start = 20;
      options.k_end = 60;
      options.extra_k_starts = {3, 10};
      options.dense_result = dense_result;
      const std::vector<int> on = sampled ? samples : std::vector<int>{};
      const std::vector<int> onto = sampled ? target_samples : std::vector<int>{};
      const ZoomOutResult several = ZoomOut(s, t, noisy, on, options, onto);
      // One residual per start, in the order k_start, extra_k_starts.
      const std::vector<int> starts = {20, 3, 10};
      ASSERT_EQ(several.start_residuals.size(), 3u);
      const auto lowest =
          std::min_element(several.start_residuals.begin(), several.start_residuals.end());
      EXPECT_GT(*lowest, 0.0);
      EXPECT_EQ(several.start, starts[lowest - several.start_residuals.begin()]);
      // The runs differ, or the choice would not be tested (measured residuals from 20, 3, 10:
      // 0.023, 0.087, 0.018 dense; 0.107, 0.213, 0.104 on the samples; kept 10 in both).
      EXPECT_GT(*std::max_element(several.start_residuals.begin(), several.start_residuals.end()),
                1.05 * *lowest);
      EXPECT_NE(several.status.message.find("kept " + std::to_string(several.start)),
                std::string::npos)
          << several.status.message;
      // The kept run is the single run from its start: same map, same trace.
      ZoomOutOptions single = options;
      single.k_start = several.start;
      single.extra_k_starts.clear();
      const ZoomOutResult one = ZoomOut(s, t, noisy, on, single, onto);
      EXPECT_EQ(several.map, one.map);
      EXPECT_EQ(several.k, one.k);
      EXPECT_EQ(several.spectral_residual, one.spectral_residual);
      EXPECT_TRUE(one.start_residuals.empty());
      EXPECT_EQ(one.start, several.start);
    }
  }
  ZoomOutOptions bad;
  bad.k_end = 60;
  for (const std::vector<int>& extra :
       {std::vector<int>{61}, std::vector<int>{0}, std::vector<int>{20}, std::vector<int>{5, 5}}) {
    bad.extra_k_starts = extra;
    EXPECT_THROW(ZoomOut(s, t, noisy, {}, bad), ConfigError) << extra[0];
  }
}

TEST_F(RefineTest, ZoomOutStageWithStartsAndTargetSamplesLowersTheError) {
  const std::vector<int> noisy = PerturbedTruth(*pair_, 0.5, 3, 7);
  const MatchResult r = MakeStage(
                            "{type: zoomout, k_start: 10, k_end: 60, extra_k_starts: [5, 20], "
                            "sample_count: 400, target_sample_count: 800}")
                            ->Run({pair_->source, pair_->target}, noisy);
  // As without the options (measured 0.031 -> 0.0040 on 400 samples).
  EXPECT_LT(MeanError(*pair_, r.map), 0.25 * MeanError(*pair_, noisy)) << r.status.message;
  EXPECT_NE(r.status.message.find("starts (k: residual at k_end)"), std::string::npos)
      << r.status.message;
  EXPECT_NE(r.status.message.find("on 400 samples onto 800 target samples"), std::string::npos)
      << r.status.message;
}

TEST_F(RefineTest, IcpFromTruthStaysAndLowersTheErrorOfANoisyTruth) {
  const auto stage = MakeStage("{type: icp, k: 30}");
  const MatchResult from_truth = stage->Run({pair_->source, pair_->target}, pair_->truth);
  // Same tolerance as zoomout (measured: 0).
  EXPECT_LT(MeanError(*pair_, from_truth.map), 0.003) << from_truth.status.message;
  const std::vector<int> noisy = PerturbedTruth(*pair_, 0.5, 3, 7);
  const MatchResult r = stage->Run({pair_->source, pair_->target}, noisy);
  // Measured 0.031 -> 0: on this mild deformation the orthogonal map at k = 30 suffices.
  EXPECT_LT(MeanError(*pair_, r.map), 0.25 * MeanError(*pair_, noisy)) << r.status.message;
}

TEST_F(RefineTest, NoneKeepsTheMap) {
  const std::vector<int> noisy = PerturbedTruth(*pair_, 0.5, 3, 7);
  EXPECT_EQ(MakeStage("{type: none}")->Run({pair_->source, pair_->target}, noisy).map, noisy);
}

TEST_F(RefineTest, RejectsMalformedMaps) {
  const auto stage = MakeStage("{type: zoomout, k_start: 10, k_end: 60, step: 5}");
  std::vector<int> map = pair_->truth;
  map.pop_back();
  EXPECT_THROW(stage->Run({pair_->source, pair_->target}, map), InvalidInputError);
  map = pair_->truth;
  map[3] = pair_->target.surface.NumVertices();
  EXPECT_THROW(stage->Run({pair_->source, pair_->target}, map), InvalidInputError);
}

TEST(RefineStages, WorkWithoutTheirNeeds) {
  Pair p = MakePair(6, 0.2);  // 218 vertices
  const MatchResult r = MakeStage("{type: zoomout, k_start: 5, k_end: 20, step: 5}")
                            ->Run({p.source, p.target}, p.truth);
  EXPECT_NE(r.status.message.find("basis computed per pair"), std::string::npos);
  EXPECT_EQ(r.map.size(), p.truth.size());
}

TEST(RefineStages, OptionsAreCheckedStrictly) {
  EXPECT_THROW(MakeStage("{type: zoomout, k_start: 30, k_end: 20}"), ConfigError);
  EXPECT_THROW(MakeStage("{type: zoomout, k_end: 120, sample_count: 50}"), ConfigError);
  EXPECT_THROW(MakeStage("{type: zoomout, steps: 5}"), ConfigError);
  EXPECT_THROW(MakeStage("{type: zoomout, extra_k_starts: [130]}"), ConfigError);
  EXPECT_THROW(MakeStage("{type: zoomout, extra_k_starts: [20]}"), ConfigError);
  EXPECT_THROW(MakeStage("{type: zoomout, sample_count: 0, target_sample_count: 1000}"),
               ConfigError);
  EXPECT_THROW(MakeStage("{type: zoomout, sample_count: 1000, target_sample_count: 50}"),
               ConfigError);
  EXPECT_EQ(MakeStage("{type: zoomout, extra_k_starts: 10}")
                ->resolved_options()["extra_k_starts"][0]
                .as<int>(),
            10);
  EXPECT_THROW(MakeStage("{type: icp, k: 0}"), ConfigError);
  const auto stage = MakeStage("{type: zoomout}");
  const YAML::Node& resolved = stage->resolved_options();
  EXPECT_EQ(resolved["k_start"].as<int>(), 20);
  EXPECT_EQ(resolved["k_end"].as<int>(), 120);
  EXPECT_EQ(resolved["step"].as<int>(), 5);
  EXPECT_EQ(resolved["sample_count"].as<int>(), 1000);
  EXPECT_EQ(resolved["target_sample_count"].as<int>(), 1000);
  EXPECT_EQ(resolved["extra_k_starts"].as<std::vector<int>>(), (std::vector<int>{5, 10, 15}));
  // The default extra starts leave out k_start and sizes beyond k_end; the default samples are
  // 1,000; dense iterations map onto every target vertex.
  EXPECT_EQ(MakeStage("{type: zoomout, k_start: 10, k_end: 60}")
                ->resolved_options()["extra_k_starts"]
                .as<std::vector<int>>(),
            (std::vector<int>{5, 15}));
  EXPECT_EQ(MakeStage("{type: zoomout, k_start: 5, k_end: 12}")
                ->resolved_options()["extra_k_starts"]
                .as<std::vector<int>>(),
            (std::vector<int>{10}));
  EXPECT_EQ(MakeStage("{type: zoomout, sample_count: 0}")
                ->resolved_options()["target_sample_count"]
                .as<int>(),
            0);
  EXPECT_EQ(
      MakeStage("{type: zoomout, extra_k_starts: []}")->resolved_options()["extra_k_starts"].size(),
      0u);
}

// Two poses of the synthetic humanoid (eval/synthetic): same rest vertices, so the identity of
// rest ids is the ground truth, and the rest mirror gives the symmetric (flipped) one.
TEST(RefineSynthetic, ZoomOutOnPosedHumanoidImprovesAndKeepsTheSide) {
  std::vector<int> mirrored;
  Pair p = testing::PosedHumanoidPair(0.0, &mirrored);
  for (size_t i = 0; i < p.truth.size(); ++i) {
    ASSERT_GE(p.truth[i], 0);
    ASSERT_GE(mirrored[i], 0);
  }
  const std::vector<int> noisy = PerturbedTruth(p, 0.5, 3, 7);
  Pair flipped = p;
  flipped.truth = mirrored;
  for (const std::string yaml : {"{type: zoomout, k_end: 80}", "{type: icp, k: 40}"}) {
    const auto stage = MakeStage(yaml);
    ComputeNeeds(stage->Needs(), &p.source);
    ComputeNeeds(stage->Needs(), &p.target);
    const MatchResult from_truth = stage->Run({p.source, p.target}, p.truth);
    const MatchResult r = stage->Run({p.source, p.target}, noisy);
    // Bending is not isometric at the joints: from the truth the map settles within about half a
    // mean edge (measured 0.014 zoomout, 0.016 icp; mean edge / sqrt(area) ~ 0.03).
    EXPECT_LT(MeanError(p, from_truth.map), 0.02) << yaml;
    // Local noise is removed (measured 0.028 -> 0.013 zoomout, 0.016 icp).
    EXPECT_LT(MeanError(p, r.map), 0.7 * MeanError(p, noisy)) << yaml;
    // No flip to the mirror: the mirrored truth is 0.43 away (a flipped map would be ~0).
    EXPECT_GT(MeanError(flipped, from_truth.map), 0.3) << yaml;
    EXPECT_GT(MeanError(flipped, r.map), 0.3) << yaml;
  }
}

TEST(SpectralNearest, KdTreeAndBruteForceMatchNaiveSearch) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int dims : {3, 64}) {
    Eigen::MatrixXd points(500, dims), queries(200, dims);
    for (int i = 0; i < points.size(); ++i) points.data()[i] = normal(rng);
    for (int i = 0; i < queries.size(); ++i) queries.data()[i] = normal(rng);
    std::vector<int> ids(points.rows());
    for (int i = 0; i < points.rows(); ++i) ids[i] = 1000 + i;
    for (auto method : {SpectralNearest::Method::kKdTree, SpectralNearest::Method::kBruteForce}) {
      const SpectralNearest search(points, ids, method);
      std::vector<int> nearest;
      std::vector<double> sq_dist;
      search.Query(queries, &nearest, &sq_dist);
      for (int q = 0; q < queries.rows(); ++q) {
        Eigen::Index best = 0;
        const double d =
            (points.rowwise() - queries.row(q)).rowwise().squaredNorm().minCoeff(&best);
        // Gaussian data: the nearest is unique by far more than float rounding (1e-6 relative).
        EXPECT_EQ(nearest[q], 1000 + best) << "dims " << dims << " query " << q;
        EXPECT_NEAR(sq_dist[q], d, 1e-9 * d);
      }
    }
  }
}

TEST(FunctionalMap, EuclideanFarthestPointsSpreadAndRespectKeep) {
  const Surface s = testing::BumpyBlob(8);
  std::vector<bool> keep(s.NumVertices(), true);
  keep[0] = false;
  const std::vector<int> samples = EuclideanFarthestPoints(s.V, 50, keep);
  ASSERT_EQ(samples.size(), 50u);
  EXPECT_EQ(std::set<int>(samples.begin(), samples.end()).size(), 50u);
  EXPECT_EQ(std::count(samples.begin(), samples.end(), 0), 0);
  // Asking for more than there are returns each kept vertex once.
  EXPECT_EQ(EuclideanFarthestPoints(s.V, 10 * s.NumVertices(), keep).size(),
            static_cast<size_t>(s.NumVertices() - 1));
}

}  // namespace
}  // namespace symembed
