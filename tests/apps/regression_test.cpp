// Accuracy regression: the README's default experiment (configs/quickstart.yaml, base pipeline,
// synthetic shapes generated in-process) must not get worse than the committed baseline
// results/baselines/synthetic.json (tolerances: the defaults of `symembed check`).
#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace symembed {
namespace {

TEST(AccuracyRegression, QuickstartBaseMatchesSyntheticBaseline) {
  testing::TempDir dir;
  const std::string bin = SYMEMBED_BINARY;
  const std::string src = testing::SourceDir();
  std::string out;
  const int run = testing::RunShell("cd " + dir.path() + " && " + bin + " run " + src +
                                        "/configs/quickstart.yaml --variant base --quiet --out " +
                                        dir.File("run") + " --cache " + dir.File("cache"),
                                    &out);
  ASSERT_EQ(run, 0) << out;
  const int check = testing::RunShell(bin + " check " + dir.File("run/base/summary.json") +
                                          " --baseline " + src + "/results/baselines/synthetic.json",
                                      &out);
  EXPECT_EQ(check, 0) << out;
}

}  // namespace
}  // namespace symembed
