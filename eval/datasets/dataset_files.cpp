#include "eval/datasets/dataset_files.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/errors.h"

namespace symembed {

namespace fs = std::filesystem;

namespace {

std::ifstream Open(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open " + path);
  return in;
}

std::string Trim(const std::string& s) {
  size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

void ThrowAtLine(const std::string& path, int line, const std::string& what) {
  throw InvalidInputError(path + ":" + std::to_string(line) + ": " + what);
}

std::vector<std::string> ReadTextLines(const std::string& path) {
  std::ifstream in = Open(path);
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

DatasetRestrictions ReadRestrictions(OptionReader& options) {
  DatasetRestrictions r;
  r.classes = options.GetStringList("classes", {});
  r.max_pairs = options.GetInt("max_pairs", 0, Range::AtLeast(0));
  r.pairs_file = options.GetString("pairs_file", "");
  return r;
}

std::string ClassOfName(const std::string& name) {
  size_t end = name.size();
  while (end > 0 && std::isdigit(static_cast<unsigned char>(name[end - 1]))) --end;
  return name.substr(0, end);
}

std::string ResolvePath(const std::string& root, const std::string& path) {
  if (path.empty() || fs::path(path).is_absolute()) return path;
  return (fs::path(root) / path).string();
}

std::vector<std::pair<std::string, std::string>> ListMeshes(const std::string& dir) {
  if (!fs::is_directory(dir)) throw IoError("not a directory: " + dir);
  std::map<std::string, std::string> found;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string ext = Lower(entry.path().extension().string());
    if (ext != ".off" && ext != ".obj" && ext != ".ply") continue;
    // A mesh name whose file cannot be resolved (a symbolic link in a loop or to nothing) is
    // listed all the same, so that its shape fails when read, naming the file, and the others
    // run; only what is plainly not a file (a folder, a device) is passed over.
    std::error_code ec;
    const fs::file_type type = entry.status(ec).type();
    if (!ec && type != fs::file_type::regular && type != fs::file_type::not_found) continue;
    const std::string stem = entry.path().stem().string();
    auto [it, inserted] = found.emplace(stem, entry.path().string());
    if (!inserted) {
      const auto& [a, b] = std::minmax(it->second, entry.path().string());
      throw InvalidInputError("two meshes for shape '" + stem + "': " + a + " and " + b);
    }
  }
  return {found.begin(), found.end()};
}

int CountMeshVertices(const std::string& path) {
  std::ifstream in = Open(path);
  const std::string ext = Lower(fs::path(path).extension().string());
  std::string line;
  int line_no = 0;
  if (ext == ".obj") {
    int count = 0;
    while (std::getline(in, line)) {
      if (line.size() > 1 && line[0] == 'v' && std::isspace(static_cast<unsigned char>(line[1]))) {
        ++count;
      }
    }
    return count;
  }
  if (ext == ".ply") {
    while (std::getline(in, line)) {
      ++line_no;
      std::istringstream words(line);
      std::string a, b;
      long long n = -1;
      words >> a >> b >> n;
      if (a == "element" && b == "vertex" && n >= 0) return static_cast<int>(n);
      if (Trim(line) == "end_header") break;
    }
    ThrowAtLine(path, line_no, "PLY header has no 'element vertex N' line");
  }
  // OFF: "OFF" (possibly followed by the counts on the same line), comments '#'.
  std::vector<std::string> tokens;
  while (tokens.size() < 2 && std::getline(in, line)) {
    ++line_no;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string w;
    while (words >> w) tokens.push_back(w);
  }
  if (tokens.empty() || tokens[0].size() < 3 || tokens[0].compare(tokens[0].size() - 3, 3, "OFF") != 0) {
    ThrowAtLine(path, std::max(line_no, 1), "not an OFF file (no OFF header)");
  }
  try {
    size_t used = 0;
    const long long n = std::stoll(tokens.at(1), &used);
    if (used != tokens[1].size() || n < 0) throw std::invalid_argument(tokens[1]);
    return static_cast<int>(n);
  } catch (const std::exception&) {
    ThrowAtLine(path, line_no, "bad OFF vertex count");
  }
}

ClassTemplate FindClassTemplate(const std::vector<std::string>& mesh_paths) {
  std::map<int, int> votes;
  std::vector<int> counts;
  for (const std::string& path : mesh_paths) {
    counts.push_back(CountMeshVertices(path));
    ++votes[counts.back()];
  }
  ClassTemplate best;
  best.total = static_cast<int>(mesh_paths.size());
  // Walking the meshes in order makes the earliest of tied counts win.
  for (size_t i = 0; i < counts.size(); ++i) {
    if (votes[counts[i]] <= best.meshes) continue;
    best = {counts[i], votes[counts[i]], best.total, mesh_paths[i]};
  }
  return best;
}

void CheckClassTemplate(const std::string& mesh_path, int num_vertices,
                        const ClassTemplate& class_template, const std::string& class_name) {
  if (num_vertices == class_template.vertices) return;
  throw InvalidInputError(
      mesh_path + ": " + std::to_string(num_vertices) + " vertices, but the template of class " +
      class_name + " has " + std::to_string(class_template.vertices) + " (" +
      std::to_string(class_template.meshes) + " of its " + std::to_string(class_template.total) +
      " meshes, e.g. " + class_template.example +
      "): the class's shared vertex ids do not apply to this mesh");
}

std::vector<long long> ReadIntegerLines(const std::string& path) {
  std::ostringstream text;
  text << Open(path).rdbuf();
  return ParseIntegerLines(text.str(), path);
}

std::vector<long long> ParseIntegerLines(const std::string& text, const std::string& path) {
  std::istringstream in(text);
  std::vector<long long> values;
  std::string line;
  int line_no = 0, first_blank = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string t = Trim(line);
    if (t.empty()) {
      if (!first_blank) first_blank = line_no;
      continue;
    }
    if (first_blank) ThrowAtLine(path, first_blank, "blank line before the end of the file");
    try {
      size_t used = 0;
      const long long v = std::stoll(t, &used);
      if (used != t.size()) throw std::invalid_argument(t);
      values.push_back(v);
    } catch (const std::exception&) {
      ThrowAtLine(path, line_no, "expected one integer vertex id, got '" + t + "'");
    }
  }
  return values;
}

std::vector<int> OneBasedIds(const std::vector<long long>& values, const std::string& path,
                             int num_vertices, bool allow_zero) {
  std::vector<int> ids(values.size());
  for (size_t k = 0; k < values.size(); ++k) {
    const long long v = values[k];
    if (v == 0 && allow_zero) {
      ids[k] = -1;
    } else if (v < 1 || v > num_vertices) {
      ThrowAtLine(path, static_cast<int>(k) + 1,
                  "vertex id " + std::to_string(v) + " out of range [1, " +
                      std::to_string(num_vertices) + "]" + (allow_zero ? " (0 = missing)" : ""));
    } else {
      ids[k] = static_cast<int>(v - 1);
    }
  }
  return ids;
}

std::vector<PairLine> ReadPairsFile(const std::string& path) {
  std::ostringstream text;
  text << Open(path).rdbuf();
  return ParsePairsText(text.str(), path);
}

std::vector<PairLine> ParsePairsText(const std::string& text, const std::string& path) {
  std::istringstream in(text);
  std::vector<PairLine> pairs;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string t = Trim(line);
    if (t.empty() || t[0] == '#') continue;
    std::istringstream words(t);
    PairLine p;
    std::string extra;
    words >> p.source >> p.target;
    if (p.target.empty() || (words >> extra)) {
      ThrowAtLine(path, line_no,
                  "expected two shape names separated by a tab or spaces, got '" + t + "'");
    }
    p.line = line_no;
    pairs.push_back(p);
  }
  return pairs;
}

std::vector<DatasetPair> AllPairsWithinClasses(const std::vector<DatasetShape>& shapes) {
  std::vector<DatasetPair> pairs;
  for (size_t i = 0; i < shapes.size(); ++i) {
    for (size_t j = i + 1; j < shapes.size(); ++j) {
      if (shapes[i].class_name == shapes[j].class_name) {
        pairs.push_back({shapes[i].name, shapes[j].name});
      }
    }
  }
  return pairs;
}

DatasetIndex Restrict(const std::vector<DatasetShape>& shapes, const std::vector<DatasetPair>& pairs,
                      const DatasetRestrictions& restrictions, const std::string& where) {
  std::map<std::string, const DatasetShape*> by_name;
  std::set<std::string> present_classes;
  for (const auto& s : shapes) {
    by_name[s.name] = &s;
    present_classes.insert(s.class_name);
  }
  const std::set<std::string> wanted(restrictions.classes.begin(), restrictions.classes.end());
  for (const auto& c : wanted) {
    if (!present_classes.count(c)) {
      std::string known;
      for (const auto& k : present_classes) known += (known.empty() ? "" : ", ") + k;
      throw InvalidInputError(where + ": classes: no shape of class '" + c + "'; classes: " + known);
    }
  }
  DatasetIndex index;
  std::set<std::string> used;
  for (const auto& p : pairs) {
    const DatasetShape* a = by_name.at(p.source);
    const DatasetShape* b = by_name.at(p.target);
    if (!wanted.empty() && (!wanted.count(a->class_name) || !wanted.count(b->class_name))) continue;
    if (restrictions.max_pairs > 0 && static_cast<int>(index.pairs.size()) >= restrictions.max_pairs) {
      break;
    }
    index.pairs.push_back(p);
    used.insert(p.source);
    used.insert(p.target);
  }
  for (const auto& name : used) index.shapes.push_back(*by_name.at(name));
  return index;
}

}  // namespace symembed
