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

// Mean |e . d| over mean |e x d| of the edges e of s: the edge extent along the unit vector d
// against across it (an anisotropic remeshing along d makes it smaller).
double EdgeExtentRatio(const Surface& s, const Eigen::Vector3d& d);

// Runs a shell command, returns its exit code; its stdout+stderr go to *output when given.
int RunShell(const std::string& command, std::string* output = nullptr);

// Runs the symembed binary under test with `args` (RunShell).
int Symembed(const std::string& args, std::string* output = nullptr);

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

// A figure exactly mirror-symmetric about x = 0 and asymmetric up-down and front-back, built
// from disconnected primitives: box torso with a box backpack at -z, sphere head at +y with a
// nose at +z, cylinder arms along +-x, cylinder legs along -y ending in box feet pointing +z. The parts at x < 0 are mirror
// images (vertex for vertex) of those at x > 0. `detail` >= 1 scales the resolution (about
// 900 vertices at 1). Without the left arm (the one at x < 0) it is partial. (*mirror)[i], when
// given, is the vertex at the mirror position of vertex i (for the partial figure, -1 where the
// mirror vertex was removed).
Surface SymmetricFigure(int detail = 1, bool with_left_arm = true,
                        std::vector<int>* mirror = nullptr);

// The same figure in a second pose: the arms lowered by `arm_angle` radians about their
// shoulders and the legs spread by `leg_angle` (vertex ids unchanged).
Surface PosedSymmetricFigure(int detail, double arm_angle, double leg_angle);

}  // namespace symembed::testing
