// The terms and decisions of the flip stage `extrinsic`: their options as nested YAML, each part
// against the function it adapts, and the stage against the functions composed directly.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

#include "core/errors.h"
#include "harness/config.h"
#include "registry/registry.h"
#include "stages/flip/decide_refined.h"
#include "stages/flip/extrinsic.h"
#include "stages/flip/term_curvature.h"
#include "stages/flip/term_descriptor.h"
#include "stages/flip/term_orientation.h"
#include "tests/stages/flip_test_util.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

using testing::HumanoidPoses;

std::unique_ptr<FlipStage> MakeStage(const std::string& yaml) {
  Registry registry;
  RegisterBuiltinStages(registry);
  return registry.CreateAs<FlipStage>("flip", YAML::Load(yaml), "t.yaml", "pipeline.flip");
}

// The ConfigError message of building the stage ("" when it builds).
std::string ErrorOf(const std::string& yaml) {
  try {
    MakeStage(yaml);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

std::string FlowText(const YAML::Node& node) {
  YAML::Emitter out;
  out << YAML::Flow << node;
  return out.c_str();
}

TEST(FlipTermOptions, DefaultsFillEveryNestedMap) {
  const std::string expected =
      "{type: extrinsic, threads: 1, terms: {"
      "curvature: {weight: 0, local_weight: 1, global_weight: 1, chamfer_weight: 0, "
      "profile_bins: 16, histogram_bins: 8, smoothing_rings: 2, smoothing_radius: 0}, "
      "descriptor: {weight: 0, k: 30, eigenpairs: 60, energies: 100, sigma: 7, mu: 0.01, "
      "samples: 300, axes: 1}, "
      "refined_maps: {weight: 1, zoomout: {k_start: 20, k_end: 60, step: 5, samples: 1000, "
      "target_samples: 1000}, sources: 40, targets: 200, distortion_weight: 0.5, "
      "distortion_front_back: false, "
      "disagreement_weight: 1, orientation_weight: 0.025, front_back_vote: 0.5, "
      "long_axis_weight: 1, long_axis_time: 0.03, distortion_decides: 2, smoothing_rings: 2, "
      "smoothing_radius: 0, "
      "normal_weight: 0.1, "
      "deformed_start: true}, "
      "orientation: {weight: 0, zoomout: {k_start: 6, k_end: 60, step: 5, samples: 200, "
      "target_samples: 1000}}}, "
      "decide: {type: argmin}}";
  EXPECT_EQ(FlowText(MakeStage("{type: extrinsic}")->resolved_options()),
            FlowText(YAML::Load(expected)));
  // A partial map keeps the defaults of the keys it does not set.
  const YAML::Node some =
      MakeStage("{type: extrinsic, terms: {orientation: {zoomout: {samples: 300}}}}")
          ->resolved_options();
  EXPECT_EQ(some["terms"]["orientation"]["zoomout"]["samples"].as<int>(), 300);
  EXPECT_EQ(some["terms"]["orientation"]["zoomout"]["k_start"].as<int>(), 6);
  EXPECT_EQ(some["terms"]["orientation"]["weight"].as<double>(), 0.0);
  const YAML::Node decide = MakeStage("{type: extrinsic, decide: {type: refined_front_back}}")
                                ->resolved_options()["decide"];
  EXPECT_EQ(decide["margin"].as<double>(), 0.05);
  EXPECT_EQ(decide["zoomout"]["k_start"].as<int>(), 20);
}

TEST(FlipTermOptions, ErrorsNameFileLineAndPath) {
  struct Case {
    const char* yaml;
    const char* message;
  };
  for (const Case& c : {
           Case{"{type: extrinsic, terms: {descriptor: {kk: 3}}}",
                "t.yaml:1:40: pipeline.flip.terms.descriptor.kk: unknown key 'kk'; known keys: "
                "axes, eigenpairs, energies, k, mu, samples, sigma, weight"},
           Case{"{type: extrinsic, terms: {orientation: {zoomout: {k_begin: 3}}}}",
                "pipeline.flip.terms.orientation.zoomout.k_begin: unknown key 'k_begin'"},
           Case{"{type: extrinsic, terms: {bogus: {weight: 1}}}",
                "pipeline.flip.terms.bogus: unknown key 'bogus'; known keys: curvature, "
                "descriptor, orientation, refined_maps"},
           Case{"{type: extrinsic, decide: {type: best}}",
                "t.yaml:1:34: pipeline.flip.decide.type: invalid value 'best'; expected one of: "
                "argmin, refined_front_back"},
           Case{"{type: extrinsic, decide: {type: argmin, margin: 0.1}}",
                "pipeline.flip.decide.margin: unknown key 'margin'; known keys: type"},
           Case{"{type: extrinsic, terms: {orientation: {weight: -1}}}",
                "pipeline.flip.terms.orientation.weight: must be in [0, inf), got -1"},
           Case{"{type: extrinsic, terms: {orientation: {zoomout: {samples: 50}}}}",
                "pipeline.flip.terms.orientation.zoomout: samples must be >= k_end (60), got 50"},
           Case{"{type: extrinsic, decide: {type: refined_front_back, zoomout: {k_start: 70}}}",
                "pipeline.flip.decide.zoomout: need 1 <= k_start <= k_end"},
           Case{"{type: extrinsic, terms: {curvature: {local_weight: 0, global_weight: 0}}}",
                "pipeline.flip.terms.curvature: at least one of local_weight"},
           Case{"{type: extrinsic, terms: {refined_maps: {weight: 0}}}",
                "pipeline.flip.terms: at least one term must have a weight > 0"},
           Case{"{type: extrinsic, terms: {refined_maps: {weight: 0}, orientation: {weight: 1}}, "
                "decide: {type: refined_front_back}}",
                "pipeline.flip.decide.type: 'refined_front_back' compares the curvature "
                "features, which the curvature and refined_maps terms prepare"},
           Case{"{type: extrinsic, orientation_weight: 0}",
                "pipeline.flip.orientation_weight: unknown key"},
       }) {
    const std::string message = ErrorOf(c.yaml);
    EXPECT_NE(message.find(c.message), std::string::npos) << c.yaml << "\n" << message;
  }
  // A term of weight 0 is still validated.
  EXPECT_NE(ErrorOf("{type: extrinsic, terms: {descriptor: {weight: 0, axes: 3}}}"), "");
  EXPECT_EQ(ErrorOf("{type: extrinsic, terms: {curvature: {weight: 0}}, decide: {type: argmin}}"),
            "");
}

TEST(FlipTermOptions, VariantAndCommandLineOverridesOfNestedPaths) {
  Registry registry;
  RegisterBuiltinStages(registry);
  const std::string text =
      "name: t\n"
      "dataset: {format: synthetic}\n"
      "pipeline:\n"
      "  flip: {type: extrinsic, terms: {curvature: {weight: 1}, descriptor: {weight: 1}, "
      "refined_maps: {weight: 0}, orientation: {weight: 1}}, "
      "decide: {type: refined_front_back, margin: 0.1}}\n"
      "variants:\n"
      "  - {name: no_orientation, set: {pipeline.flip.terms.orientation.weight: 0}}\n"
      "  - {name: argmin, set: {pipeline.flip.decide.type: argmin}}\n"
      "  - {name: paper, set: {pipeline.flip.terms.orientation.weight: 0,\n"
      "                        pipeline.flip.terms.descriptor.weight: 0,\n"
      "                        pipeline.flip.decide.type: argmin}}\n";
  const ExperimentConfig c =
      ParseExperimentConfig(text, "t.yaml", registry, {"pipeline.flip.terms.descriptor.k=20"});
  auto flip_of = [&](const ExperimentConfig& config, const std::string& variant) {
    return YAML::Clone(
        BuildPipeline(config, *config.Find(variant), registry).flip->resolved_options());
  };
  for (const std::string variant : {"base", "no_orientation", "argmin", "paper"}) {
    const YAML::Node flip = flip_of(c, variant);
    EXPECT_EQ(flip["terms"]["descriptor"]["k"].as<int>(), 20) << variant;
    EXPECT_EQ(flip["terms"]["orientation"]["weight"].as<double>(),
              variant == "no_orientation" || variant == "paper" ? 0.0 : 1.0)
        << variant;
    EXPECT_EQ(flip["terms"]["descriptor"]["weight"].as<double>(), variant == "paper" ? 0.0 : 1.0);
    // Changing the decision's type drops the options of the old type.
    const bool argmin = variant == "argmin" || variant == "paper";
    EXPECT_EQ(flip["decide"]["type"].as<std::string>(), argmin ? "argmin" : "refined_front_back");
    EXPECT_EQ(flip["decide"]["margin"].IsDefined(), !argmin) << variant;
    // The resolved config of each variant loads back to the same pipeline.
    const VariantConfig& v = *c.Find(variant);
    const std::string resolved =
        ResolvedConfigYaml(c, v, BuildPipeline(c, v, registry));
    const ExperimentConfig again = ParseExperimentConfig(resolved, "resolved.yaml", registry);
    EXPECT_EQ(FlowText(flip_of(again, "base")), FlowText(flip)) << variant;
    EXPECT_EQ(ResolvedConfigYaml(c, v, BuildPipeline(again, again.variants[0], registry)),
              resolved);
  }
  // A misspelt key set by a variant fails at the variant's line; one set by --set without a line.
  std::string message;
  try {
    ParseExperimentConfig(text + "  - {name: typo, set: {pipeline.flip.terms.orientation.wieght: 0}}\n",
                          "t.yaml", registry);
  } catch (const ConfigError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("t.yaml:11:"), std::string::npos) << message;
  EXPECT_NE(message.find("pipeline.flip.terms.orientation.wieght: unknown key 'wieght'"),
            std::string::npos)
      << message;
  try {
    ParseExperimentConfig(text, "t.yaml", registry, {"pipeline.flip.decide.zoomout.stpe=2"});
  } catch (const ConfigError& e) {
    message = e.what();
  }
  EXPECT_EQ(message.find("--set 'pipeline.flip.decide.zoomout.stpe=2': "
                         "pipeline.flip.decide.zoomout.stpe: unknown key 'stpe'"),
            0u)
      << message;
}

// A humanoid pair prepared by the default stage (features, 60 eigenpairs, signature products),
// the target's embedding turned by candidate `turn`, with what every part reads.
struct TermInputs {
  std::array<ShapeData, 2> shapes;
  PreprocessedGroundTruth gt;
  CandidateMaps maps;
  LaplaceBasis source_basis, target_basis;

  explicit TermInputs(int turn) : shapes(HumanoidPoses(1200)) {
    shapes[1].Y = shapes[1].Y * CandidateRotations()[turn];
    const auto stage = MakeStage(testing::kFormerDefault);
    for (ShapeData& shape : shapes) ComputeNeeds(stage->Needs(), &shape);
    gt = testing::IdentityGroundTruth(shapes[0].surface.NumVertices());
    maps = ComputeCandidateMaps(shapes[0].Y, shapes[1].Y);
    source_basis = LeadingEigenpairs(shapes[0].basis, 60);
    target_basis = LeadingEigenpairs(shapes[1].basis, 60);
  }
  PairInput Pair() const { return PairInput{shapes[0], shapes[1], &gt}; }
  FlipTermContext Context(const PairInput& pair) const {
    return {pair,
            maps,
            source_basis,
            target_basis,
            &ProductOf(shapes[0], CurvatureFeaturesKey({2})),
            &ProductOf(shapes[1], CurvatureFeaturesKey({2})),
            1};
  }
};

TEST(CurvatureTerm, IsThePapersScoreTimesItsWeight) {
  const TermInputs in(0);
  const PairInput pair = in.Pair();
  ExtrinsicFlipOptions options;
  options.chamfer_weight = 0.5;
  const ExtrinsicScores s = ExtrinsicFlipScores(
      pair.source.Y, pair.target.Y, *in.Context(pair).source_features,
      *in.Context(pair).target_features, options, in.maps);
  for (const double weight : {1.0, 2.5}) {
    const CurvatureTerm term(weight, options);
    std::array<double, 4> total{};
    std::ostringstream detail;
    term.Score(in.Context(pair), &total, &detail);
    for (int k = 0; k < 4; ++k) EXPECT_EQ(total[k], weight * s.total[k]) << k;
    std::ostringstream expected;
    expected << "; local " << s.local[0] << " " << s.local[1] << " " << s.local[2] << " "
             << s.local[3] << "; global " << s.global[0] << " " << s.global[1] << " "
             << s.global[2] << " " << s.global[3];
    EXPECT_EQ(detail.str(), expected.str());
  }
  // Its per-shape data: the features, nothing else.
  ShapeData shape = in.shapes[0];
  shape.products.Clear();
  ShapeNeeds needs;
  CurvatureTerm(1.0, options).AddNeeds(60, &needs);
  EXPECT_EQ(needs.basis, 0);
  ComputeNeeds(needs, &shape);
  ASSERT_EQ(shape.products.size(), 1u);
  EXPECT_EQ(ProductOf(shape, CurvatureFeaturesKey({2})), ExtrinsicFeatures(shape.surface, {2}));
  EXPECT_THROW(CurvatureTerm(1.0, ExtrinsicFlipOptions{0, 0, 0}), ConfigError);
}

TEST(DescriptorTerm, AddsWeightedDisagreementWithTheDescriptorMap) {
  const TermInputs in(1);
  const PairInput pair = in.Pair();
  DescriptorMapOptions options;
  const DescriptorAgreement a = DescriptorMapAgreement(
      pair.source.Y, pair.target.Y, in.source_basis, in.target_basis,
      ComputeWksProducts(in.source_basis, options.k, options.eigenpairs),
      ComputeWksProducts(in.target_basis, options.k, options.eigenpairs), pair.source.samples,
      options);
  const DescriptorTerm term(0.5, options);
  EXPECT_EQ(term.BasisSize(), 60);
  const std::array<double, 4> before{0.1, 0.2, 0.3, 0.4};
  std::array<double, 4> total = before;
  std::ostringstream detail;
  term.Score(in.Context(pair), &total, &detail);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(total[k], before[k] + 0.5 * (1.0 - a.agreement[k]) / 2.0) << k;
  }
  EXPECT_EQ(detail.str().substr(0, 12), "; descriptor");
  // Its per-shape data: the products of the stage's basis, for its k and eigenpairs.
  ShapeData shape = in.shapes[0];
  shape.products.Erase(term.ProductsKey().Id());
  ShapeNeeds needs;
  term.AddNeeds(60, &needs);
  ASSERT_EQ(needs.products.size(), 1u);
  EXPECT_EQ(needs.products[0].input, ProductInput::kBasis);
  EXPECT_EQ(needs.products[0].basis_size, 60);
  ComputeNeeds(needs, &shape);
  const WksProducts products = ComputeWksProducts(in.source_basis, options.k, options.eigenpairs);
  EXPECT_EQ(ProductOf(shape, term.ProductsKey()).P, products.P);
  EXPECT_EQ(ProductOf(shape, term.ProductsKey()).Q, products.Q);
  shape.products.Erase(term.ProductsKey().Id());
  EXPECT_THROW(term.Score(in.Context(PairInput{shape, in.shapes[1]}), &total, &detail),
               InvalidInputError);
}

TEST(OrientationTerm, IsTheOrientationTermOnTheTotalsBeforeIt) {
  const TermInputs in(2);
  const PairInput pair = in.Pair();
  const OrientationOptions options;
  const CandidateOrientation measure(pair.source.surface, pair.target.surface, in.source_basis,
                                     in.target_basis, pair.source.samples, pair.target.samples,
                                     options);
  const OrientationTerm term(2.0, options);
  EXPECT_EQ(term.BasisSize(), options.zoomout.k_end);
  // A spread that leaves some candidates unmeasured ("-").
  const std::array<double, 4> before{0.0, 5.0, 0.1, 5.0};
  const OrientationScores expected = AddOrientationTerm(before, 2.0, in.maps, measure);
  std::array<double, 4> total = before;
  std::ostringstream detail;
  term.Score(in.Context(pair), &total, &detail);
  EXPECT_EQ(total, expected.total);
  std::ostringstream message;
  message << "; orientation";
  for (double o : expected.orientation) {
    if (std::isnan(o)) message << " -";
    else message << " " << o;
  }
  EXPECT_EQ(detail.str(), message.str());
  EXPECT_NE(detail.str().find(" -"), std::string::npos) << detail.str();
}

TEST(RefinedDecision, IsTheRefinedFrontBackChoice) {
  const TermInputs in(3);
  const PairInput pair = in.Pair();
  RefinedAgreementOptions options;
  // Margin 0: the partner wins whenever it scores lower, so both branches of the message occur.
  options.margin = 0.0;
  const RefinedDecision decision(options);
  EXPECT_TRUE(decision.ReadsFeatures());
  EXPECT_EQ(decision.BasisSize(), 60);
  const FlipTermContext context = in.Context(pair);
  for (int best = 0; best < 4; ++best) {
    std::array<double, 4> total{1, 1, 1, 1};
    total[best] = 0;
    const RefinedChoice expected =
        RefinedFrontBackChoice(total, pair.source, pair.target, in.source_basis,
                               in.target_basis, *context.source_features,
                               *context.target_features, options);
    std::ostringstream detail;
    EXPECT_EQ(decision.Decide(context, total, &detail), expected.chosen) << best;
    EXPECT_EQ(detail.str().find("; refined "), 0u) << detail.str();
    EXPECT_EQ(detail.str().find("refined maps choose") != std::string::npos,
              expected.chosen != best)
        << detail.str();
  }
}

// The stage as it was before its terms became a list: the functions composed in the old order,
// the message in the old layout.
struct OldStageOptions {
  double orientation_weight = 1.0;
  double descriptor_weight = 1.0;
  bool refined = true;
};

FlipResult OldExtrinsicRun(const PairInput& pair, const OldStageOptions& o) {
  const ExtrinsicFlipOptions curvature;
  const OrientationOptions orientation;
  const DescriptorMapOptions descriptor;
  const RefinedAgreementOptions refined_options;
  const CandidateMaps maps = ComputeCandidateMaps(pair.source.Y, pair.target.Y);
  const Eigen::MatrixXd Fs = ExtrinsicFeatures(pair.source.surface, curvature.smoothing);
  const Eigen::MatrixXd Ft = ExtrinsicFeatures(pair.target.surface, curvature.smoothing);
  ExtrinsicScores s = ExtrinsicFlipScores(pair.source.Y, pair.target.Y, Fs, Ft, curvature, maps);
  const LaplaceBasis bs = LeadingEigenpairs(pair.source.basis, 60);
  const LaplaceBasis bt = LeadingEigenpairs(pair.target.basis, 60);
  DescriptorAgreement d;
  if (o.descriptor_weight > 0.0) {
    d = DescriptorMapAgreement(pair.source.Y, pair.target.Y, bs, bt,
                               ComputeWksProducts(bs, descriptor.k, descriptor.eigenpairs),
                               ComputeWksProducts(bt, descriptor.k, descriptor.eigenpairs),
                               pair.source.samples, descriptor);
    for (int k = 0; k < 4; ++k) s.total[k] += o.descriptor_weight * (1.0 - d.agreement[k]) / 2.0;
  }
  OrientationScores r;
  if (o.orientation_weight > 0.0) {
    const CandidateOrientation measure(pair.source.surface, pair.target.surface, bs, bt,
                                       pair.source.samples, pair.target.samples, orientation);
    r = AddOrientationTerm(s.total, o.orientation_weight, maps, measure);
    s.total = r.total;
  }
  RefinedChoice f;
  if (o.refined) {
    f = RefinedFrontBackChoice(s.total, pair.source, pair.target, bs, bt, Fs, Ft,
                               refined_options);
  }
  FlipResult result = MakeFlipResult(s.total, "extrinsic", o.refined ? f.chosen : -1);
  std::ostringstream detail;
  detail << "; local";
  for (double v : s.local) detail << " " << v;
  detail << "; global";
  for (double v : s.global) detail << " " << v;
  if (o.descriptor_weight > 0.0) {
    detail << "; descriptor";
    for (double v : d.agreement) detail << " " << v;
  }
  if (o.orientation_weight > 0.0) {
    detail << "; orientation";
    for (double v : r.orientation) {
      if (std::isnan(v)) detail << " -";
      else detail << " " << v;
    }
  }
  if (o.refined) {
    detail << "; refined";
    for (int k = 0; k < 4; ++k) {
      if (std::isnan(f.disagreement[k])) detail << " -";
      else detail << " " << f.disagreement[k] << "/" << f.orientation[k];
    }
    if (f.chosen != f.best) {
      detail << "; refined maps choose " << kCandidateNames[f.chosen] << " over "
             << kCandidateNames[f.best] << " (score " << f.score[f.chosen] << " against "
             << f.score[f.best] << ")";
    }
  }
  result.status.message += detail.str();
  return result;
}

TEST(ExtrinsicStage, GivesWhatTheOldFunctionsComposedGive) {
  struct Case {
    std::string yaml;
    OldStageOptions old;
  };
  const Case cases[] = {
      {testing::kFormerDefault, {}},
      {testing::FormerTerms(1, 0), {0.0, 1.0, true}},
      {testing::FormerTerms(0, 1), {1.0, 0.0, true}},
      {testing::FormerTerms(1, 1, "{type: argmin}"), {1.0, 1.0, false}},
      {testing::FormerTerms(0, 0, "{type: argmin}"), {0.0, 0.0, false}},
      {testing::FormerTerms(2, 0.5), {0.5, 2.0, true}},
  };
  for (const int turn : {0, 2}) {
    const TermInputs in(turn);
    const PairInput pair = in.Pair();
    for (const Case& c : cases) {
      const FlipResult expected = OldExtrinsicRun(pair, c.old);
      const FlipResult got = MakeStage(c.yaml)->Run(pair);
      // Bit for bit: the same operations in the same order.
      EXPECT_EQ(got.scores, expected.scores) << c.yaml;
      EXPECT_EQ(got.chosen, expected.chosen) << c.yaml;
      EXPECT_EQ(got.status.residual, expected.status.residual) << c.yaml;
      EXPECT_EQ(got.status.message, expected.status.message) << c.yaml;
    }
  }
}

// smoothing_radius (refined_maps and curvature terms) averages the features over a radius on the
// surface: its features are a product of their own, the rings' keep the key they always had (so
// their cache entries stay valid), and a bad radius is a ConfigError naming the key.
TEST(ExtrinsicStage, ASmoothingRadiusHasFeaturesOfItsOwn) {
  EXPECT_EQ(CurvatureFeaturesKey({2}).options, "smoothing_rings=2");
  EXPECT_NE(CurvatureFeaturesKey({2, 0.06}).Id(), CurvatureFeaturesKey({2}).Id());
  EXPECT_NE(CurvatureFeaturesKey({2, 0.06}).Id(), CurvatureFeaturesKey({2, 0.08}).Id());
  const auto stage =
      MakeStage("{type: extrinsic, terms: {refined_maps: {smoothing_radius: 0.06}}}");
  const ShapeNeeds needs = stage->Needs();
  int features = 0;
  for (const ProductNeed& need : needs.products) {
    if (need.name != "curvature_features") continue;
    ++features;
    EXPECT_EQ(need.id, CurvatureFeaturesKey({2, 0.06}).Id());
  }
  EXPECT_EQ(features, 1);
  ShapeData shape = testing::FlipShape("rest", testing::SymmetricFigure());
  ComputeNeeds(needs, &shape);
  EXPECT_EQ(ProductOf(shape, CurvatureFeaturesKey({2, 0.06})),
            ExtrinsicFeatures(shape.surface, {2, 0.06}));
  EXPECT_NE(ErrorOf("{type: extrinsic, terms: {refined_maps: {smoothing_radius: -1}}}")
                .find("smoothing_radius"),
            std::string::npos);
  EXPECT_NE(ErrorOf("{type: extrinsic, terms: {curvature: {weight: 1, smoothing_radius: -0.5}}}")
                .find("smoothing_radius"),
            std::string::npos);
}

TEST(ExtrinsicStage, TermOfWeightZeroIsNeitherPreparedNorComputed) {
  ShapeData shapes[2] = {testing::FlipShape("rest", testing::SymmetricFigure()),
                         testing::FlipShape("posed", testing::PosedSymmetricFigure(1, 0.5, 0.2))};
  const auto stage = MakeStage(testing::FormerTerms(0, 0, "{type: argmin}"));
  for (ShapeData& shape : shapes) {
    ComputeNeeds(stage->Needs(), &shape);
    // No basis, no signature products: the features only.
    EXPECT_EQ(shape.basis.NumEigenpairs(), 0);
    ASSERT_EQ(shape.products.size(), 1u);
    EXPECT_TRUE(shape.products.Has(CurvatureFeaturesKey({2}).Id()));
  }
  const std::string message = stage->Run(PairInput{shapes[0], shapes[1]}).status.message;
  EXPECT_NE(message.find("; local"), std::string::npos) << message;
  for (const char* part : {"descriptor", "orientation", "refined"}) {
    EXPECT_EQ(message.find(part), std::string::npos) << part << ": " << message;
  }
  // The descriptor term alone prepares its products, the orientation term a basis only.
  const ShapeNeeds descriptor = MakeStage(testing::FormerTerms(1, 0, "{type: argmin}"))->Needs();
  ASSERT_EQ(descriptor.products.size(), 2u);
  EXPECT_EQ(descriptor.products[1].name, "flip_descriptor_products");
  const ShapeNeeds orientation = MakeStage(testing::FormerTerms(0, 1, "{type: argmin}"))->Needs();
  ASSERT_EQ(orientation.products.size(), 1u);
  EXPECT_EQ(orientation.products[0].name, "curvature_features");
  EXPECT_EQ(orientation.basis, 60);
}

}  // namespace
}  // namespace symembed
