#include <stdio.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "apps/args.h"
#include "apps/commands.h"
#include "core/errors.h"
#include "core/files.h"
#include "harness/config.h"
#include "harness/slurm_scripts.h"
#include "registry/registry.h"

namespace fs = std::filesystem;

namespace symembed {
namespace {

std::string Absolute(const std::string& path) {
  return fs::absolute(path).lexically_normal().string();
}

// The directory of PATH holding an executable `name`, or empty.
std::string FindOnPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (!dir.empty() && access((dir + "/" + name).c_str(), X_OK) == 0) return dir;
  }
  return "";
}

// The shapes and pairs of the variants the jobs run (their datasets are loaded, which also
// generates a synthetic one once, here, instead of in every task).
struct StudySize {
  int shapes = 0;
  int pairs = 0;
  int max_pair_shards = 0;
  int variants = 0;
};

StudySize MeasureStudy(const ExperimentConfig& config, const Registry& registry,
                       const std::string& variant, ShardSplit split) {
  StudySize size;
  for (const VariantConfig& v : config.variants) {
    if (!variant.empty() && v.name != variant) continue;
    ++size.variants;
    const Pipeline pipeline = BuildPipeline(config, v, registry);
    const std::vector<DatasetPair> pairs = SortedPairs(pipeline.dataset->Load().pairs);
    size.shapes = std::max(size.shapes, static_cast<int>(ShapesOfPairs(pairs).size()));
    size.pairs = std::max(size.pairs, static_cast<int>(pairs.size()));
    size.max_pair_shards = std::max(size.max_pair_shards, MaxPairShards(pairs, split));
  }
  if (size.variants == 0) {
    throw ConfigError(config.file + ": no variant '" + variant + "'");
  }
  return size;
}

// Runs submit.sh and returns its stdout ("shapes job ID" ...); sbatch's errors reach stderr.
std::string Submit(const std::string& submit_script) {
  if (FindOnPath("sbatch").empty()) {
    throw IoError(
        "sbatch not found on PATH: --submit needs the Slurm client commands (Debian "
        "package slurm-client); the scripts are written, submit them later with " +
        submit_script);
  }
  FILE* pipe = popen(("bash " + ShellQuote(submit_script)).c_str(), "r");
  if (!pipe) throw IoError("cannot run " + submit_script);
  std::string out;
  char buffer[256];
  while (fgets(buffer, sizeof buffer, pipe)) out += buffer;
  const int status = pclose(pipe);
  if (status != 0) {
    throw IoError("submitting failed (" + submit_script + " exited with status " +
                  std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : status) +
                  "; sbatch's message is above)" +
                  (out.empty() ? "" : "; submitted so far:\n" + out));
  }
  return out;
}

// The command's options.
ArgParser SlurmParser() {
  ArgParser parser(
      "slurm",
      "Write sbatch scripts that run the study CONFIG on a Slurm cluster, and with --submit "
      "submit them: an array job filling the shared per-shape cache (each shape computed by one "
      "task), an array job of pair shards after it (symembed run --shard I/N --resume, each into "
      "OUT/shards/I), and a merge job after that (symembed merge, which refuses an unfinished "
      "set and names the shards to rerun). Scripts and logs go to OUT/slurm/ (docs/cluster.md).");
  parser.Option("shards", "tasks of each array job (capped by the shapes and the pair groups)", "");
  parser.Option("out", "output folder (on a file system every node sees)", "results/<config name>");
  parser.Option("cache", "per-shape cache shared by the tasks (every node sees it)",
                "results/.cache");
  parser.Option("shard-by",
                "how the pair tasks split the pairs: target (each target's evaluation distances "
                "computed once) or pair (balanced to one pair)",
                "target");
  parser.Option("partition", "Slurm partition (--partition); default: the cluster's", "");
  parser.Option("time", "time limit per task (--time, e.g. 1:00:00)", "");
  parser.Option("cpus", "CPUs per task (--cpus-per-task; each task runs that many threads)", "1");
  parser.Option("mem", "memory per task (--mem, e.g. 8G)", "");
  parser.Repeated("sbatch", "another #SBATCH option for every job (e.g. --sbatch --account=lab)");
  parser.Option("variant", "run only this variant", "");
  parser.Repeated("set", "override dotted.path=value in the base and every variant");
  parser.Option("symembed", "the symembed executable the jobs run", "this one");
  parser.Switch("submit", "submit the jobs with sbatch and print their ids");
  parser.Positionals("CONFIG", "the experiment's YAML file", 1, 1);
  return parser;
}

// The job options given on the command line (not those that depend on the study).
SlurmOptions SlurmJobOptions(const ArgParser& parser) {
  SlurmOptions options;
  try {
    options.split = ParseShardSplit(parser.Get("shard-by"));
  } catch (const ConfigError& e) {
    throw UsageError{std::string("--shard-by: ") + e.what()};
  }
  options.cpus = parser.GetInt("cpus");
  options.partition = parser.Get("partition");
  options.time = parser.Get("time");
  options.mem = parser.Get("mem");
  options.sbatch_args = parser.GetAll("sbatch");
  options.variant = parser.Get("variant");
  options.sets = parser.GetAll("set");
  return options;
}

