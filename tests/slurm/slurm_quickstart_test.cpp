// The quickstart study through a real Slurm (label `slurm`): `symembed slurm --submit` with 4
// shards on the single-node cluster of scripts/slurm-local, waited for, and compared with a
// single-machine run: the merged outputs are the same bytes (timings aside), and the per-shape
// stages were computed as often as in the single run, so by exactly one task each.
// Skipped, with the reason, when no Slurm answers: scripts/slurm-local start brings one up
// (scripts/test --slurm does, around ctest).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <thread>

#include "harness/shards.h"
#include "tests/harness/run_outputs_fixture.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

namespace fs = std::filesystem;
using testing::OutputsWithoutTimings;
using testing::ReadText;
using testing::RunShell;
using testing::SourceDir;
using testing::TempDir;

const char* const kShapeStages[] = {"preprocess",    "sampling",         "geodesics",
                                    "embedding",     "symmetry",         "symmetrize",
                                    "laplace_basis", "sample_geodesics", "curvature_features"};

// Why Slurm cannot be used here, or empty when it can (sets SLURM_CONF when it finds the
// local cluster's configuration).
std::string SlurmUnavailable() {
  std::string out;
  if (RunShell("command -v sbatch squeue scontrol", &out) != 0) {
    return "the Slurm commands are not installed (Debian slurm-wlm; scripts/install-deps --slurm)";
  }
  if (!std::getenv("SLURM_CONF")) {
    const char* dir = std::getenv("SYMEMBED_SLURM_DIR");
    const std::string conf = std::string(dir ? dir : "/tmp/symembed-slurm") + "/slurm.conf";
    if (fs::exists(conf)) setenv("SLURM_CONF", conf.c_str(), 1);
  }
  // The Slurm commands wait a minute for a missing slurm.conf to appear.
  const char* conf = std::getenv("SLURM_CONF");
  const std::string conf_path = conf ? conf : "/etc/slurm/slurm.conf";
  if (!fs::exists(conf_path)) {
    return "no " + conf_path + " (SLURM_CONF); start the local Slurm with scripts/slurm-local start";
  }
  if (RunShell("timeout 30 scontrol ping", &out) != 0 || out.find("is UP") == std::string::npos) {
    return "no Slurm controller answers (scontrol ping: " + out.substr(0, out.find('\n')) +
           "); start the local one with scripts/slurm-local start";
  }
  return "";
}

// Per-shape stage computations summed over the "stages computed: a=1 b=2; ..." lines of logs.
std::map<std::string, int> ShapeStagesComputed(const std::vector<std::string>& logs) {
  std::map<std::string, int> counts;
  const std::regex entry("([a-z_]+)=([0-9]+)");
  for (const std::string& log : logs) {
    std::istringstream lines(log);
    for (std::string line; std::getline(lines, line);) {
      const size_t at = line.find("stages computed: ");
      if (at == std::string::npos) continue;
      const std::string computed = line.substr(at, line.find(';', at) - at);
      for (std::sregex_iterator it(computed.begin(), computed.end(), entry), end; it != end; ++it) {
        for (const char* stage : kShapeStages) {
          if ((*it)[1] == stage) counts[stage] += std::stoi((*it)[2]);
        }
      }
    }
  }
  return counts;
}

// The outputs of a run folder without timings, without what the Slurm jobs add beside them.
std::map<std::string, std::string> StudyOutputs(const std::string& dir) {
  auto files = OutputsWithoutTimings(dir);
  for (auto it = files.begin(); it != files.end();) {
    const bool extra = it->first.rfind("slurm/", 0) == 0 || it->first.rfind("shards/", 0) == 0;
    it = extra ? files.erase(it) : std::next(it);
  }
  return files;
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

TEST(SlurmQuickstart, FourShardsThroughSlurmEqualASingleRunAndComputeEachShapeOnce) {
  const std::string reason = SlurmUnavailable();
  if (!reason.empty()) GTEST_SKIP() << reason;
  TempDir tmp;
  const std::string binary = SYMEMBED_BINARY;
  const std::string config = SourceDir() + "/configs/quickstart.yaml";
  const std::string in_tmp = "cd " + ShellQuote(tmp.path()) + " && ";

  auto start = std::chrono::steady_clock::now();
  std::string single_log;
  ASSERT_EQ(RunShell(in_tmp + ShellQuote(binary) + " run " + ShellQuote(config) +
                         " --jobs 2 --out single --cache single_cache",
                     &single_log),
            0)
      << single_log;
  const double single_seconds = Seconds(start);

  start = std::chrono::steady_clock::now();
  std::string submit_log;
  ASSERT_EQ(RunShell(in_tmp + ShellQuote(binary) + " slurm " + ShellQuote(config) +
                         " --shards 4 --cpus 1 --time 0:20:00 --out 'slurm study'"
                         " --cache slurm_cache --submit",
                     &submit_log),
            0)
      << submit_log;
  std::smatch ids;
  ASSERT_TRUE(std::regex_search(
      submit_log, ids, std::regex("shapes job ([0-9]+)\npairs job ([0-9]+)\nmerge job ([0-9]+)")))
      << submit_log;
  const std::string jobs = ids[1].str() + "," + ids[2].str() + "," + ids[3].str();
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(20);
  for (std::string queue;;) {
    ASSERT_EQ(RunShell("squeue -h -j " + jobs + " -o '%i %T %r'", &queue), 0) << queue;
    if (queue.find_first_not_of(" \n") == std::string::npos) break;
    if (std::chrono::steady_clock::now() > deadline) {
      RunShell("scancel " + jobs);
      FAIL() << "the jobs did not end within 20 minutes:\n" << queue;
    }
    std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  const double slurm_seconds = Seconds(start);
  const std::string out = tmp.File("slurm study");
  std::string merge_job;
  RunShell("scontrol show job " + ids[3].str(), &merge_job);
  EXPECT_NE(merge_job.find("JobState=COMPLETED"), std::string::npos)
      << merge_job << "\n"
      << ReadText(out + "/slurm/logs/merge.log");

  std::vector<std::string> task_logs;
  std::vector<std::string> pair_logs;
  for (const auto& e : fs::directory_iterator(out + "/slurm/logs")) {
    const std::string name = e.path().filename().string();
    task_logs.push_back(ReadText(e.path().string()));
    if (name.rfind("pairs-", 0) == 0) pair_logs.push_back(task_logs.back());
  }
  ASSERT_EQ(task_logs.size(), 9u);  // 4 shape tasks, 4 pair tasks, the merge
  const std::map<std::string, int> single = ShapeStagesComputed({single_log});
  ASSERT_FALSE(single.empty()) << single_log;
  EXPECT_EQ(ShapeStagesComputed(task_logs), single) << "a per-shape stage ran more often than in "
                                                       "the single run, so in two tasks";
  EXPECT_TRUE(ShapeStagesComputed(pair_logs).empty()) << "a pair task computed a shape";

  const auto expected = StudyOutputs(tmp.File("single"));
  ASSERT_TRUE(expected.count("base/summary.json"));
  EXPECT_EQ(StudyOutputs(out), expected);

  std::cout << "quickstart: single run " << single_seconds << " s; through Slurm (4 shards, "
            << "submit to the merge job's end) " << slurm_seconds << " s; per-shape stage runs "
            << "in the Slurm tasks equal the single run's (" << single.at("preprocess")
            << " preprocess, " << single.at("embedding") << " embeddings)\n";
}

}  // namespace
}  // namespace symembed
