#include "stages/flip/orientation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.h"
#include "core/knn.h"
#include "stages/flip/flip_common.h"
#include "stages/refine/zoomout.h"

namespace symembed {

bool OrientationOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  if (k_start < 1 || k_end < k_start) out << "need 1 <= k_start <= k_end";
  else if (step < 1) out << "step must be >= 1, got " << step;
  else if (samples < k_end) out << "samples must be >= k_end (" << k_end << "), got " << samples;
  else if (neighbors < 2) out << "neighbors must be >= 2, got " << neighbors;
  if (error) *error = out.str();
  return out.str().empty();
}

namespace {

// Area-weighted vertex normals (not normalised).
Eigen::MatrixX3d VertexNormals(const Surface& s) {
  Eigen::MatrixX3d N = Eigen::MatrixX3d::Zero(s.NumVertices(), 3);
  for (int f = 0; f < s.NumFaces(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).transpose();
    for (int k = 0; k < 3; ++k) N.row(s.F(f, k)) += n;
  }
  return N;
}

double Sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

}  // namespace

double MapOrientation(const Surface& source, const Surface& target, const std::vector<int>& map,
                      const std::vector<int>& samples, int neighbors) {
  const int n = static_cast<int>(samples.size());
  if (n < 3 || static_cast<int>(map.size()) != source.NumVertices()) {
    throw InvalidInputError("flip orientation: need >= 3 samples and a map of every source vertex");
  }
  const Eigen::MatrixX3d Ns = VertexNormals(source), Nt = VertexNormals(target);
  Eigen::MatrixX3d P(n, 3);
  for (int i = 0; i < n; ++i) P.row(i) = source.V.row(samples[i]);
  const int kk = std::min(neighbors + 1, n);
  Eigen::MatrixXi nn;
  KnnIndex(P).Query(P, kk, &nn, nullptr, 1);
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i < n; ++i) {
    const int vi = samples[i];
    const Eigen::Vector3d pi = source.V.row(vi), ni = Ns.row(vi);
    const Eigen::Vector3d qi = target.V.row(map[vi]), mi = Nt.row(map[vi]);
    for (int a = 1; a < kk; ++a) {
      for (int b = a + 1; b < kk; ++b) {
        const int vj = samples[nn(i, a)], vk = samples[nn(i, b)];
        const Eigen::Vector3d ej = source.V.row(vj).transpose() - pi;
        const Eigen::Vector3d ek = source.V.row(vk).transpose() - pi;
        const Eigen::Vector3d cs = ej.cross(ek);
        // Nearly collinear triangles, or triangles far from tangent to the surface, say nothing
        // reliable about orientation.
        if (cs.norm() < 0.2 * ej.norm() * ek.norm()) continue;
        if (std::abs(cs.dot(ni)) < 0.5 * cs.norm() * ni.norm()) continue;
        const Eigen::Vector3d fj = target.V.row(map[vj]).transpose() - qi;
        const Eigen::Vector3d fk = target.V.row(map[vk]).transpose() - qi;
        const Eigen::Vector3d ct = fj.cross(fk);
        if (ct.norm() < 0.2 * fj.norm() * fk.norm() || ct.norm() == 0.0) continue;
        if (std::abs(ct.dot(mi)) < 0.5 * ct.norm() * mi.norm()) continue;
        sum += Sign(cs.dot(ni)) * Sign(ct.dot(mi));
        ++count;
      }
    }
  }
  return count > 0 ? sum / count : 0.0;
}

std::array<double, 4> CandidateOrientations(const Surface& source, const Surface& target,
                                            const Eigen::MatrixX3d& Ys,
                                            const Eigen::MatrixX3d& Yt,
                                            const LaplaceBasis& source_basis,
                                            const LaplaceBasis& target_basis,
                                            const std::vector<int>& samples_in,
                                            const OrientationOptions& options, int threads) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("flip orientation: " + error);
  const std::vector<int> samples(
      samples_in.begin(),
      samples_in.begin() + std::min<size_t>(samples_in.size(), options.samples));
  if (static_cast<int>(samples.size()) < options.k_end) {
    throw InvalidInputError("flip orientation: the source has " +
                            std::to_string(samples_in.size()) + " samples, fewer than k_end");
  }
  ZoomOutOptions zoomout;
  zoomout.k_start = options.k_start;
  zoomout.k_end = options.k_end;
  zoomout.step = options.step;
  const CandidateMaps maps = ComputeCandidateMaps(Ys, Yt, threads);
  std::array<double, 4> out{};
  for (int k = 0; k < 4; ++k) {
    const ZoomOutResult refined =
        ZoomOut(source_basis, target_basis, maps.map[k], samples, zoomout);
    out[k] = MapOrientation(source, target, refined.map, samples, options.neighbors);
  }
  return out;
}

}  // namespace symembed
