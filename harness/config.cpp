#include "harness/config.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "core/errors.h"

namespace symembed {

const Stage& Pipeline::StageOf(const std::string& kind) const {
  const Stage* found = nullptr;
  ForEachStage(*this, [&](const char* name, const auto& stage) {
    if (kind == name) found = stage.get();
  });
  SYMEMBED_CHECK(found != nullptr, "unknown pipeline kind '" << kind << "'");
  return *found;
}

const VariantConfig* ExperimentConfig::Find(const std::string& variant) const {
  for (const auto& v : variants) {
    if (v.name == variant) return &v;
  }
  return nullptr;
}

const VariantConfig& ExperimentConfig::Get(const std::string& variant) const {
  if (const VariantConfig* v = Find(variant)) return *v;
  std::string names;
  for (const auto& v : variants) names += (names.empty() ? "" : ", ") + v.name;
  throw ConfigError(file + ": no variant '" + variant + "'; variants: " + names);
}

namespace {

std::string MarkLocation(const std::string& file, const YAML::Mark& mark) {
  std::ostringstream out;
  out << file << ":" << mark.line + 1 << ":" << mark.column + 1;
  return out.str();
}

// Walks the parser's events and counts the nodes of the tree they describe, an alias counting
// the nodes of what it names, so that a recursive alias or an alias bomb is refused from the
// text alone (milliseconds) rather than found by building or walking the tree.
class AliasGuard : public YAML::EventHandler {
 public:
  explicit AliasGuard(std::string file) : file_(std::move(file)) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { Leaf(mark, anchor); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                const std::string&) override {
    Leaf(mark, anchor);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    for (const Open& open : open_) {
      if (open.anchor == anchor) {
        throw ConfigError(MarkLocation(file_, mark) + ": the alias *" + names_[anchor] +
                          " is inside the node &" + names_[anchor] +
                          " it names (a recursive alias): YAML aliases in a config must name a "
                          "node defined before them and outside them");
      }
    }
    Add(mark, sizes_[anchor]);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    Start(mark, anchor);
  }
  void OnSequenceEnd() override { End(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    Start(mark, anchor);
  }
  void OnMapEnd() override { End(); }
  void OnAnchor(const YAML::Mark&, const std::string& name) override { pending_name_ = name; }

 private:
  struct Open {
    YAML::anchor_t anchor;
    YAML::Mark mark;
    long long size;
  };
  void Name(YAML::anchor_t anchor) {
    if (anchor != YAML::NullAnchor) names_[anchor] = pending_name_;
  }
  void Leaf(const YAML::Mark& mark, YAML::anchor_t anchor) {
    Name(anchor);
    if (anchor != YAML::NullAnchor) sizes_[anchor] = 1;
    Add(mark, 1);
  }
  void Start(const YAML::Mark& mark, YAML::anchor_t anchor) {
    Name(anchor);
    open_.push_back({anchor, mark, 1});
  }
  void End() {
    const Open done = open_.back();
    open_.pop_back();
    if (done.anchor != YAML::NullAnchor) sizes_[done.anchor] = done.size;
    Add(done.mark, done.size);
  }
  // Adds n nodes to the innermost open collection (or the document); each open collection's
  // count is at most the document's, so the bound is checked where the count grows.
  void Add(const YAML::Mark& mark, long long n) {
    long long& total = open_.empty() ? document_ : open_.back().size;
    total += n;
    if (total > kMaxYamlNodes) {
      throw ConfigError(MarkLocation(file_, mark) + ": the YAML expands to more than " +
                        std::to_string(kMaxYamlNodes) +
                        " nodes through its aliases (an alias bomb?); a config is far smaller");
    }
  }

  std::string file_;
  std::vector<Open> open_;
  std::map<YAML::anchor_t, long long> sizes_;
  std::map<YAML::anchor_t, std::string> names_;
  std::string pending_name_;
  long long document_ = 0;
};

}  // namespace

YAML::Node LoadConfigYaml(const std::string& text, const std::string& file) {
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    AliasGuard guard(file);
    while (parser.HandleNextDocument(guard)) {
    }
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(MarkLocation(file, e.mark) + ": YAML syntax error: " + e.msg);
  }
}

std::string ExpandEnvironment(const std::string& text, const std::string& where) {
  static const std::regex pattern(R"(\$\{([A-Za-z_][A-Za-z0-9_]*)(:-([^}]*))?\})");
  std::string out;
  auto begin = std::sregex_iterator(text.begin(), text.end(), pattern);
  size_t last = 0;
  for (auto it = begin; it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    out += text.substr(last, m.position() - last);
    const char* value = std::getenv(m[1].str().c_str());
    if (value && *value) {
      out += value;
    } else if (m[2].matched) {
      out += m[3].str();
    } else {
      throw ConfigError(where + ": environment variable " + m[1].str() +
                        " is not set and has no default (write ${" + m[1].str() + ":-default})");
    }
    last = m.position() + m.length();
  }
  out += text.substr(last);
  return out;
}

namespace {

const std::set<std::string> kTopLevelKeys = {"name",     "description", "dataset",
                                             "pipeline", "evaluation",  "variants"};

std::string JoinSet(const std::set<std::string>& s) {
  std::string out;
  for (const auto& x : s) out += (out.empty() ? "" : ", ") + x;
  return out;
}

// Substitutes the environment in the text line by line (before YAML parsing, so that
// `root: ${SYMEMBED_DATA}/x` also works inside flow maps); comments are left alone.
std::string SubstituteText(const std::string& text, const std::string& file) {
  std::string out;
  std::istringstream in(text);
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    // A '#' at the start or after a blank starts a YAML comment; only the part before it is
    // substituted, so a comment may mention ${VAR} freely.
    size_t comment = line.find('#');
    while (comment != std::string::npos && comment > 0 && line[comment - 1] != ' ' &&
           line[comment - 1] != '\t') {
      comment = line.find('#', comment + 1);
    }
    const std::string code = line.substr(0, comment);
    const std::string rest = comment == std::string::npos ? "" : line.substr(comment);
    out += (code.find("${") == std::string::npos)
               ? code
               : ExpandEnvironment(code, file + ":" + std::to_string(line_number));
    out += rest + "\n";
  }
  return out;
}

// Sets tree[path] = value where path is dotted ("pipeline.embedding.type"), creating maps.
// When the last key is a type key (a stage's, or a nested one such as pipeline.flip.decide.type)
// and the type changes, the other options of its map are dropped (they belonged to the old
// type).
void ApplyOverride(YAML::Node tree, const std::string& path, const YAML::Node& value,
                   const YAML::Node& key_node, const std::string& file) {
  std::vector<std::string> parts;
  std::stringstream ss(path);
  for (std::string part; std::getline(ss, part, '.');) parts.push_back(part);
  auto fail = [&](const std::string& what) {
    throw ConfigError(NodeLocation(file, key_node) + ": override '" + path + "': " + what);
  };
  if (parts.size() < 2 || parts[0].empty())
    fail("expected a dotted path such as pipeline.embedding.type");
  if (parts[0] != "dataset" && parts[0] != "pipeline" && parts[0] != "evaluation") {
    fail("the path must start with dataset, pipeline or evaluation");
  }
  if (parts[0] == "pipeline") {
    const auto& kinds = PipelineKinds();
    if (std::find(kinds.begin(), kinds.end(), parts[1]) == kinds.end()) {
      std::set<std::string> known(kinds.begin(), kinds.end());
      fail("unknown stage kind '" + parts[1] + "'; known: " + JoinSet(known));
    }
  }
  YAML::Node node = tree;
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    if (parts[i].empty()) fail("empty path component");
    YAML::Node child = node[parts[i]];
    if (!child.IsDefined() || child.IsNull()) {
      node[parts[i]] = YAML::Node(YAML::NodeType::Map);
      child = node[parts[i]];
    } else if (!child.IsMap()) {
      fail("'" + parts[i] + "' is not a map");
    }
    node.reset(child);  // re-point the handle; operator= would overwrite the tree
  }
  const std::string& last = parts.back();
  const bool is_type = (parts.size() >= 3 && parts[0] == "pipeline" && last == "type") ||
                       (parts.size() == 2 && parts[0] == "dataset" && last == "format");
  if (is_type) {
    const YAML::Node old = node[last];
    const bool changed =
        !old.IsDefined() || !old.IsScalar() || !value.IsScalar() || old.Scalar() != value.Scalar();
    if (changed) {
      std::vector<std::string> keys;
      for (const auto& kv : node) keys.push_back(kv.first.Scalar());
      for (const auto& k : keys) node.remove(k);
    }
  }
  node[last] = value;
}

