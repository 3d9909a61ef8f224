#include "eval/datasets/remeshed_dataset.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <sstream>
#include <vector>

#include "core/errors.h"
#include "eval/synthetic/dataset_writer.h"

namespace symembed {

namespace fs = std::filesystem;

namespace {

// Bump when the remeshing's output changes for the same input and options.
constexpr const char* kRemeshVersion = "remeshed-dataset-1";

// "name size mtime" of a file, one line; nothing when it does not exist.
std::string FileStamp(const fs::path& path, const std::string& name) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) return "";
  const auto time = fs::last_write_time(path, ec).time_since_epoch();
  std::ostringstream out;
  out << name << " " << size << " "
      << std::chrono::duration_cast<std::chrono::nanoseconds>(time).count() << "\n";
  return out.str();
}

// The stamps of the files of root/sub, by name.
std::string FolderStamps(const fs::path& root, const std::string& sub) {
  std::vector<std::string> lines;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(root / sub, ec)) {
    if (entry.is_regular_file()) {
      lines.push_back(FileStamp(entry.path(), sub + "/" + entry.path().filename().string()));
    }
  }
  std::sort(lines.begin(), lines.end());
  std::string text;
  for (const std::string& line : lines) text += line;
  return text;
}

}  // namespace

std::string RemeshedDatasetHash(const std::string& root, const RemeshDatasetOptions& remesh) {
  std::error_code ec;
  fs::path absolute = fs::weakly_canonical(fs::absolute(root), ec);
  if (ec) absolute = fs::absolute(root);
  std::ostringstream text;
  text.precision(17);
  text << kRemeshVersion << "\nvertices " << remesh.vertices << "\nanisotropy " << remesh.anisotropy
       << "\nseed " << remesh.seed;
  // Absent at 0, so that caches written before the option keep their names.
  if (remesh.subdivide != 0) text << "\nsubdivide " << remesh.subdivide;
  text << "\nroot " << absolute.string() << "\n"
       << FolderStamps(absolute, "shapes") << FolderStamps(absolute, "corres")
       << FileStamp(absolute / "test_pairs.txt", "test_pairs.txt");
  return HashHex(text.str());
}

RemeshedDataset::RemeshedDataset(std::string root, RemeshDatasetOptions remesh, std::string cache,
                                 DatasetRestrictions restrictions)
    : GeneratedDataset(std::move(cache), std::move(restrictions)),
      root_(std::move(root)),
      remesh_(remesh) {}

void RemeshedDataset::Write(const std::string& dir) const {
  WriteRemeshedDataset(root_, dir, remesh_);
}

std::unique_ptr<Dataset> CreatePairsVtsDataset(OptionReader& options) {
  PairsVtsOptions o = ReadPairsVtsOptions(options);
  RemeshDatasetOptions remesh;
  // 0: no remeshing; else RemeshDatasetOptions::kVertices, checked by IsValid below.
  remesh.vertices = options.GetInt("remesh", 0, Range::AtLeast(0));
  remesh.anisotropy =
      options.GetDouble("remesh_anisotropy", 1.0, RemeshDatasetOptions::kAnisotropy);
  remesh.seed = options.GetInt("remesh_seed", 1, Range::AtLeast(0));
  remesh.subdivide = options.GetInt("remesh_subdivide", 0, RemeshDatasetOptions::kSubdivide);
  std::string cache = options.GetString("cache", "");
  if (remesh.vertices == 0) {
    if (remesh.anisotropy != 1.0) {
      options.Fail("remesh_anisotropy", "needs remesh > 0 (the anisotropy is the remeshing's)");
    }
    if (remesh.subdivide != 0) {
      options.Fail("remesh_subdivide", "needs remesh > 0 (the target after the subdivision)");
    }
    if (!cache.empty()) options.Fail("cache", "needs remesh > 0 (only a remeshing is cached)");
    return std::make_unique<PairsVtsDataset>(o);
  }
  std::string error;
  if (!remesh.IsValid(&error)) options.Fail("remesh", error);
  if (cache.empty()) cache = "results/.cache/remeshed/" + RemeshedDatasetHash(o.root, remesh);
  // The pairs file names a file of the input dataset, not of the copy.
  if (!o.restrictions.pairs_file.empty()) {
    o.restrictions.pairs_file =
        fs::absolute(ResolvePath(o.root, o.restrictions.pairs_file)).string();
  }
  return std::make_unique<RemeshedDataset>(o.root, remesh, cache, o.restrictions);
}

}  // namespace symembed
