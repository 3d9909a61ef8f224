#include "eval/synthetic/figure.h"

#include <cmath>
#include <map>
#include <tuple>
#include <utility>

#include "core/errors.h"

namespace symembed {

namespace {

// A cross-section ring of a limb: distance from the torso face along the limb, half sizes
// along the two world axes perpendicular to the limb (in increasing axis order), and the bone
// blend b: weight 1 - frac(b) on limb bone floor(b), frac(b) on the next; bone -1 is the torso;
// and a forward (+z) shift of the ring's centre (faces and feet point forwards, so that the
// figure is not front-back symmetric).
struct RingSpec {
  double d, h1, h2, blend;
  double forward = 0.0;
};

// A limb bone: its joint's distance from the torso face, rotation ranges in degrees.
struct LimbBoneSpec {
  const char* name;
  double head_d;
  double x[2], y[2], z[2];
};

struct LimbSpec {
  bool paired;             // a left limb, mirrored to the right; else central
  int axis, sign;          // the torso face it grows from (outward normal sign * e_axis)
  std::array<int, 3> cell; // the face cell (component along `axis` unused)
  std::vector<LimbBoneSpec> bones;
  std::vector<RingSpec> rings;
  int cuttable_bone;       // limb bone that `partial` may cut (-1: none)
};

struct FigureSpec {
  std::array<double, 4> lines[3];  // torso grid lines along x, y, z
  std::vector<LimbSpec> limbs;
};

FigureSpec HumanoidSpec() {
  FigureSpec s;
  s.lines[0] = {-0.18, -0.06, 0.06, 0.18};
  s.lines[1] = {0.85, 1.05, 1.27, 1.45};
  s.lines[2] = {-0.10, -0.05, 0.05, 0.12};  // the chest bulges forwards
  // Head on the top face; neck yaw/pitch/roll and a smaller head motion.
  s.limbs.push_back({false, 1, +1, {1, 3, 1},
                     {{"neck", 0.0, {-15, 20}, {-35, 35}, {-15, 15}},
                      {"head", 0.12, {-15, 15}, {-20, 20}, {-10, 10}}},
                     {{0.03, 0.05, 0.045, -0.5},
                      {0.08, 0.045, 0.045, 0.0},
                      {0.12, 0.06, 0.07, 0.5},
                      {0.20, 0.09, 0.10, 1.0, 0.015},
                      {0.30, 0.085, 0.095, 1.0, 0.02},
                      {0.36, 0.05, 0.06, 1.0, 0.01}},
                     1});
  // Left arm in T-pose along +x from the upper cell of the lateral face. Rz < 0 lowers it,
  // Ry < 0 swings it forward; the elbow flexes forward (Ry < 0).
  s.limbs.push_back({true, 0, +1, {3, 2, 1},
                     {{"upper_arm", 0.0, {-30, 30}, {-30, 20}, {-60, 20}},
                      {"forearm", 0.30, {-20, 20}, {-80, 0}, {-5, 5}},
                      {"hand", 0.56, {-20, 20}, {-20, 20}, {-30, 30}}},
                     {{0.04, 0.07, 0.055, -0.5},
                      {0.16, 0.055, 0.05, 0.0},
                      {0.30, 0.045, 0.045, 0.5},
                      {0.43, 0.04, 0.04, 1.0},
                      {0.56, 0.03, 0.035, 1.5},
                      {0.66, 0.018, 0.05, 2.0},
                      {0.72, 0.014, 0.04, 2.0}},
                     2});
  // Left leg down from the bottom face. Rx < 0 flexes the hip forward, Rz > 0 abducts; the
  // knee flexes backwards (Rx > 0).
  s.limbs.push_back({true, 1, -1, {2, 0, 1},
                     {{"thigh", 0.0, {-60, 20}, {-20, 20}, {-5, 30}},
                      {"shin", 0.42, {0, 90}, {-5, 5}, {-5, 5}},
                      {"foot", 0.78, {-20, 20}, {-10, 10}, {-10, 10}}},
                     {{0.05, 0.06, 0.065, -0.5},
                      {0.25, 0.055, 0.06, 0.0},
                      {0.42, 0.045, 0.05, 0.5},
                      {0.62, 0.04, 0.045, 1.0},
                      {0.78, 0.035, 0.035, 1.5},
                      {0.84, 0.04, 0.07, 2.0, 0.04},
                      {0.88, 0.035, 0.06, 2.0, 0.06}},
                     2});
  return s;
}

FigureSpec QuadrupedSpec() {
  FigureSpec s;
  s.lines[0] = {-0.15, -0.07, 0.07, 0.15};
  s.lines[1] = {0.45, 0.55, 0.63, 0.75};
  s.lines[2] = {-0.45, -0.33, 0.33, 0.45};
  // Neck and head forward (+z) from the upper front cell; Rx < 0 raises them.
  s.limbs.push_back({false, 2, +1, {1, 2, 3},
                     {{"neck", 0.0, {-40, 25}, {-35, 35}, {-10, 10}},
                      {"head", 0.16, {-25, 25}, {-20, 20}, {-10, 10}}},
                     {{0.04, 0.06, 0.055, -0.5},
                      {0.10, 0.05, 0.05, 0.0},
                      {0.16, 0.065, 0.065, 0.5},
                      {0.26, 0.07, 0.07, 1.0},
                      {0.36, 0.045, 0.045, 1.0},
                      {0.42, 0.03, 0.03, 1.0}},
                     1});
  // Tail backwards (-z) from the upper back cell; Rx > 0 raises it.
  s.limbs.push_back({false, 2, -1, {1, 2, 0},
                     {{"tail_base", 0.0, {-30, 40}, {-35, 35}, {-5, 5}},
                      {"tail_tip", 0.20, {-30, 30}, {-35, 35}, {-5, 5}}},
                     {{0.03, 0.03, 0.03, -0.5},
                      {0.12, 0.025, 0.025, 0.0},
                      {0.20, 0.02, 0.02, 0.5},
                      {0.30, 0.015, 0.015, 1.0},
                      {0.38, 0.01, 0.01, 1.0}},
                     -1});
  const std::vector<RingSpec> leg = {{0.04, 0.04, 0.05, -0.5},  {0.13, 0.04, 0.045, 0.0},
                                     {0.22, 0.035, 0.04, 0.5},  {0.31, 0.03, 0.035, 1.0},
                                     {0.40, 0.028, 0.03, 1.5},  {0.44, 0.035, 0.045, 2.0},
                                     {0.46, 0.03, 0.035, 2.0}};
  // Legs down from the bottom corner cells; Rx swings them, Rz > 0 abducts.
  s.limbs.push_back({true, 1, -1, {2, 0, 2},
                     {{"front_upper_leg", 0.0, {-35, 35}, {-10, 10}, {-5, 15}},
                      {"front_lower_leg", 0.22, {-10, 50}, {-5, 5}, {-5, 5}},
                      {"front_paw", 0.40, {-30, 30}, {-5, 5}, {-5, 5}}},
                     leg, 2});
  s.limbs.push_back({true, 1, -1, {2, 0, 0},
                     {{"hind_upper_leg", 0.0, {-35, 35}, {-10, 10}, {-5, 15}},
                      {"hind_lower_leg", 0.22, {-50, 10}, {-5, 5}, {-5, 5}},
                      {"hind_paw", 0.40, {-30, 30}, {-5, 5}, {-5, 5}}},
                     leg, 2});
  return s;
}

constexpr double kDegree = M_PI / 180.0;

class Builder {
 public:
  Builder(const FigureSpec& spec, int rings_per_segment) : spec_(spec), rps_(rings_per_segment) {}

