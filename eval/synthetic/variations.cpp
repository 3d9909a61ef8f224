#include "eval/synthetic/variations.h"

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "core/laplacian.h"
#include "eval/synthetic/posing.h"
#include "eval/synthetic/random.h"

namespace symembed {

namespace {

// Collapse priority: squared edge length, stretched by `anisotropy` along `direction`, times a
// per-vertex factor of the removed vertex.
template <class MeshT>
class ModJitteredLengthT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModJitteredLengthT, MeshT, JitteredLength);

  explicit ModJitteredLengthT(MeshT& mesh) : Base(mesh, false) {}

  void set_factors(const std::vector<double>* factors) { factors_ = factors; }
  void set_stretch(double anisotropy, const Eigen::Vector3d& direction) {
    extra_ = anisotropy * anisotropy - 1.0;
    direction_ = direction;
  }

  float collapse_priority(const CollapseInfo& ci) override {
    const auto e = ci.p0 - ci.p1;
    const double along = e[0] * direction_.x() + e[1] * direction_.y() + e[2] * direction_.z();
    return static_cast<float>((e.sqrnorm() + extra_ * along * along) * (*factors_)[ci.v0.idx()]);
  }

 private:
  const std::vector<double>* factors_ = nullptr;
  double extra_ = 0.0;  // anisotropy^2 - 1
  Eigen::Vector3d direction_ = Eigen::Vector3d::UnitX();
};

// Drops faces listed as false in keep_face and vertices no kept face uses; renumbers.
TrackedSurface KeepFaces(const TrackedSurface& shape, const std::vector<bool>& keep_face) {
  const Surface& s = shape.surface;
  std::vector<int> new_id(s.V.rows(), -1);
  int nf = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    if (!keep_face[f]) continue;
    ++nf;
    for (int k = 0; k < 3; ++k) new_id[s.F(f, k)] = 0;
  }
  TrackedSurface out;
  int nv = 0;
  for (int v = 0; v < s.V.rows(); ++v) {
    if (new_id[v] < 0) continue;
    new_id[v] = nv++;
    out.rest_ids.push_back(shape.rest_ids[v]);
  }
  out.surface.V.resize(nv, 3);
  for (int v = 0; v < s.V.rows(); ++v) {
    if (new_id[v] >= 0) out.surface.V.row(new_id[v]) = s.V.row(v);
  }
  out.surface.F.resize(nf, 3);
  for (int f = 0, g = 0; f < s.F.rows(); ++f) {
    if (!keep_face[f]) continue;
    for (int k = 0; k < 3; ++k) out.surface.F(g, k) = new_id[s.F(f, k)];
    ++g;
  }
  return out;
}

}  // namespace

TrackedSurface CutPart(const TrackedSurface& shape, const Eigen::MatrixXd& weights,
                       const std::vector<Bone>& bones, int bone) {
  const int nb = static_cast<int>(bones.size());
  std::vector<bool> in_part(nb, false);
  for (int b = 0; b < nb; ++b) {
    // Parents precede children, so one pass marks the whole subtree.
    in_part[b] = b == bone || (bones[b].parent >= 0 && in_part[bones[b].parent]);
  }
  const Surface& s = shape.surface;
  std::vector<bool> removed(s.V.rows(), false);
  for (int v = 0; v < s.V.rows(); ++v) {
    double w = 0.0;
    for (int b = 0; b < nb; ++b) {
      if (in_part[b]) w += weights(shape.rest_ids[v], b);
    }
    removed[v] = w > 0.5;
  }
  std::vector<bool> keep(s.F.rows(), true);
  for (int f = 0; f < s.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (removed[s.F(f, k)]) keep[f] = false;
    }
  }
  return KeepFaces(shape, keep);
}

TrackedSurface Remesh(const TrackedSurface& shape, int target_vertices, uint32_t seed,
                      double anisotropy, const Eigen::Vector3d& direction) {
  SYMEMBED_CHECK(target_vertices >= 4, "remesh target must be >= 4 vertices");
  SYMEMBED_CHECK(anisotropy >= 1.0, "remesh anisotropy must be >= 1");
  SYMEMBED_CHECK(std::abs(direction.norm() - 1.0) < 1e-9, "remesh direction must be a unit vector");
  int skipped = 0;
  TriMesh mesh = FromSurface(shape.surface, &skipped);
  SYMEMBED_CHECK(skipped == 0, "remesh input is not a manifold mesh");
  OpenMesh::VPropHandleT<int> rest_id;
  mesh.add_property(rest_id);
  for (auto v : mesh.vertices()) mesh.property(rest_id, v) = shape.rest_ids[v.idx()];
  mesh.update_face_normals();

  std::vector<double> factors(mesh.n_vertices());
  SynthRandom random(seed);
  for (double& f : factors) f = random.Uniform(0.5, 1.5);

  using Decimater = OpenMesh::Decimater::DecimaterT<TriMesh>;
  Decimater decimater(mesh);
  typename ModJitteredLengthT<TriMesh>::Handle length;
  typename OpenMesh::Decimater::ModNormalFlippingT<TriMesh>::Handle flipping;
  decimater.add(length);
  decimater.add(flipping);
  decimater.module(length).set_factors(&factors);
  decimater.module(length).set_stretch(anisotropy, direction);
  decimater.module(flipping).set_max_normal_deviation(45.0);
  // Elongated triangles are the point of an anisotropic remeshing, slivers are not: a collapse
  // that leaves a triangle thinner than the anisotropy asks for is refused.
  typename OpenMesh::Decimater::ModAspectRatioT<TriMesh>::Handle aspect;
  if (anisotropy > 1.0) {
    decimater.add(aspect);
    decimater.module(aspect).set_aspect_ratio(static_cast<float>(3.0 * anisotropy));
  }
  SYMEMBED_CHECK(decimater.initialize(), "decimater did not initialize");
  decimater.decimate_to(static_cast<size_t>(target_vertices));
  mesh.garbage_collection();

  TrackedSurface out;
  out.surface = ToSurface(mesh);
  out.rest_ids.resize(mesh.n_vertices());
  for (auto v : mesh.vertices()) out.rest_ids[v.idx()] = mesh.property(rest_id, v);
  return out;
}

TrackedSurface Subdivide(const TrackedSurface& shape, int levels) {
  SYMEMBED_CHECK(levels >= 0, "subdivision levels must be >= 0");
  if (levels == 0) return shape;
  int skipped = 0;
  TriMesh mesh = FromSurface(shape.surface, &skipped);
  SYMEMBED_CHECK(skipped == 0, "subdivision input is not a manifold mesh");
  OpenMesh::Subdivider::Uniform::LoopT<TriMesh> loop;
  loop.attach(mesh);
  loop(static_cast<size_t>(levels));
  loop.detach();
  // LoopT only adds vertices (splitting edges), so the old ones keep their handles.
  TrackedSurface out;
  out.surface = ToSurface(mesh);
  out.rest_ids.assign(mesh.n_vertices(), -1);
  std::copy(shape.rest_ids.begin(), shape.rest_ids.end(), out.rest_ids.begin());
  return out;
}

void AddNormalNoise(Surface* surface, double amplitude, uint32_t seed) {
  const Eigen::MatrixX3d N = VertexNormals(*surface);
  const double scale = amplitude * MeanEdgeLength(*surface);
  SynthRandom random(seed);
  for (int v = 0; v < surface->V.rows(); ++v) {
    surface->V.row(v) += scale * random.Uniform(-1.0, 1.0) * N.row(v);
  }
}

}  // namespace symembed
