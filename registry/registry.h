// The stage registry: (kind, name) -> description and factory.
//
// Registration is explicit and at runtime: each implementation file defines
// `void RegisterXxx(Registry&)` and RegisterBuiltinStages calls them all. A third-party stage is
// added with Add() before the run. No static registrar objects.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "registry/options.h"
#include "registry/stage_kinds.h"
#include "registry/stages.h"

namespace symembed {

class Registry {
 public:
  // Builds a stage from its options (the reader excludes `type`); may throw ConfigError.
  using Factory = std::function<std::unique_ptr<Stage>(OptionReader& options)>;

  struct Entry {
    std::string kind;
    std::string name;
    std::string description;
    Factory factory;
  };

  // Throws ConfigError for an unknown kind or a (kind, name) already registered.
  void Add(const std::string& kind, const std::string& name, const std::string& description,
           Factory factory);

  // Creates the stage named by `type` in `node` (a map with `type` and options; when `type` is
  // missing, default_type is used). Unknown names fail with the list of known ones; unknown
  // options fail through OptionReader::Finish. The stage's resolved options are set.
  // type_key names the key holding the type (`format` for datasets).
  std::unique_ptr<Stage> Create(const std::string& kind, const YAML::Node& node,
                                const std::string& file, const std::string& path,
                                const std::string& default_type = "",
                                const std::string& type_key = "type") const;

  template <typename T>
  std::unique_ptr<T> CreateAs(const std::string& kind, const YAML::Node& node,
                              const std::string& file, const std::string& path,
                              const std::string& default_type = "",
                              const std::string& type_key = "type") const {
    std::unique_ptr<Stage> stage = Create(kind, node, file, path, default_type, type_key);
    T* typed = dynamic_cast<T*>(stage.get());
    SYMEMBED_CHECK(typed != nullptr, "stage of kind '" << kind << "' has the wrong interface");
    stage.release();
    return std::unique_ptr<T>(typed);
  }

  bool Has(const std::string& kind, const std::string& name) const;
  // Names registered for a kind, sorted.
  std::vector<std::string> Names(const std::string& kind) const;
  // All entries sorted by kind then name.
  std::vector<Entry> List() const;

 private:
  std::map<std::pair<std::string, std::string>, Entry> entries_;
};

// Registers every built-in stage and dataset loader.
void RegisterBuiltinStages(Registry& registry);

}  // namespace symembed
