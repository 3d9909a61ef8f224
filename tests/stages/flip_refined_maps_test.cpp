// The refined-maps term of the flip stage (stages/flip/term_refined_maps.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <any>
#include <cmath>
#include <memory>
#include <sstream>
#include <utility>
#include <vector>

#include "core/canonical_frame.h"
#include "core/errors.h"
#include "core/fmap/functional_map.h"
#include "core/knn.h"
#include "core/mesh_graph.h"
#include "core/primitives.h"
#include "core/spectral.h"
#include "eval/synthetic/synthetic.h"
#include "registry/registry.h"
#include "stages/flip/extrinsic.h"
#include "stages/flip/flip_common.h"
#include "stages/flip/refined_agreement.h"
#include "stages/flip/term_refined_maps.h"
#include "stages/geodesics/dijkstra.h"
#include "tests/stages/chain_test_util.h"
#include "tests/stages/flip_test_util.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

using testing::FlipShape;
using testing::OracleChoice;
using testing::RestGroundTruth;
using testing::TwoPoses;

// Options for shapes with 300 samples.
RefinedMapsTermOptions SmallOptions() {
  RefinedMapsTermOptions options;
  options.zoomout.samples = 300;
  options.zoomout.target_samples = 300;
  options.sources = 20;
  options.targets = 150;
  return options;
}

// Computes into `shape` the products `term` needs and returns its basis of the term's size.
LaplaceBasis PrepareForTerm(const RefinedMapsTerm& term, ShapeData* shape) {
  ShapeNeeds needs;
  term.AddNeeds(term.BasisSize(), &needs);
  ComputeNeeds(needs, shape);
  LaplaceBasisOptions basis_options;
  basis_options.k = term.BasisSize();
  return ComputeLaplaceBasis(shape->surface, basis_options);
}

// `term`'s scores of the four candidate rotations between the two shapes' embeddings; its
// message through *detail.
std::array<double, 4> ScoreTerm(const RefinedMapsTerm& term, const ShapeData& source,
                                const ShapeData& target, const LaplaceBasis& source_basis,
                                const LaplaceBasis& target_basis, std::string* detail) {
  const CandidateMaps maps = ComputeCandidateMaps(source.Y, target.Y);
  const PairInput pair{source, target};
  const FlipTermContext context{pair, maps, source_basis, target_basis, nullptr, nullptr, 1};
  std::array<double, 4> total{};
  std::ostringstream out;
  term.Score(context, &total, &out);
  *detail = out.str();
  return total;
}

TEST(RefinedMapsFlip, DistortionMatchesABruteForceSum) {
  SynthOptions synth;
  synth.poses = 1;
  synth.vertices = 400;
  const Surface surface = GenerateClass(FigureKind::kHumanoid, synth).shapes[0].shape.surface;
  const int n = surface.NumVertices();
  const MeshGraph graph = BuildMeshGraph(surface);
  std::vector<int> samples = EuclideanFarthestPoints(surface.V, 30);
  const std::vector<int> sources(samples.begin(), samples.begin() + 5);
  const Eigen::MatrixXd Ds = DijkstraDistances(surface, sources);
  std::vector<int> identity(n);
  for (int i = 0; i < n; ++i) identity[i] = i;
  EXPECT_NEAR(GeodesicDistortion(Ds, graph, samples, 30, identity), 0.0, 1e-12);

  // A map that shifts every vertex: the sum over all pairs, with every distance from Dijkstra.
  std::vector<int> shifted(n);
  for (int i = 0; i < n; ++i) shifted[i] = (i * 7 + 3) % n;
  const Eigen::MatrixXd all = DijkstraDistances(surface, [&] {
    std::vector<int> v(n);
    for (int i = 0; i < n; ++i) v[i] = i;
    return v;
  }());
  double difference = 0.0, length = 0.0;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 30; ++j) {
      const double ds = all(samples[i], samples[j]);
      difference += std::abs(ds - all(shifted[samples[i]], shifted[samples[j]]));
      length += ds;
    }
  }
  EXPECT_NEAR(GeodesicDistortion(Ds, graph, samples, 30, shifted), difference / length, 1e-9);
  EXPECT_GT(difference / length, 0.1);

  std::vector<int> bad = identity;
  bad[samples[3]] = n;
  EXPECT_THROW(GeodesicDistortion(Ds, graph, samples, 30, bad), InvalidInputError);
  EXPECT_THROW(GeodesicDistortion(Ds, graph, samples, 31, identity), InvalidInputError);
}

