#include "registry/registry.h"

#include <algorithm>

namespace symembed {

namespace {

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out.empty() ? "(none registered)" : out;
}

}  // namespace

void Registry::Add(const std::string& kind, const std::string& name, const std::string& description,
                   Factory factory) {
  const auto& kinds = StageKinds();
  if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) {
    throw ConfigError("cannot register '" + name + "': unknown stage kind '" + kind +
                      "'; known kinds: " + JoinNames(kinds));
  }
  if (name.empty() || !factory) {
    throw ConfigError("cannot register a " + kind + " stage without a name and a factory");
  }
  auto key = std::make_pair(kind, name);
  if (entries_.count(key)) {
    throw ConfigError("duplicate " + kind + " stage '" + name + "'; registered " + kind +
                      " stages: " + JoinNames(Names(kind)));
  }
  entries_[key] = Entry{kind, name, description, std::move(factory)};
}

std::unique_ptr<Stage> Registry::Create(const std::string& kind, const YAML::Node& node,
                                        const std::string& file, const std::string& path,
                                        const std::string& default_type,
                                        const std::string& type_key) const {
  OptionReader reader(node, file, path);
  std::string type = reader.GetString(type_key, default_type);
  if (type.empty()) {
    reader.Fail("", "missing required key '" + type_key + "'; known " + kind +
                        " types: " + JoinNames(Names(kind)));
  }
  auto it = entries_.find(std::make_pair(kind, type));
  if (it == entries_.end()) {
    reader.Fail(reader.Has(type_key) ? type_key : "",
                "unknown " + kind + " type '" + type + "'; known: " + JoinNames(Names(kind)));
  }
  std::unique_ptr<Stage> stage = it->second.factory(reader);
  SYMEMBED_CHECK(stage != nullptr, "factory of " << kind << " '" << type << "' returned null");
  reader.Finish();
  stage->set_resolved_options(YAML::Clone(reader.resolved()));
  stage->set_unset_defaults(YAML::Clone(reader.unset_defaults()));
  return stage;
}

bool Registry::Has(const std::string& kind, const std::string& name) const {
  return entries_.count(std::make_pair(kind, name)) > 0;
}

std::vector<std::string> Registry::Names(const std::string& kind) const {
  std::vector<std::string> names;
  for (const auto& [key, entry] : entries_) {
    if (key.first == kind) names.push_back(key.second);
  }
  return names;
}

std::vector<Registry::Entry> Registry::List() const {
  std::vector<Entry> out;
  for (const auto& [key, entry] : entries_) out.push_back(entry);
  return out;  // std::map orders by (kind, name)
}

}  // namespace symembed
