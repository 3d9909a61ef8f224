// Configs from Python: the pipeline of one variant from None, a dict of dotted options or a
// config file, read by the same code as `symembed run CONFIG --set KEY=VALUE`.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "harness/config.h"
#include "registry/registry.h"

namespace symembed::python {

namespace py = pybind11;

// The built-in stages and dataset loaders, registered once.
const Registry& BuiltinRegistry();

// A Python value as the YAML text of a --set value: None, bool, int, float (repr, which reads
// back to the same double), str, list or tuple, dict (flow style). key: the option, for
// messages. Throws py::type_error for any other type.
std::string YamlText(const py::handle& value, const std::string& key);

// {dotted.path: value, ...} (None: none) as "dotted.path=VALUE" overrides, in the dict's order.
// Throws py::type_error when it is not a dict or a key is not a string.
std::vector<std::string> Overrides(const py::handle& set);

// A path given as str or os.PathLike.
std::string PathOf(const py::handle& path);

// One variant of a config with its instantiated stages. Immutable once loaded, so shapes and
// pairs share it across threads.
struct LoadedPipeline {
  ExperimentConfig config;
  Pipeline pipeline;
  std::string resolved;  // ResolvedConfigYaml: every option with its default
  // The resolved options of every stage and of the evaluation (not the dataset or the name):
  // two pipelines with equal texts compute the same shapes and maps.
  std::string stages;
};

// config: None (the defaults), a dict {dotted.path: value} of overrides of the defaults, or the
// path of a config file (str or os.PathLike), whose `variant` ("base": its base pipeline) is
// taken, with `set` (a dict, or None) applied as `symembed run --set` applies it. The defaults
// are a config with `dataset: {format: synthetic}` (the dataset is not read) and every stage at
// its default. Throws ConfigError or IoError with the messages of `symembed run`, py::type_error
// for a config of another type.
std::shared_ptr<const LoadedPipeline> LoadPipeline(const py::object& config, const py::object& set,
                                                   const std::string& variant);

}  // namespace symembed::python
