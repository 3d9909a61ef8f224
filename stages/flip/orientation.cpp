#include "stages/flip/orientation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors.h"
#include "core/fmap/zoomout.h"
#include "core/knn.h"
#include "core/laplacian.h"
#include "stages/flip/flip_common.h"

namespace symembed {

bool OrientationOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  std::string schedule;
  if (!zoomout.IsValid(&schedule)) out << "zoomout: " << schedule;
  else if (neighbors < 2) out << "neighbors must be >= 2, got " << neighbors;
  if (error) *error = out.str();
  return out.str().empty();
}

namespace {

double Sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

// |a x b| >= 0.2 |a| |b|: not nearly collinear.
bool Spread(const Eigen::Vector3d& cross, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return cross.norm() >= 0.2 * a.norm() * b.norm();
}

// |c . n| >= 0.5 |c| |n|: the triangle is near tangent to the surface at its apex.
bool NearTangent(const Eigen::Vector3d& cross, const Eigen::Vector3d& normal) {
  return std::abs(cross.dot(normal)) >= 0.5 * cross.norm() * normal.norm();
}

void CheckOrientationInput(const Surface& source, const std::vector<int>& map,
                           const std::vector<int>& samples) {
  if (samples.size() < 3 || static_cast<int>(map.size()) != source.NumVertices()) {
    throw InvalidInputError("flip orientation: need >= 3 samples and a map of every source vertex");
  }
}

}  // namespace

SourceTriangles MakeSourceTriangles(const Surface& source, const std::vector<int>& samples,
                                    int neighbors) {
  const int n = static_cast<int>(samples.size());
  const Eigen::MatrixX3d normals = VertexNormals(source);
  Eigen::MatrixX3d P(n, 3);
  for (int i = 0; i < n; ++i) P.row(i) = source.V.row(samples[i]);
  const int kk = std::min(neighbors + 1, n);
  Eigen::MatrixXi nn;
  KnnIndex(P).Query(P, kk, &nn, nullptr, 1);
  SourceTriangles out;
  for (int i = 0; i < n; ++i) {
    const int vi = samples[i];
    const Eigen::Vector3d pi = source.V.row(vi);
    for (int a = 1; a < kk; ++a) {
      for (int b = a + 1; b < kk; ++b) {
        const int vj = samples[nn(i, a)], vk = samples[nn(i, b)];
        const Eigen::Vector3d ej = source.V.row(vj).transpose() - pi;
        const Eigen::Vector3d ek = source.V.row(vk).transpose() - pi;
        const Eigen::Vector3d cs = ej.cross(ek);
        // Nearly collinear triangles, or triangles far from tangent to the surface, say nothing
        // reliable about orientation.
        if (!Spread(cs, ej, ek) || !NearTangent(cs, normals.row(vi).transpose())) continue;
        out.vertices.push_back({vi, vj, vk});
        out.sign.push_back(Sign(cs.dot(normals.row(vi).transpose())));
      }
    }
  }
  return out;
}

double TriangleOrientation(const SourceTriangles& triangles, const Surface& target,
                           const Eigen::MatrixX3d& target_normals, const std::vector<int>& map) {
  double sum = 0.0;
  int count = 0;
  for (size_t t = 0; t < triangles.vertices.size(); ++t) {
    const auto& [vi, vj, vk] = triangles.vertices[t];
    const Eigen::Vector3d qi = target.V.row(map[vi]);
    const Eigen::Vector3d fj = target.V.row(map[vj]).transpose() - qi;
    const Eigen::Vector3d fk = target.V.row(map[vk]).transpose() - qi;
    const Eigen::Vector3d ct = fj.cross(fk);
    const Eigen::Vector3d mi = target_normals.row(map[vi]);
    if (ct.norm() == 0.0 || !Spread(ct, fj, fk) || !NearTangent(ct, mi)) continue;
    sum += triangles.sign[t] * Sign(ct.dot(mi));
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

double MapOrientation(const Surface& source, const Surface& target, const std::vector<int>& map,
                      const std::vector<int>& samples, int neighbors) {
  CheckOrientationInput(source, map, samples);
  return TriangleOrientation(MakeSourceTriangles(source, samples, neighbors), target,
                             VertexNormals(target), map);
}

CandidateOrientation::CandidateOrientation(const Surface& source, const Surface& target,
                                           const LaplaceBasis& source_basis,
                                           const LaplaceBasis& target_basis,
                                           const std::vector<int>& samples,
                                           const std::vector<int>& target_samples,
                                           const OrientationOptions& options)
    : source_(source), target_(target) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("flip orientation: " + error);
  samples_ = SamplePrefix(samples, options.zoomout.samples, options.zoomout.k_end,
                          "flip orientation: the source");
  // ZoomOut maps onto this prefix of the target's samples (all target vertices when empty). The
  // triangles are made of samples only: the map of the other vertices is not needed.
  zoomout_.emplace(source_basis, target_basis, samples_, options.zoomout.ZoomOut(),
                   options.zoomout.TargetPrefix(target_samples, "flip orientation: the target"));
  triangles_ = MakeSourceTriangles(source, samples_, options.neighbors);
  target_normals_ = VertexNormals(target);
}

double CandidateOrientation::operator()(const std::vector<int>& map) const {
  CheckOrientationInput(source_, map, samples_);
  const ZoomOutResult refined = zoomout_->Run(map);
  return TriangleOrientation(triangles_, target_, target_normals_, refined.map);
}

std::array<double, 4> CandidateOrientations(const CandidateOrientation& measure,
                                            const CandidateMaps& maps) {
  std::array<double, 4> out{};
  for (int k = 0; k < 4; ++k) out[k] = measure(maps.map[k]);
  return out;
}

OrientationScores AddOrientationTerm(const std::array<double, 4>& scores, double weight,
                                     const CandidateMaps& maps,
                                     const CandidateOrientation& measure) {
  if (!(weight >= 0.0)) throw ConfigError("flip orientation: weight must be >= 0");
  OrientationScores out;
  out.total = scores;
  out.orientation.fill(std::numeric_limits<double>::quiet_NaN());
  double best = std::numeric_limits<double>::infinity();
  for (int k : CandidateOrder(scores)) {
    // total_k >= scores[k]: a candidate whose score already exceeds the lowest total cannot be
    // the lowest (ties are measured, so the choice is the one of measuring all four).
    if (scores[k] > best) continue;
    out.orientation[k] = measure(maps.map[k]);
    out.total[k] = scores[k] + weight * (1.0 - out.orientation[k]) / 2.0;
    best = std::min(best, out.total[k]);
    ++out.measured;
  }
  return out;
}

}  // namespace symembed