// `what` names the key in messages ("name" of the experiment, "variants[i].name").
void ValidateName(const std::string& name, const YAML::Node& at, const std::string& file,
                  const std::string& what) {
  static const std::regex ok("[A-Za-z0-9_.-]+");
  if (!std::regex_match(name, ok) || name == "." || name == "..") {
    throw ConfigError(NodeLocation(file, at) + ": " + what + ": '" + name +
                      "' is not a valid name (letters, digits, '_', '-', '.'; it names a folder)");
  }
}

// yaml-cpp keeps both entries of a repeated key and reads the first: refuse the file instead.
void RejectDuplicateKeys(const YAML::Node& node, const std::string& file,
                         const std::string& path) {
  if (node.IsSequence()) {
    for (size_t i = 0; i < node.size(); ++i) {
      RejectDuplicateKeys(node[i], file, path + "[" + std::to_string(i) + "]");
    }
    return;
  }
  if (!node.IsMap()) return;
  std::map<std::string, YAML::Node> seen;
  for (const auto& kv : node) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "";
    const std::string key_path = path.empty() ? key : path + "." + key;
    auto [it, inserted] = seen.emplace(key, kv.first);
    if (!inserted) {
      throw ConfigError(NodeLocation(file, kv.first) + ": " + key_path + ": duplicate key '" +
                        key + "' (first at " + NodeLocation(file, it->second) + ")");
    }
    RejectDuplicateKeys(kv.second, file, key_path);
  }
}

