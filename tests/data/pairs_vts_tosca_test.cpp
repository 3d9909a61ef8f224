// The pairs_vts loader on the TOSCA 5k benchmark (label `tosca`; skipped without the data).
#include <gtest/gtest.h>

#include <set>

#include "core/mesh_io.h"
#include "eval/datasets/pairs_vts.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

TEST(PairsVtsTosca, ReadsTheWholeBenchmark) {
  const std::string data = testing::DataRoot();
  if (data.empty()) GTEST_SKIP() << "no benchmark data root (set SYMEMBED_DATA)";
  PairsVtsDataset dataset(PairsVtsOptions{data + "/tosca_iso_5k", {}});
  const DatasetIndex index = dataset.Load();
  EXPECT_EQ(index.shapes.size(), 76u);
  EXPECT_EQ(index.pairs.size(), 284u);  // the trailing blank line is not a pair
  std::set<std::string> classes;
  for (const auto& s : index.shapes) classes.insert(s.class_name);
  EXPECT_EQ(classes, (std::set<std::string>{"cat", "centaur", "david", "dog", "horse", "michael",
                                            "victoria", "wolf"}));
  for (const auto& p : index.pairs) {
    EXPECT_EQ(index.Find(p.source)->class_name, index.Find(p.target)->class_name);
  }
  // Ground truth: 5,000 lines, ids within the mesh, not a bijection.
  for (const std::string name : {"cat0", "wolf1", "victoria10"}) {
    const DatasetShape* shape = index.Find(name);
    ASSERT_NE(shape, nullptr) << name;
    const Surface surface = LoadSurface(shape->mesh_path);
    const ShapeGroundTruth gt = dataset.GroundTruth(*shape, surface.NumVertices());
    EXPECT_EQ(gt.ids.size(), 5000u) << name;
    EXPECT_EQ(gt.sym_ids.size(), 5000u) << name;
    const std::set<int> distinct(gt.ids.begin(), gt.ids.end());
    EXPECT_LT(distinct.size(), gt.ids.size()) << name;
    EXPECT_GE(*distinct.begin(), 0) << name;
  }
  PairsVtsDataset dogs(PairsVtsOptions{data + "/tosca_iso_5k", {{"dog"}, 5, ""}});
  EXPECT_EQ(dogs.Load().pairs.size(), 5u);
}

}  // namespace
}  // namespace symembed
