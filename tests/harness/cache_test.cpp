#include "harness/cache.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "harness/progress.h"
#include "harness/run_outputs.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

using testing::TempDir;

TEST(DiskCache, StoresAndLoadsAndTreatsDamageAsAMiss) {
  TempDir tmp;
  DiskCache cache(tmp.File("cache"));
  SamplingResult value;
  value.samples = {3, 1, 4};
  value.coverage_radius = 0.5;
  EXPECT_FALSE(cache.Load("sampling", 1, &value));
  EXPECT_TRUE(cache.Store("sampling", 1, value));
  SamplingResult loaded;
  ASSERT_TRUE(cache.Load("sampling", 1, &loaded));
  EXPECT_EQ(loaded.samples, value.samples);
  EXPECT_EQ(loaded.coverage_radius, 0.5);
  // Another kind under the same key is a different entry.
  EXPECT_FALSE(cache.Load("embedding", 1, &loaded));
  // Truncated file: a miss.
  const std::string path = cache.Path("sampling", 1);
  const std::string bytes = *ReadFileBytes(path);
  testing::WriteText(path, bytes.substr(0, bytes.size() - 3));
  EXPECT_FALSE(cache.Load("sampling", 1, &loaded));
}

TEST(DiskCache, DisabledCacheNeverHits) {
  DiskCache cache("");
  SamplingResult value;
  EXPECT_FALSE(cache.Store("sampling", 1, value));
  EXPECT_FALSE(cache.Load("sampling", 1, &value));
}

TEST(WriteFileAtomically, ReplacesContentAndLeavesNoTemporaryFile) {
  TempDir tmp;
  const std::string path = tmp.File("a/b/file.txt");
  WriteFileAtomically(path, "one");
  WriteFileAtomically(path, "two");
  EXPECT_EQ(testing::ReadText(path), "two");
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(tmp.File("a/b"))) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 1);
}

TEST(RunOutputs, FailuresCsvIsSortedUniqueAndRoundTrips) {
  std::vector<Failure> failures = {{"pair", "b", "c", "solver, \"diverged\"\nline 2"},
                                   {"shape", "a", "", "bad mesh"},
                                   {"pair", "a", "b", "x"},
                                   {"pair", "a", "b", "x"}};
  const std::string text = FailuresCsv(failures);
  EXPECT_EQ(text,
            "kind,source,target,message\npair,a,b,x\n"
            "pair,b,c,\"solver, \"\"diverged\"\"\nline 2\"\nshape,a,,bad mesh\n");
  const std::vector<Failure> parsed = ParseFailuresCsv(text, "f.csv");
  ASSERT_EQ(parsed.size(), 3u);
  EXPECT_EQ(parsed[1].message, "solver, \"diverged\"\nline 2");
  EXPECT_EQ(parsed[2].target, "");
  EXPECT_THROW(ParseFailuresCsv("a,b\n", "f.csv"), InvalidInputError);
}

TEST(RunOutputs, ShapeRecordRoundTrips) {
  ShapeRecord record{"cat0", {{"load", 0.25, false}, {"embedding", 1.5, true}}, {{"samples", 1000}}};
  const ShapeRecord parsed = ParseShapeRecord("cat0", FormatShapeRecord(record), "r");
  ASSERT_EQ(parsed.times.size(), 2u);
  EXPECT_EQ(parsed.times[1].stage, "embedding");
  EXPECT_EQ(parsed.times[1].seconds, 1.5);
  EXPECT_TRUE(parsed.times[1].cached);
  EXPECT_EQ(parsed.report, record.report);
  EXPECT_THROW(ParseShapeRecord("x", "time\tonly\n", "r"), InvalidInputError);
}

TEST(Progress, FormatsCountRateAndEta) {
  EXPECT_EQ(FormatProgress("base: pairs", 10, 40, 5.0), "base: pairs  10/40  2.00/s  ETA 0:15");
  EXPECT_EQ(FormatProgress("base: pairs", 0, 40, 0.0), "base: pairs  0/40  0.00/s");
  std::ostringstream out;
  {
    Progress progress("x", 2, ProgressMode::kPlain, out, 1e9);
    progress.Tick();
    progress.Tick();
  }
  EXPECT_EQ(out.str().substr(0, 8), "x  2/2  ");  // one final line only
  std::ostringstream quiet;
  {
    Progress progress("x", 2, ProgressMode::kQuiet, quiet);
    progress.Tick();
  }
  EXPECT_TRUE(quiet.str().empty());
}

}  // namespace
}  // namespace symembed