// An error in a value given with --set has no position in the file: name the --set argument
// instead of the file. `message` is "LOCATION: dotted.path: what".
std::string WithSetArgument(const std::string& message, const std::string& file,
                            const std::vector<std::string>& overrides) {
  if (message.compare(0, file.size() + 2, file + ": ") != 0) return message;  // has a position
  const std::string rest = message.substr(file.size() + 2);
  const std::string error_path = rest.substr(0, rest.find(": "));
  for (auto o = overrides.rbegin(); o != overrides.rend(); ++o) {
    const std::string set_path = o->substr(0, o->find('='));
    const bool related = error_path == set_path ||
                         error_path.compare(0, set_path.size() + 1, set_path + ".") == 0 ||
                         set_path.compare(0, error_path.size() + 1, error_path + ".") == 0;
    if (related) return "--set '" + *o + "': " + rest;
  }
  return message;
}

// A copy of node without positions: those of a --set value are in the --set text, and messages
// would give them as positions in the config file.
YAML::Node WithoutPosition(const YAML::Node& node) {
  if (node.IsScalar()) return YAML::Node(node.Scalar());
  if (node.IsSequence()) {
    YAML::Node out(YAML::NodeType::Sequence);
    for (const auto& item : node) out.push_back(WithoutPosition(item));
    return out;
  }
  if (node.IsMap()) {
    YAML::Node out(YAML::NodeType::Map);
    for (const auto& kv : node) out[kv.first.Scalar()] = WithoutPosition(kv.second);
    return out;
  }
  return YAML::Node(node.Type());
}

