// `symembed run` and `symembed merge` as a user runs them, with the default stages on a small
// synthetic dataset: a run killed while it writes pair records and resumed gives the outputs
// of an uninterrupted run; shards merged give them too; a bad mesh is recorded, exit code 1.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <sstream>
#include <thread>

#include "core/mesh_io.h"
#include "tests/harness/run_outputs_fixture.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

using testing::Symembed;

namespace fs = std::filesystem;
using testing::OutputsWithoutTimings;
using testing::ReadText;
using testing::TempDir;
using testing::WriteText;

// Starts the binary with args (stdout and stderr to log); returns its pid.
pid_t Spawn(const std::vector<std::string>& args, const std::string& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
    }
    std::vector<char*> argv = {const_cast<char*>(SYMEMBED_BINARY)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(SYMEMBED_BINARY, argv.data());
    _exit(127);
  }
  return pid;
}

int CountFiles(const std::string& dir, const std::string& extension) {
  int n = 0;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().extension() == extension) ++n;
  }
  return n;
}

// A small synthetic dataset (5 poses: 10 pairs) and a fast config of the default pipeline.
class RunCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string out;
    ASSERT_EQ(Symembed("synth --poses 5 --vertices 600 --out " + tmp_.File("data"), &out), 0) << out;
    config_ = tmp_.File("config.yaml");
    WriteText(config_,
              "name: small\n"
              "dataset: {format: pairs_vts, root: " + tmp_.File("data") + "}\n"
              "pipeline:\n"
              "  sampling: {type: farthest_point, count: 80}\n"
              "  symmetry: {type: plane3d}\n"
              "evaluation: {geodesics: dijkstra}\n");
  }

  std::string Run(const std::string& out, const std::string& extra, int expected_exit = 0) {
    std::string log;
    EXPECT_EQ(Symembed("run " + config_ + " --quiet --jobs 2 --cache " + tmp_.File("cache") +
                           " --out " + out + " " + extra, &log),
              expected_exit)
        << log;
    return log;
  }

  // Starts a run with one job and a cache of its own (cold) into `out`, and kills it with
  // SIGKILL as soon as a pair record exists.
  void KillAfterFirstRecord(const std::string& out, const std::string& cache) {
    const std::string log_file = out + ".killed.log";
    const pid_t pid =
        Spawn({"run", config_, "--jobs", "1", "--cache", cache, "--out", out}, log_file);
    ASSERT_GT(pid, 0);
    const int before = CountFiles(out + "/base/pairs", ".rec");
    int status = 0;
    bool exited = false;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
    // A run without --resume first deletes the earlier run's records, then writes its own.
    while (before > 0 && CountFiles(out + "/base/pairs", ".rec") >= before) {
      ASSERT_LT(std::chrono::steady_clock::now(), deadline);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    while (CountFiles(out + "/base/pairs", ".rec") < 1) {
      if (waitpid(pid, &status, WNOHANG) == pid) {
        exited = true;
        break;
      }
      ASSERT_LT(std::chrono::steady_clock::now(), deadline);
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    if (!exited) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
    }
    ASSERT_FALSE(exited) << "the run finished before it could be killed: "
                         << ReadText(log_file);
  }

  TempDir tmp_;
  std::string config_;
};

TEST_F(RunCommandTest, KilledRunResumesToTheOutputsOfAnUninterruptedRun) {
  Run(tmp_.File("full"), "");
  const auto full = OutputsWithoutTimings(tmp_.File("full"));
  ASSERT_TRUE(full.count("base/summary.json"));
  ASSERT_TRUE(full.count("comparison.csv"));
  const int pairs = CountFiles(tmp_.File("full/base/pairs"), ".rec");
  ASSERT_EQ(pairs, 10);

  const std::string killed = tmp_.File("killed");
  ASSERT_NO_FATAL_FAILURE(KillAfterFirstRecord(killed, tmp_.File("cache2")));
  const int done = CountFiles(killed + "/base/pairs", ".rec");
  EXPECT_LT(done, pairs);
  EXPECT_FALSE(fs::exists(killed + "/base/summary.json"));
  EXPECT_TRUE(fs::exists(killed + "/base/IN_PROGRESS"));

  const std::string log = Run(killed, "--resume");
  EXPECT_FALSE(fs::exists(killed + "/base/IN_PROGRESS"));
  EXPECT_EQ(OutputsWithoutTimings(killed), full);
}