// For each turn R_j of the target's canonical embedding, the term alone gives the oracle's
// candidate the lowest total on two poses of a figure whose bones were scaled differently in each
// pose (the generator's non-isometric option): the pair is not an isometry, yet the right
// rotation's refined map distorts the geodesics and the curvature least. With each candidate's
// distortion and with the lower one of front-back partners.
void ExpectTermFindsTheOracle(FigureKind kind, bool distortion_front_back) {
  auto [source, posed] = TwoPoses(kind, 1500, 0.3);
  RefinedMapsTermOptions options = SmallOptions();
  options.distortion_front_back = distortion_front_back;
  const RefinedMapsTerm term(1.0, options);
  const LaplaceBasis source_basis = PrepareForTerm(term, &source);
  const LaplaceBasis target_basis = PrepareForTerm(term, &posed);
  const auto rotations = CandidateRotations();
  for (int j = 0; j < 4; ++j) {
    ShapeData target = posed;
    target.Y = posed.Y * rotations[j];
    const int right = OracleChoice(source, target);
    std::string detail;
    const auto total = ScoreTerm(term, source, target, source_basis, target_basis, &detail);
    EXPECT_EQ(CandidateOrder(total)[0], right) << "turn " << j << detail;
    EXPECT_NE(detail.find("; refined_maps"), std::string::npos);
  }
}

TEST(RefinedMapsFlip, RightCandidateOfANonIsometricHumanoidScoresLowest) {
  ExpectTermFindsTheOracle(FigureKind::kHumanoid, true);
  ExpectTermFindsTheOracle(FigureKind::kHumanoid, false);
}

TEST(RefinedMapsFlip, RightCandidateOfANonIsometricQuadrupedScoresLowest) {
  ExpectTermFindsTheOracle(FigureKind::kQuadruped, true);
  ExpectTermFindsTheOracle(FigureKind::kQuadruped, false);
}

// Per candidate, the distortion, disagreement and orientation printed after "; refined_maps".
std::array<std::array<double, 3>, 4> RefinedMapsMeasures(const std::string& detail) {
  std::istringstream in(detail.substr(detail.find("; refined_maps ") + 15));
  std::array<std::array<double, 3>, 4> measures{};
  for (auto& m : measures) {
    char slash = 0;
    in >> m[0] >> slash >> m[1] >> slash >> m[2];
  }
  return measures;
}

// With distortion_front_back false a candidate and its front-back partner add the lower of their
// two distortions: on a humanoid pair (whose front-back partner is the right map reflected front
// to back) the totals differ from the per-candidate ones by exactly that, the measures themselves
// are unchanged, and the partners' totals then differ by their disagreement and orientation
// alone.
TEST(RefinedMapsFlip, PartnersShareTheirLowerDistortionAndCurvatureDecidesBetweenThem) {
  auto [source, target] = TwoPoses(FigureKind::kHumanoid, 1500);
  RefinedMapsTermOptions alone = SmallOptions();
  alone.distortion_front_back = true;
  alone.front_back_vote = 0.0;
  RefinedMapsTermOptions shared = alone;
  shared.distortion_front_back = false;
  const RefinedMapsTerm per_candidate(1.0, alone), per_axis(1.0, shared);
  const LaplaceBasis source_basis = PrepareForTerm(per_axis, &source);
  const LaplaceBasis target_basis = PrepareForTerm(per_axis, &target);
  std::string detail_alone, detail_shared;
  const auto total_alone =
      ScoreTerm(per_candidate, source, target, source_basis, target_basis, &detail_alone);
  const auto total_shared =
      ScoreTerm(per_axis, source, target, source_basis, target_basis, &detail_shared);
  EXPECT_EQ(detail_alone, detail_shared);
  const auto m = RefinedMapsMeasures(detail_alone);
  // The printed values are rounded to 6 significant digits.
  const double tolerance = 1e-5;
  for (int k = 0; k < 4; ++k) {
    const int partner = FrontBackPartner(k);
    EXPECT_GT(m[k][0], 0.0) << k;
    EXPECT_NEAR(total_shared[k] - total_alone[k],
                alone.distortion_weight * (std::min(m[k][0], m[partner][0]) - m[k][0]), tolerance)
        << k << detail_alone;
    const double between_partners = total_shared[k] - total_shared[partner];
    const double expected = alone.disagreement_weight * (m[k][1] - m[partner][1]) +
                            alone.orientation_weight * (m[partner][2] - m[k][2]);
    EXPECT_NEAR(between_partners, expected, tolerance) << k << detail_alone;
  }
  // The right candidate still scores lowest.
  EXPECT_EQ(CandidateOrder(total_shared)[0], OracleChoice(source, target)) << detail_shared;
}

