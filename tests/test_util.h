// Helpers shared by the tests and benchmarks.
#pragma once

#include <string>
#include <vector>

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

// A closed, smooth, asymmetric blob with 6 n^2 + 2 vertices: BoxMesh(n) projected to
// the unit sphere, stretched to an ellipsoid with semi-axes (1.3, 1.0, 0.8) and displaced
// radially by random Gaussian bumps (seeded). It has no nontrivial self-isometry, so maps onto a
// deformed copy are unambiguous.
Surface BumpyBlob(int n, unsigned seed = 1);

// A near-isometric pose of `surface`: twisted about the z axis by `twist` radians per unit of
// height, then its vertices shuffled (seeded). (*ground_truth)[i] is the vertex of the result
// that vertex i of `surface` became.
Surface TwistedShuffledCopy(const Surface& surface, double twist, unsigned seed,
                            std::vector<int>* ground_truth);

}  // namespace symembed::testing