  Figure Build(FigureKind kind) {
    Figure figure;
    figure.kind = kind;
    Bone torso;
    torso.name = "torso";
    torso.head = Eigen::Vector3d(0, spec_.lines[1][0], 0.5 * (spec_.lines[2][0] + spec_.lines[2][3]));
    torso.tail = Eigen::Vector3d(0, spec_.lines[1][3], torso.head.z());
    bones_.push_back(torso);
    BuildTorso();
    for (const LimbSpec& limb : spec_.limbs) {
      const std::vector<int> left = AddLimb(limb, false, figure.cuttable);
      if (!limb.paired) continue;
      const std::vector<int> right = AddLimb(limb, true, figure.cuttable);
      for (size_t i = 0; i < left.size(); ++i) {
        bones_[left[i]].mirror = right[i];
        bones_[right[i]].mirror = left[i];
      }
    }
    ControlMesh& c = figure.control;
    c.points = points_;
    for (size_t q = 0; q < quads_.size(); ++q) {
      if (!removed_[q]) c.quads.push_back(quads_[q]);
    }
    c.weights = Eigen::MatrixXd::Zero(static_cast<int>(points_.size()), static_cast<int>(bones_.size()));
    for (size_t i = 0; i < weights_.size(); ++i) {
      for (const auto& [bone, w] : weights_[i]) c.weights(static_cast<int>(i), bone) += w;
    }
    figure.bones = bones_;
    return figure;
  }