// Applies "dotted.path=value" overrides given on the command line to a config tree.
void ApplyCommandLineOverrides(YAML::Node tree, const std::vector<std::string>& overrides,
                               const std::string& file) {
  for (const std::string& o : overrides) {
    const size_t eq = o.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw ConfigError("--set '" + o + "': expected dotted.path=value");
    }
    const std::string text = o.substr(eq + 1);
    if (text.find_first_not_of(" \t") == std::string::npos) {
      throw ConfigError("--set '" + o + "': no value after '=' (an empty value would reset " +
                        o.substr(0, eq) + " to its default; give the value, or leave the " +
                        "--set out)");
    }
    YAML::Node value;
    try {
      value = WithoutPosition(LoadConfigYaml(text, "--set '" + o + "'"));
    } catch (const ConfigError& e) {
      throw ConfigError("--set '" + o + "': value is not valid YAML: " + e.what());
    }
    ApplyOverride(tree, o.substr(0, eq), value, YAML::Node(), file + " (--set " + o + ")");
  }
}


// The top level of a config besides its variants: name, description, that a dataset is given,
// and that every key of `pipeline` is a stage kind. Throws ConfigError.
void ReadTopLevel(const YAML::Node& croot, const std::string& file, ExperimentConfig* config) {
  if (!croot["name"] || !croot["name"].IsScalar() || croot["name"].Scalar().empty()) {
    throw ConfigError(NodeLocation(file, croot) +
                      ": name: missing required key 'name' "
                      "(the experiment's name; outputs go to results/<name>/)");
  }
  config->name = croot["name"].Scalar();
  ValidateName(config->name, croot["name"], file, "name");
  if (croot["description"]) {
    if (!croot["description"].IsScalar()) {
      throw ConfigError(NodeLocation(file, croot["description"]) +
                        ": description: expected a string");
    }
    config->description = croot["description"].Scalar();
  }
  if (!croot["dataset"]) {
    throw ConfigError(NodeLocation(file, croot) +
                      ": dataset: missing required key 'dataset' "
                      "(a map with `format` and the loader's options)");
  }
  const YAML::Node pipeline = croot["pipeline"];
  if (pipeline.IsDefined() && !pipeline.IsNull()) {
    if (!pipeline.IsMap())
      throw ConfigError(NodeLocation(file, pipeline) + ": pipeline: expected a map of stage kinds");
    const auto& kinds = PipelineKinds();
    for (const auto& kv : pipeline) {
      const std::string key = kv.first.Scalar();
      if (std::find(kinds.begin(), kinds.end(), key) == kinds.end()) {
        throw ConfigError(
            NodeLocation(file, kv.first) + ": pipeline." + key + ": unknown stage kind '" + key +
            "'; known: " + JoinSet(std::set<std::string>(kinds.begin(), kinds.end())));
      }
    }
  }
}

// Whether dotted paths a and b name the same option or one holds the other.
bool PathsOverlap(const std::string& a, const std::string& b) {
  const std::string& shorter = a.size() <= b.size() ? a : b;
  const std::string& longer = a.size() <= b.size() ? b : a;
  return longer.compare(0, shorter.size(), shorter) == 0 &&
         (longer.size() == shorter.size() || longer[shorter.size()] == '.');
}

// Whether the dotted path names a node of tree.
bool HasPath(const YAML::Node& tree, const std::string& path) {
  YAML::Node node = tree;
  std::stringstream parts(path);
  for (std::string part; std::getline(parts, part, '.');) {
    if (!node.IsMap() || !node[part].IsDefined()) return false;
    node.reset(node[part]);
  }
  return true;
}

