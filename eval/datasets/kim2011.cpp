#include "eval/datasets/kim2011.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/errors.h"

namespace symembed {

namespace fs = std::filesystem;

namespace {

struct Landmark {
  long long id;
  int line;
};

// name -> (raw id, line) of one landmark file.
std::map<std::string, Landmark> ReadLandmarks(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError("cannot open " + path);
  std::map<std::string, Landmark> out;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    std::istringstream words(line);
    std::string id_text, name, extra;
    if (!(words >> id_text) || id_text[0] == '#') continue;
    const std::string at = path + ":" + std::to_string(line_no) + ": ";
    long long id = 0;
    try {
      size_t used = 0;
      id = std::stoll(id_text, &used);
      if (used != id_text.size()) throw std::invalid_argument(id_text);
    } catch (const std::exception&) {
      throw InvalidInputError(at + "expected '<vertex id> <landmark name>', got '" + line + "'");
    }
    if (!(words >> name) || (words >> extra)) {
      throw InvalidInputError(at + "expected '<vertex id> <landmark name>', got '" + line + "'");
    }
    auto [it, inserted] = out.emplace(name, Landmark{id, line_no});
    if (!inserted) {
      throw InvalidInputError(at + "landmark '" + name + "' already given on line " +
                              std::to_string(it->second.line));
    }
  }
  return out;
}

std::string SetDir(const std::string& root, const std::string& set) {
  return (fs::path(root) / "Data" / set).string();
}

std::string LandmarkPath(const std::string& root, const std::string& set, const std::string& name) {
  return (fs::path(SetDir(root, set)) / "Landmarks" / (name + ".vts")).string();
}

// The set's landmark names (sorted union) and the mirror of each (by index).
struct SetLandmarks {
  std::vector<std::string> names;
  std::vector<int> mirror;  // empty without symmetric_landmarks.txt
};

SetLandmarks ReadSetLandmarks(const std::string& root, const std::string& set) {
  const std::string dir = SetDir(root, set);
  std::set<std::string> names;
  for (const auto& [stem, path] : ListMeshes((fs::path(dir) / "Meshes").string())) {
    const std::string lm = LandmarkPath(root, set, stem);
    if (!fs::exists(lm)) {
      throw InvalidInputError("kim2011: missing landmark file " + lm + " of mesh " + path);
    }
    for (const auto& [name, landmark] : ReadLandmarks(lm)) names.insert(name);
  }
  SetLandmarks out;
  out.names.assign(names.begin(), names.end());
  const std::string sym = (fs::path(dir) / "symmetric_landmarks.txt").string();
  if (!fs::exists(sym)) return out;
  out.mirror.resize(out.names.size());
  for (size_t i = 0; i < out.names.size(); ++i) out.mirror[i] = static_cast<int>(i);
  std::vector<int> paired_on(out.names.size(), 0);
  for (const PairLine& p : ReadPairsFile(sym)) {
    const std::string at = sym + ":" + std::to_string(p.line) + ": ";
    int ids[2];
    const std::string* both[2] = {&p.source, &p.target};
    for (int k = 0; k < 2; ++k) {
      auto it = std::lower_bound(out.names.begin(), out.names.end(), *both[k]);
      if (it == out.names.end() || *it != *both[k]) {
        throw InvalidInputError(at + "unknown landmark '" + *both[k] +
                                "' (no landmark file of set " + set + " names it)");
      }
      ids[k] = static_cast<int>(it - out.names.begin());
      if (paired_on[ids[k]]) {
        throw InvalidInputError(at + "landmark '" + *both[k] + "' already paired on line " +
                                std::to_string(paired_on[ids[k]]));
      }
    }
    if (ids[0] == ids[1]) throw InvalidInputError(at + "a landmark paired with itself");
    paired_on[ids[0]] = paired_on[ids[1]] = p.line;
    out.mirror[ids[0]] = ids[1];
    out.mirror[ids[1]] = ids[0];
  }
  return out;
}

}  // namespace

Kim2011Options ReadKim2011Options(OptionReader& options) {
  Kim2011Options o;
  o.root = options.GetRequiredString("root");
  o.id_base = options.GetInt("id_base", 0, 0, 1);
  o.restrictions = ReadRestrictions(options);
  return o;
}