// Writes the scripts into OUT/slurm/ (submit.sh executable); returns that folder.
std::string WriteSlurmScripts(const SlurmOptions& options, const SlurmScripts& scripts) {
  const std::string dir = SlurmScriptDir(options.out_dir);
  fs::create_directories(SlurmLogDir(options.out_dir));
  WriteFileAtomically(dir + "/shapes.sbatch", scripts.shapes);
  WriteFileAtomically(dir + "/pairs.sbatch", scripts.pairs);
  WriteFileAtomically(dir + "/merge.sbatch", scripts.merge);
  WriteFileAtomically(dir + "/submit.sh", scripts.submit);
  fs::permissions(dir + "/submit.sh", fs::perms::owner_exec | fs::perms::group_exec,
                  fs::perm_options::add);
  return dir;
}

// What the three jobs will do, on stdout.
void PrintSlurmPlan(const std::string& name, const StudySize& size, const SlurmOptions& options,
                    int shards, const std::string& dir) {
  std::cout << "symembed slurm: " << name << ", " << size.variants << " variant(s), "
            << size.shapes << " shapes, " << size.pairs << " pairs; scripts in " << dir << "\n"
            << "  shapes.sbatch  " << options.shape_tasks << " array tasks: the per-shape stages "
            << "of every variant into " << options.cache_dir << ", each shape in one task\n"
            << "  pairs.sbatch   " << options.pair_tasks << " array tasks, after the shapes job: "
            << "the pairs split by " << ShardSplitName(options.split) << ", task I into "
            << options.out_dir << "/shards/I\n"
            << "  merge.sbatch   after the pairs job: the shards merged into " << options.out_dir
            << "\n";
  if (options.shape_tasks < shards || options.pair_tasks < shards) {
    std::cout << "  (--shards " << shards << " capped: " << size.shapes << " shapes, "
              << size.max_pair_shards << " pair groups split by " << ShardSplitName(options.split)
              << ")\n";
  }
}

}  // namespace

int SlurmCommand(const Args& args) {
  ArgParser parser = SlurmParser();
  if (!parser.Parse(args)) return 0;
  if (!parser.Given("shards")) throw UsageError{"--shards N is required"};
  const int shards = parser.GetInt("shards");
  if (shards < 1) throw UsageError{"--shards: must be >= 1, got " + std::to_string(shards)};
  SlurmOptions options = SlurmJobOptions(parser);

  const std::string config_path = parser.positionals()[0];
  if (!fs::is_regular_file(config_path)) throw ConfigError(config_path + ": no such config file");
  Registry registry;
  RegisterBuiltinStages(registry);
  const ExperimentConfig config =
      LoadExperimentConfig(config_path, registry, options.sets, options.variant);
  const StudySize size = MeasureStudy(config, registry, options.variant, options.split);
  if (size.pairs == 0) throw ConfigError(config_path + ": the dataset has no pairs");

  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  options.binary = parser.Given("symembed") ? Absolute(parser.Get("symembed"))
                                            : (ec ? std::string() : self.string());
  if (options.binary.empty())
    throw UsageError{"cannot tell this executable's path; give --symembed"};
  options.config = Absolute(config_path);
  options.workdir = fs::current_path().string();
  options.out_dir = Absolute(parser.Given("out") ? parser.Get("out") : "results/" + config.name);
  options.cache_dir = Absolute(parser.Get("cache"));
  options.job_name = "symembed-" + config.name;
  options.shape_tasks = std::min(shards, size.shapes);
  options.pair_tasks = std::min(shards, size.max_pair_shards);
  const std::string dir = WriteSlurmScripts(options, MakeSlurmScripts(options));
  PrintSlurmPlan(config.name, size, options, shards, dir);
  if (!parser.Flag("submit")) {
    std::cout << "to submit (or run again with --submit): " << ShellQuote(dir + "/submit.sh")
              << "\nwhich runs:\n"
              << "  sbatch --parsable " << ShellQuote(dir + "/shapes.sbatch") << "\n"
              << "  sbatch --parsable --dependency=afterany:SHAPES_JOB "
              << ShellQuote(dir + "/pairs.sbatch") << "\n"
              << "  sbatch --parsable --dependency=afterany:PAIRS_JOB "
              << ShellQuote(dir + "/merge.sbatch") << "\n";
    return 0;
  }
  // Markers left by an earlier submission into OUT would let the merge take a task that never
  // ran this time for finished; the tasks write them again (and resume what is done).
  for (int i = 0; i < options.pair_tasks; ++i) {
    fs::remove(ShardMarkerPath(SlurmShardDir(options.out_dir, i)), ec);
  }
  std::cout << Submit(dir + "/submit.sh") << "logs in " << SlurmLogDir(options.out_dir)
            << "; the results are in " << options.out_dir
            << " when the merge job has ended (see merge.log)\n";
  return 0;
}

}  // namespace symembed
