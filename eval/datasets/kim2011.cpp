#include "eval/datasets/kim2011.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <set>

#include "core/errors.h"
#include "eval/datasets/kim2011_files.h"

namespace symembed {

namespace fs = std::filesystem;

namespace {

// The SHREC'07 Watertight set numbers its 400 meshes from 1, 20 consecutive ones per class
// (1-20 humans, 21-40 cups, ...), and names no class in its files.
constexpr int kNumberedClassSize = 20;

bool IsDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

bool IsNumber(const std::string& s) {
  return !s.empty() && s.size() <= 9 && std::all_of(s.begin(), s.end(), IsDigit);
}

// Natural order: runs of digits compare as numbers (cat2 < cat10, 9 < 10); names equal in that
// order (mesh5, mesh05) fall back to plain order so the order is total.
bool NaturalLess(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (!IsDigit(a[i]) || !IsDigit(b[j])) {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i, ++j;
      continue;
    }
    size_t ie = i, je = j;
    while (ie < a.size() && IsDigit(a[ie])) ++ie;
    while (je < b.size() && IsDigit(b[je])) ++je;
    while (i + 1 < ie && a[i] == '0') ++i;
    while (j + 1 < je && b[j] == '0') ++j;
    if (ie - i != je - j) return ie - i < je - j;
    if (const int c = a.compare(i, ie - i, b, j, je - j)) return c < 0;
    i = ie, j = je;
  }
  if (i == a.size() && j == b.size()) return a < b;
  return i == a.size();
}

bool SameIgnoringCase(const std::string& a, const std::string& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

std::string Join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// One set's folder: its meshes in natural order and the landmark files in Corrs/.
struct SetLayout {
  std::string name, dir;
  std::vector<std::pair<std::string, std::string>> meshes;  // (name, path)
  std::set<std::string> class_files;                        // stems of Corrs/*.pid
  std::set<std::string> own_files;                          // stems of Corrs/*.vts
  bool one_class = false;  // the single class file is the class of every mesh (SCAPE)
};

std::string CorrsFile(const SetLayout& set, const std::string& stem, const std::string& ext) {
  return (fs::path(set.dir) / "Corrs" / (stem + ext)).string();
}

SetLayout ReadSetLayout(const std::string& root, const std::string& name) {
  SetLayout set;
  set.name = name;
  set.dir = (fs::path(root) / "Data" / name).string();
  for (const auto& mesh : ListMeshes((fs::path(set.dir) / "Meshes").string())) {
    const std::string& stem = mesh.first;
    if (stem.size() >= 4 && stem.compare(stem.size() - 4, 4, ".hks") == 0) continue;
    set.meshes.push_back(mesh);
  }
  std::sort(set.meshes.begin(), set.meshes.end(),
            [](const auto& a, const auto& b) { return NaturalLess(a.first, b.first); });
  const fs::path corrs = fs::path(set.dir) / "Corrs";
  if (fs::is_directory(corrs)) {
    for (const auto& entry : fs::directory_iterator(corrs)) {
      if (!entry.is_regular_file()) continue;
      const std::string ext = entry.path().extension().string();
      if (ext == ".pid") set.class_files.insert(entry.path().stem().string());
      if (ext == ".vts") set.own_files.insert(entry.path().stem().string());
    }
  }
  set.one_class = set.class_files.size() == 1 &&
                  std::none_of(set.meshes.begin(), set.meshes.end(), [&](const auto& mesh) {
                    return set.class_files.count(ClassOfName(mesh.first)) > 0;
                  });
  return set;
}

std::string NumberedClass(const std::string& name) {
  const int n = std::stoi(name);
  if (n < 1) return name;
  const int first = (n - 1) / kNumberedClassSize * kNumberedClassSize + 1;
  return std::to_string(first) + "-" + std::to_string(first + kNumberedClassSize - 1);
}

// The class of a mesh within its set (see the header).
std::string ClassOf(const SetLayout& set, const std::string& mesh) {
  const std::string by_name = ClassOfName(mesh);
  if (!set.own_files.count(mesh)) {
    if (set.class_files.count(by_name)) return by_name;
    if (set.one_class) return *set.class_files.begin();
  }
  if (IsNumber(mesh)) return NumberedClass(mesh);
  return by_name.empty() ? mesh : by_name;
}

// Where a mesh's landmarks are: its own file, else its class's (which may not exist).
struct LandmarkFiles {
  std::string ids;
  std::string mirror;  // empty when there is no mirror file
  bool shared = false;
};

LandmarkFiles LandmarkFilesOf(const SetLayout& set, const std::string& mesh,
                              const std::string& class_name) {
  const bool own = set.own_files.count(mesh) > 0;
  const std::string stem = own ? mesh : class_name;
  LandmarkFiles out{CorrsFile(set, stem, own ? ".vts" : ".pid"), CorrsFile(set, stem, ".sym.info"),
                    !own};
  if (!fs::exists(out.mirror)) out.mirror.clear();
  return out;
}

// "<SET>/<CLASS>" -> (set, class).
std::pair<std::string, std::string> SplitClass(const std::string& class_name) {
  const size_t slash = class_name.find('/');
  SYMEMBED_CHECK(slash != std::string::npos, "kim2011 class without a set: " + class_name);
  return {class_name.substr(0, slash), class_name.substr(slash + 1)};
}

// The sets under Data/ (folders with a Meshes/ folder), sorted.
std::vector<std::string> ListSets(const std::string& root) {
  const fs::path data = fs::path(root) / "Data";
  if (!fs::is_directory(data)) throw IoError("kim2011: not a directory: " + data.string());
  std::vector<std::string> sets;
  for (const auto& entry : fs::directory_iterator(data)) {
    if (fs::is_directory(entry.path() / "Meshes")) sets.push_back(entry.path().filename().string());
  }
  std::sort(sets.begin(), sets.end());
  return sets;
}

// The sets `classes` selects (all when empty): each entry names a set or a <SET>/<CLASS>.
std::vector<std::string> SelectSets(const std::vector<std::string>& sets,
                                    const std::vector<std::string>& classes,
                                    const std::string& where) {
  if (classes.empty()) return sets;
  std::set<std::string> selected;
  for (const std::string& entry : classes) {
    const std::string set = entry.substr(0, entry.find('/'));
    if (std::find(sets.begin(), sets.end(), set) == sets.end()) {
      throw InvalidInputError(where + ": classes: '" + entry +
                              "' names no set under Data/ (sets: " + Join(sets) + ")");
    }
    selected.insert(set);
  }
  return {selected.begin(), selected.end()};
}

// The queried meshes of each selected set, as indices into its meshes, in query order.
std::map<std::string, std::vector<int>> ReadQueries(
    const std::string& root, const std::vector<std::string>& sets,
    const std::map<std::string, SetLayout>& layouts) {
  std::map<std::string, std::vector<int>> queried;
  const fs::path results = fs::path(root) / "Results";
  if (!fs::is_directory(results)) return queried;
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(results)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && name.rfind("Corr_", 0) == 0 &&
        entry.path().extension() == ".query") {
      files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  std::map<std::string, std::map<int, std::string>> seen;  // set -> index -> where queried
  for (const std::string& file : files) {
    for (const KimQuery& q : ReadQueryFile(file)) {
      const auto set = std::find_if(sets.begin(), sets.end(), [&](const std::string& s) {
        return SameIgnoringCase(s, q.set);
      });
      if (set == sets.end()) {
        throw InvalidInputError(file + ":" + std::to_string(q.set_line) + ": unknown set '" +
                                q.set + "': no Data/" + q.set + "/Meshes (sets: " + Join(sets) +
                                ")");
      }
      const auto layout = layouts.find(*set);
      if (layout == layouts.end()) continue;  // not selected
      const auto& meshes = layout->second.meshes;
      const std::string at = file + ":" + std::to_string(q.line);
      if (q.index >= static_cast<int>(meshes.size())) {
        throw InvalidInputError(at + ": mesh index " + std::to_string(q.index) + " of set " + *set +
                                " has no mesh: " + layout->second.dir + "/Meshes has " +
                                std::to_string(meshes.size()) +
                                " meshes, indices from 0 in natural name order");
      }
      const auto [it, fresh] = seen[*set].emplace(q.index, at);
      if (!fresh) {
        throw InvalidInputError(at + ": mesh " + meshes[q.index].first + " (index " +
                                std::to_string(q.index) + ") is already queried at " + it->second);
      }
      queried[*set].push_back(q.index);
    }
  }
  return queried;
}

// The pairs of `pairs_file`: named shapes of one class.
std::vector<DatasetPair> ReadListedPairs(const std::string& path,
                                         const std::map<std::string, DatasetShape>& shapes) {
  std::vector<DatasetPair> pairs;
  for (const PairLine& p : ReadPairsFile(path)) {
    const std::string at = path + ":" + std::to_string(p.line) + ": ";
    for (const std::string& name : {p.source, p.target}) {
      if (!shapes.count(name)) {
        throw InvalidInputError(at + "unknown shape '" + name + "' (no Data/<SET>/Meshes/" + name +
                                ".off in the selected sets)");
      }
    }
    const std::string& a = shapes.at(p.source).class_name;
    const std::string& b = shapes.at(p.target).class_name;
    if (a != b) {
      throw InvalidInputError(at + "shapes '" + p.source + "' (" + a + ") and '" + p.target +
                              "' (" + b + ") are in different classes");
    }
    pairs.push_back({p.source, p.target});
  }
  return pairs;
}

// Reads every landmark and mirror file the pairs need, so malformed ones stop the run before
// it starts; a missing one fails only its shape (GroundTruth).
void CheckLandmarkFiles(const std::vector<DatasetPair>& pairs,
                        const std::map<std::string, DatasetShape>& shapes,
                        const std::map<std::string, SetLayout>& layouts) {
  std::map<std::string, size_t> lines;  // landmark file -> landmark lines
  std::set<std::string> mirrors_read;
  auto landmark_lines = [&](const DatasetShape& shape) -> std::pair<std::string, size_t> {
    const auto [set, class_name] = SplitClass(shape.class_name);
    const LandmarkFiles files = LandmarkFilesOf(layouts.at(set), shape.name, class_name);
    if (!fs::exists(files.ids)) return {"", 0};
    if (!lines.count(files.ids)) lines[files.ids] = ReadLandmarkIds(files.ids).size();
    if (!files.mirror.empty() && mirrors_read.insert(files.mirror).second) {
      ReadMirrorLines(files.mirror, static_cast<int>(lines[files.ids]), files.ids);
    }
    return {files.ids, lines[files.ids]};
  };
  for (const DatasetPair& pair : pairs) {
    const auto a = landmark_lines(shapes.at(pair.source));
    const auto b = landmark_lines(shapes.at(pair.target));
    if (!a.first.empty() && !b.first.empty() && a.second != b.second) {
      throw InvalidInputError("kim2011: the pair " + pair.source + " -> " + pair.target +
                              " has landmark files of different lengths: " + a.first + " has " +
                              std::to_string(a.second) + " lines, " + b.first + " has " +
                              std::to_string(b.second));
    }
  }
}

}  // namespace

Kim2011Options ReadKim2011Options(OptionReader& options) {
  Kim2011Options o;
  o.root = options.GetRequiredString("root");
  o.restrictions = ReadRestrictions(options);
  return o;
}

DatasetIndex Kim2011Dataset::Load() const {
  const std::string where = "kim2011 " + options_.root;
  const std::vector<std::string> sets = ListSets(options_.root);
  std::map<std::string, SetLayout> layouts;
  std::map<std::string, DatasetShape> shapes;
  std::vector<DatasetShape> all_shapes;
  for (const std::string& set : SelectSets(sets, options_.restrictions.classes, where)) {
    const SetLayout& layout = layouts[set] = ReadSetLayout(options_.root, set);
    for (const auto& [name, path] : layout.meshes) {
      const DatasetShape shape{name, set + "/" + ClassOf(layout, name), path};
      const auto [it, fresh] = shapes.emplace(name, shape);
      if (!fresh) {
        throw InvalidInputError("kim2011: shape name '" + name +
                                "' is used twice: " + it->second.mesh_path + " and " + path +
                                " (restrict `classes` to one of the sets)");
      }
      all_shapes.push_back(shape);
    }
  }

  std::vector<DatasetPair> pairs;
  if (!options_.restrictions.pairs_file.empty()) {
    pairs = ReadListedPairs(ResolvePath(options_.root, options_.restrictions.pairs_file), shapes);
  } else {
    const auto queried = ReadQueries(options_.root, sets, layouts);
    for (const auto& [set, layout] : layouts) {
      // Pairs within a class, in query order (else in name order) of the set's meshes.
      std::vector<DatasetShape> order;
      const auto q = queried.find(set);
      if (q != queried.end()) {
        for (int index : q->second) order.push_back(shapes.at(layout.meshes[index].first));
      } else {
        for (const auto& mesh : layout.meshes) order.push_back(shapes.at(mesh.first));
      }
      for (const DatasetPair& p : AllPairsWithinClasses(order)) pairs.push_back(p);
    }
  }
  CheckLandmarkFiles(pairs, shapes, layouts);

  // A set named in `classes` stands for all of its classes.
  DatasetRestrictions restrictions = options_.restrictions;
  std::vector<std::string> classes;
  for (const std::string& entry : options_.restrictions.classes) {
    if (!layouts.count(entry)) {
      classes.push_back(entry);
      continue;
    }
    for (const DatasetShape& s : all_shapes) {
      if (SplitClass(s.class_name).first == entry) classes.push_back(s.class_name);
    }
  }
  restrictions.classes = classes;
  return Restrict(all_shapes, pairs, restrictions, where);
}

ShapeGroundTruth Kim2011Dataset::GroundTruth(const DatasetShape& shape, int num_vertices) const {
  const auto [set_name, class_name] = SplitClass(shape.class_name);
  const SetLayout set = ReadSetLayout(options_.root, set_name);
  const LandmarkFiles files = LandmarkFilesOf(set, shape.name, class_name);
  if (!fs::exists(files.ids)) {
    throw InvalidInputError(shape.mesh_path + ": no landmarks: neither " +
                            CorrsFile(set, shape.name, ".vts") + " nor " +
                            CorrsFile(set, class_name, ".pid") + " exists");
  }
  if (files.shared) {
    std::vector<std::string> members;
    for (const auto& [name, path] : set.meshes) {
      if (!set.own_files.count(name) && ClassOf(set, name) == class_name) members.push_back(path);
    }
    CheckClassTemplate(shape.mesh_path, num_vertices, FindClassTemplate(members),
                       shape.class_name + " (" + files.ids + ")");
  }
  const std::vector<long long> ids = ReadLandmarkIds(files.ids);
  ShapeGroundTruth gt;
  for (size_t k = 0; k < ids.size(); ++k) {
    if (ids[k] >= num_vertices) {
      throw InvalidInputError(files.ids + ":" + std::to_string(k + 1) + ": vertex id " +
                              std::to_string(ids[k]) + " out of range [0, " +
                              std::to_string(num_vertices - 1) + "] of " + shape.mesh_path);
    }
    gt.ids.push_back(static_cast<int>(ids[k]));
  }
  if (!files.mirror.empty()) {
    for (int m : ReadMirrorLines(files.mirror, static_cast<int>(ids.size()), files.ids)) {
      gt.sym_ids.push_back(m < 0 ? -1 : gt.ids[m]);
    }
  }
  return gt;
}

}  // namespace symembed
