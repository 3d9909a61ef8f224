// symembed: the command line of the harness.
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "apps/args.h"
#include "apps/commands.h"
#include "core/errors.h"

namespace {

struct Command {
  int (*run)(const symembed::Args&);
  const char* summary;
};

const std::map<std::string, Command>& Commands() {
  static const std::map<std::string, Command> commands = {
      {"run", {symembed::RunCommand, "run an experiment (all variants) from a YAML config"}},
      {"eval", {symembed::EvalCommand, "score a folder of A_B.map files against ground truth"}},
      {"check", {symembed::CheckCommand, "compare a summary.json with a committed baseline"}},
      {"merge", {symembed::MergeCommand, "join the outputs of sharded runs"}},
      {"slurm", {symembed::SlurmCommand, "write (and submit) the sbatch jobs of a study on Slurm"}},
      {"stages", {symembed::StagesCommand, "list the registered stages (kind, name, description)"}},
      {"remesh", {symembed::RemeshCommand, "write a remeshed copy of a ground-truth dataset"}},
      {"synth", {symembed::SynthCommand, "generate a synthetic ground-truth dataset"}},
      {"validate", {symembed::ValidateCommand, "print the validation report of meshes"}},
      {"report", {symembed::ReportCommand, "write the HTML report of a results folder"}},
  };
  return commands;
}

void PrintUsage(std::ostream& out) {
  out << "usage: symembed COMMAND [options] [args]\n\ncommands:\n";
  for (const auto& [name, cmd] : Commands()) {
    out << "  " << name << std::string(10 - name.size(), ' ') << cmd.summary << "\n";
  }
  out << "\n'symembed COMMAND --help' describes a command.\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    PrintUsage(args.empty() ? std::cerr : std::cout);
    return args.empty() ? 2 : 0;
  }
  auto it = Commands().find(args[0]);
  if (it == Commands().end()) {
    std::cerr << "symembed: unknown command '" << args[0] << "'\n\n";
    PrintUsage(std::cerr);
    return 2;
  }
  try {
    return it->second.run(std::vector<std::string>(args.begin() + 1, args.end()));
  } catch (const symembed::UsageError& e) {
    std::cerr << "symembed " << args[0] << ": " << e.message << "\n"
              << "run 'symembed " << args[0] << " --help' for usage\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "symembed " << args[0] << ": error: " << e.what() << "\n";
    return 1;
  }
}
