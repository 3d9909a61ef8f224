#include "harness/config.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "core/errors.h"
#include "registry/options.h"
#include "registry/registry.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

// Test doubles for every kind: each reads a few typed options so strictness can be exercised.
template <typename Base>
class Fake : public Base {};

class FakeDataset : public Dataset {
 public:
  DatasetIndex Load() const override { return {}; }
  ShapeGroundTruth GroundTruth(const DatasetShape&, int) const override { return {}; }
};

class FakeSampling : public SamplingStage {
 public:
  SamplingResult Run(const Surface&) const override { return {}; }
};

template <typename T>
Registry::Factory Factory() {
  return [](OptionReader&) -> std::unique_ptr<Stage> { return std::make_unique<T>(); };
}

struct FakePreprocess : PreprocessStage {
  PreprocessResult Run(const Surface&) const override { return {}; }
};
struct FakeGeodesics : GeodesicsStage {
  std::unique_ptr<GeodesicSolver> Prepare(const Surface&) const override { return nullptr; }
};
struct FakeEmbedding : EmbeddingStage {
  EmbeddingResult Run(const EmbeddingInput&) const override { return {}; }
};
struct FakeSymmetry : SymmetryStage {
  SymmetryResult Run(const SymmetryInput&) const override { return {}; }
};
struct FakeSymmetrize : SymmetrizeStage {
  SymmetrizeResult Run(const SymmetryInput&, const SymmetryResult&) const override { return {}; }
};
struct FakeFlip : FlipStage {
  FlipResult Run(const PairInput&) const override { return {}; }
};
struct FakeMatching : MatchingStage {
  MatchResult Run(const EmbeddedPoints&, const EmbeddedPoints&) const override { return {}; }
};
struct FakeRefine : RefineStage {
  MatchResult Run(const RefineInput&) const override { return {}; }
};

Registry FakeRegistry() {
  Registry r;
  r.Add("dataset", "pairs_vts", "d", [](OptionReader& o) -> std::unique_ptr<Stage> {
    o.GetRequiredString("root");
    o.GetInt("max_pairs", 0, Range::AtLeast(0));
    return std::make_unique<FakeDataset>();
  });
  r.Add("preprocess", "standard", "d", Factory<FakePreprocess>());
  r.Add("sampling", "farthest_point", "d", [](OptionReader& o) -> std::unique_ptr<Stage> {
    o.GetInt("count", 1000, Range::Closed(1, 1000000));
    o.GetInt("seed", 1);
    return std::make_unique<FakeSampling>();
  });
  r.Add("geodesics", "dijkstra", "d", Factory<FakeGeodesics>());
  r.Add("geodesics", "fast_marching", "d", Factory<FakeGeodesics>());
  r.Add("embedding", "lsmds", "d", [](OptionReader& o) -> std::unique_ptr<Stage> {
    o.GetInt("dims", 3, Range::Closed(2, 3));
    o.GetChoice("init", "original", {"original", "isomap", "random"});
    o.GetDouble("tolerance", 1e-6, Range::Closed(0.0, 1.0));
    return std::make_unique<FakeEmbedding>();
  });
  r.Add("embedding", "isomap", "d", [](OptionReader& o) -> std::unique_ptr<Stage> {
    o.GetInt("dims", 3, Range::Closed(2, 3));
    o.GetBool("fix_orientation", false);
    return std::make_unique<FakeEmbedding>();
  });
  r.Add("symmetry", "plane2d", "d", Factory<FakeSymmetry>());
  r.Add("symmetrize", "ceres", "d", [](OptionReader& o) -> std::unique_ptr<Stage> {
    o.GetDouble("symmetry_weight", 10.0, Range::AtLeast(0.0));
    return std::make_unique<FakeSymmetrize>();
  });
  r.Add("symmetrize", "none", "d", Factory<FakeSymmetrize>());
  r.Add("flip", "extrinsic", "d", Factory<FakeFlip>());
  r.Add("matching", "nearest", "d", Factory<FakeMatching>());
  r.Add("matching", "deformed", "d", Factory<FakeMatching>());
  r.Add("refine", "none", "d", Factory<FakeRefine>());
  return r;
}