// The long-axis measure scores a candidate and its front-back partner (the same direction of the
// long axis y) alike, by the better of their two maps, so it changes which way the long axis
// points and never which side of the short one is the front; on a quadruped pair, whose ends differ
// at the scale of the body, it separates the two directions, and the totals without it are those of
// the other three measures.
TEST(RefinedMapsFlip, LongAxisMeasureScoresFrontBackPartnersAlike) {
  auto [source, target] = TwoPoses(FigureKind::kQuadruped, 1500);
  // The measure alone: no pair ruled out by the distortions.
  RefinedMapsTermOptions off = SmallOptions();
  off.long_axis_weight = 0.0;
  off.distortion_decides = 0.0;
  RefinedMapsTermOptions on = off;
  on.long_axis_weight = 2.0;
  const RefinedMapsTerm without(1.0, off), with(1.0, on);
  const LaplaceBasis source_basis = PrepareForTerm(with, &source);
  const LaplaceBasis target_basis = PrepareForTerm(with, &target);
  std::string detail_without, detail_with;
  const auto total_without =
      ScoreTerm(without, source, target, source_basis, target_basis, &detail_without);
  const auto total_with = ScoreTerm(with, source, target, source_basis, target_basis, &detail_with);
  EXPECT_EQ(detail_without.find("long_axis"), std::string::npos);
  ASSERT_NE(detail_with.find("; long_axis "), std::string::npos) << detail_with;
  std::array<double, 4> added{};
  for (int k = 0; k < 4; ++k) added[k] = total_with[k] - total_without[k];
  std::istringstream values_in(detail_with.substr(detail_with.find("; long_axis ") + 12));
  std::array<double, 4> diffused{};
  for (double& c : diffused) values_in >> c;
  for (int k = 0; k < 4; ++k) {
    EXPECT_GT(added[k], 0.0) << k;
    EXPECT_NEAR(added[k], added[FrontBackPartner(k)], 1e-12) << k;
    // The better of the two maps (printed to 6 digits).
    EXPECT_NEAR(added[k],
                on.long_axis_weight * std::min(diffused[k], diffused[FrontBackPartner(k)]), 1e-5)
        << k << detail_with;
  }
  // The right direction of the long axis (the oracle's candidate and its partner) adds least.
  const int right = OracleChoice(source, target);
  const int other = right ^ 1;
  EXPECT_LT(added[right], added[other]) << detail_with;
  // Only the long-axis measure differs: the other three are those of the run without it.
  std::string values = detail_with;
  const size_t section = values.find("; long_axis");
  values.erase(section, values.find(';', section + 1) - section);
  EXPECT_EQ(values, detail_without);
}

