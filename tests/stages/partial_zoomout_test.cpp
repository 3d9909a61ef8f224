// ZoomOut between a part and a whole (core/fmap/partial_zoomout.h) on the synthetic
// reproduction of SHREC'16's cuts: a humanoid pose cut by a plane onto another pose of the
// whole body, with the exact ground truth by rest id.
#include "core/fmap/partial_zoomout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "core/errors.h"
#include "core/fmap/zoomout.h"
#include "core/mesh_graph.h"
#include "core/spectral.h"
#include "eval/synthetic/synthetic.h"
#include "registry/registry.h"
#include "registry/stages.h"
#include "tests/stages/partial_test_util.h"

namespace symembed {
namespace {

// A cut pose (the part: the pose that lost the most, 10-40% of its vertices) and another pose of
// the whole, their bases, the true map part -> whole and a map that errs by a few rings around it.
struct CutPair {
  TrackedSurface part, whole;
  LaplaceBasis part_basis, whole_basis;
  std::vector<int> truth, noisy;
};

// Mean edge-graph distance on `on` between map[v] and truth[v] (every 5th v), over sqrt(area).
double MeanError(const Surface& on, const std::vector<int>& map, const std::vector<int>& truth) {
  const MeshGraph graph = BuildMeshGraph(on);
  std::vector<int> sources, rows;
  for (size_t v = 0; v < truth.size(); v += 5) {
    sources.push_back(truth[v]);
    rows.push_back(static_cast<int>(v));
  }
  const Eigen::MatrixXd D = EdgeGraphDistances(graph, sources, 1);
  double sum = 0.0;
  for (size_t i = 0; i < rows.size(); ++i) sum += D(i, map[rows[i]]);
  return sum / rows.size() / std::sqrt(TotalArea(on));
}

const CutPair& Cut() {
  static const CutPair* pair = [] {
    const testing::CutAndWholeClasses classes = testing::CutHumanoidClasses(2000);
    const SynthClass& full = classes.whole;
    const SynthClass& cut = classes.cut;
    auto* out = new CutPair;
    // The cut pose that lost the most.
    double least = 0.95;
    for (size_t p = 0; p < cut.shapes.size(); ++p) {
      const TrackedSurface& c = cut.shapes[p].shape;
      const double share = TotalArea(c.surface) / TotalArea(full.shapes[p].shape.surface);
      if (share >= least) continue;
      least = share;
      out->part = c;
      out->whole = full.shapes[(p + 1) % full.shapes.size()].shape;
    }
    EXPECT_GT(out->part.surface.NumVertices(), 0) << "no shape of the class lost 5% of its area";
    LaplaceBasisOptions b;
    b.k = 60;
    out->part_basis = ComputeLaplaceBasis(out->part.surface, b);
    out->whole_basis = ComputeLaplaceBasis(out->whole.surface, b);
    std::map<int, int> whole_of_rest;
    for (int v = 0; v < out->whole.surface.NumVertices(); ++v) {
      whole_of_rest[out->whole.rest_ids[v]] = v;
    }
    const int n = out->part.surface.NumVertices();
    out->truth.resize(n);
    for (int v = 0; v < n; ++v) out->truth[v] = whole_of_rest.at(out->part.rest_ids[v]);
    // Each image moved by a random walk of up to three edges on the whole.
    const MeshGraph graph = BuildMeshGraph(out->whole.surface);
    std::mt19937 rng(7);
    out->noisy = out->truth;
    for (int& j : out->noisy) {
      for (int step = 0; step < 3; ++step) {
        const int degree = graph.offsets[j + 1] - graph.offsets[j];
        j = graph.neighbors[graph.offsets[j] + rng() % degree];
      }
    }
    return out;
  }();
  return *pair;
}

ZoomOutOptions Schedule() {
  ZoomOutOptions o;
  o.k_start = 10;
  o.k_end = 60;
  o.step = 5;
  return o;
}

TEST(PartBasisSize, CountsThePartsEigenvaluesUpToTheWholesWithAFloor) {
  Eigen::VectorXd whole(10), part(10);
  for (int i = 0; i < 10; ++i) whole(i) = i, part(i) = 2.0 * i;
  // The whole's 10th eigenvalue is 9: the part has 0, 2, 4, 6, 8 up to it.
  EXPECT_EQ(PartBasisSize(whole, part, 10), 5);
  // Never fewer than kMinPartSize functions (or k_w when smaller), never more than k_w.
  EXPECT_EQ(PartBasisSize(whole, part, 3), 3);
  EXPECT_EQ(PartBasisSize(whole, part, 5), kMinPartSize);
  EXPECT_EQ(PartBasisSize(whole, whole, 7), 7);
  EXPECT_THROW(PartBasisSize(whole, part, 11), InvalidInputError);
}

TEST(PartialZoomOut, RefinesAPartsMapWhereEqualSizesPullItOverTheWhole) {
  const CutPair& c = Cut();
  const double before = MeanError(c.whole.surface, c.noisy, c.truth);
  const ZoomOutResult partial =
      PartialZoomOut(c.part_basis, 1.0, c.whole_basis, 1.0, c.noisy, {}, Schedule());
  const double after = MeanError(c.whole.surface, partial.map, c.truth);
  EXPECT_LT(after, 0.6 * before) << partial.status.message;
  // ZoomOut with the same sizes on both shapes ends farther from the truth.
  const ZoomOutResult equal = ZoomOut(c.part_basis, c.whole_basis, c.noisy, {}, Schedule());
  EXPECT_GT(MeanError(c.whole.surface, equal.map, c.truth), 1.2 * after);
}

TEST(PartialZoomOut, ComparesTheShapesInTheirCommonUnit) {
  const CutPair& c = Cut();
  // The part's basis as if its surface were scaled by 3 (eigenvalues / 9, mass * 9, functions
  // / 3), with the unit that brings it back: the same map.
  LaplaceBasis scaled = c.part_basis;
  scaled.evals /= 9.0;
  scaled.mass *= 9.0;
  scaled.evecs /= 3.0;
  const ZoomOutResult reference =
      PartialZoomOut(c.part_basis, 1.0, c.whole_basis, 1.0, c.noisy, {}, Schedule());
  const ZoomOutResult same =
      PartialZoomOut(scaled, 1.0 / 3.0, c.whole_basis, 1.0, c.noisy, {}, Schedule());
  int equal = 0;
  for (size_t v = 0; v < reference.map.size(); ++v) equal += reference.map[v] == same.map[v];
  EXPECT_GE(equal, 0.99 * reference.map.size());
  // Read in the wrong unit, the scaled part looks 9 times the whole's area and its rows are
  // compared at another scale: the map ends worse.
  const ZoomOutResult wrong =
      PartialZoomOut(scaled, 1.0, c.whole_basis, 1.0, c.noisy, {}, Schedule());
  EXPECT_GT(MeanError(c.whole.surface, wrong.map, c.truth),
            1.5 * MeanError(c.whole.surface, reference.map, c.truth));
}

TEST(PartialZoomOut, RefinesOnSamplesAndLeavesAMapFromTheWhole) {
  const CutPair& c = Cut();
  std::vector<int> samples;
  for (int v = 0; v < c.part.surface.NumVertices(); v += 4) samples.push_back(v);
  std::vector<int> target_samples;
  for (int v = 0; v < c.whole.surface.NumVertices(); v += 2) target_samples.push_back(v);
  const ZoomOutResult r = PartialZoomOut(c.part_basis, 1.0, c.whole_basis, 1.0, c.noisy, samples,
                                         Schedule(), target_samples);
  EXPECT_LT(MeanError(c.whole.surface, r.map, c.truth),
            0.75 * MeanError(c.whole.surface, c.noisy, c.truth))
      << r.status.message;
  EXPECT_NE(r.status.message.find("on " + std::to_string(samples.size()) + " samples"),
            std::string::npos);
  // From the whole, the part's vertices the whole lacks would pull the fit: left unchanged.
  std::vector<int> from_whole(c.whole.surface.NumVertices(), 0);
  const ZoomOutResult w =
      PartialZoomOut(c.whole_basis, 1.0, c.part_basis, 1.0, from_whole, {}, Schedule());
  EXPECT_EQ(w.map, from_whole);
  EXPECT_NE(w.status.message.find("not run: the source is the whole"), std::string::npos);
}

TEST(PartialZoomOut, AnAnchorHoldsTheMapNearItsStart) {
  const CutPair& c = Cut();
  const Eigen::MatrixX3d& X = c.whole.surface.V;
  const ZoomOutResult free =
      PartialZoomOut(c.part_basis, 1.0, c.whole_basis, 1.0, c.noisy, {}, Schedule());
  // Weight 0 is no anchor.
  EXPECT_EQ(PartialZoomOut(c.part_basis, 1.0, c.whole_basis, 1.0, c.noisy, {}, Schedule(), {},
                           PartialAnchor{&X, 0.0})
                .map,
            free.map);
  // A moderate anchor still smooths the start; an overwhelming one keeps it.
  const ZoomOutResult held = PartialZoomOut(c.part_basis, 1.0, c.whole_basis, 1.0, c.noisy, {},
                                            Schedule(), {}, PartialAnchor{&X, 1.0});
  EXPECT_LT(MeanError(c.whole.surface, held.map, c.truth),
            0.75 * MeanError(c.whole.surface, c.noisy, c.truth))
      << held.status.message;
  EXPECT_NE(held.status.message.find("anchored to the initial map"), std::string::npos);
  const ZoomOutResult kept = PartialZoomOut(c.part_basis, 1.0, c.whole_basis, 1.0, c.noisy, {},
                                            Schedule(), {}, PartialAnchor{&X, 1e12});
  EXPECT_EQ(kept.map, c.noisy);
  EXPECT_THROW(PartialZoomOut(c.part_basis, 1.0, c.whole_basis, 1.0, c.noisy, {}, Schedule(), {},
                              PartialAnchor{nullptr, 1.0}),
               InvalidInputError);
}

TEST(PartialZoomOut, RejectsBadInput) {
  const CutPair& c = Cut();
  ZoomOutOptions o = Schedule();
  o.k_end = 61;
  EXPECT_THROW(PartialZoomOut(c.part_basis, 1.0, c.whole_basis, 1.0, c.noisy, {}, o),
               InvalidInputError);
  o = Schedule();
  o.k_start = 70;
  EXPECT_THROW(PartialZoomOut(c.part_basis, 1.0, c.whole_basis, 1.0, c.noisy, {}, o), ConfigError);
  EXPECT_THROW(PartialZoomOut(c.part_basis, 0.0, c.whole_basis, 1.0, c.noisy, {}, Schedule()),
               InvalidInputError);
  std::vector<int> bad = c.noisy;
  bad[0] = c.whole.surface.NumVertices();
  EXPECT_THROW(PartialZoomOut(c.part_basis, 1.0, c.whole_basis, 1.0, bad, {}, Schedule()),
               InvalidInputError);
}

// The refine stages given a part and a whole: the spectral ones refine it as a part's, the
// functional-map ICP leaves it.
TEST(PartialZoomOut, RefineStagesRefineAPartAsAPart) {
  const CutPair& c = Cut();
  Registry registry;
  RegisterBuiltinStages(registry);
  ShapeData part, whole;
  part.surface = c.part.surface;
  whole.surface = c.whole.surface;
  part.basis = c.part_basis;
  whole.basis = c.whole_basis;
  const PairInput pair{part, whole};
  for (const std::string yaml : {"{type: zoomout, k_start: 10, k_end: 60, sample_count: 0}",
                                 "{type: discrete, k_start: 10, k_end: 60, sample_count: 0}"}) {
    const auto stage =
        registry.CreateAs<RefineStage>("refine", YAML::Load(yaml), "test.yaml", "pipeline.refine");
    const MatchResult r = stage->Run(RefineInput{pair, c.noisy, nullptr, nullptr, true});
    EXPECT_NE(r.status.message.find("partial zoomout"), std::string::npos) << yaml;
    // The discrete stage anchors the part to its start as it anchors a whole to the embedding.
    EXPECT_EQ(r.status.message.find("anchored") != std::string::npos,
              std::string(yaml).find("discrete") != std::string::npos)
        << r.status.message;
    EXPECT_LT(MeanError(c.whole.surface, r.map, c.truth),
              0.6 * MeanError(c.whole.surface, c.noisy, c.truth))
        << yaml;
  }
  const auto icp = registry.CreateAs<RefineStage>("refine", YAML::Load("{type: icp, k: 30}"),
                                                  "test.yaml", "pipeline.refine");
  const MatchResult r = icp->Run(RefineInput{pair, c.noisy, nullptr, nullptr, true});
  EXPECT_EQ(r.map, c.noisy);
  EXPECT_NE(r.status.message.find("not run"), std::string::npos);
}

}  // namespace
}  // namespace symembed
