#include "eval/datasets/pairs_vts.h"

#include <filesystem>
#include <map>

#include "core/errors.h"

namespace symembed {

namespace fs = std::filesystem;

namespace {

std::string VtsPath(const std::string& root, const std::string& name, bool sym) {
  return (fs::path(root) / "corres" / (name + (sym ? ".sym.vts" : ".vts"))).string();
}

}  // namespace

PairsVtsOptions ReadPairsVtsOptions(OptionReader& options) {
  PairsVtsOptions o;
  o.root = options.GetRequiredString("root");
  o.restrictions = ReadRestrictions(options);
  return o;
}

DatasetIndex PairsVtsDataset::Load() const {
  const std::string& root = options_.root;
  if (!fs::is_directory(root)) throw IoError("pairs_vts: dataset root is not a directory: " + root);
  const std::string shapes_dir = (fs::path(root) / "shapes").string();
  if (!fs::is_directory(shapes_dir)) {
    throw InvalidInputError("pairs_vts: missing folder " + shapes_dir);
  }
  std::vector<DatasetShape> shapes;
  std::map<std::string, size_t> by_name;
  for (const auto& [stem, path] : ListMeshes(shapes_dir)) {
    by_name[stem] = shapes.size();
    shapes.push_back({stem, ClassOfName(stem), path});
  }

  std::string pairs_path = ResolvePath(root, options_.restrictions.pairs_file);
  if (pairs_path.empty()) {
    const std::string default_path = (fs::path(root) / "test_pairs.txt").string();
    if (fs::exists(default_path)) pairs_path = default_path;
  }
  std::vector<DatasetPair> pairs;
  std::map<std::string, std::string> named_at;  // shape -> "file:line" of its first pair
  if (pairs_path.empty()) {
    pairs = AllPairsWithinClasses(shapes);
  } else {
    for (const PairLine& p : ReadPairsFile(pairs_path)) {
      const std::string at = pairs_path + ":" + std::to_string(p.line);
      for (const std::string& name : {p.source, p.target}) {
        if (!by_name.count(name)) {
          throw InvalidInputError(at + ": unknown shape '" + name + "': no " + shapes_dir + "/" +
                                  name + ".off|obj|ply");
        }
        named_at.emplace(name, at);
      }
      pairs.push_back({p.source, p.target});
    }
    if (pairs.empty()) {
      throw InvalidInputError(pairs_path + ": no pairs (expected lines 'SOURCE TARGET')");
    }
  }
  DatasetIndex index = Restrict(shapes, pairs, options_.restrictions, "pairs_vts " + root);

  // Ground-truth files exist, parse, and have as many lines as their partners'.
  std::map<std::string, std::pair<size_t, long long>> lines;  // name -> (#vts, #sym or -1)
  for (const auto& s : index.shapes) {
    const std::string vts = VtsPath(root, s.name, false), sym = VtsPath(root, s.name, true);
    if (!fs::exists(vts)) {
      auto at = named_at.find(s.name);
      throw InvalidInputError("pairs_vts: missing ground truth " + vts + " of shape " + s.name +
                              (at == named_at.end() ? "" : " (named at " + at->second + ")"));
    }
    const size_t n = ReadIntegerLines(vts).size();
    long long n_sym = -1;
    if (fs::exists(sym)) {
      n_sym = static_cast<long long>(ReadIntegerLines(sym).size());
      if (n_sym != static_cast<long long>(n)) {
        throw InvalidInputError(sym + ": " + std::to_string(n_sym) + " lines, but " + vts +
                                " has " + std::to_string(n));
      }
    }
    lines[s.name] = {n, n_sym};
  }
  for (const auto& p : index.pairs) {
    const auto& a = lines.at(p.source);
    const auto& b = lines.at(p.target);
    if (a.first != b.first) {
      auto at = named_at.find(p.source);
      throw InvalidInputError(VtsPath(root, p.target, false) + ": " + std::to_string(b.first) +
                              " lines, but its partner " + VtsPath(root, p.source, false) +
                              " has " + std::to_string(a.first) + " (pair " + p.source + " " +
                              p.target +
                              (at == named_at.end() ? "" : " at " + at->second) + ")");
    }
  }
  return index;
}

ShapeGroundTruth PairsVtsDataset::GroundTruth(const DatasetShape& shape, int num_vertices) const {
  ShapeGroundTruth gt;
  const std::string vts = VtsPath(options_.root, shape.name, false);
  gt.ids = OneBasedIds(ReadIntegerLines(vts), vts, num_vertices, true);
  const std::string sym = VtsPath(options_.root, shape.name, true);
  if (fs::exists(sym)) {
    gt.sym_ids = OneBasedIds(ReadIntegerLines(sym), sym, num_vertices, true);
    if (gt.sym_ids.size() != gt.ids.size()) {
      throw InvalidInputError(sym + ": " + std::to_string(gt.sym_ids.size()) + " lines, but " +
                              vts + " has " + std::to_string(gt.ids.size()));
    }
  }
  return gt;
}

}  // namespace symembed