 private:
  int AddPoint(const Eigen::Vector3d& p, std::vector<std::pair<int, double>> w) {
    points_.push_back(p);
    weights_.push_back(std::move(w));
    return static_cast<int>(points_.size()) - 1;
  }

  void BuildTorso() {
    std::map<std::tuple<int, int, int>, int> ids;
    auto vertex = [&](int i, int j, int k) {
      auto key = std::make_tuple(i, j, k);
      auto it = ids.find(key);
      if (it != ids.end()) return it->second;
      const Eigen::Vector3d p(spec_.lines[0][i], spec_.lines[1][j], spec_.lines[2][k]);
      return ids[key] = AddPoint(p, {{0, 1.0}});
    };
    for (int a = 0; a < 3; ++a) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      for (int sign : {-1, +1}) {
        for (int p = 0; p < 3; ++p) {
          for (int q = 0; q < 3; ++q) {
            std::array<int, 4> quad;
            const int du[4] = {0, 1, 1, 0}, dv[4] = {0, 0, 1, 1};
            for (int k = 0; k < 4; ++k) {
              int g[3];
              g[a] = sign > 0 ? 3 : 0;
              g[u] = p + du[k];
              g[v] = q + dv[k];
              quad[k] = vertex(g[0], g[1], g[2]);
            }
            if (sign < 0) std::swap(quad[1], quad[3]);
            std::array<int, 3> cell = {0, 0, 0};
            cell[u] = p;
            cell[v] = q;
            face_of_[std::make_tuple(a, sign, cell[0], cell[1], cell[2])] =
                static_cast<int>(quads_.size());
            quads_.push_back(quad);
            removed_.push_back(false);
          }
        }
      }
    }
  }

  // Extrudes one limb (mirrored when `right`); returns its bone ids in limb order.
  std::vector<int> AddLimb(const LimbSpec& limb, bool right, std::vector<int>& cuttable) {
    int sign = limb.sign;
    std::array<int, 3> cell = limb.cell;
    if (right) {
      if (limb.axis == 0) sign = -sign;
      cell[0] = 2 - cell[0];
    }
    cell[limb.axis] = 0;
    auto it = face_of_.find(std::make_tuple(limb.axis, sign, cell[0], cell[1], cell[2]));
    SYMEMBED_CHECK(it != face_of_.end(), "limb face cell not found");
    SYMEMBED_CHECK(!removed_[it->second], "two limbs grow from the same torso face cell");
    removed_[it->second] = true;
    const std::array<int, 4> face = quads_[it->second];

    Eigen::Vector3d center = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) center += points_[face[k]];
    center /= 4.0;
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    n[limb.axis] = sign;
    const int e1 = limb.axis == 0 ? 1 : 0, e2 = limb.axis == 2 ? 1 : 2;
    double s1[4], s2[4];
    for (int k = 0; k < 4; ++k) {
      s1[k] = points_[face[k]][e1] > center[e1] ? 1.0 : -1.0;
      s2[k] = points_[face[k]][e2] > center[e2] ? 1.0 : -1.0;
    }