// Variant i of the config's `variants` list: its name (unique in *names) and its tree, parsed
// afresh by `parse(i)` (the tree and the index of the variant in the tree's own list), with the
// command-line overrides and then its own `set` applied (type changes first, so that options set
// next to them are kept). Each override its `set` replaces (PathsOverlap), or drops by changing
// its stage's type, is added to *shadowed, except that a dropped one applies again on top when
// the variant is `only_variant`. Throws ConfigError.
template <typename Parse>
VariantConfig ReadVariant(const YAML::Node& variants, size_t i, const Parse& parse,
                          const std::vector<std::string>& overrides, const std::string& file,
                          const std::string& only_variant, std::set<std::string>* names,
                          std::vector<std::pair<std::string, std::string>>* shadowed) {
  const YAML::Node v = variants[i];
  const std::string path = "variants[" + std::to_string(i) + "]";
  if (!v.IsMap())
    throw ConfigError(NodeLocation(file, v) + ": " + path + ": expected a map with keys name, set");
  for (const auto& kv : v) {
    const std::string key = kv.first.Scalar();
    if (key != "name" && key != "set") {
      throw ConfigError(NodeLocation(file, kv.first) + ": " + path + "." + key + ": unknown key '" +
                        key + "'; known keys: name, set");
    }
  }
  if (!v["name"] || !v["name"].IsScalar()) {
    throw ConfigError(NodeLocation(file, v) + ": " + path + ".name: missing required key 'name'");
  }
  const std::string name = v["name"].Scalar();
  ValidateName(name, v["name"], file, path + ".name");
  if (!names->insert(name).second) {
    throw ConfigError(NodeLocation(file, v["name"]) + ": " + path +
                      ".name: duplicate variant name '" + name + "'");
  }
  const auto [parsed, index] = parse(i);
  YAML::Node tree = parsed;
  const YAML::Node set = static_cast<const YAML::Node&>(tree)["variants"][index]["set"];
  tree.remove("variants");
  ApplyCommandLineOverrides(tree, overrides, file);
  if (set.IsDefined() && !set.IsNull()) {
    if (!set.IsMap())
      throw ConfigError(NodeLocation(file, set) + ": " + path +
                        ".set: expected a map of dotted.path: value");
    std::vector<bool> replaced(overrides.size(), false);
    for (size_t i = 0; i < overrides.size(); ++i) {
      const std::string& o = overrides[i];
      const std::string key = o.substr(0, o.find('='));
      for (const auto& kv : set) {
        if (!PathsOverlap(key, kv.first.Scalar())) continue;
        replaced[i] = true;
        shadowed->emplace_back(name, "variant '" + name + "' sets " + kv.first.Scalar() +
                                         " itself (" + NodeLocation(file, kv.first) +
                                         "), so --set " + o + " does not apply to it there");
      }
    }
    // Type changes first, so that options set next to them are kept.
    for (int pass = 0; pass < 2; ++pass) {
      for (const auto& kv : set) {
        const std::string key = kv.first.Scalar();
        const bool is_type =
            key.size() >= 5 && (key.substr(key.size() - 5) == ".type" || key == "dataset.format");
        if ((pass == 0) == is_type) ApplyOverride(tree, key, kv.second, kv.first, file);
      }
    }
    // A type the set changes drops the old type's options, among them those --set gave to the
    // stage. When this variant is the one asked for, they are meant for it and apply again on
    // top (failing validation if the new type has no such option); otherwise they stay dropped,
    // with a note, since a --set for every variant need not fit a stage one variant replaces.
    for (size_t i = 0; i < overrides.size(); ++i) {
      const std::string& o = overrides[i];
      // Only a type change removes a key from the tree: one the set does not name is gone
      // exactly when the set retyped its stage.
      if (replaced[i] || HasPath(tree, o.substr(0, o.find('=')))) continue;
      if (name == only_variant) {
        ApplyCommandLineOverrides(tree, {o}, file);
      } else {
        shadowed->emplace_back(name, "variant '" + name +
                                         "' changes the type of its stage, which drops --set " + o +
                                         " there (with --variant " + name + " it applies)");
      }
    }
  }
  return VariantConfig{name, tree};
}

