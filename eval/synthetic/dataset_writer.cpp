#include "eval/synthetic/dataset_writer.h"

#include <fstream>

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

}  // namespace symembed
