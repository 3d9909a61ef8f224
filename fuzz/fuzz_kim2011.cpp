// Fuzz target of the readers of the Kim, Lipman & Funkhouser 2011 benchmark files
// (eval/datasets/kim2011_files.h): the first byte chooses the reader (landmark file, mirror
// file of a landmark file of 1 + byte / 3 lines, query file); the rest is the file, written to
// a temporary file since the readers take paths.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/errors.h"
#include "eval/datasets/kim2011_files.h"
#include "fuzz/fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  // One file per process, removed at exit.
  static const struct TempFile {
    std::string path = "/tmp/symembed_fuzz_kim2011." + std::to_string(getpid());
    ~TempFile() { std::remove(path.c_str()); }
  } temp;
  const std::string& path = temp.path;
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data + 1, 1, size - 1, f);
    std::fclose(f);
  } else {
    std::abort();
  }
  try {
    switch (data[0] % 3) {
      case 0:
        for (long long id : symembed::ReadLandmarkIds(path)) {
          if (id < 0) std::abort();
        }
        break;
      case 1: {
        const int lines = 1 + data[0] / 3;
        const std::vector<int> mirror = symembed::ReadMirrorLines(path, lines, "fuzz.pid");
        if (static_cast<int>(mirror.size()) != lines) std::abort();
        for (int m : mirror) {
          if (m < -1 || m >= lines) std::abort();
        }
        break;
      }
      default:
        symembed::ReadQueryFile(path);
        break;
    }
  } catch (const symembed::Error&) {
  }
  return 0;
}
