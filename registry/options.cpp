#include "registry/options.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors.h"

namespace symembed {

std::string NodeLocation(const std::string& file, const YAML::Node& node) {
  std::ostringstream out;
  out << (file.empty() ? "<config>" : file);
  if (node.IsDefined() && node.Mark().line >= 0) {
    out << ":" << node.Mark().line + 1 << ":" << node.Mark().column + 1;
  }
  return out.str();
}

namespace {

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out;
}

std::string Scalar(const YAML::Node& node) { return node.IsScalar() ? node.Scalar() : "<non-scalar>"; }

}  // namespace

OptionReader::OptionReader(YAML::Node node, std::string file, std::string path)
    : node_(node.IsDefined() ? std::move(node) : YAML::Node()), file_(std::move(file)),
      path_(std::move(path)), resolved_(YAML::NodeType::Map) {
  if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap()) {
    throw ConfigError(NodeLocation(file_, node_) + ": " + (path_.empty() ? "<root>" : path_) +
                      ": expected a map of options");
  }
}

std::string OptionReader::KeyPath(const std::string& key) const {
  return path_.empty() ? key : (key.empty() ? path_ : path_ + "." + key);
}

void OptionReader::Fail(const std::string& key, const std::string& what) const {
  const YAML::Node& n = node_;
  YAML::Node at = (!key.empty() && n.IsMap() && n[key]) ? n[key] : n;
  // A map made by a dotted override has no position of its own; its first value given in the
  // file has.
  if (at.IsMap() && at.Mark().line < 0) {
    for (const auto& kv : at) {
      if (kv.second.Mark().line >= 0) {
        at.reset(kv.second);  // re-point the handle; operator= would overwrite the tree
        break;
      }
    }
  }
  throw ConfigError(NodeLocation(file_, at) + ": " + KeyPath(key) + ": " + what);
}

bool OptionReader::Has(const std::string& key) const {
  const YAML::Node& n = node_;
  return n.IsMap() && n[key].IsDefined();
}

YAML::Node OptionReader::Lookup(const std::string& key) {
  read_.insert(key);
  const YAML::Node& n = node_;
  if (!n.IsMap()) return YAML::Node();
  YAML::Node v = n[key];
  // A key without a value (`key:`, `key: ~`) would silently stand for the default.
  if (v.IsDefined() && v.IsNull()) {
    Fail(key, "no value; give one, or remove the key for the default");
  }
  return v;
}

double OptionReader::GetDouble(const std::string& key, double default_value, const Range& range) {
  YAML::Node v = Lookup(key);
  double value = default_value;
  if (v.IsDefined() && !v.IsNull()) {
    try {
      if (!v.IsScalar()) throw YAML::Exception(YAML::Mark(), "");
      value = v.as<double>();
    } catch (const YAML::Exception&) {
      Fail(key, "expected a number, got '" + Scalar(v) + "'");
    }
    if (!std::isfinite(value)) Fail(key, "expected a finite number, got '" + Scalar(v) + "'");
  }
  CheckRange(key, value, range);
  resolved_[key] = FormatNumber(value);
  return value;
}

int OptionReader::ReadInteger(const std::string& key, const YAML::Node& v, const Range& range,
                              const std::string& expected) const {
  long long value = 0;
  try {
    if (!v.IsScalar()) throw YAML::Exception(YAML::Mark(), "");
    value = v.as<long long>();
  } catch (const YAML::Exception&) {
    Fail(key, "expected " + expected + ", got '" + Scalar(v) + "'");
  }
  CheckRange(key, static_cast<double>(value),
             Range::Closed(std::numeric_limits<int>::min(), std::numeric_limits<int>::max()));
  CheckRange(key, static_cast<double>(value), range);
  return static_cast<int>(value);
}

void OptionReader::CheckRange(const std::string& key, double value, const Range& range) const {
  if (!range.Contains(value)) Fail(key, range.Violation(value));
}

int OptionReader::GetInt(const std::string& key, int default_value, const Range& range) {
  YAML::Node v = Lookup(key);
  int value = default_value;
  if (v.IsDefined() && !v.IsNull()) {
    value = ReadInteger(key, v, range, "an integer");
  } else {
    CheckRange(key, value, range);
  }
  resolved_[key] = value;
  return value;
}

