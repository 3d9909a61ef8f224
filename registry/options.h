// Strict reading of stage options and config sections from YAML.
//
// Every key is read through an OptionReader, which records it; Finish() then rejects any key
// that was not read, naming file:line:col, the dotted path and the known keys. Values are
// type-checked and range-checked on read. The reader also builds the resolved node (every
// option with its default filled in), which is written beside results and hashed for caching.
// Only const YAML::Node access is used, so reading never inserts keys.
#pragma once

#include <yaml-cpp/yaml.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/range.h"

namespace symembed {

// "file:line:col" of a node (1-based), or "file" when the node has no position.
std::string NodeLocation(const std::string& file, const YAML::Node& node);

class OptionReader {
 public:
  // node: a YAML map (or null/undefined: all defaults). file: the config file the node came
  // from. path: the dotted path of node in the config ("pipeline.embedding").
  OptionReader(YAML::Node node, std::string file, std::string path);

  // The number at `key`, or default_value when absent; either must lie in `range` (declared
  // with the option, e.g. SmacofOptions::kRelaxation, which IsValid checks too). Throws
  // ConfigError naming file:line:col, the dotted key, the range and the value.
  double GetDouble(const std::string& key, double default_value, const Range& range = Range::Any());
  // As GetDouble, for an integer (which must also fit an int).
  int GetInt(const std::string& key, int default_value, const Range& range = Range::Any());
  // An option read only when given, so that the resolved node (and every cache key made from
  // it) stays as it was without it: as GetDouble / GetInt when `key` is present; else
  // default_value, recorded in unset_defaults() (and as a known key) instead of resolved().
  double GetDoubleIfGiven(const std::string& key, double default_value,
                          const Range& range = Range::Any());
  int GetIntIfGiven(const std::string& key, int default_value, const Range& range = Range::Any());
  bool GetBool(const std::string& key, bool default_value);
  std::string GetString(const std::string& key, const std::string& default_value);
  // A required string (throws ConfigError when missing).
  std::string GetRequiredString(const std::string& key);
  // One of `choices` (the error lists them all).
  std::string GetChoice(const std::string& key, const std::string& default_value,
                        const std::vector<std::string>& choices);
  // Enum through a string table.
  template <typename E>
  E GetEnum(const std::string& key, E default_value,
            const std::vector<std::pair<std::string, E>>& table) {
    std::string default_name;
    std::vector<std::string> names;
    for (const auto& [name, value] : table) {
      names.push_back(name);
      if (value == default_value) default_name = name;
    }
    const std::string chosen = GetChoice(key, default_name, names);
    for (const auto& [name, value] : table) {
      if (name == chosen) return value;
    }
    return default_value;
  }
  std::vector<std::string> GetStringList(const std::string& key,
                                         const std::vector<std::string>& default_value);
  // A list of integers, each in `range` (a single integer is a list of one).
  std::vector<int> GetIntList(const std::string& key, const std::vector<int>& default_value,
                              const Range& range = Range::Any());
  // A nested map, read with its own reader (recorded as read; its keys checked by its Finish).
  OptionReader Child(const std::string& key);
  // Marks the nested reader's resolved values as part of this reader's resolved node.
  void AdoptChild(const std::string& key, const OptionReader& child);

  bool Has(const std::string& key) const;
  // Throws ConfigError for every key present but never read.
  void Finish() const;

  // Throws ConfigError located at `key` (or at the map when key is empty).
  [[noreturn]] void Fail(const std::string& key, const std::string& what) const;

  const YAML::Node& resolved() const { return resolved_; }
  // The defaults of the options read only when given that were not (a map like resolved(),
  // children's under their key): what `symembed stages --options` lists besides resolved().
  const YAML::Node& unset_defaults() const { return unset_defaults_; }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }

 private:
  YAML::Node Lookup(const std::string& key);
  // The integer in the scalar `v` (the value of `key`, or an item of its list), checked against
  // `range` and the limits of int; fails with "expected <expected>" when v is not an integer.
  int ReadInteger(const std::string& key, const YAML::Node& v, const Range& range,
                  const std::string& expected) const;
  // Fails with range.Violation(value) unless range contains value.
  void CheckRange(const std::string& key, double value, const Range& range) const;
  std::string KeyPath(const std::string& key) const;

  YAML::Node node_;
  std::string file_;
  std::string path_;
  std::set<std::string> read_;
  YAML::Node resolved_;
  YAML::Node unset_defaults_;
};

// Reads every option Options::Fields declares (core/range.h) into *options, in its order, each
// member's value the default.
template <typename Options>
void ReadFields(OptionReader& reader, Options* options) {
  struct Read {
    OptionReader& r;
    void operator()(const char* key, int& value, const Range& range) const {
      value = r.GetInt(key, value, range);
    }
    void operator()(const char* key, unsigned& value, const Range& range) const {
      value = static_cast<unsigned>(r.GetInt(key, static_cast<int>(value), range));
    }
    void operator()(const char* key, double& value, const Range& range) const {
      value = r.GetDouble(key, value, range);
    }
    void operator()(const char* key, int& value, const Range& range, IfGiven) const {
      value = r.GetIntIfGiven(key, value, range);
    }
    void operator()(const char* key, double& value, const Range& range, IfGiven) const {
      value = r.GetDoubleIfGiven(key, value, range);
    }
    void operator()(const char* key, bool& value) const { value = r.GetBool(key, value); }
  };
  Options::Fields(*options, Read{reader});
}

// Throws ConfigError located at the reader's map with options.IsValid's message when it fails.
template <typename Options>
void RequireValid(const OptionReader& reader, const Options& options) {
  std::string error;
  if (!options.IsValid(&error)) reader.Fail("", error);
}

// ReadFields, then RequireValid.
template <typename Options>
void ReadValidFields(OptionReader& reader, Options* options) {
  ReadFields(reader, options);
  RequireValid(reader, *options);
}

}  // namespace symembed
