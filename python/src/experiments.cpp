#include <pybind11/stl.h>
#include <yaml-cpp/yaml.h>

#include "apps/commands.h"
#include "apps/stage_options.h"
#include "core/errors.h"
#include "python/src/bindings.h"
#include "python/src/pipeline.h"

namespace symembed::python {
namespace {

using namespace pybind11::literals;

// A YAML value as Python: null, bool, int and float scalars as such, other scalars as str,
// sequences as lists, maps as dicts.
py::object FromYaml(const YAML::Node& node) {
  if (node.IsNull()) return py::none();
  if (node.IsSequence()) {
    py::list list;
    for (const auto& item : node) list.append(FromYaml(item));
    return std::move(list);
  }
  if (node.IsMap()) {
    py::dict dict;
    for (const auto& kv : node) dict[py::str(kv.first.Scalar())] = FromYaml(kv.second);
    return std::move(dict);
  }
  const std::string& text = node.Scalar();
  if (node.Tag() != "!") {  // a plain scalar: typed as YAML 1.2's core schema types it
    if (text == "true" || text == "false") return py::bool_(text == "true");
    long long integer;
    if (YAML::convert<long long>::decode(node, integer)) return py::int_(integer);
    double real;
    if (YAML::convert<double>::decode(node, real)) return py::float_(real);
  }
  return py::str(text);
}

// `symembed run CONFIG` with these arguments; returns its exit status (0: everything succeeded,
// 1: some shape or pair failed, recorded in failures.csv).
int RunOnce(const std::string& config, const std::string& out, const std::string& variant,
            const std::vector<std::string>& overrides, const std::string& cache, int jobs,
            bool resume, bool quiet, bool report) {
  Args args = {config, "--out", out, "--cache", cache, "--jobs", std::to_string(jobs)};
  if (!variant.empty()) args.insert(args.end(), {"--variant", variant});
  for (const std::string& o : overrides) args.insert(args.end(), {"--set", o});
  if (resume) args.push_back("--resume");
  if (quiet) args.push_back("--quiet");
  if (!report) args.push_back("--no-report");
  py::gil_scoped_release release;
  return RunCommand(args);
}

}  // namespace

void BindExperiments(py::module_& m) {
  m.def(
      "run",
      [](const py::object& config, const py::object& out, const py::object& variants,
         const py::object& set, const py::object& cache, int jobs, bool resume, bool quiet,
         bool report) {
        const std::string path = PathOf(config);
        const std::vector<std::string> overrides = Overrides(set);
        std::string out_dir;
        if (out.is_none()) {
          // The binary's default, results/<experiment name>.
          out_dir = "results/" + LoadExperimentConfig(path, BuiltinRegistry(), overrides).name;
        } else {
          out_dir = PathOf(out);
        }
        std::vector<std::string> names;
        if (py::isinstance<py::str>(variants)) {
          names.push_back(variants.cast<std::string>());
        } else if (!variants.is_none()) {
          names = variants.cast<std::vector<std::string>>();
        }
        if (names.empty()) names.push_back("");  // every variant in one run
        bool ok = true;
        for (const std::string& variant : names) {
          ok = RunOnce(path, out_dir, variant, overrides, PathOf(cache), jobs, resume, quiet,
                       report) == 0 &&
               ok;
        }
        return py::make_tuple(out_dir, ok);
      },
      "config"_a, "out"_a = py::none(), py::kw_only(), "variants"_a = py::none(),
      "set"_a = py::none(), "cache"_a = "results/.cache", "jobs"_a = 0, "resume"_a = false,
      "quiet"_a = false, "report"_a = true, R"doc(
Runs an experiment as `symembed run CONFIG` does, into the same folder layout.

run(config, out=None, *, variants=None, set=None, cache="results/.cache", jobs=0,
    resume=False, quiet=False, report=True) -> (out, ok)

out: the results folder (None: results/<experiment name>, as the binary). variants: None (all,
in one run), a name, or a list of names (each run as `--variant NAME`, in order, into out).
set: {dotted.path: value} overrides (`--set`). cache: the per-shape cache folder ("" for none).
Returns the results folder and whether every shape and pair succeeded (failures are recorded
in OUT/VARIANT/failures.csv and the run goes on, as with the binary). Raises
symembed.ConfigError, IoError, InvalidInputError, UsageError as the binary exits with an error.
Progress goes to stderr unless quiet.)doc");

  m.def(
      "stages",
      [] {
        const Registry& registry = BuiltinRegistry();
        py::list list;
        for (const Registry::Entry& entry : registry.List()) {
          py::dict options, texts;
          for (const auto& [name, text] : StageDefaultOptions(registry, entry)) {
            options[py::str(name)] = FromYaml(YAML::Load(text));
            texts[py::str(name)] = text;
          }
          list.append(py::dict("kind"_a = entry.kind, "name"_a = entry.name,
                               "description"_a = entry.description, "options"_a = options,
                               "options_text"_a = texts));
        }
        return list;
      },
      R"doc(
Every registered stage and dataset loader, sorted by kind and name, as `symembed stages
--options` lists them: [{kind, name, description, options, options_text}], options mapping each
dotted option name to its default (None, bool, int, float, str or list) and options_text to the
default as the YAML text the binary prints.)doc");
}

}  // namespace symembed::python