// The tree of variant i: text with the entries of the top-level `variants` list other than
// entry i made blank lines (line numbers kept) and parsed, so that each tree holds its own entry
// only and the trees take memory linear in the number of variants; the variant is then entry 0
// of its tree's list. The whole text and i when the entries cannot be told apart by lines (a
// flow-style list, entries sharing lines) or the rest does not parse without them.
std::pair<YAML::Node, size_t> VariantTree(const std::string& text, const YAML::Node& root,
                                           size_t i, const std::string& file) {
  const auto whole = [&]() -> std::pair<YAML::Node, size_t> {
    return {LoadConfigYaml(text, file), i};
  };
  const YAML::Node variants = root["variants"];
  if (root.Style() == YAML::EmitterStyle::Flow || !variants.IsSequence() ||
      variants.Style() == YAML::EmitterStyle::Flow || i >= variants.size()) {
    return whole();
  }
  // Entry k spans the lines [start[k], start[k + 1]); the last ends at the next top-level key.
  std::vector<int> start;
  for (const auto& entry : variants) start.push_back(entry.Mark().line);
  int section_end = -1;
  for (const auto& kv : root) {
    const int line = kv.first.Mark().line;
    if (line > start.back() && (section_end < 0 || line < section_end)) section_end = line;
  }
  for (size_t k = 1; k < start.size(); ++k) {
    if (start[k] <= start[k - 1]) return whole();
  }
  const int keep_begin = start[i];
  const int keep_end = i + 1 < start.size() ? start[i + 1] : section_end;
  std::string out;
  std::istringstream in(text);
  std::string line;
  for (int n = 0; std::getline(in, line); ++n) {
    const bool other_entry = n >= start.front() && (section_end < 0 || n < section_end) &&
                             (n < keep_begin || (keep_end >= 0 && n >= keep_end));
    if (!other_entry) out += line;
    out += '\n';
  }
  try {
    YAML::Node tree = LoadConfigYaml(out, file);
    const YAML::Node list = static_cast<const YAML::Node&>(tree)["variants"];
    if (list.IsSequence() && list.size() == 1) return {tree, 0};
  } catch (const ConfigError&) {
  }
  return whole();
}

}  // namespace

ExperimentConfig ParseExperimentConfig(const std::string& yaml_text, const std::string& file,
                                       const Registry& registry,
                                       const std::vector<std::string>& overrides,
                                       const std::string& only_variant) {
  const std::string text = SubstituteText(yaml_text, file);
  YAML::Node root = LoadConfigYaml(text, file);
  RejectDuplicateKeys(root, file, "");
  if (!root.IsMap())
    throw ConfigError(file + ": expected a YAML map with keys " + JoinSet(kTopLevelKeys));
  for (const auto& kv : root) {
    const std::string key = kv.first.Scalar();
    if (!kTopLevelKeys.count(key)) {
      throw ConfigError(NodeLocation(file, kv.first) + ": " + key + ": unknown key '" + key +
                        "'; known keys: " + JoinSet(kTopLevelKeys));
    }
  }

  ExperimentConfig config;
  config.file = file;
  const YAML::Node& croot = root;
  ReadTopLevel(croot, file, &config);
  const YAML::Node variants = croot["variants"];
  if (variants.IsDefined() && variants.IsSequence() && variants.size() > kMaxVariants) {
    throw ConfigError(NodeLocation(file, variants) + ": variants: " +
                      std::to_string(variants.size()) + " variants; at most " +
                      std::to_string(kMaxVariants) + " in one config (split the study)");
  }
  // Each variant gets its own parse of the text with its own entry only (VariantTree), so that
  // every node keeps its file position (YAML::Clone drops positions), no node is shared between
  // variants, and the trees take memory linear in the number of variants.
  auto parse = [&](size_t i) { return VariantTree(text, croot, i, file); };

  YAML::Node base = LoadConfigYaml(text, file);
  base.remove("variants");
  ApplyCommandLineOverrides(base, overrides, file);
  config.variants.push_back(VariantConfig{"base", base});

  if (variants.IsDefined() && !variants.IsNull()) {
    if (!variants.IsSequence()) {
      throw ConfigError(NodeLocation(file, variants) +
                        ": variants: expected a list of {name, set}");
    }
    std::set<std::string> names = {"base"};
    for (size_t i = 0; i < variants.size(); ++i) {
      config.variants.push_back(ReadVariant(variants, i, parse, overrides, file, only_variant,
                                            &names, &config.shadowed_overrides));
    }
  }
  // Validate every variant that will run completely before anything runs.
  const bool one = config.Find(only_variant) != nullptr;
  for (const auto& v : config.variants) {
    if (one && v.name != only_variant) continue;
    try {
      BuildPipeline(config, v, registry);
    } catch (const ConfigError& e) {
      // The base is validated first, so an error found later is one that a variant's own set
      // (or a --set meeting it) makes: the message names that variant.
      std::string message = WithSetArgument(e.what(), file, overrides);
      if (v.name != "base") message += " (in variant '" + v.name + "')";
      throw ConfigError(message);
    }
  }
  return config;
}