    // Bones of the limb.
    std::vector<int> bone_ids;
    const std::string suffix = limb.paired ? (right ? "_r" : "_l") : "";
    for (size_t b = 0; b < limb.bones.size(); ++b) {
      const LimbBoneSpec& spec = limb.bones[b];
      Bone bone;
      bone.name = spec.name + suffix;
      bone.parent = b == 0 ? 0 : bone_ids.back();
      bone.mirror = static_cast<int>(bones_.size());
      bone.right = right;
      bone.head = center + spec.head_d * n;
      const double tail_d = b + 1 < limb.bones.size() ? limb.bones[b + 1].head_d : limb.rings.back().d;
      bone.tail = center + tail_d * n;
      bone.min_angles = Eigen::Vector3d(spec.x[0], spec.y[0], spec.z[0]) * kDegree;
      bone.max_angles = Eigen::Vector3d(spec.x[1], spec.y[1], spec.z[1]) * kDegree;
      bone_ids.push_back(static_cast<int>(bones_.size()));
      bones_.push_back(bone);
    }
    if (limb.cuttable_bone >= 0) cuttable.push_back(bone_ids[limb.cuttable_bone]);

    auto limb_bone = [&](int i) { return i < 0 ? 0 : bone_ids[i]; };
    RingSpec prev = {0.0, 0.5 * std::abs(points_[face[0]][e1] - points_[face[2]][e1]),
                     0.5 * std::abs(points_[face[0]][e2] - points_[face[2]][e2]), -1.0, 0.0};
    std::array<int, 4> loop = face;
    for (const RingSpec& target : limb.rings) {
      for (int step = 1; step <= rps_; ++step) {
        const double t = static_cast<double>(step) / rps_;
        const RingSpec r = {prev.d + t * (target.d - prev.d), prev.h1 + t * (target.h1 - prev.h1),
                            prev.h2 + t * (target.h2 - prev.h2),
                            prev.blend + t * (target.blend - prev.blend),
                            prev.forward + t * (target.forward - prev.forward)};
        const int lo = static_cast<int>(std::floor(r.blend));
        const double frac = r.blend - lo;
        std::vector<std::pair<int, double>> w = {{limb_bone(lo), 1.0 - frac}};
        if (frac > 0.0) w.push_back({limb_bone(lo + 1), frac});
        std::array<int, 4> ring;
        for (int k = 0; k < 4; ++k) {
          Eigen::Vector3d p = center + r.d * n;
          p.z() += r.forward;
          p[e1] += s1[k] * r.h1;
          p[e2] += s2[k] * r.h2;
          ring[k] = AddPoint(p, w);
        }
        for (int k = 0; k < 4; ++k) {
          quads_.push_back({loop[k], loop[(k + 1) % 4], ring[(k + 1) % 4], ring[k]});
          removed_.push_back(false);
        }
        loop = ring;
      }
      prev = target;
    }
    quads_.push_back(loop);
    removed_.push_back(false);
    return bone_ids;
  }

  const FigureSpec& spec_;
  const int rps_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::vector<std::pair<int, double>>> weights_;
  std::vector<std::array<int, 4>> quads_;
  std::vector<bool> removed_;
  std::map<std::tuple<int, int, int, int, int>, int> face_of_;
  std::vector<Bone> bones_;
};

}  // namespace

std::string FigureKindName(FigureKind kind) {
  return kind == FigureKind::kHumanoid ? "humanoid" : "quadruped";
}

FigureKind FigureKindFromName(const std::string& name) {
  if (name == "humanoid") return FigureKind::kHumanoid;
  if (name == "quadruped") return FigureKind::kQuadruped;
  throw ConfigError("unknown figure kind '" + name + "'; expected one of: humanoid, quadruped");
}

Figure BuildFigure(FigureKind kind, int rings_per_segment) {
  SYMEMBED_CHECK(rings_per_segment >= 1, "rings_per_segment must be >= 1");
  const FigureSpec spec = kind == FigureKind::kHumanoid ? HumanoidSpec() : QuadrupedSpec();
  return Builder(spec, rings_per_segment).Build(kind);
}

int ControlQuadCount(FigureKind kind, int rings_per_segment) {
  return static_cast<int>(BuildFigure(kind, rings_per_segment).control.quads.size());
}

}  // namespace symembed
