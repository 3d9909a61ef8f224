// Accuracy regression on TOSCA (label `tosca`; skipped without the data): the paper's pipeline
// (variant `base` of configs/tosca_paper.yaml, all 284 pairs, dijkstra evaluation) must not get
// worse than the committed baseline results/baselines/tosca_iso_5k.json (tolerances: the
// defaults of `symembed check`). A cold run takes about 3 minutes on 2 cores.
#include <gtest/gtest.h>

#include "tests/test_util.h"

namespace symembed {
namespace {

TEST(AccuracyRegressionTosca, PaperPipelineMatchesToscaBaseline) {
  const std::string data = testing::DataRoot();
  if (data.empty()) GTEST_SKIP() << "no benchmark data root (set SYMEMBED_DATA)";
  testing::TempDir dir;
  const std::string bin = SYMEMBED_BINARY;
  const std::string src = testing::SourceDir();
  std::string out;
  const int run = testing::RunShell("SYMEMBED_DATA=" + data + " " + bin + " run " + src +
                                        "/configs/tosca_paper.yaml --variant base --quiet --out " +
                                        dir.File("run") + " --cache " + dir.File("cache"),
                                    &out);
  ASSERT_EQ(run, 0) << out;
  const int check = testing::RunShell(bin + " check " + dir.File("run/base/summary.json") +
                                          " --baseline " + src +
                                          "/results/baselines/tosca_iso_5k.json",
                                      &out);
  EXPECT_EQ(check, 0) << out;
}

}  // namespace
}  // namespace symembed
