// scripts/results-doc: docs/results.md from the runs of the two ablation studies.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/test_util.h"

namespace symembed {
namespace {

// A run folder of configs/synthetic_paper.yaml with the variants base and zoomout (two pairs
// each; in base the second pair's rotation is not the oracle's).
void WriteSyntheticRun(const std::string& dir) {
  const std::string header =
      "source,target,status,mean_direct,mean_flip_tolerant,flip,chosen,oracle,refine_side,"
      "candidate_errors\n";
  const std::string summary =
      "{\"pairs\": 2, \"failed_pairs\": 0, \"mean_direct\": %MEAN%, \"pct_direct\": {\"0.05\": "
      "80.0, \"0.10\": 90.0, \"0.25\": 100.0}, \"mean_flip_tolerant\": 0.03, "
      "\"pct_flip_tolerant\": {\"0.05\": 81.0, \"0.10\": 91.0, \"0.25\": 100.0}, "
      "\"flipped_pairs\": {\"left_right\": 0, "
      "\"front_back\": %FB%, \"up_down\": 0}, \"time_per_shape_s\": 2.5, \"time_per_pair_s\": "
      "0.25}";
  auto fill = [](std::string text, const std::string& mean, const std::string& fb) {
    text.replace(text.find("%MEAN%"), 6, mean);
    text.replace(text.find("%FB%"), 4, fb);
    return text;
  };
  std::filesystem::create_directories(dir + "/base");
  std::filesystem::create_directories(dir + "/zoomout");
  testing::WriteText(dir + "/variants.txt", "base\nzoomout\n");
  testing::WriteText(dir + "/base/summary.json", fill(summary, "0.0333", "1"));
  testing::WriteText(dir + "/base/pairs.csv",
                     header +
                         "humanoid0,humanoid1,ok,0.02,0.02,none,0,0,,0.02 0.5 0.6 0.7\n"
                         "humanoid0,humanoid2,ok,0.04,0.03,front_back,2,0,,0.03 0.5 0.04 0.7\n");
  testing::WriteText(dir + "/zoomout/summary.json", fill(summary, "0.0181", "0"));
  testing::WriteText(dir + "/zoomout/pairs.csv",
                     header +
                         "humanoid0,humanoid1,ok,0.01,0.01,none,0,0,,0.02 0.5 0.6 0.7\n"
                         "quadruped0,quadruped1,ok,0.03,0.03,none,0,0,to_direct,"
                         "0.03 0.5 0.6 0.7\n");
}

TEST(ResultsDoc, WritesEachStudysTableAndClassesAndSkipsAStudyWithoutData) {
  testing::TempDir dir;
  WriteSyntheticRun(dir.File("runs/synthetic_paper"));
  const std::string doc = dir.File("results.md");
  std::string out;
  ASSERT_EQ(testing::RunShell("SYMEMBED_DATA=" + dir.File("no_data") + " python3 " +
                                  testing::SourceDir() + "/scripts/results-doc --no-run --out " +
                                  dir.File("runs") + " --write " + doc,
                              &out),
            0)
      << out;
  const std::string text = testing::ReadText(doc);
  EXPECT_NE(out.find(text), std::string::npos) << "stdout holds the document:\n" << out;
  // TOSCA has no data here: named as skipped, with the folder.
  EXPECT_NE(text.find("Skipped: no data at `" + dir.File("no_data") + "/tosca_iso_5k`"),
            std::string::npos)
      << text;
  // The variants' table: pairs, mean, percentages, chosen != oracle (1), the mean of the
  // lowest candidate errors ((0.02 + 0.03) / 2), flips, seconds.
  EXPECT_NE(text.find("| base | 2 | 0.033 | 80.0 / 90.0 / 100.0 | 1 | 0.025 | 0 / 1 / 0 | 2.50 | "
                      "0.250 |"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("| zoomout | 2 | 0.018 |"), std::string::npos) << text;
  // Per class for base and zoomout; zoomout's refined pairs count where refinement moved them.
  EXPECT_NE(text.find("base:"), std::string::npos) << text;
  EXPECT_NE(text.find("| humanoid | 2 | 0.030 | 0.025 | 0 / 1 / 0 | 1 |"), std::string::npos)
      << text;
  EXPECT_NE(text.find("| quadruped | 1 | 0.030 | 0.030 | 0 / 0 / 0 | 0 | 0 / 1 |"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("scripts/results-doc --write docs/results.md"), std::string::npos) << text;
}

TEST(ResultsDoc, AnUnknownArgumentIsAnError) {
  std::string out;
  EXPECT_EQ(testing::RunShell("python3 " + testing::SourceDir() + "/scripts/results-doc --bogus",
                              &out),
            2);
  EXPECT_NE(out.find("unknown argument '--bogus'"), std::string::npos) << out;
}

}  // namespace
}  // namespace symembed