// Two runs into one folder would mix their outputs (one's config, the other's maps): a second
// run into a folder in use fails at once, naming the folder and the first run, and leaves the
// first's outputs alone; once the first has finished, the folder is free again.
TEST_F(RunCommandTest, ASecondRunIntoAFolderInUseFailsAtOnceNamingTheFirst) {
  const std::string out = tmp_.File("busy");
  const pid_t first =
      Spawn({"run", config_, "--jobs", "1", "--cache", tmp_.File("cold"), "--out", out},
            out + ".first.log");
  ASSERT_GT(first, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(2);
  while (!fs::exists(out + "/.symembed.lock") ||
         ReadText(out + "/.symembed.lock").find("pid ") == std::string::npos) {
    ASSERT_LT(std::chrono::steady_clock::now(), deadline);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const std::string log = Run(out, "--set pipeline.sampling.count=60", 1);
  EXPECT_NE(log.find(out + ": in use by another symembed command (pid " + std::to_string(first)),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("symembed run"), std::string::npos) << log;
  int status = 0;
  ASSERT_EQ(waitpid(first, &status, 0), first);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << ReadText(out + ".first.log");
  EXPECT_NE(ReadText(out + "/base/config.yaml").find("count: 80"), std::string::npos);
  EXPECT_EQ(CountFiles(out + "/base/pairs", ".rec"), 10);
  EXPECT_FALSE(fs::exists(out + "/.symembed.lock"));  // removed by its holder
  Run(out, "--resume");
}

// A run without --resume into an earlier run's folder starts it empty: the earlier run's maps
// and records of pairs the new run does not have would be read as the new run's.
TEST_F(RunCommandTest, ARunWithoutResumeLeavesNoMapOrRecordOfAnEarlierRun) {
  const std::string out = tmp_.File("again");
  Run(out, "");
  ASSERT_EQ(CountFiles(out + "/base/pairs", ".rec"), 10);
  Run(out, "--set dataset.max_pairs=3");
  EXPECT_EQ(CountFiles(out + "/base/pairs", ".rec"), 3);
  EXPECT_EQ(CountFiles(out + "/base/maps", ".map"), 3);
  EXPECT_NE(ReadText(out + "/base/summary.json").find("\"pairs\": 3,"), std::string::npos);
}

// A later variant's dataset that cannot be read ends the run before the first variant computes
// anything, naming the config, the variant and the problem.
TEST_F(RunCommandTest, AVariantWhoseDatasetCannotBeReadStopsTheRunBeforeAnyWork) {
  WriteText(config_, ReadText(config_) + "variants:\n"
                                         "  - {name: elsewhere, set: {dataset.root: " +
                         tmp_.File("nowhere") + "}}\n");
  const std::string out = tmp_.File("early");
  const std::string log = Run(out, "", 1);
  EXPECT_NE(log.find(config_ + ":8:"), std::string::npos) << log;  // the variant's root
  EXPECT_NE(log.find("dataset of variant 'elsewhere'"), std::string::npos) << log;
  EXPECT_NE(log.find(tmp_.File("nowhere")), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(out + "/base/summary.json"));
  EXPECT_EQ(CountFiles(out + "/base/maps", ".map"), 0);
  EXPECT_FALSE(fs::exists(tmp_.File("cache")) && !fs::is_empty(tmp_.File("cache")));
}

// A cache folder that cannot be written (/proc refuses new files even to root) stays empty: a
// run says so once and goes on; a --shapes-only run, whose only product is the cache, fails.
TEST_F(RunCommandTest, AnUnwritableCacheIsSaidOnceAndFailsAShapesOnlyRun) {
  std::string log;
  EXPECT_EQ(Symembed("run " + config_ + " --jobs 2 --cache /proc --no-report --out " +
                         tmp_.File("nocache"),
                     &log),
            0)
      << log;
  const std::string warning = "/proc: the cache folder is not writable";
  ASSERT_NE(log.find(warning), std::string::npos) << log;
  EXPECT_EQ(log.find(warning, log.find(warning) + 1), std::string::npos) << log;
  EXPECT_EQ(Symembed("run " + config_ + " --shapes-only --cache /proc", &log), 1)
      << log;
  EXPECT_NE(log.find(warning + "; a --shapes-only run writes only the cache"), std::string::npos)
      << log;
}

// A run started without --resume into the folder of a finished run and killed must not leave
// the old run's summary beside its own config, and readers of results refuse the folder.
TEST_F(RunCommandTest, KilledRunOverAnEarlierRunLeavesAFolderMarkedIncomplete) {
  const std::string out = tmp_.File("out");
  Run(out, "");
  ASSERT_TRUE(fs::exists(out + "/base/summary.json"));
  ASSERT_NO_FATAL_FAILURE(KillAfterFirstRecord(out, tmp_.File("cold")));
  EXPECT_TRUE(fs::exists(out + "/base/IN_PROGRESS"));
  for (const char* file : {"summary.json", "pairs.csv", "curve.csv", "failures.csv"}) {
    EXPECT_FALSE(fs::exists(out + "/base/" + file)) << file;
  }
  std::string log;
  EXPECT_EQ(Symembed("merge --out " + tmp_.File("merged") + " " + out, &log), 1) << log;
  EXPECT_NE(log.find(out + "/base: the folder is incomplete"), std::string::npos) << log;
  EXPECT_NE(Symembed("eval --dataset " + config_ + " --maps " + out + "/base/maps --base 1 " +
                         "--name x --out " + tmp_.File("eval"),
                     &log),
            0)
      << log;
  EXPECT_NE(log.find(out + "/base: the folder is incomplete"), std::string::npos) << log;
}

// The curve plot helper ends with its parent: a run killed while it plots leaves no process
// that writes figures later. A stand-in plot script (found through SYMEMBED_ROOT) records its
// pid, then writes a file after a pause.
TEST_F(RunCommandTest, KilledWhilePlottingLeavesNoPlotHelperBehind) {
  const std::string root = tmp_.File("root");
  WriteText(root + "/scripts/plot-curves",
            "import os, sys, time\n"
            "open(sys.argv[1] + '/plot.pid', 'w').write(str(os.getpid()))\n"
            "time.sleep(3)\n"
            "open(sys.argv[1] + '/plot.late', 'w').write('late')\n");
  const std::string out = tmp_.File("out");
  setenv("SYMEMBED_ROOT", root.c_str(), 1);
  const pid_t pid = Spawn({"run", config_, "--jobs", "2", "--cache", tmp_.File("cache"), "--out",
                           out},
                          tmp_.File("plot.log"));
  unsetenv("SYMEMBED_ROOT");
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  while (!fs::exists(out + "/plot.pid") || ReadText(out + "/plot.pid").empty()) {
    int status = 0;
    ASSERT_NE(waitpid(pid, &status, WNOHANG), pid) << ReadText(tmp_.File("plot.log"));
    ASSERT_LT(std::chrono::steady_clock::now(), deadline);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  const pid_t helper = std::stoi(ReadText(out + "/plot.pid"));
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  // The helper is not our child: poll until it is gone (or a zombie reaped by init).
  bool gone = false;
  for (int i = 0; i < 200 && !gone; ++i) {
    const std::string stat = "/proc/" + std::to_string(helper) + "/stat";
    gone = !fs::exists(stat) || ReadText(stat).find(") Z ") != std::string::npos;
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(gone) << "plot helper " << helper << " outlived the run";
  std::this_thread::sleep_for(std::chrono::milliseconds(3500));
  EXPECT_FALSE(fs::exists(out + "/plot.late"));
}

TEST_F(RunCommandTest, ShardsMergedEqualASingleRun) {
  Run(tmp_.File("full"), "");
  std::string shards;
  for (int i = 0; i < 3; ++i) {
    const std::string dir = tmp_.File("shard" + std::to_string(i));
    Run(dir, "--shard " + std::to_string(i) + "/3");
    shards += " " + dir;
  }
  std::string log;
  ASSERT_EQ(Symembed("merge --out " + tmp_.File("merged") + shards, &log), 0) << log;
  EXPECT_EQ(OutputsWithoutTimings(tmp_.File("merged")), OutputsWithoutTimings(tmp_.File("full")));
}

// merge proves each pair of a shard as --resume does: a record deleted, a map deleted or cut
// short after the shard finished is named (with what to do), not merged as ok; --resume of the
// shard computes it again and the merge goes through.
TEST_F(RunCommandTest, MergeProvesEachPairOfItsShards) {
  std::string shards;
  for (int i = 0; i < 2; ++i) {
    const std::string dir = tmp_.File("part" + std::to_string(i));
    Run(dir, "--shard " + std::to_string(i) + "/2");
    shards += " " + dir;
  }
  const std::string pairs = tmp_.File("part0/base/pairs");
  const std::string maps = tmp_.File("part0/base/maps");
  std::vector<fs::path> records;
  for (const auto& entry : fs::directory_iterator(pairs)) records.push_back(entry.path());
  std::sort(records.begin(), records.end());
  ASSERT_GE(records.size(), 3u);
  const auto map_of = [&](const fs::path& record) {
    return maps + "/" + record.stem().string() + ".map";
  };
  const auto merge_fails_naming = [&](const std::string& what) {
    std::string log;
    EXPECT_EQ(Symembed("merge --no-report --out " + tmp_.File("merged") + shards, &log), 1)
        << log;
    EXPECT_NE(log.find(what), std::string::npos) << log;
    EXPECT_NE(log.find("rerun this run (or shard) with --resume"), std::string::npos) << log;
  };
  // A map cut to 10 lines (restored after), a map deleted (restored after), a record deleted.
  const std::string map = map_of(records[2]), full_map = ReadText(map);
  std::string head;
  for (size_t line = 0, at = 0; line < 10; ++line) {
    const size_t end = full_map.find('\n', at);
    head += full_map.substr(at, end + 1 - at);
    at = end + 1;
  }
  WriteText(map, head);
  merge_fails_naming(map + ":");
  WriteText(map, full_map);
  fs::remove(map);
  merge_fails_naming(map);
  WriteText(map, full_map);
  fs::remove(records[0]);
  merge_fails_naming("as ok, but its record " + records[0].string() + " is missing");
  Run(tmp_.File("part0"), "--shard 0/2 --resume");
  std::string log;
  EXPECT_EQ(Symembed("merge --no-report --out " + tmp_.File("merged") + shards, &log), 0) << log;
  EXPECT_EQ(CountFiles(tmp_.File("merged/base/pairs"), ".rec"), 10);
}

// What `symembed slurm` runs: shapes-only shards (each shape computed in one), pair shards
// split by target; a shard that was killed and one that never started make merge refuse and
// print the commands that finish them, which it then merges into the single run's outputs.
TEST_F(RunCommandTest, ShapesOnlyAndTargetShardsMergeAndUnfinishedShardsAreNamedAndResumed) {
  Run(tmp_.File("full"), "");
  std::string shape_logs;
  for (int i = 0; i < 2; ++i) {
    std::string log;
    ASSERT_EQ(Symembed("run " + config_ + " --shapes-only --shard " + std::to_string(i) +
                           "/2 --jobs 2 --cache " + tmp_.File("cache2"),
                       &log),
              0)
        << log;
    shape_logs += log;
  }
  // 5 shapes, each computed by one of the two shards.
  int computed = 0;
  for (size_t at = shape_logs.find("[base]: computed"); at != std::string::npos;
       at = shape_logs.find("[base]: computed", at + 1)) {
    ++computed;
  }
  EXPECT_EQ(computed, 5) << shape_logs;
  EXPECT_FALSE(fs::exists(tmp_.File("shards"))) << "a shapes-only run writes no outputs";

  std::string merge_args;
  for (int i = 0; i < 3; ++i) {
    const std::string dir = tmp_.File("shards/" + std::to_string(i));
    std::string log;
    ASSERT_EQ(Symembed("run " + config_ + " --shard " + std::to_string(i) +
                           "/3 --shard-by target"
                           " --jobs 2 --cache " +
                           tmp_.File("cache2") + " --out " + dir,
                       &log),
              0)
        << log;
    const size_t at = log.find("stages computed: ");
    ASSERT_NE(at, std::string::npos) << log;
    const std::string stages = log.substr(at, log.find(';', at) - at);
    for (const char* kind :
         {"preprocess=", "geodesics=", "embedding=", "symmetrize=", "laplace_basis=",
          "curvature_features=", "sample_geodesics="}) {
      EXPECT_EQ(stages.find(kind), std::string::npos) << "a shape was computed again: " << stages;
    }
    EXPECT_NE(ReadText(dir + "/shard.txt").find("status: complete"), std::string::npos);
    merge_args += " " + dir;
  }
  // Shard 1 killed (its marker still says running), shard 2 never started.
  const std::string marker = tmp_.File("shards/1/shard.txt");
  std::string text = ReadText(marker);
  text.replace(text.find("complete"), 8, "running");
  WriteText(marker, text);
  fs::remove_all(tmp_.File("shards/2"));
  std::string log;
  ASSERT_EQ(Symembed("merge --out " + tmp_.File("merged") + merge_args +
                         " --rerun-hint 'resubmit {shards}'",
                     &log),
            3)
      << log;
  EXPECT_NE(log.find("shard 1/3 (" + tmp_.File("shards/1") + "): started but did not finish"),
            std::string::npos)
      << log;
  EXPECT_NE(log.find("shard 2/3 (" + tmp_.File("shards/2") + "): never started"), std::string::npos)
      << log;
  EXPECT_NE(log.find("resubmit 1,2"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(tmp_.File("merged")));
  // The printed commands finish the set.
  std::istringstream lines(log);
  int reruns = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  cd ", 0) != 0) continue;
    std::string rerun_log;
    EXPECT_EQ(testing::RunShell(line.substr(2), &rerun_log), 0) << line << "\n" << rerun_log;
    ++reruns;
  }
  EXPECT_EQ(reruns, 2) << log;
  ASSERT_EQ(Symembed("merge --out " + tmp_.File("merged") + merge_args, &log), 0) << log;
  EXPECT_EQ(OutputsWithoutTimings(tmp_.File("merged")), OutputsWithoutTimings(tmp_.File("full")));
}

TEST_F(RunCommandTest, BadMeshIsRecordedAndTheExitCodeIs1) {
  std::string name;
  for (const auto& e : fs::directory_iterator(tmp_.File("data/shapes"))) {
    name = e.path().stem().string();
    WriteText(e.path().string(), "OFF\n3 1 0\n0 0 0\n");  // truncated
    break;
  }
  Run(tmp_.File("out"), "", 1);
  const std::string failures = ReadText(tmp_.File("out/base/failures.csv"));
  EXPECT_NE(failures.find("shape," + name + ",,"), std::string::npos) << failures;
  // The other shapes' pairs were computed: 4 of the 5 poses give 6 pairs.
  EXPECT_EQ(CountFiles(tmp_.File("out/base/pairs"), ".rec"), 6);
  EXPECT_TRUE(fs::exists(tmp_.File("out/base/summary.json")));
}

// Meshes accepted but wrong: a triangle soup is welded and runs; a body in two pieces fails
// with its file and the area it would lose; a small loose piece is dropped and counted.
TEST_F(RunCommandTest, SoupsAreWeldedAndMeshesInPiecesFailOrAreCounted) {
  std::vector<std::string> shapes;
  for (const auto& e : fs::directory_iterator(tmp_.File("data/shapes"))) {
    shapes.push_back(e.path().string());
  }
  std::sort(shapes.begin(), shapes.end());
  ASSERT_GE(shapes.size(), 3u);
  // Soup: the input vertices first (the ground truth's ids), unreferenced, then three copies
  // per face.
  const Surface soup_source = LoadSurface(shapes[0]);
  Surface soup;
  const int nv = soup_source.NumVertices(), nf = soup_source.NumFaces();
  soup.V.resize(nv + 3 * nf, 3);
  soup.V.topRows(nv) = soup_source.V;
  soup.F.resize(nf, 3);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      soup.V.row(nv + 3 * f + k) = soup_source.V.row(soup_source.F(f, k));
      soup.F(f, k) = nv + 3 * f + k;
    }
  }
  SaveMesh(shapes[0], soup);
  // Two pieces of equal area; one with a piece of about 1% of its area.
  auto with_copy = [](const Surface& s, double scale) {
    Surface out;
    out.V.resize(2 * s.NumVertices(), 3);
    out.V << s.V, (s.V * scale).rowwise() + Eigen::RowVector3d(10, 0, 0);
    out.F.resize(2 * s.NumFaces(), 3);
    out.F << s.F, (s.F.array() + s.NumVertices()).matrix();
    return out;
  };
  SaveMesh(shapes[1], with_copy(LoadSurface(shapes[1]), 1.0));
  SaveMesh(shapes[2], with_copy(LoadSurface(shapes[2]), 0.1));
  Run(tmp_.File("out"), "", 1);
  const std::string failures = ReadText(tmp_.File("out/base/failures.csv"));
  const std::string split = fs::path(shapes[1]).stem().string();
  EXPECT_NE(failures.find("shape," + split + ",," + shapes[1] +
                          ": preprocess: the mesh has 2 connected components and keeping the "
                          "largest would remove 50.0% of its area"),
            std::string::npos)
      << failures;
  // The header, the split shape and its four pairs.
  EXPECT_EQ(std::count(failures.begin(), failures.end(), '\n'), 1 + 1 + 4) << failures;
  const std::string shapes_csv = ReadText(tmp_.File("out/base/shapes.csv"));
  EXPECT_NE(shapes_csv.find("welded_vertices"), std::string::npos);
  const std::string summary = ReadText(tmp_.File("out/base/summary.json"));
  EXPECT_NE(summary.find("\"shapes_lost_area\": 1"), std::string::npos) << summary;
  // Every pair without the split shape, the soup's included, was computed.
  EXPECT_EQ(CountFiles(tmp_.File("out/base/pairs"), ".rec"), 6);
}

// The flip scorer's orientation term needs 60 eigenpairs, the icp refinement asks for 20: each
// prepares its own basis and the larger one must survive for both.
TEST_F(RunCommandTest, StagesPreparingBasesOfDifferentSizesShareTheLargerOne) {
  Run(tmp_.File("out"), "--set pipeline.refine.type=icp --set pipeline.refine.k=20");
  EXPECT_EQ(ReadText(tmp_.File("out/base/failures.csv")), "kind,source,target,message\n");
  EXPECT_EQ(CountFiles(tmp_.File("out/base/pairs"), ".rec"), 10);
}

// shapes.csv: one row per shape with its report, including how well the symmetric embedding
// matches the dataset's symmetric ground truth and how far the symmetry's self map moves the
// samples. The synthetic poses are mirror-symmetric, and
// with the left-right plane found (plane2d; this fixture's fast plane3d on 80 samples finds it
// on none of these small humanoids) each mirrored point lands near its partner.
TEST_F(RunCommandTest, ShapesCsvHasEveryShapeAndTheSymmetryAgainstGroundTruth) {
  Run(tmp_.File("out"), "--set pipeline.symmetry.type=plane2d");
  std::istringstream csv(ReadText(tmp_.File("out/base/shapes.csv")));
  std::string header;
  ASSERT_TRUE(std::getline(csv, header));
  std::vector<std::string> columns;
  std::istringstream fields(header);
  for (std::string c; std::getline(fields, c, ',');) columns.push_back(c);
  ASSERT_EQ(columns.front(), "shape");
  const auto at = std::find(columns.begin(), columns.end(), "symmetry_gt_error");
  ASSERT_NE(at, columns.end()) << header;
  // The left-right self map moves the limbs across the body, far from the identity.
  const auto moved = std::find(columns.begin(), columns.end(), "self_map_displacement");
  ASSERT_NE(moved, columns.end()) << header;
  ASSERT_NE(std::find(columns.begin(), columns.end(), "canonical_x_spread"), columns.end());
  // The poses are mirror images of themselves, so their own distances are near symmetric.
  const auto own = std::find(columns.begin(), columns.end(), "gt_geodesic_asymmetry");
  ASSERT_NE(own, columns.end()) << header;
  int rows = 0;
  for (std::string line; std::getline(csv, line); ++rows) {
    std::vector<std::string> values;
    std::istringstream row(line);
    for (std::string v; std::getline(row, v, ',');) values.push_back(v);
    ASSERT_EQ(values.size(), columns.size()) << line;
    const double error = std::stod(values[at - columns.begin()]);
    EXPECT_GE(error, 0.0) << line;
    EXPECT_LT(error, 0.1) << line;
    EXPECT_GT(std::stod(values[moved - columns.begin()]), 0.3) << line;
    EXPECT_GE(std::stod(values[own - columns.begin()]), 0.0) << line;
    EXPECT_LT(std::stod(values[own - columns.begin()]), 0.02) << line;
  }
  EXPECT_EQ(rows, 5);
}

TEST(RunCommand, UsageErrorsExit2) {
  std::string out;
  EXPECT_EQ(Symembed("run", &out), 2) << out;
  EXPECT_EQ(Symembed("run c.yaml --shard 3/2", &out), 2) << out;
  EXPECT_NE(out.find("--shard"), std::string::npos) << out;
  EXPECT_EQ(Symembed("run c.yaml --jobs -1", &out), 2) << out;
  EXPECT_EQ(Symembed("run c.yaml --shard-by shape", &out), 2) << out;
  EXPECT_NE(out.find("pair, target"), std::string::npos) << out;
  EXPECT_EQ(Symembed("run c.yaml --shapes-only --out x", &out), 2) << out;
  EXPECT_EQ(Symembed("merge a b", &out), 2) << out;
  EXPECT_NE(out.find("--out"), std::string::npos) << out;
}

// A dataset whose poses are all cut by a plane: every pair has a part, which the default
// matching stage maps on the surfaces as well (where that map is kept, the flip stage's choice
// is unused and the refinement is the part's, core/fmap/partial_zoomout.h), and
// `partial_boundary_ratio: 0` sends every pair through the embeddings alone.
TEST(RunCommand, PairsWithAPartAreMatchedOnTheSurfacesUnlessTheRouteIsOff) {
  TempDir tmp;
  std::string out;
  ASSERT_EQ(Symembed("synth --poses 3 --vertices 1500 --plane-cuts 1 --out " + tmp.File("data"),
                     &out),
            0)
      << out;
  const std::string config = tmp.File("config.yaml");
  WriteText(config,
            "name: cuts\n"
            "dataset: {format: pairs_vts, root: " + tmp.File("data") + "}\n"
            "pipeline:\n"
            "  sampling: {type: farthest_point, count: 200}\n"
            "  refine: {type: discrete}\n"
            "evaluation: {geodesics: dijkstra}\n"
            "variants:\n"
            "  - {name: embeddings, set: {pipeline.matching.partial_boundary_ratio: 0}}\n");
  ASSERT_EQ(Symembed("run " + config + " --quiet --jobs 2 --no-report --cache " +
                         tmp.File("cache") + " --out " + tmp.File("out"),
                     &out),
            0)
      << out;
  const std::string base = ReadText(tmp.File("out/base/pairs.csv"));
  const std::string off = ReadText(tmp.File("out/embeddings/pairs.csv"));
  auto count = [](const std::string& text, const std::string& what) {
    int n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
  };
  // Every pair is mapped on the surfaces; the map kept is the one of lower distortion, and a
  // pair that keeps it is refined as a part's when the source is the part, else left.
  EXPECT_EQ(count(base, "the matching stage mapped the surfaces (partial: the "), 3) << base;
  EXPECT_EQ(
      count(base, "not used: the matching stage mapped the surfaces"),
      count(base, "partial zoomout (area ratio") + count(base, "not run: the source is the whole"));
  EXPECT_GE(count(base, "partial zoomout (area ratio"), 1) << base;
  EXPECT_GE(count(base, "not used: the matching stage mapped the surfaces"), 1) << base;
  EXPECT_EQ(off.find("mapped the surfaces"), std::string::npos) << off;
}

}  // namespace
}  // namespace symembed