DatasetIndex Kim2011Dataset::Load() const {
  const std::string data = (fs::path(options_.root) / "Data").string();
  if (!fs::is_directory(data)) throw IoError("kim2011: not a directory: " + data);
  std::vector<std::string> sets;
  for (const auto& entry : fs::directory_iterator(data)) {
    if (entry.is_directory()) sets.push_back(entry.path().filename().string());
  }
  std::sort(sets.begin(), sets.end());
  const auto& wanted = options_.restrictions.classes;

  std::vector<DatasetShape> shapes;
  std::map<std::string, size_t> by_name;
  std::vector<DatasetPair> pairs;
  for (const std::string& set : sets) {
    if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), set) == wanted.end()) continue;
    const std::string dir = SetDir(options_.root, set);
    const std::string meshes_dir = (fs::path(dir) / "Meshes").string();
    if (!fs::is_directory(meshes_dir)) continue;
    std::vector<DatasetShape> members;
    for (const auto& [stem, path] : ListMeshes(meshes_dir)) {
      if (by_name.count(stem)) {
        throw InvalidInputError("kim2011: shape name '" + stem + "' is used twice: " +
                                shapes[by_name[stem]].mesh_path + " and " + path +
                                " (restrict `classes` to one of the sets)");
      }
      by_name[stem] = shapes.size();
      shapes.push_back({stem, set, path});
      members.push_back(shapes.back());
    }
    // Landmark files: one per mesh and no orphans; the set's names and mirror pairs parse.
    const std::string lm_dir = (fs::path(dir) / "Landmarks").string();
    if (fs::is_directory(lm_dir)) {
      for (const auto& entry : fs::directory_iterator(lm_dir)) {
        if (entry.path().extension() != ".vts") continue;
        const std::string stem = entry.path().stem().string();
        if (!by_name.count(stem) || shapes[by_name[stem]].class_name != set) {
          throw InvalidInputError("kim2011: landmark file " + entry.path().string() +
                                  " has no mesh " + meshes_dir + "/" + stem + ".off");
        }
      }
    }
    ReadSetLandmarks(options_.root, set);
    const std::string set_pairs = (fs::path(dir) / "pairs.txt").string();
    if (!options_.restrictions.pairs_file.empty()) continue;
    if (!fs::exists(set_pairs)) {
      for (const auto& p : AllPairsWithinClasses(members)) pairs.push_back(p);
      continue;
    }
    for (const PairLine& p : ReadPairsFile(set_pairs)) {
      for (const std::string& name : {p.source, p.target}) {
        auto it = by_name.find(name);
        if (it == by_name.end() || shapes[it->second].class_name != set) {
          throw InvalidInputError(set_pairs + ":" + std::to_string(p.line) + ": unknown shape '" +
                                  name + "': no " + meshes_dir + "/" + name + ".off");
        }
      }
      pairs.push_back({p.source, p.target});
    }
  }
  if (!options_.restrictions.pairs_file.empty()) {
    const std::string path = ResolvePath(options_.root, options_.restrictions.pairs_file);
    for (const PairLine& p : ReadPairsFile(path)) {
      for (const std::string& name : {p.source, p.target}) {
        if (!by_name.count(name)) {
          throw InvalidInputError(path + ":" + std::to_string(p.line) + ": unknown shape '" +
                                  name + "' (no Data/<SET>/Meshes/" + name + ".off)");
        }
      }
      if (shapes[by_name[p.source]].class_name != shapes[by_name[p.target]].class_name) {
        throw InvalidInputError(path + ":" + std::to_string(p.line) + ": shapes '" + p.source +
                                "' and '" + p.target + "' are in different sets");
      }
      pairs.push_back({p.source, p.target});
    }
  }
  return Restrict(shapes, pairs, options_.restrictions, "kim2011 " + options_.root);
}

ShapeGroundTruth Kim2011Dataset::GroundTruth(const DatasetShape& shape, int num_vertices) const {
  const SetLandmarks set = ReadSetLandmarks(options_.root, shape.class_name);
  const std::string path = LandmarkPath(options_.root, shape.class_name, shape.name);
  const auto landmarks = ReadLandmarks(path);
  ShapeGroundTruth gt;
  gt.ids.assign(set.names.size(), -1);
  for (size_t i = 0; i < set.names.size(); ++i) {
    auto it = landmarks.find(set.names[i]);
    if (it == landmarks.end()) continue;
    const long long id = it->second.id - options_.id_base;
    if (id < 0 || id >= num_vertices) {
      throw InvalidInputError(path + ":" + std::to_string(it->second.line) + ": vertex id " +
                              std::to_string(it->second.id) + " out of range [" +
                              std::to_string(options_.id_base) + ", " +
                              std::to_string(num_vertices - 1 + options_.id_base) + "]");
    }
    gt.ids[i] = static_cast<int>(id);
  }
  if (!set.mirror.empty()) {
    gt.sym_ids.resize(gt.ids.size());
    for (size_t i = 0; i < gt.ids.size(); ++i) gt.sym_ids[i] = gt.ids[set.mirror[i]];
  }
  return gt;
}

}  // namespace symembed
