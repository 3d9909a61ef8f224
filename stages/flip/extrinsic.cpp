#include "stages/flip/extrinsic.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "core/procrustes.h"
#include "registry/types.h"
#include "stages/flip/flip_common.h"

namespace symembed {

bool ExtrinsicFlipOptions::IsValid(std::string* error) const {
  std::string why = FieldViolation(*this);
  if (why.empty() && local_weight + global_weight + chamfer_weight <= 0.0) {
    why = "at least one of local_weight, global_weight, chamfer_weight must be > 0";
  }
  return NoViolation(why, error);
}

namespace {

constexpr int kShapeIndex = 0;
constexpr int kCurvedness = 1;
constexpr int kArea = 2;

// Area-weighted standard deviation of column f.
double WeightedStd(const Eigen::MatrixXd& F, int f) {
  const Eigen::VectorXd a = F.col(kArea) / std::max(F.col(kArea).sum(), 1e-300);
  const double mean = a.dot(F.col(f));
  return std::sqrt(std::max(0.0, a.dot((F.col(f).array() - mean).square().matrix())));
}

// The global descriptor of one shape along one axis of its (rotated) canonical frame.
struct AxisDescriptor {
  Eigen::VectorXd profile;       // area fraction per bin along the axis
  Eigen::VectorXd hist[2];       // shape-index histogram of the halves u > 0, u <= 0
  double curvedness[2] = {0, 0}; // mean curvedness of the halves
};

AxisDescriptor Describe(const Eigen::VectorXd& u_raw, const Eigen::MatrixXd& F, double radius,
                        const ExtrinsicFlipOptions& options) {
  AxisDescriptor d;
  d.profile = Eigen::VectorXd::Zero(options.profile_bins);
  double half_area[2] = {0, 0};
  for (int h = 0; h < 2; ++h) d.hist[h] = Eigen::VectorXd::Zero(options.histogram_bins);
  for (int v = 0; v < u_raw.size(); ++v) {
    const double a = F(v, kArea);
    const double u = u_raw(v) / radius;
    const int pb = std::clamp(static_cast<int>((u + 2.0) / 4.0 * options.profile_bins), 0,
                              options.profile_bins - 1);
    d.profile(pb) += a;
    const int h = u > 0.0 ? 0 : 1;
    const int hb = std::clamp(static_cast<int>((F(v, kShapeIndex) + 1.0) / 2.0 * options.histogram_bins),
                              0, options.histogram_bins - 1);
    d.hist[h](hb) += a;
    d.curvedness[h] += a * F(v, kCurvedness);
    half_area[h] += a;
  }
  d.profile /= std::max(d.profile.sum(), 1e-300);
  for (int h = 0; h < 2; ++h) {
    if (half_area[h] > 0.0) {
      d.hist[h] /= half_area[h];
      d.curvedness[h] /= half_area[h];
    }
  }
  return d;
}

}  // namespace

std::array<double, 2> FeatureScales(const Eigen::MatrixXd& Fs, const Eigen::MatrixXd& Ft) {
  std::array<double, 2> scales{};
  for (int f : {kShapeIndex, kCurvedness}) {
    scales[f] = std::max(0.5 * (WeightedStd(Fs, f) + WeightedStd(Ft, f)), 1e-6);
  }
  return scales;
}

namespace {

// sum_f |Fs(v, f) - Ft(t, f)| / scales[f] over the shape index and curvedness.
double FeatureDifference(const Eigen::MatrixXd& Fs, const Eigen::MatrixXd& Ft, int v, int t,
                         const std::array<double, 2>& scales) {
  double diff = 0.0;
  for (int f : {kShapeIndex, kCurvedness}) diff += std::abs(Fs(v, f) - Ft(t, f)) / scales[f];
  return diff;
}

}  // namespace

double FeatureDisagreement(const Eigen::MatrixXd& Fs, const Eigen::MatrixXd& Ft,
                           const std::vector<int>& map, const std::array<double, 2>& scales,
                           const std::vector<int>& vertices) {
  const int n = vertices.empty() ? static_cast<int>(Fs.rows()) : static_cast<int>(vertices.size());
  double sum = 0.0, area = 0.0;
  for (int i = 0; i < n; ++i) {
    const int v = vertices.empty() ? i : vertices[i];
    sum += Fs(v, kArea) * FeatureDifference(Fs, Ft, v, map[v], scales) / 2.0;
    area += Fs(v, kArea);
  }
  return sum / std::max(area, 1e-300);
}

double FeatureVote(const Eigen::MatrixXd& Fs, const Eigen::MatrixXd& Ft, const std::vector<int>& a,
                   const std::vector<int>& b, const std::array<double, 2>& scales,
                   const std::vector<int>& vertices) {
  if (vertices.empty()) throw InvalidInputError("flip: a feature vote over no vertices");
  double votes = 0.0, area = 0.0;
  for (const int v : vertices) {
    const double ea = FeatureDifference(Fs, Ft, v, a[v], scales);
    const double eb = FeatureDifference(Fs, Ft, v, b[v], scales);
    votes += Fs(v, kArea) * ((ea < eb) - (eb < ea));
    area += Fs(v, kArea);
  }
  return votes / std::max(area, 1e-300);
}

ExtrinsicScores ExtrinsicFlipScores(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                                    const Eigen::MatrixXd& Fs, const Eigen::MatrixXd& Ft,
                                    const ExtrinsicFlipOptions& options,
                                    const CandidateMaps& maps, int threads) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("flip extrinsic: " + error);
  if (Fs.rows() != Ys.rows() || Ft.rows() != Yt.rows() || Fs.cols() != 3 || Ft.cols() != 3) {
    throw InvalidInputError("flip extrinsic: features do not match the embeddings");
  }
  const std::array<double, 2> sigma = FeatureScales(Fs, Ft);
  ExtrinsicScores out;
  const double rs = std::max(RmsRadius(Ys), 1e-300), rt = std::max(RmsRadius(Yt), 1e-300);
  AxisDescriptor source_axes[2];
  for (int axis = 1; axis <= 2; ++axis) {
    source_axes[axis - 1] = Describe(Ys.col(axis), Fs, rs, options);
  }
  const auto rotations = CandidateRotations();
  std::array<double, 4> chamfer{};
  if (options.chamfer_weight > 0.0) chamfer = ChamferScores(Ys, Yt, threads);
  for (int k = 0; k < 4; ++k) {
    const double local = FeatureDisagreement(Fs, Ft, maps.map[k], sigma);
    const Eigen::MatrixX3d Ytk = Yt * rotations[k].transpose();
    double global = 0.0;
    for (int axis = 1; axis <= 2; ++axis) {
      const AxisDescriptor& s = source_axes[axis - 1];
      const AxisDescriptor t = Describe(Ytk.col(axis), Ft, rt, options);
      global += (s.profile - t.profile).cwiseAbs().sum();
      for (int h = 0; h < 2; ++h) {
        global += 0.5 * (s.hist[h] - t.hist[h]).cwiseAbs().sum();
        global += 0.5 * std::abs(s.curvedness[h] - t.curvedness[h]) / sigma[kCurvedness];
      }
    }
    out.local[k] = local;
    out.global[k] = global / 2.0;
    out.chamfer[k] = chamfer[k];
    out.total[k] = options.local_weight * out.local[k] + options.global_weight * out.global[k] +
                   options.chamfer_weight * out.chamfer[k];
  }
  return out;
}

}  // namespace symembed
