#include "eval/datasets/same_connectivity.h"

#include <algorithm>
#include <filesystem>
#include <map>

#include "core/errors.h"

namespace symembed {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> MeshPaths(const std::vector<std::pair<std::string, std::string>>& meshes) {
  std::vector<std::string> paths;
  for (const auto& [stem, path] : meshes) paths.push_back(path);
  return paths;
}

}  // namespace

SameConnectivityOptions ReadSameConnectivityOptions(OptionReader& options) {
  SameConnectivityOptions o;
  o.root = options.GetRequiredString("root");
  o.restrictions = ReadRestrictions(options);
  return o;
}

DatasetIndex SameConnectivityDataset::Load() const {
  const std::string& root = options_.root;
  if (!fs::is_directory(root)) {
    throw IoError("same_connectivity: dataset root is not a directory: " + root);
  }
  std::vector<std::string> classes;
  for (const auto& entry : fs::directory_iterator(root)) {
    if (entry.is_directory()) classes.push_back(entry.path().filename().string());
  }
  std::sort(classes.begin(), classes.end());

  std::vector<DatasetShape> shapes;
  std::map<std::string, size_t> by_name;
  std::vector<DatasetPair> pairs;
  for (const std::string& c : classes) {
    const std::string dir = (fs::path(root) / c).string();
    const auto meshes = ListMeshes(dir);
    if (meshes.empty()) continue;
    std::vector<DatasetShape> members;
    for (const auto& [stem, path] : meshes) {
      if (by_name.count(stem)) {
        throw InvalidInputError("same_connectivity: shape name '" + stem + "' is used twice: " +
                                shapes[by_name[stem]].mesh_path + " and " + path);
      }
      by_name[stem] = shapes.size();
      shapes.push_back({stem, c, path});
      members.push_back(shapes.back());
    }
    const std::string sym = (fs::path(dir) / "sym.txt").string();
    if (fs::exists(sym)) {
      // Checked against the class's template; a mesh that breaks the template fails on its own
      // (GroundTruth), together with its pairs, not the dataset.
      const ClassTemplate shared = FindClassTemplate(MeshPaths(meshes));
      const auto values = ReadIntegerLines(sym);
      if (static_cast<int>(values.size()) != shared.vertices) {
        throw InvalidInputError(
            sym + ": " + std::to_string(values.size()) + " lines, but the meshes of class " + c +
            " have " + std::to_string(shared.vertices) + " vertices (" + shared.example + ")");
      }
      OneBasedIds(values, sym, shared.vertices, false);
    }
    if (options_.restrictions.pairs_file.empty()) {
      const std::string class_pairs = (fs::path(dir) / "pairs.txt").string();
      if (!fs::exists(class_pairs)) {
        for (const auto& p : AllPairsWithinClasses(members)) pairs.push_back(p);
        continue;
      }
      for (const PairLine& p : ReadPairsFile(class_pairs)) {
        for (const std::string& name : {p.source, p.target}) {
          auto it = by_name.find(name);
          if (it == by_name.end() || shapes[it->second].class_name != c) {
            throw InvalidInputError(class_pairs + ":" + std::to_string(p.line) +
                                    ": unknown shape '" + name + "': no " + dir + "/" + name +
                                    ".off|obj|ply");
          }
        }
        pairs.push_back({p.source, p.target});
      }
    }
  }
  if (!options_.restrictions.pairs_file.empty()) {
    const std::string path = ResolvePath(root, options_.restrictions.pairs_file);
    for (const PairLine& p : ReadPairsFile(path)) {
      for (const std::string& name : {p.source, p.target}) {
        if (!by_name.count(name)) {
          throw InvalidInputError(path + ":" + std::to_string(p.line) + ": unknown shape '" +
                                  name + "' (no mesh " + name + ".off|obj|ply in a class folder)");
        }
      }
      if (shapes[by_name[p.source]].class_name != shapes[by_name[p.target]].class_name) {
        throw InvalidInputError(path + ":" + std::to_string(p.line) + ": shapes '" + p.source +
                                "' and '" + p.target + "' are in different classes");
      }
      pairs.push_back({p.source, p.target});
    }
  }
  return Restrict(shapes, pairs, options_.restrictions, "same_connectivity " + root);
}

ShapeGroundTruth SameConnectivityDataset::GroundTruth(const DatasetShape& shape,
                                                      int num_vertices) const {
  const std::string dir = (fs::path(options_.root) / shape.class_name).string();
  CheckClassTemplate(shape.mesh_path, num_vertices, FindClassTemplate(MeshPaths(ListMeshes(dir))),
                     shape.class_name + " (" + dir + ")");
  ShapeGroundTruth gt;
  gt.ids.resize(num_vertices);
  for (int v = 0; v < num_vertices; ++v) gt.ids[v] = v;
  const std::string sym = (fs::path(dir) / "sym.txt").string();
  if (fs::exists(sym)) {
    const auto values = ReadIntegerLines(sym);
    if (static_cast<int>(values.size()) != num_vertices) {
      throw InvalidInputError(sym + ": " + std::to_string(values.size()) + " lines, but " +
                              shape.mesh_path + " has " + std::to_string(num_vertices) +
                              " vertices");
    }
    gt.sym_ids = OneBasedIds(values, sym, num_vertices, false);
  }
  return gt;
}

}  // namespace symembed
