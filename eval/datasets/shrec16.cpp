#include "eval/datasets/shrec16.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "core/errors.h"
#include "core/mesh_io.h"

namespace symembed {

namespace fs = std::filesystem;

namespace {

// The pairs of `pairs_file` when given (each name checked against the shapes), else `fallback`.
std::vector<DatasetPair> PairsOrFile(const std::string& root, const std::string& pairs_file,
                                     const std::map<std::string, size_t>& by_name,
                                     std::vector<DatasetPair> fallback) {
  const std::string path = ResolvePath(root, pairs_file);
  if (path.empty()) return fallback;
  std::vector<DatasetPair> pairs;
  for (const PairLine& p : ReadPairsFile(path)) {
    for (const std::string& name : {p.source, p.target}) {
      if (!by_name.count(name)) {
        ThrowAtLine(path, p.line, "unknown shape '" + name + "' (not in " + root + ")");
      }
    }
    pairs.push_back({p.source, p.target});
  }
  if (pairs.empty()) throw InvalidInputError(path + ": no pairs (expected lines 'SOURCE TARGET')");
  return pairs;
}

// The whitespace-separated fields of a line.
std::vector<std::string> Fields(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

bool ParseNumber(const std::string& token, double* value) {
  char* end = nullptr;
  *value = std::strtod(token.c_str(), &end);
  return end != token.c_str() && *end == '\0' && std::isfinite(*value);
}

// A 1-based index in [1, count] written as an integer (possibly in floating-point notation,
// as the SHREC'16 files write it: "1.4700000e+02"); returns it 0-based.
int OneBasedIndex(const std::string& token, int count, const std::string& path, int line,
                  const std::string& what) {
  double v = 0.0;
  if (!ParseNumber(token, &v) || v != std::floor(v)) {
    ThrowAtLine(path, line, what + " '" + token + "' is not an integer");
  }
  if (v < 1 || v > count) {
    ThrowAtLine(path, line,
                what + " " + token + " out of range [1, " + std::to_string(count) + "]");
  }
  return static_cast<int>(v) - 1;
}

// Reads the rows, dropping trailing blank lines; a blank line before the last row is an error.
std::vector<std::string> DataRows(const std::string& path) {
  std::vector<std::string> lines = ReadTextLines(path);
  while (!lines.empty() && Fields(lines.back()).empty()) lines.pop_back();
  for (size_t i = 0; i < lines.size(); ++i) {
    if (Fields(lines[i]).empty()) ThrowAtLine(path, static_cast<int>(i + 1), "blank line");
  }
  return lines;
}

// The mesh file of `stem` in dir (ListMeshes); empty when there is none.
std::string MeshOfStem(const std::string& dir, const std::string& stem) {
  for (const auto& [name, path] : ListMeshes(dir)) {
    if (name == stem) return path;
  }
  return "";
}

}  // namespace

// --- shrec16_partial -------------------------------------------------------------------------

Shrec16PartialOptions ReadShrec16PartialOptions(OptionReader& options) {
  Shrec16PartialOptions o;
  o.root = options.GetRequiredString("root");
  o.track = options.GetChoice("track", "auto", {"auto", "cuts", "holes"});
  o.restrictions = ReadRestrictions(options);
  return o;
}

std::string Shrec16PartialClass(const std::string& stem, const std::string& track) {
  const std::string prefix = track + "_";
  const std::string infix = "_shape_";
  if (stem.compare(0, prefix.size(), prefix) != 0) return "";
  const size_t at = stem.rfind(infix);
  if (at == std::string::npos || at <= prefix.size()) return "";
  const std::string number = stem.substr(at + infix.size());
  if (number.empty() ||
      !std::all_of(number.begin(), number.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return "";
  }
  return stem.substr(prefix.size(), at - prefix.size());
}

std::string Shrec16PartialDataset::Track() const {
  if (options_.track != "auto") return options_.track;
  const bool cuts = fs::is_directory(fs::path(options_.root) / "cuts");
  const bool holes = fs::is_directory(fs::path(options_.root) / "holes");
  if (cuts && holes) {
    throw InvalidInputError("shrec16_partial: " + options_.root +
                            " has both cuts/ and holes/: choose one with `track`");
  }
  if (!cuts && !holes) {
    throw InvalidInputError("shrec16_partial: " + options_.root + " has neither cuts/ nor holes/");
  }
  return cuts ? "cuts" : "holes";
}

DatasetIndex Shrec16PartialDataset::Load() const {
  const std::string& root = options_.root;
  if (!fs::is_directory(root)) {
    throw IoError("shrec16_partial: dataset root is not a directory: " + root);
  }
  const std::string track = Track();
  const std::string track_dir = (fs::path(root) / track).string();
  const std::string null_dir = (fs::path(root) / "null").string();
  if (!fs::is_directory(track_dir))
    throw InvalidInputError("shrec16_partial: missing folder " + track_dir);
  if (!fs::is_directory(null_dir))
    throw InvalidInputError("shrec16_partial: missing folder " + null_dir);

  std::vector<DatasetShape> shapes;
  std::map<std::string, size_t> by_name;
  for (const auto& [stem, path] : ListMeshes(null_dir)) {
    by_name[stem] = shapes.size();
    shapes.push_back({stem, stem, path});
  }
  // Partial shapes in class order, then by their number (shape_2 before shape_10).
  std::vector<std::pair<std::pair<std::string, long long>, DatasetShape>> partial;
  for (const auto& [stem, path] : ListMeshes(track_dir)) {
    const std::string class_name = Shrec16PartialClass(stem, track);
    if (class_name.empty()) {
      throw InvalidInputError("shrec16_partial: " + path + ": name is not " + track +
                              "_CLASS_shape_N");
    }
    if (!by_name.count(class_name)) {
      throw InvalidInputError("shrec16_partial: " + path + ": no null shape " + null_dir + "/" +
                              class_name + ".off|obj|ply for its class");
    }
    if (by_name.count(stem)) {
      throw InvalidInputError("shrec16_partial: " + path + ": name taken by a null shape");
    }
    const long long number = std::stoll(stem.substr(stem.rfind('_') + 1));
    partial.push_back({{class_name, number}, {stem, class_name, path}});
  }
  std::sort(partial.begin(), partial.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<DatasetPair> pairs;
  for (const auto& [order, shape] : partial) {
    by_name[shape.name] = shapes.size();
    shapes.push_back(shape);
    pairs.push_back({shape.name, shape.class_name});
  }
  if (pairs.empty()) throw InvalidInputError("shrec16_partial: no partial shapes in " + track_dir);
  pairs = PairsOrFile(root, options_.restrictions.pairs_file, by_name, std::move(pairs));
  DatasetIndex index = Restrict(shapes, pairs, options_.restrictions, "shrec16_partial " + root);
  for (const DatasetShape& s : index.shapes) {
    if (s.name == s.class_name) continue;  // a null shape
    const std::string gt = (fs::path(track_dir) / (s.name + ".baryc_gt")).string();
    if (!fs::exists(gt)) {
      throw InvalidInputError("shrec16_partial: missing ground truth " + gt + " of shape " +
                              s.name);
    }
  }
  return index;
}

std::vector<int> ReadBarycentricTruth(const std::string& path, const Eigen::MatrixX3i& faces,
                                      int rows) {
  const std::vector<std::string> lines = DataRows(path);
  if (static_cast<int>(lines.size()) != rows) {
    throw InvalidInputError(path + ": " + std::to_string(lines.size()) +
                            " rows, but the partial shape has " + std::to_string(rows) +
                            " vertices");
  }
  const int num_faces = static_cast<int>(faces.rows());
  std::vector<int> ids(lines.size());
  for (size_t i = 0; i < lines.size(); ++i) {
    const int line = static_cast<int>(i + 1);
    const std::vector<std::string> f = Fields(lines[i]);
    if (f.size() != 4) {
      ThrowAtLine(path, line, std::to_string(f.size()) + " fields; expected 'TRIANGLE W1 W2 W3'");
    }
    const int t = OneBasedIndex(f[0], num_faces, path, line, "triangle");
    int best = 0;
    double best_weight = -1.0;
    for (int k = 0; k < 3; ++k) {
      double w = 0.0;
      if (!ParseNumber(f[k + 1], &w) || w < -1e-6) {
        ThrowAtLine(path, line, "weight '" + f[k + 1] + "' is not a finite non-negative number");
      }
      if (w > best_weight) {
        best_weight = w;
        best = k;
      }
    }
    ids[i] = faces(t, best);
  }
  return ids;
}

std::shared_ptr<const Eigen::MatrixX3i> Shrec16PartialDataset::NullFaces(
    const std::string& class_name) const {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = null_faces_.find(class_name);
    if (it != null_faces_.end()) return it->second;
  }
  const std::string path = MeshOfStem((fs::path(options_.root) / "null").string(), class_name);
  if (path.empty()) {
    throw InvalidInputError("shrec16_partial: no null shape for class " + class_name);
  }
  auto faces = std::make_shared<const Eigen::MatrixX3i>(LoadSurface(path).F);
  std::lock_guard<std::mutex> lock(mutex_);
  return null_faces_.emplace(class_name, std::move(faces)).first->second;
}

ShapeGroundTruth Shrec16PartialDataset::GroundTruth(const DatasetShape& shape,
                                                    int num_vertices) const {
  ShapeGroundTruth gt;
  if (shape.name == shape.class_name) return gt;  // a null shape: the partial shapes carry it
  const std::string track_dir = (fs::path(options_.root) / Track()).string();
  const std::shared_ptr<const Eigen::MatrixX3i> null_faces = NullFaces(shape.class_name);
  const std::string base = (fs::path(track_dir) / shape.name).string();
  gt.onto = shape.class_name;
  gt.onto_lines.target_ids = ReadBarycentricTruth(base + ".baryc_gt", *null_faces, num_vertices);
  gt.onto_lines.source_ids.resize(num_vertices);
  for (int i = 0; i < num_vertices; ++i) gt.onto_lines.source_ids[i] = i;
  if (fs::exists(base + ".baryc_gt_sym")) {
    gt.onto_lines.target_sym_ids =
        ReadBarycentricTruth(base + ".baryc_gt_sym", *null_faces, num_vertices);
  }
  return gt;
}

// --- topkids ---------------------------------------------------------------------------------

TopKidsOptions ReadTopKidsOptions(OptionReader& options) {
  TopKidsOptions o;
  o.root = options.GetRequiredString("root");
  o.null_shape = options.GetString("null_shape", o.null_shape);
  o.restrictions = ReadRestrictions(options);
  return o;
}

namespace {

std::string RefPath(const std::string& root, const std::string& name) {
  return (fs::path(root) / (name + "_ref.txt")).string();
}

}  // namespace

DatasetIndex TopKidsDataset::Load() const {
  const std::string& root = options_.root;
  if (!fs::is_directory(root)) throw IoError("topkids: dataset root is not a directory: " + root);
  std::vector<DatasetShape> shapes;
  std::map<std::string, size_t> by_name;
  for (const auto& [stem, path] : ListMeshes(root)) {
    by_name[stem] = shapes.size();
    shapes.push_back({stem, ClassOfName(stem), path});
  }
  if (!by_name.count(options_.null_shape)) {
    throw InvalidInputError("topkids: no null shape " + root + "/" + options_.null_shape +
                            ".off|obj|ply");
  }
  std::vector<DatasetPair> pairs;
  for (const DatasetShape& s : shapes) {
    if (s.name == options_.null_shape) continue;
    if (!fs::exists(RefPath(root, s.name))) {
      throw InvalidInputError("topkids: missing ground truth " + RefPath(root, s.name) +
                              " of shape " + s.name);
    }
    pairs.push_back({s.name, options_.null_shape});
  }
  if (pairs.empty()) throw InvalidInputError("topkids: no shape besides the null shape in " + root);
  pairs = PairsOrFile(root, options_.restrictions.pairs_file, by_name, std::move(pairs));
  return Restrict(shapes, pairs, options_.restrictions, "topkids " + root);
}

ShapeGroundTruth TopKidsDataset::GroundTruth(const DatasetShape& shape, int num_vertices) const {
  ShapeGroundTruth gt;
  if (shape.name == options_.null_shape) return gt;
  const std::string path = RefPath(options_.root, shape.name);
  const std::string null_mesh = MeshOfStem(options_.root, options_.null_shape);
  if (null_mesh.empty()) {
    throw InvalidInputError("topkids: no null shape " + options_.root + "/" + options_.null_shape +
                            ".off|obj|ply");
  }
  const int null_vertices = CountMeshVertices(null_mesh);
  const std::vector<std::string> lines = DataRows(path);
  if (lines.empty()) throw InvalidInputError(path + ": no rows");
  gt.onto = options_.null_shape;
  for (size_t i = 0; i < lines.size(); ++i) {
    const int line = static_cast<int>(i + 1);
    const std::vector<std::string> f = Fields(lines[i]);
    if (f.size() != 2) {
      ThrowAtLine(path, line,
                  std::to_string(f.size()) + " fields; expected 'KID_VERTEX NULL_VERTEX'");
    }
    gt.onto_lines.source_ids.push_back(
        OneBasedIndex(f[0], num_vertices, path, line, "vertex of " + shape.name));
    gt.onto_lines.target_ids.push_back(
        OneBasedIndex(f[1], null_vertices, path, line, "vertex of " + options_.null_shape));
  }
  return gt;
}

}  // namespace symembed