// The failure mode of the long-axis measure: curvature at the body's ends, which an uneven
// meshing or a body of other proportions can turn, read backwards (here the target's diffused
// features taken from its vertices turned head to tail, about the frame's z axis), against maps
// whose distortions tell the direction apart by a wide factor. Without the ratio the measure
// turns the pair head to tail; with it the distances decide, the better pair's totals are
// untouched and the other pair's lie above them.
TEST(RefinedMapsFlip, DistortionsAFactorApartDecideTheLongAxis) {
  auto [source, target] = TwoPoses(FigureKind::kQuadruped, 1500);
  RefinedMapsTermOptions measure_decides = SmallOptions();
  measure_decides.distortion_decides = 0.0;
  const RefinedMapsTermOptions ratio_decides = SmallOptions();
  const RefinedMapsTerm without(1.0, measure_decides), with(1.0, ratio_decides);
  const LaplaceBasis source_basis = PrepareForTerm(with, &source);
  const LaplaceBasis target_basis = PrepareForTerm(with, &target);
  const int right = OracleChoice(source, target);
  std::string detail;
  const auto before = ScoreTerm(with, source, target, source_basis, target_basis, &detail);
  EXPECT_EQ(std::min_element(before.begin(), before.end()) - before.begin(), right) << detail;

  const auto key = DiffusedFeaturesKey(ratio_decides.smoothing, ratio_decides.long_axis_time);
  const Eigen::MatrixXd& features = ProductOf(target, key);
  Eigen::MatrixXd turned_points = target.Y;
  turned_points.leftCols<2>() *= -1.0;
  const std::vector<int> turned = KnnIndex(target.Y).Nearest(turned_points);
  Eigen::MatrixXd turned_features(features.rows(), features.cols());
  for (int v = 0; v < features.rows(); ++v) turned_features.row(v) = features.row(turned[v]);
  target.products.PutAny(key.Id(), std::make_shared<const std::any>(turned_features));

  std::string detail_without, detail_with;
  const auto total_without =
      ScoreTerm(without, source, target, source_basis, target_basis, &detail_without);
  const auto total_with = ScoreTerm(with, source, target, source_basis, target_basis, &detail_with);
  const int chosen_without =
      std::min_element(total_without.begin(), total_without.end()) - total_without.begin();
  const int chosen_with =
      std::min_element(total_with.begin(), total_with.end()) - total_with.begin();
  // The turned measure takes the other direction of the long axis; the ratio keeps the right one.
  EXPECT_NE(chosen_without, right) << detail_without;
  EXPECT_NE(chosen_without, FrontBackPartner(right)) << detail_without;
  EXPECT_EQ(chosen_with, right) << detail_with;
  EXPECT_EQ(detail_without.find("long axis by distortion"), std::string::npos);
  EXPECT_NE(detail_with.find("; long axis by distortion"), std::string::npos) << detail_with;
  for (const int k : {right, FrontBackPartner(right)}) {
    EXPECT_EQ(total_with[k], total_without[k]) << k;
    EXPECT_GT(total_with[k ^ 1], std::max(total_with[right], total_with[FrontBackPartner(right)]));
  }
}

// Mean distance on the surface (in units of sqrt(area)) between each sample and its image, for a
// map between two copies of one surface (identity ground truth).
double MeanSampleError(const Surface& surface, const std::vector<int>& samples,
                       const std::vector<int>& map) {
  double sum = 0.0;
  for (const int s : samples) sum += (surface.V.row(s) - surface.V.row(map[s])).norm();
  return sum / samples.size() / std::sqrt(TotalArea(surface));
}