const char* kConfig = R"(name: demo
dataset: {format: pairs_vts, root: /data/x}  # root: ${NOT_SET_ANYWHERE}
pipeline:
  sampling: {type: farthest_point, count: 500}
  embedding: {type: lsmds, init: original}
evaluation: {geodesics: dijkstra, max_error: 0.25, step: 0.0025}
variants:
  - {name: isomap, set: {pipeline.embedding.type: isomap}}
  - {name: more_samples, set: {pipeline.sampling.count: 2000}}
)";

// Parses `text` and returns the ConfigError message ("" when it parses).
std::string ErrorOf(const std::string& text) {
  try {
    ParseExperimentConfig(text, "exp.yaml", FakeRegistry());
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

std::string Replace(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

TEST(Config, ParsesBaseAndVariants) {
  const ExperimentConfig c = ParseExperimentConfig(kConfig, "exp.yaml", FakeRegistry());
  EXPECT_EQ(c.name, "demo");
  ASSERT_EQ(c.variants.size(), 3u);
  EXPECT_EQ(c.variants[0].name, "base");
  const Pipeline base = BuildPipeline(c, c.variants[0], FakeRegistry());
  EXPECT_EQ(base.sampling->resolved_options()["count"].as<int>(), 500);
  EXPECT_EQ(base.embedding->resolved_options()["type"].as<std::string>(), "lsmds");
  EXPECT_EQ(base.symmetrize->resolved_options()["type"].as<std::string>(), "ceres");  // default
  EXPECT_EQ(base.evaluation.geodesics, "dijkstra");
  EXPECT_EQ(base.evaluation.points, 0);

  // Changing the type drops the old type's options (init belongs to lsmds).
  const Pipeline iso = BuildPipeline(c, *c.Find("isomap"), FakeRegistry());
  EXPECT_EQ(iso.embedding->resolved_options()["type"].as<std::string>(), "isomap");
  EXPECT_FALSE(iso.embedding->resolved_options()["init"]);
  EXPECT_EQ(iso.sampling->resolved_options()["count"].as<int>(), 500);

  const Pipeline more = BuildPipeline(c, *c.Find("more_samples"), FakeRegistry());
  EXPECT_EQ(more.sampling->resolved_options()["count"].as<int>(), 2000);
  EXPECT_EQ(more.embedding->resolved_options()["init"].as<std::string>(), "original");
}

TEST(Config, UnknownKeyNamesLinePathAndKnownKeys) {
  const std::string msg = ErrorOf(Replace(kConfig, "init: original", "inti: original"));
  EXPECT_NE(msg.find("exp.yaml:5:28:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("pipeline.embedding.inti: unknown key 'inti'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("known keys: dims, init, tolerance, type"), std::string::npos) << msg;
}

// A recursive alias would make the tree infinite (walking it overflowed the stack); an alias
// bomb would expand without end. Both are refused from the text, naming the place.
TEST(Config, RecursiveAliasesAndAliasBombsAreRefusedAtOnce) {
  std::string msg = ErrorOf("name: x\ndataset: &d {format: pairs_vts, root: R, x: *d}\n");
  EXPECT_EQ(msg.find("exp.yaml:2:"), 0u) << msg;
  EXPECT_NE(msg.find("*d is inside the node &d it names"), std::string::npos) << msg;
  msg = ErrorOf("name: x\nvariants:\n  - &v [a, [b, *v]]\n");
  EXPECT_NE(msg.find("recursive alias"), std::string::npos) << msg;
  // Nine levels of ten aliases: 10^9 nodes from 600 bytes.
  std::string bomb = "name: x\nl0: &l0 [a, a, a, a, a, a, a, a, a, a]\n";
  for (int level = 1; level <= 9; ++level) {
    const std::string prev = "*l" + std::to_string(level - 1);
    bomb += "l" + std::to_string(level) + ": &l" + std::to_string(level) + " [";
    for (int k = 0; k < 10; ++k) bomb += (k ? ", " : "") + prev;
    bomb += "]\n";
  }
  msg = ErrorOf(bomb);
  EXPECT_EQ(msg.find("exp.yaml:"), 0u) << msg;
  EXPECT_NE(msg.find("more than 1000000 nodes"), std::string::npos) << msg;
  // Aliases that name an earlier node outside them are fine.
  EXPECT_EQ(ErrorOf(Replace(kConfig, "set: {pipeline.sampling.count: 2000}}",
                            "set: &s {pipeline.sampling.count: 2000}}\n"
                            "  - {name: again, set: *s}")),
            "");
}

// Each variant's tree is parsed from the text with its own entry of the list only (positions
// kept), whatever the list's style; a list past kMaxVariants entries is refused.
TEST(Config, VariantsKeepTheirPositionsInBlockAndFlowListsAndAreBounded) {
  const std::string block =
      std::string(kConfig) + "  - {name: bad, set: {pipeline.sampling.count: x}}\n";
  std::string msg = ErrorOf(block);
  EXPECT_EQ(msg.find("exp.yaml:10:"), 0u) << msg;
  EXPECT_NE(msg.find("pipeline.sampling.count: expected an integer"), std::string::npos) << msg;
  EXPECT_NE(msg.find("(in variant 'bad')"), std::string::npos) << msg;
  const std::string flow =
      Replace(kConfig,
              "variants:\n"
              "  - {name: isomap, set: {pipeline.embedding.type: isomap}}\n"
              "  - {name: more_samples, set: {pipeline.sampling.count: 2000}}\n",
              "variants: [{name: isomap, set: {pipeline.embedding.type: isomap}},"
              " {name: more_samples, set: {pipeline.sampling.count: 2000}}]\n");
  const ExperimentConfig c = ParseExperimentConfig(flow, "exp.yaml", FakeRegistry());
  ASSERT_EQ(c.variants.size(), 3u);
  EXPECT_EQ(BuildPipeline(c, *c.Find("more_samples"), FakeRegistry())
                .sampling->resolved_options()["count"].as<int>(),
            2000);
  std::string many = "name: many\ndataset: {format: pairs_vts, root: /data/x}\nvariants:\n";
  for (size_t i = 0; i <= kMaxVariants; ++i) {
    many += "  - {name: v" + std::to_string(i) + "}\n";
  }
  msg = ErrorOf(many);
  EXPECT_EQ(msg.find("exp.yaml:4:"), 0u) << msg;
  EXPECT_NE(msg.find("10001 variants; at most 10000"), std::string::npos) << msg;
}

// An empty value stands for nothing the user could mean: `key:` in a file or `--set key=` would
// silently reset the option to its default.
TEST(Config, KeysAndSetsWithoutAValueAreRefused) {
  std::string msg = ErrorOf(Replace(kConfig, "count: 500", "count:"));
  EXPECT_NE(msg.find("exp.yaml:4:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("pipeline.sampling.count: no value"), std::string::npos) << msg;
  msg = ErrorOf(Replace(kConfig, "count: 500", "count: ~"));
  EXPECT_NE(msg.find("pipeline.sampling.count: no value"), std::string::npos) << msg;
  for (const std::string set : {"pipeline.sampling.count=", "pipeline.sampling.count= "}) {
    try {
      ParseExperimentConfig(kConfig, "exp.yaml", FakeRegistry(), {set});
      ADD_FAILURE() << set;
    } catch (const ConfigError& e) {
      EXPECT_EQ(std::string(e.what()).find("--set '" + set + "': no value after '='"), 0u)
          << e.what();
    }
  }
}

TEST(Config, UnknownTopLevelKeyAndStageKind) {
  std::string msg = ErrorOf(std::string(kConfig) + "evalution: {}\n");
  EXPECT_NE(msg.find("exp.yaml:10:1: evalution: unknown key"), std::string::npos) << msg;
  EXPECT_NE(msg.find("evaluation"), std::string::npos) << msg;
  msg = ErrorOf(Replace(kConfig, "  sampling:", "  smapling:"));
  EXPECT_NE(msg.find("exp.yaml:4:3: pipeline.smapling: unknown stage kind"), std::string::npos)
      << msg;
}

TEST(Config, WrongTypeNamesExpectation) {
  const std::string msg = ErrorOf(Replace(kConfig, "count: 500", "count: many"));
  EXPECT_NE(msg.find("exp.yaml:4:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("pipeline.sampling.count: expected an integer, got 'many'"), std::string::npos)
      << msg;
}

TEST(Config, BadEnumListsValidValues) {
  const std::string msg = ErrorOf(Replace(kConfig, "init: original", "init: orignal"));
  EXPECT_NE(msg.find("pipeline.embedding.init: invalid value 'orignal'; expected one of: "
                     "original, isomap, random"),
            std::string::npos)
      << msg;
  const std::string type_msg = ErrorOf(Replace(kConfig, "type: lsmds", "type: lsmd"));
  EXPECT_NE(type_msg.find("unknown embedding type 'lsmd'; known: isomap, lsmds"), std::string::npos)
      << type_msg;
}

TEST(Config, OutOfRangeNamesTheRange) {
  const std::string msg = ErrorOf(Replace(kConfig, "count: 500", "count: 0"));
  EXPECT_NE(msg.find("pipeline.sampling.count: must be in [1, 1000000], got 0"), std::string::npos)
      << msg;
  const std::string eval = ErrorOf(Replace(kConfig, "step: 0.0025", "step: 0.5"));
  EXPECT_NE(eval.find("evaluation.step: must be in [1e-06, 0.25], got 0.5"), std::string::npos)
      << eval;
}

TEST(Config, IntListsAcceptAListOrOneIntegerAndCheckEachItem) {
  OptionReader o(YAML::Load("{a: [3, 1], b: 4, c: [2, x], d: [0], e: {f: 1}}"), "f.yaml", "p");
  EXPECT_EQ(o.GetIntList("a", {}), (std::vector<int>{3, 1}));
  EXPECT_EQ(o.GetIntList("b", {}), (std::vector<int>{4}));
  EXPECT_EQ(o.GetIntList("missing", {7, 8}), (std::vector<int>{7, 8}));
  EXPECT_EQ(o.resolved()["a"].size(), 2u);
  EXPECT_EQ(o.resolved()["missing"][1].as<int>(), 8);
  auto error_of = [&](const std::string& key, int min) -> std::string {
    try {
      o.GetIntList(key, {}, Range::AtLeast(min));
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error_of("c", 0).find("p.c: expected a list of integers, got 'x'"), std::string::npos)
      << error_of("c", 0);
  EXPECT_NE(error_of("d", 1).find("p.d: must be in [1, inf), got 0"), std::string::npos)
      << error_of("d", 1);
  EXPECT_NE(error_of("e", 0).find("expected a list of integers"), std::string::npos);
}

TEST(Config, MissingRequiredKeys) {
  std::string msg = ErrorOf(Replace(kConfig, "root: /data/x", "max_pairs: 3"));
  EXPECT_NE(msg.find("dataset: missing required key 'root'"), std::string::npos) << msg;
  msg = ErrorOf(Replace(kConfig, "name: demo\n", ""));
  EXPECT_NE(msg.find("missing required key 'name'"), std::string::npos) << msg;
  msg = ErrorOf(Replace(kConfig, "format: pairs_vts, ", ""));
  EXPECT_NE(msg.find("dataset: missing required key 'format'; known dataset types: pairs_vts"),
            std::string::npos)
      << msg;
}

TEST(Config, VariantErrorsPointAtTheVariant) {
  std::string msg =
      ErrorOf(Replace(kConfig, "pipeline.sampling.count: 2000", "pipeline.sampling.count: -3"));
  EXPECT_NE(msg.find("exp.yaml:9:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("pipeline.sampling.count: must be in [1, 1000000], got -3"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("(in variant 'more_samples')"), std::string::npos) << msg;
  // An error of the base pipeline is every variant's: no variant is named.
  msg = ErrorOf(Replace(kConfig, "count: 500", "count: -5"));
  EXPECT_NE(msg.find("must be in [1, 1000000], got -5"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("in variant"), std::string::npos) << msg;
  msg = ErrorOf(Replace(kConfig, "pipeline.sampling.count", "pipeline.smpling.count"));
  EXPECT_NE(msg.find("exp.yaml:9:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("unknown stage kind 'smpling'"), std::string::npos) << msg;
  msg = ErrorOf(Replace(kConfig, "name: more_samples", "name: isomap"));
  EXPECT_NE(msg.find("duplicate variant name 'isomap'"), std::string::npos) << msg;
  msg = ErrorOf(Replace(kConfig, "{name: isomap, set", "{name: isomap, sett"));
  EXPECT_NE(msg.find("variants[0].sett: unknown key"), std::string::npos) << msg;
}

// An override of an option that only one variant's stage has (isomap's fix_orientation) fails
// the config as a whole, naming the --set, and loads when only that variant is asked for; a name
// that is not a variant validates every variant.
TEST(Config, AnOverrideForOneVariantLoadsWhenOnlyThatVariantRuns) {
  const std::vector<std::string> set = {"pipeline.embedding.fix_orientation=true"};
  try {
    ParseExperimentConfig(kConfig, "exp.yaml", FakeRegistry(), set);
    FAIL() << "an option of a stage the base does not select was accepted";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("--set 'pipeline.embedding.fix_orientation=true'"),
              std::string::npos)
        << error.what();
  }
  // Asked for alone, the variant whose set changes the embedding's type gets the option on top.
  const ExperimentConfig c =
      ParseExperimentConfig(kConfig, "exp.yaml", FakeRegistry(), set, "isomap");
  const Pipeline p = BuildPipeline(c, *c.Find("isomap"), FakeRegistry());
  EXPECT_TRUE(p.embedding->resolved_options()["fix_orientation"].as<bool>());
  EXPECT_TRUE(c.shadowed_overrides.empty());
  // Among all variants the type change drops an override of the old type's option, and says so.
  const std::vector<std::string> init = {"pipeline.embedding.init=random"};
  const ExperimentConfig all = ParseExperimentConfig(kConfig, "exp.yaml", FakeRegistry(), init);
  const Pipeline isomap = BuildPipeline(all, *all.Find("isomap"), FakeRegistry());
  EXPECT_FALSE(isomap.embedding->resolved_options()["init"].IsDefined());
  ASSERT_EQ(all.shadowed_overrides.size(), 1u);
  EXPECT_EQ(all.shadowed_overrides[0].first, "isomap");
  EXPECT_NE(all.shadowed_overrides[0].second.find("drops --set pipeline.embedding.init=random"),
            std::string::npos)
      << all.shadowed_overrides[0].second;
  EXPECT_THROW(ParseExperimentConfig(kConfig, "exp.yaml", FakeRegistry(), set, "no_such_variant"),
               ConfigError);
}

TEST(Config, YamlSyntaxErrorHasLocation) {
  const std::string msg = ErrorOf("name: x\ndataset: {format: [\n");
  EXPECT_NE(msg.find("exp.yaml:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("YAML syntax error"), std::string::npos) << msg;
}

TEST(Config, EnvironmentSubstitution) {
  setenv("SYMEMBED_TEST_ROOT", "/from/env", 1);
  unsetenv("SYMEMBED_TEST_UNSET");
  EXPECT_EQ(ExpandEnvironment("${SYMEMBED_TEST_ROOT}/tosca", "w"), "/from/env/tosca");
  EXPECT_EQ(ExpandEnvironment("${SYMEMBED_TEST_UNSET:-../shared/data}/t", "w"), "../shared/data/t");
  EXPECT_EQ(ExpandEnvironment("${SYMEMBED_TEST_ROOT:-x}", "w"), "/from/env");
  EXPECT_THROW(ExpandEnvironment("${SYMEMBED_TEST_UNSET}", "w"), ConfigError);
  const ExperimentConfig c = ParseExperimentConfig(
      Replace(kConfig, "/data/x", "${SYMEMBED_TEST_ROOT}/tosca"), "exp.yaml", FakeRegistry());
  const Pipeline p = BuildPipeline(c, c.variants[0], FakeRegistry());
  EXPECT_EQ(p.dataset->resolved_options()["root"].as<std::string>(), "/from/env/tosca");
}

TEST(Config, ResolvedConfigRoundTrips) {
  const Registry registry = FakeRegistry();
  const ExperimentConfig c = ParseExperimentConfig(kConfig, "exp.yaml", registry);
  for (const auto& v : c.variants) {
    const Pipeline p = BuildPipeline(c, v, registry);
    const std::string resolved = ResolvedConfigYaml(c, v, p);
    // Defaults are filled in.
    EXPECT_NE(resolved.find("seed: 1"), std::string::npos) << resolved;
    const ExperimentConfig again = ParseExperimentConfig(resolved, "resolved.yaml", registry);
    ASSERT_EQ(again.variants.size(), 1u);
    const Pipeline q = BuildPipeline(again, again.variants[0], registry);
    EXPECT_EQ(ResolvedConfigYaml(c, v, q), resolved) << v.name;
  }
}

}  // namespace
}  // namespace symembed

namespace symembed {
namespace {

TEST(Config, CommandLineOverridesApplyToEveryVariant) {
  const Registry registry = FakeRegistry();
  const ExperimentConfig c =
      ParseExperimentConfig(kConfig, "exp.yaml", registry,
                            {"evaluation.geodesics=fast_marching", "pipeline.sampling.seed=7"});
  for (const auto& v : c.variants) {
    const Pipeline p = BuildPipeline(c, v, registry);
    EXPECT_EQ(p.evaluation.geodesics, "fast_marching") << v.name;
    EXPECT_EQ(p.sampling->resolved_options()["seed"].as<int>(), 7) << v.name;
  }
  // The variant's own override still wins over the command line for the same key.
  const ExperimentConfig d =
      ParseExperimentConfig(kConfig, "exp.yaml", registry, {"pipeline.sampling.count=50"});
  EXPECT_EQ(BuildPipeline(d, *d.Find("more_samples"), registry)
                .sampling->resolved_options()["count"]
                .as<int>(),
            2000);
  EXPECT_EQ(
      BuildPipeline(d, *d.Find("base"), registry).sampling->resolved_options()["count"].as<int>(),
      50);
  // ... and says so, naming the variant, its key and the override; unrelated overrides do not.
  ASSERT_EQ(d.shadowed_overrides.size(), 1u);
  EXPECT_EQ(d.shadowed_overrides[0].first, "more_samples");
  for (const char* part :
       {"'more_samples'", "pipeline.sampling.count", "--set pipeline.sampling.count=50"}) {
    const std::string& line = d.shadowed_overrides[0].second;
    EXPECT_NE(line.find(part), std::string::npos) << line;
  }
  EXPECT_TRUE(c.shadowed_overrides.empty());
  EXPECT_EQ(ParseExperimentConfig(kConfig, "exp.yaml", registry, {"pipeline.sampling={count: 9}"})
                .shadowed_overrides.size(),
            1u);
  EXPECT_THROW(ParseExperimentConfig(kConfig, "exp.yaml", registry, {"evaluation.geodesics"}),
               ConfigError);
  EXPECT_THROW(ParseExperimentConfig(kConfig, "exp.yaml", registry, {"pipline.x.y=1"}),
               ConfigError);
}

}  // namespace
}  // namespace symembed

namespace symembed {
namespace {

TEST(Config, PipelineAndEvaluationSectionsAreOptional) {
  const Registry registry = FakeRegistry();
  const ExperimentConfig c = ParseExperimentConfig(
      "name: minimal\ndataset: {format: pairs_vts, root: /x}\n", "m.yaml", registry);
  const Pipeline p = BuildPipeline(c, c.variants[0], registry);
  EXPECT_EQ(p.embedding->resolved_options()["type"].as<std::string>(), "lsmds");
  EXPECT_EQ(p.evaluation.geodesics, "fast_marching");
}

}  // namespace
}  // namespace symembed

namespace symembed {
namespace {

TEST(Config, UnknownKeySetByAnOverrideNamesWhereItWasSet) {
  // By a variant: the line of its value in the variant.
  std::string msg =
      ErrorOf(Replace(kConfig, "pipeline.sampling.count: 2000", "pipeline.sampling.cuont: 2000"));
  EXPECT_NE(msg.find("exp.yaml:9:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("pipeline.sampling.cuont: unknown key 'cuont'"), std::string::npos) << msg;
  // By --set: the --set argument (a position in its text is not one in the file).
  auto with_set = [](const std::vector<std::string>& overrides) {
    try {
      ParseExperimentConfig(kConfig, "exp.yaml", FakeRegistry(), overrides);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  msg = with_set({"pipeline.sampling.count=7", "pipeline.sampling.cuont=[1, 2]"});
  EXPECT_EQ(msg.find("--set 'pipeline.sampling.cuont=[1, 2]': pipeline.sampling.cuont: unknown "
                     "key 'cuont'"),
            0u)
      << msg;
  msg = with_set({"pipeline.sampling.count=abc"});
  EXPECT_EQ(msg.find("--set 'pipeline.sampling.count=abc': pipeline.sampling.count: expected"), 0u)
      << msg;
}

TEST(Config, DuplicateKeysAreRefusedWithBothPositions) {
  std::string msg = ErrorOf(Replace(kConfig, "  embedding:", "  sampling: {count: 3}\n  embedding:"));
  EXPECT_NE(msg.find("exp.yaml:5:3: pipeline.sampling: duplicate key 'sampling' (first at "
                     "exp.yaml:4:3)"),
            std::string::npos)
      << msg;
  msg = ErrorOf(Replace(kConfig, "init: original", "init: original, init: isomap"));
  EXPECT_NE(msg.find("pipeline.embedding.init: duplicate key 'init'"), std::string::npos) << msg;
  msg = ErrorOf(Replace(kConfig, "{pipeline.sampling.count: 2000}",
                        "{pipeline.sampling.count: 2000, pipeline.sampling.count: 3}"));
  EXPECT_NE(msg.find("variants[1].set.pipeline.sampling.count: duplicate key"), std::string::npos)
      << msg;
}

TEST(Config, BadExperimentNameIsNamedAsTheName) {
  const std::string msg = ErrorOf(Replace(kConfig, "name: demo", "name: 'a b'"));
  EXPECT_NE(msg.find("exp.yaml:1:7: name: 'a b' is not a valid name"), std::string::npos) << msg;
}

// A check across options of a map a variant's dotted keys made: the line of a value it set.
TEST(Config, CrossOptionErrorOfAMapMadeByAVariantHasALine) {
  Registry registry;
  RegisterBuiltinStages(registry);
  const std::string text =
      "name: x\ndataset: {format: synthetic}\nvariants:\n  - name: v\n    set:\n"
      "      pipeline.refine.type: zoomout\n      pipeline.refine.k_start: 100\n"
      "      pipeline.refine.k_end: 20\n";
  try {
    ParseExperimentConfig(text, "exp.yaml", registry);
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("exp.yaml:6:29: pipeline.refine: k_end (20) must be"),
              std::string::npos)
        << e.what();
  }
}

// Every config shipped in configs/ (the quickstart, the paper studies, the suite) loads: its keys
// exist and every variant's stages, dataset included, are built with their options. No data is
// read.
TEST(Config, EveryShippedConfigLoads) {
  Registry registry;
  RegisterBuiltinStages(registry);
  int configs = 0;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(testing::SourceDir() + "/configs")) {
    if (entry.path().extension() != ".yaml") continue;
    ++configs;
    try {
      const ExperimentConfig config = LoadExperimentConfig(entry.path().string(), registry);
      EXPECT_FALSE(config.variants.empty()) << entry.path();
      for (const VariantConfig& variant : config.variants) {
        EXPECT_NO_THROW(BuildPipeline(config, variant, registry))
            << entry.path() << " " << variant.name;
      }
    } catch (const Error& e) {
      ADD_FAILURE() << e.what();
    }
  }
  EXPECT_GE(configs, 7);
}

TEST(Config, AnEmbeddingThatCannotRunIsRefused) {
  Registry registry;
  RegisterBuiltinStages(registry);
  for (const char* type : {"lsmds", "isomap"}) {
    const std::string text = std::string("name: x\ndataset: {format: synthetic}\npipeline:\n") +
                             "  embedding: {type: " + type + ", dims: 2}\n";
    try {
      ParseExperimentConfig(text, "exp.yaml", registry);
      ADD_FAILURE() << type << ": no error";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("exp.yaml:4:"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("only 3 is supported, got 2"), std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace symembed

namespace symembed {
namespace {

// The evaluation section is read by one parser, for a config and for a resolved config.yaml
// read back by merge and eval (no registry: the geodesics name is not checked there).
TEST(Config, EvaluationOptionsHaveOneStrictParser) {
  const EvaluationOptions e = ParseEvaluationOptions(
      YAML::Load("{geodesics: dijkstra, max_error: 0.5, step: 0.01, points: 200}"),
      "run/base/config.yaml", nullptr);
  EXPECT_EQ(e.geodesics, "dijkstra");
  EXPECT_DOUBLE_EQ(e.max_error, 0.5);
  EXPECT_DOUBLE_EQ(e.step, 0.01);
  EXPECT_EQ(e.points, 200);
  const EvaluationOptions defaults =
      ParseEvaluationOptions(YAML::Node(), "run/base/config.yaml", nullptr);
  EXPECT_EQ(defaults.geodesics, EvaluationOptions().geodesics);
  EXPECT_EQ(defaults.points, 0);
  try {
    ParseEvaluationOptions(YAML::Load("{max_eror: 0.5}"), "run/base/config.yaml", nullptr);
    FAIL() << "an unknown key was accepted";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("run/base/config.yaml"), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("max_eror"), std::string::npos);
  }
  EXPECT_THROW(
      ParseEvaluationOptions(YAML::Load("{points: some}"), "run/base/config.yaml", nullptr),
      ConfigError);
  EXPECT_EQ(defaults.refine_start, "matching");
  EXPECT_EQ(ParseEvaluationOptions(YAML::Load("{refine_start: ground_truth}"),
                                   "run/base/config.yaml", nullptr)
                .refine_start,
            "ground_truth");
  try {
    ParseEvaluationOptions(YAML::Load("{refine_start: truth}"), "run/base/config.yaml", nullptr);
    FAIL() << "a bad refine_start was accepted";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("refine_start"), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("ground_truth"), std::string::npos) << error.what();
  }
}

// evaluation.refine_start appears in a resolved config only when set (the resolved configs of
// runs without it keep their text, which resuming compares) and reads back from it.
TEST(Config, RefineStartIsWrittenOnlyWhenSetAndReadsBack) {
  const Registry registry = FakeRegistry();
  const ExperimentConfig c = ParseExperimentConfig(
      Replace(kConfig, "variants:\n",
              "variants:\n  - {name: truth, set: {evaluation.refine_start: ground_truth}}\n"),
      "exp.yaml", registry);
  int with_truth = 0;
  for (const auto& v : c.variants) {
    const Pipeline p = BuildPipeline(c, v, registry);
    const std::string resolved = ResolvedConfigYaml(c, v, p);
    const bool set = v.name == "truth";
    with_truth += set;
    EXPECT_EQ(p.evaluation.refine_start, set ? "ground_truth" : "matching") << v.name;
    EXPECT_EQ(resolved.find("refine_start") != std::string::npos, set) << resolved;
    const ExperimentConfig again = ParseExperimentConfig(resolved, "resolved.yaml", registry);
    const Pipeline q = BuildPipeline(again, again.variants[0], registry);
    EXPECT_EQ(q.evaluation.refine_start, p.evaluation.refine_start) << v.name;
  }
  EXPECT_EQ(with_truth, 1);
}

}  // namespace
}  // namespace symembed

namespace symembed {
namespace {

// Every default type of the kind table is a registered stage of its kind, and the registry
// accepts the kinds of the table and `dataset`, no other.
TEST(Config, TheKindTablesDefaultsAreRegisteredAndItsKindsTheOnlyOnes) {
  Registry registry;
  RegisterBuiltinStages(registry);
  for (const StageKind& kind : kPipelineStageKinds) {
    EXPECT_TRUE(registry.Has(kind.name, kind.default_type))
        << kind.name << ": default type '" << kind.default_type << "' is not registered";
  }
  EXPECT_EQ(StageKinds().back(), "dataset");
  EXPECT_THROW(
      registry.Add("not_a_kind", "x", "", [](OptionReader&) { return std::unique_ptr<Stage>(); }),
      ConfigError);
}

}  // namespace
}  // namespace symembed
