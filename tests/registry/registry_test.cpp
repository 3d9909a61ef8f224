#include "registry/registry.h"

#include <gtest/gtest.h>

#include <set>

namespace symembed {
namespace {

class DummySampling : public SamplingStage {
 public:
  explicit DummySampling(int count) : count_(count) {}
  SamplingResult Run(const Surface&) const override {
    SamplingResult r;
    for (int i = 0; i < count_; ++i) r.samples.push_back(i);
    return r;
  }

 private:
  int count_;
};

Registry::Factory DummyFactory() {
  return [](OptionReader& o) {
    return std::make_unique<DummySampling>(o.GetInt("count", 3, Range::Closed(1, 100)));
  };
}

TEST(Registry, BuiltinSetIsExactlyTheExpectedOne) {
  Registry registry;
  RegisterBuiltinStages(registry);
  std::set<std::string> actual;
  for (const auto& e : registry.List()) {
    EXPECT_FALSE(e.description.empty()) << e.kind << "/" << e.name;
    actual.insert(e.kind + "/" + e.name);
  }
  // Every built-in stage and loader; update together with RegisterBuiltinStages.
  const std::set<std::string> expected = {
      "dataset/kim2011",
      "dataset/pairs_vts",
      "dataset/same_connectivity",
      "dataset/shrec16_partial",
      "dataset/synthetic",
      "dataset/topkids",
      "embedding/isomap",
      "embedding/lsmds",
      "flip/chamfer",
      "flip/extrinsic",
      "flip/hks",
      "flip/oracle",
      "geodesics/dijkstra",
      "geodesics/fast_marching",
      "geodesics/heat",
      "matching/deformed",
      "matching/nearest",
      "matching/nearest_scaled",
      "preprocess/standard",
      "refine/discrete",
      "refine/icp",
      "refine/none",
      "refine/zoomout",
      "sampling/all",
      "sampling/farthest_point",
      "symmetrize/average",
      "symmetrize/ceres",
      "symmetrize/none",
      "symmetry/plane2d",
      "symmetry/plane3d",
  };
  EXPECT_EQ(actual, expected);
}

TEST(Registry, CreatesWithResolvedOptions) {
  Registry registry;
  registry.Add("sampling", "dummy", "test stage", DummyFactory());
  YAML::Node node = YAML::Load("{type: dummy, count: 5}");
  auto stage = registry.CreateAs<SamplingStage>("sampling", node, "c.yaml", "pipeline.sampling");
  EXPECT_EQ(stage->Run(Surface{}).samples.size(), 5u);
  EXPECT_EQ(stage->resolved_options()["type"].as<std::string>(), "dummy");
  EXPECT_EQ(stage->resolved_options()["count"].as<int>(), 5);
  // Defaults are filled in.
  auto defaulted = registry.CreateAs<SamplingStage>("sampling", YAML::Load("{type: dummy}"),
                                                    "c.yaml", "pipeline.sampling");
  EXPECT_EQ(defaulted->resolved_options()["count"].as<int>(), 3);
}

TEST(Registry, DuplicateNameFailsListingKnown) {
  Registry registry;
  registry.Add("sampling", "dummy", "test stage", DummyFactory());
  try {
    registry.Add("sampling", "dummy", "again", DummyFactory());
    FAIL() << "duplicate accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("duplicate sampling stage 'dummy'"), std::string::npos);
  }
  EXPECT_THROW(registry.Add("nonsense", "x", "d", DummyFactory()), ConfigError);
}

TEST(Registry, UnknownNameFailsListingKnownWithLocation) {
  Registry registry;
  registry.Add("sampling", "dummy", "test stage", DummyFactory());
  registry.Add("sampling", "other", "test stage", DummyFactory());
  YAML::Node node = YAML::Load("\n{type: dumy}");
  try {
    registry.Create("sampling", node, "c.yaml", "pipeline.sampling");
    FAIL() << "unknown name accepted";
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("c.yaml:2:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("pipeline.sampling.type"), std::string::npos) << msg;
    EXPECT_NE(msg.find("known: dummy, other"), std::string::npos) << msg;
  }
}

TEST(Registry, UnknownOptionFails) {
  Registry registry;
  registry.Add("sampling", "dummy", "test stage", DummyFactory());
  try {
    registry.Create("sampling", YAML::Load("{type: dummy, cout: 4}"), "c.yaml",
                    "pipeline.sampling");
    FAIL() << "unknown option accepted";
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("pipeline.sampling.cout: unknown key 'cout'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("known keys: count, type"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace symembed