// The failure mode of the term's initial maps: where the target's embedding is bent away from the
// source's (here one body whose embedding is sheared along x by a smooth function of the height,
// as LS-MDS keeps part of a pose), the right candidate's nearest neighbours mix parts that the
// bend brought together, ZoomOut from them settles on a poor map, and the term then judges the
// right rotation by it. With deformed_start the source is bent onto the target first, as the
// matching stage does, and the right candidate refines to a map much closer to the identity.
TEST(RefinedMapsFlip, DeformedStartFollowsAnEmbeddingBentAwayFromTheSource) {
  SynthOptions synth;
  synth.poses = 1;
  synth.vertices = 1500;
  const SynthClass figures = GenerateClass(FigureKind::kHumanoid, synth);
  const ShapeData source = FlipShape("straight", figures.shapes[0].shape.surface);
  ShapeData target = source;
  target.name = "bent";
  const Eigen::VectorXd y = source.Y.col(1);
  const double height = y.maxCoeff() - y.minCoeff();
  const double radius = std::sqrt(source.Y.rowwise().squaredNorm().mean());
  for (int i = 0; i < target.Y.rows(); ++i) {
    target.Y(i, 0) += 0.6 * radius * std::sin(2.0 * M_PI * (y(i) - y.minCoeff()) / height);
  }
  RefinedMapsTermOptions options = SmallOptions();
  LaplaceBasisOptions basis_options;
  basis_options.k = options.zoomout.k_end;
  const LaplaceBasis basis = ComputeLaplaceBasis(source.surface, basis_options);
  DeformOptions deform;
  deform.samples = 300;
  const RefinedCandidates nearest(source, target, basis, basis, options.zoomout,
                                  options.normal_weight, "test");
  const RefinedCandidates bent(source, target, basis, basis, options.zoomout, options.normal_weight,
                               "test", &deform);
  const double from_nearest =
      MeanSampleError(source.surface, nearest.samples(), nearest.Refine(0).map);
  const double from_bent = MeanSampleError(source.surface, bent.samples(), bent.Refine(0).map);
  EXPECT_LT(from_bent, 0.5 * from_nearest) << from_bent << " " << from_nearest;
  EXPECT_LT(from_bent, 0.02) << from_bent;
  // The term reads the option and asks for the deformation's basis.
  options.deformed_start = true;
  options.zoomout.k_start = 6;
  options.zoomout.k_end = 10;
  EXPECT_EQ(RefinedMapsTerm(1.0, options).BasisSize(), deform.k_end);
}

// The failure mode of the mean disagreement on uneven meshings: humanoid poses decimated each on
// its own with edges kept short along a random direction (the synthetic benchmark's
// `anisotropic` variant), where per-vertex curvature has outliers that the two meshings do not
// share. The synthetic humanoid's front and back differ in details (face, chest, toes), so the
// mean disagreements of a map and of its front-back reflection differ by little, and a few
// outliers turn 5 of the 28 pairs front to back; the vote of the samples counts the details, not
// the outliers, and turns one.
TEST(RefinedMapsFlip, TheSamplesVoteForTheFrontWhereUnevenMeshingsTurnTheMean) {
  SynthOptions synth;
  synth.poses = 8;
  synth.remesh = 2500;
  synth.remesh_anisotropy = 4.0;
  const SynthClass figures = GenerateClass(FigureKind::kHumanoid, synth);
  RefinedMapsTermOptions mean_options;
  mean_options.front_back_vote = 0.0;
  const RefinedMapsTermOptions vote_options;
  const RefinedMapsTerm by_mean(1.0, mean_options), by_vote(1.0, vote_options);
  std::vector<ShapeData> shapes;
  std::vector<LaplaceBasis> bases;
  for (const SynthShape& s : figures.shapes) {
    shapes.push_back(FlipShape(s.name, s.shape.surface));
    shapes.back().samples =
        EuclideanFarthestPoints(s.shape.surface.V, vote_options.zoomout.samples);
    bases.push_back(PrepareForTerm(by_vote, &shapes.back()));
  }
  int pairs = 0, mean_turned = 0, vote_turned = 0;
  std::ostringstream log;
  for (size_t a = 0; a < shapes.size(); ++a) {
    for (size_t b = a + 1; b < shapes.size(); ++b) {
      const int right =
          OracleChoice(shapes[a], shapes[b],
                       RestGroundTruth(figures.shapes[a].shape, figures.shapes[b].shape,
                                       figures.rest.surface.NumVertices()));
      const int partner = FrontBackPartner(right);
      std::string mean_detail, vote_detail;
      const auto mean_total =
          ScoreTerm(by_mean, shapes[a], shapes[b], bases[a], bases[b], &mean_detail);
      const auto vote_total =
          ScoreTerm(by_vote, shapes[a], shapes[b], bases[a], bases[b], &vote_detail);
      ++pairs;
      mean_turned += mean_total[partner] < mean_total[right];
      vote_turned += vote_total[partner] < vote_total[right];
      // The vote moves only the front-back decision: the rest of the measures are the mean's.
      EXPECT_EQ(vote_detail.substr(0, vote_detail.find("; front_back_vote")), mean_detail);
      log << a << "-" << b << " right " << right << vote_detail << "\n";
    }
  }
  EXPECT_EQ(pairs, 28);
  EXPECT_GE(mean_turned, 4) << log.str();
  EXPECT_LE(vote_turned, 1) << log.str();
}

