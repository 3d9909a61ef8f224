// Helpers shared by the tests and benchmarks.
#pragma once

#include <string>

#include "core/mesh.h"

namespace symembed::testing {

// A fresh empty directory under the system temp dir, removed by the destructor.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string File(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

// Writes text to a file (creating parent directories); throws on failure.
void WriteText(const std::string& path, const std::string& text);
std::string ReadText(const std::string& path);

// The repository root (compile-time).
std::string SourceDir();

// The benchmark data root: $SYMEMBED_DATA, else ../shared/data beside the repository.
// Empty when the folder does not exist.
std::string DataRoot();

// Runs a shell command, returns its exit code; its stdout+stderr go to *output when given.
int RunShell(const std::string& command, std::string* output = nullptr);

}  // namespace symembed::testing