ExperimentConfig LoadExperimentConfig(const std::string& path, const Registry& registry,
                                      const std::vector<std::string>& overrides,
                                      const std::string& only_variant) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open config file");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseExperimentConfig(text.str(), path, registry, overrides, only_variant);
}

Pipeline BuildPipeline(const ExperimentConfig& config, const VariantConfig& variant,
                       const Registry& registry) {
  const std::string& file = config.file;
  const YAML::Node& tree = variant.tree;
  const YAML::Node stages = tree["pipeline"];
  auto node = [&](const std::string& kind) {
    return stages.IsDefined() && stages.IsMap() ? stages[kind] : YAML::Node();
  };
  Pipeline p;
  p.dataset = registry.CreateAs<Dataset>("dataset", tree["dataset"], file, "dataset", "", "format");
  Pipeline::ForEachStage(p, [&](const char* kind, auto& stage) {
    using T = typename std::remove_reference_t<decltype(stage)>::element_type;
    stage = registry.CreateAs<T>(kind, node(kind), file, std::string("pipeline.") + kind,
                                 DefaultStageType(kind));
  });
  p.evaluation = ParseEvaluationOptions(tree["evaluation"], file, &registry);
  YAML::Node geodesics_node(YAML::NodeType::Map);
  geodesics_node["type"] = p.evaluation.geodesics;
  p.evaluation_geodesics =
      registry.CreateAs<GeodesicsStage>("geodesics", geodesics_node, file, "evaluation.geodesics");
  return p;
}

std::string ResolvedConfigYaml(const ExperimentConfig& config, const VariantConfig& variant,
                               const Pipeline& pipeline) {
  YAML::Emitter out;
  out << YAML::Comment("resolved config of variant '" + variant.name + "' of " + config.file);
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << config.name;
  if (!config.description.empty()) {
    out << YAML::Key << "description" << YAML::Value << config.description;
  }
  out << YAML::Key << "dataset" << YAML::Value << pipeline.dataset->resolved_options();
  out << YAML::Key << "pipeline" << YAML::Value << YAML::BeginMap;
  for (const auto& kind : PipelineKinds()) {
    out << YAML::Key << kind << YAML::Value << YAML::Flow
        << pipeline.StageOf(kind).resolved_options();
  }
  out << YAML::EndMap;
  const EvaluationOptions& e = pipeline.evaluation;
  out << YAML::Key << "evaluation" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "geodesics" << YAML::Value << e.geodesics;
  out << YAML::Key << "max_error" << YAML::Value << FormatNumber(e.max_error);
  out << YAML::Key << "step" << YAML::Value << FormatNumber(e.step);
  out << YAML::Key << "points" << YAML::Value
      << (e.points == 0 ? std::string("all") : std::to_string(e.points));
  // Written only when set, so that the resolved configs of runs without it keep their text.
  if (e.refine_start != EvaluationOptions().refine_start) {
    out << YAML::Key << "refine_start" << YAML::Value << e.refine_start;
  }
  out << YAML::EndMap;
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace symembed