// The vote of two maps: each vertex for the map that puts it on more alike features, with its
// area; one vertex far off under one map outweighs the others in the mean disagreement, not in
// the vote.
TEST(RefinedMapsFlip, AVoteCountsAreasNotHowFarOff) {
  // Source features: shape index, curvedness, area fraction; target vertices 0..3 are copies,
  // 4..7 the same features slightly off, 8 far off.
  Eigen::MatrixXd Fs(4, 3), Ft(9, 3);
  Fs << 0.1, 1.0, 0.1,  //
      0.5, 2.0, 0.2,    //
      -0.3, 1.5, 0.3,   //
      0.8, 0.5, 0.4;
  Ft.topRows(4) = Fs;
  Ft.block(4, 0, 4, 3) = Fs;
  Ft.block(4, 0, 4, 1).array() += 0.05;
  Ft.row(8) << -0.9, 4.0, 0.1;
  const std::array<double, 2> scales = FeatureScales(Fs, Ft);
  const std::vector<int> vertices = {0, 1, 2, 3};
  // Map a: exact at vertices 0..2, far off at vertex 3; map b: slightly off everywhere.
  const std::vector<int> a = {0, 1, 2, 8}, b = {4, 5, 6, 7};
  EXPECT_GT(FeatureDisagreement(Fs, Ft, a, scales, vertices),
            FeatureDisagreement(Fs, Ft, b, scales, vertices));
  // a wins at vertices 0..2 (area 0.6 of 1.0), b at vertex 3 (0.4).
  EXPECT_NEAR(FeatureVote(Fs, Ft, a, b, scales, vertices), 0.2, 1e-12);
  EXPECT_EQ(FeatureVote(Fs, Ft, b, a, scales, vertices),
            -FeatureVote(Fs, Ft, a, b, scales, vertices));
  // Ties vote for neither.
  EXPECT_EQ(FeatureVote(Fs, Ft, a, a, scales, vertices), 0.0);
  EXPECT_THROW(FeatureVote(Fs, Ft, a, b, scales, {}), InvalidInputError);
}

TEST(RefinedMapsFlip, BadOptionsAndInputsFailClearly) {
  RefinedMapsTermOptions options = SmallOptions();
  options.targets = 10;  // fewer than the sources
  EXPECT_THROW(RefinedMapsTerm(1.0, options), ConfigError);
  options = SmallOptions();
  options.targets = 400;  // more than the samples ZoomOut maps
  EXPECT_THROW(RefinedMapsTerm(1.0, options), ConfigError);
  options = SmallOptions();
  options.orientation_weight = -1.0;
  EXPECT_THROW(RefinedMapsTerm(1.0, options), ConfigError);
  options = SmallOptions();
  options.long_axis_weight = -1.0;
  EXPECT_THROW(RefinedMapsTerm(1.0, options), ConfigError);
  options = SmallOptions();
  options.long_axis_time = 0.0;
  try {
    RefinedMapsTerm(1.0, options);
    ADD_FAILURE() << "a diffusion time of 0 was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("long_axis_time must be in (0, inf), got 0"),
              std::string::npos)
        << e.what();
  }
  // A shape without samples.
  ShapeData shape = FlipShape("rest", testing::SymmetricFigure());
  shape.samples.clear();
  ShapeNeeds needs;
  RefinedMapsTerm(1.0, SmallOptions()).AddNeeds(60, &needs);
  EXPECT_THROW(ComputeNeeds(needs, &shape), InvalidInputError);
}

}  // namespace
}  // namespace symembed
