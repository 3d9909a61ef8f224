#include "eval/synthetic/dataset_writer.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <random>

#include "core/errors.h"

namespace symembed {

namespace fs = std::filesystem;

void CreateDatasetFolders(const fs::path& root) {
  std::error_code ec;
  fs::create_directories(root / "shapes", ec);
  fs::create_directories(root / "corres", ec);
  if (!fs::is_directory(root / "shapes") || !fs::is_directory(root / "corres")) {
    throw IoError("cannot create " + (root / "shapes").string() + " and " +
                  (root / "corres").string());
  }
}

void WriteDatasetFile(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw IoError("cannot write " + path.string());
}

std::string VtsText(const std::vector<int>& kept, const std::vector<int>& lines, int num_source) {
  std::vector<int> id_of(num_source, 0);
  for (size_t v = 0; v < kept.size(); ++v) {
    if (kept[v] >= 0) id_of[kept[v]] = static_cast<int>(v) + 1;
  }
  std::string text;
  text.reserve(6 * lines.size());
  for (int r : lines) text += std::to_string(r >= 0 ? id_of[r] : 0) + "\n";
  return text;
}

void PrepareDatasetOutput(const fs::path& out, bool force) {
  if (fs::exists(out) && !fs::is_directory(out)) {
    throw IoError(out.string() + " exists and is not a directory");
  }
  if (!fs::is_directory(out) || fs::is_empty(out)) return;
  if (!force) throw IoError(out.string() + " is not empty; use --force to replace a dataset there");
  for (const char* name : {"shapes", "corres", "test_pairs.txt", "README.md"}) {
    fs::remove_all(out / name);
  }
}

std::string HashHex(const std::string& text) {
  uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(h));
  return buffer;
}

void GenerateOnce(const std::string& folder, const std::function<void(const std::string&)>& write) {
  if (fs::exists(fs::path(folder) / "README.md")) return;
  const fs::path target(folder);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  std::random_device rd;
  const fs::path tmp = target.string() + ".tmp" + std::to_string(rd());
  try {
    write(tmp.string());
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(tmp, ignored);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove_all(tmp);
    // Another process may have finished first; anything else is an error.
    if (!fs::exists(target / "README.md")) {
      throw IoError("cannot move the generated dataset to " + folder + ": " + ec.message());
    }
  }
}

}  // namespace symembed