bool OptionReader::GetBool(const std::string& key, bool default_value) {
  YAML::Node v = Lookup(key);
  bool value = default_value;
  if (v.IsDefined() && !v.IsNull()) {
    try {
      if (!v.IsScalar()) throw YAML::Exception(YAML::Mark(), "");
      value = v.as<bool>();
    } catch (const YAML::Exception&) {
      Fail(key, "expected true or false, got '" + Scalar(v) + "'");
    }
  }
  resolved_[key] = value;
  return value;
}

std::string OptionReader::GetString(const std::string& key, const std::string& default_value) {
  YAML::Node v = Lookup(key);
  std::string value = default_value;
  if (v.IsDefined() && !v.IsNull()) {
    if (!v.IsScalar()) Fail(key, "expected a string");
    value = v.Scalar();
  }
  resolved_[key] = value;
  return value;
}

std::string OptionReader::GetRequiredString(const std::string& key) {
  if (!Has(key)) Fail("", "missing required key '" + key + "'");
  return GetString(key, "");
}

std::string OptionReader::GetChoice(const std::string& key, const std::string& default_value,
                                    const std::vector<std::string>& choices) {
  const std::string value = GetString(key, default_value);
  for (const auto& c : choices) {
    if (c == value) return value;
  }
  Fail(key, "invalid value '" + value + "'; expected one of: " + Join(choices));
}

std::vector<std::string> OptionReader::GetStringList(const std::string& key,
                                                     const std::vector<std::string>& default_value) {
  YAML::Node v = Lookup(key);
  std::vector<std::string> value = default_value;
  if (v.IsDefined() && !v.IsNull()) {
    if (!v.IsSequence()) Fail(key, "expected a list of strings");
    value.clear();
    for (const auto& item : v) {
      if (!item.IsScalar()) Fail(key, "expected a list of strings");
      value.push_back(item.Scalar());
    }
  }
  YAML::Node out(YAML::NodeType::Sequence);
  for (const auto& s : value) out.push_back(s);
  resolved_[key] = out;
  return value;
}

std::vector<int> OptionReader::GetIntList(const std::string& key,
                                          const std::vector<int>& default_value,
                                          const Range& range) {
  YAML::Node v = Lookup(key);
  std::vector<int> value = default_value;
  if (v.IsDefined() && v.IsSequence()) {
    value.clear();
    for (const auto& item : v) {
      value.push_back(ReadInteger(key, item, range, "a list of integers"));
    }
  } else if (v.IsDefined() && !v.IsNull()) {
    value = {ReadInteger(key, v, range, "a list of integers")};
  }
  YAML::Node out(YAML::NodeType::Sequence);
  for (int x : value) out.push_back(x);
  resolved_[key] = out;
  return value;
}

double OptionReader::GetDoubleIfGiven(const std::string& key, double default_value,
                                      const Range& range) {
  if (Has(key)) return GetDouble(key, default_value, range);
  read_.insert(key);
  unset_defaults_[key] = FormatNumber(default_value);
  return default_value;
}

int OptionReader::GetIntIfGiven(const std::string& key, int default_value, const Range& range) {
  if (Has(key)) return GetInt(key, default_value, range);
  read_.insert(key);
  unset_defaults_[key] = default_value;
  return default_value;
}

OptionReader OptionReader::Child(const std::string& key) {
  return OptionReader(Lookup(key), file_, KeyPath(key));
}

void OptionReader::AdoptChild(const std::string& key, const OptionReader& child) {
  resolved_[key] = child.resolved();
  if (child.unset_defaults().size() > 0) unset_defaults_[key] = child.unset_defaults();
}

void OptionReader::Finish() const {
  const YAML::Node& n = node_;
  if (!n.IsMap()) return;
  std::vector<std::string> known(read_.begin(), read_.end());
  for (const auto& kv : n) {
    const std::string key = kv.first.Scalar();
    if (read_.count(key)) continue;
    // A key a variant's override added has no position; its value has the override's.
    const YAML::Node& at = kv.first.Mark().line >= 0 ? kv.first : kv.second;
    throw ConfigError(NodeLocation(file_, at) + ": " + KeyPath(key) + ": unknown key '" +
                      key + "'; known keys: " + (known.empty() ? "(none)" : Join(known)));
  }
}

}  // namespace symembed
