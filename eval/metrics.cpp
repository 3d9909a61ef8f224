#include "eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numeric>
#include <sstream>
#include <tuple>

#include "core/errors.h"
#include "eval/evaluation_options.h"
#include "registry/types.h"

namespace symembed {

const std::array<std::string, 3>& ErrorThresholdKeys() {
  static const std::array<std::string, 3> keys = {"0.05", "0.10", "0.25"};
  return keys;
}

const char* FlipClassName(FlipClass flip) {
  switch (flip) {
    case FlipClass::kNone: return "none";
    case FlipClass::kLeftRight: return "left_right";
    case FlipClass::kFrontBack: return "front_back";
    case FlipClass::kUpDown: return "up_down";
  }
  return "none";
}

FlipClass ParseFlipClass(const std::string& name) {
  for (FlipClass f : {FlipClass::kNone, FlipClass::kLeftRight, FlipClass::kFrontBack,
                      FlipClass::kUpDown}) {
    if (name == FlipClassName(f)) return f;
  }
  throw InvalidInputError("unknown flip class '" + name +
                          "'; known: none, left_right, front_back, up_down");
}

const std::vector<double>& PairEvaluation::FlipTolerantErrors() const {
  return has_sym && mean_sym < mean_direct ? errors_sym : errors_direct;
}

double Mean(const std::vector<double>& x) {
  if (x.empty()) return std::numeric_limits<double>::quiet_NaN();
  return std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
}

double Median(std::vector<double> x) {
  if (x.empty()) return std::numeric_limits<double>::quiet_NaN();
  const size_t mid = x.size() / 2;
  std::nth_element(x.begin(), x.begin() + mid, x.end());
  const double upper = x[mid];
  if (x.size() % 2 == 1) return upper;
  const double lower = *std::max_element(x.begin(), x.begin() + mid);
  return 0.5 * (lower + upper);
}

double PercentAtMost(const std::vector<double>& x, double t) {
  if (x.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto n = std::count_if(x.begin(), x.end(), [t](double e) { return e <= t; });
  return 100.0 * static_cast<double>(n) / static_cast<double>(x.size());
}

void ComputePairStatistics(PairEvaluation& pair) {
  const auto& e = pair.errors_direct;
  pair.points = static_cast<int>(e.size());
  pair.mean_direct = Mean(e);
  pair.median_direct = Median(e);
  pair.max_direct = e.empty() ? std::numeric_limits<double>::quiet_NaN()
                              : *std::max_element(e.begin(), e.end());
  for (size_t k = 0; k < kErrorThresholds.size(); ++k) {
    pair.pct_direct[k] = PercentAtMost(e, kErrorThresholds[k]);
  }
  pair.has_sym = !pair.errors_sym.empty();
  pair.mean_sym = pair.has_sym ? Mean(pair.errors_sym) : 0.0;
  pair.mean_flip_tolerant =
      pair.has_sym ? std::min(pair.mean_direct, pair.mean_sym) : pair.mean_direct;
}

std::string PairEvaluation::RefineSide() const {
  if (!refined || !has_sym) return "";
  const bool before = initial_mean_sym < initial_mean_direct;
  const bool after = mean_sym < mean_direct;
  if (before == after) return "kept";
  return after ? "to_symmetric" : "to_direct";
}

FlipClass ClassifyFlip(int chosen, int oracle, bool has_sym, double mean_direct,
                       double mean_sym) {
  if (chosen >= 0 && oracle >= 0 && chosen != oracle) {
    SYMEMBED_CHECK(chosen < 4 && oracle < 4, "candidate index out of range: chosen=" << chosen
                                                 << " oracle=" << oracle);
    const auto R = CandidateRotations();
    const Eigen::Matrix3d relative = R[chosen] * R[oracle].transpose();
    return relative(1, 1) < 0 ? FlipClass::kUpDown : FlipClass::kFrontBack;
  }
  if (has_sym && mean_sym < mean_direct) return FlipClass::kLeftRight;
  return FlipClass::kNone;
}

std::vector<double> CurveThresholds(double max_error, double step) {
  SYMEMBED_CHECK(max_error > 0 && step > 0, "curve needs max_error > 0 and step > 0");
  const long n = std::lround(max_error / step);
  std::vector<double> t(n + 1);
  // Exact multiples of step (not accumulated) so every run gets the same thresholds.
  for (long k = 0; k <= n; ++k) t[k] = std::min(max_error, static_cast<double>(k) * step);
  t[n] = max_error;
  return t;
}

std::vector<double> CumulativeCurve(const std::vector<double>& errors,
                                    const std::vector<double>& thresholds) {
  std::vector<double> sorted(errors);
  std::sort(sorted.begin(), sorted.end());
  std::vector<double> curve(thresholds.size(), 0.0);
  if (sorted.empty()) return curve;
  for (size_t k = 0; k < thresholds.size(); ++k) {
    const auto count = std::upper_bound(sorted.begin(), sorted.end(), thresholds[k]) -
                       sorted.begin();
    curve[k] = static_cast<double>(count) / static_cast<double>(sorted.size());
  }
  return curve;
}

double CurveArea(const std::vector<double>& thresholds, const std::vector<double>& curve) {
  SYMEMBED_CHECK(thresholds.size() == curve.size() && thresholds.size() >= 2,
                 "curve and thresholds must have the same size >= 2");
  double area = 0.0;
  for (size_t k = 1; k < curve.size(); ++k) {
    area += 0.5 * (curve[k] + curve[k - 1]) * (thresholds[k] - thresholds[k - 1]);
  }
  return area / (thresholds.back() - thresholds.front());
}

double PeakRssMb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.compare(0, 6, "VmHWM:") == 0) {
      std::istringstream fields(line.substr(6));
      double kb = 0.0;
      fields >> kb;
      return kb / 1024.0;
    }
  }
  return 0.0;
}

void SortPairs(std::vector<PairEvaluation>& pairs) {
  std::stable_sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) {
    return std::tie(a.source, a.target) < std::tie(b.source, b.target);
  });
}

namespace {

double SumSeconds(const std::map<std::string, double>& stages) {
  double total = 0.0;
  for (const auto& [name, seconds] : stages) total += seconds;
  return total;
}

}  // namespace

VariantSummary Summarize(const std::string& variant, std::vector<PairEvaluation> pairs,
                         const EvaluationOptions& options, const VariantTimings& timings) {
  SortPairs(pairs);
  VariantSummary s;
  s.variant = variant;
  s.evaluation_geodesics = options.geodesics;
  s.max_error = options.max_error;
  s.step = options.step;
  s.points_option = options.points;
  std::vector<double> direct, tolerant, pair_means_direct, pair_means_tolerant;
  double pair_seconds = 0.0;
  for (const auto& p : pairs) {
    pair_seconds += SumSeconds(p.stage_seconds);
    ++s.pairs;
    if (!p.ok) {
      ++s.failed_pairs;
      continue;
    }
    direct.insert(direct.end(), p.errors_direct.begin(), p.errors_direct.end());
    const auto& t = p.FlipTolerantErrors();
    tolerant.insert(tolerant.end(), t.begin(), t.end());
    pair_means_direct.push_back(p.mean_direct);
    pair_means_tolerant.push_back(p.mean_flip_tolerant);
    switch (p.flip) {
      case FlipClass::kLeftRight: ++s.flipped_left_right; break;
      case FlipClass::kFrontBack: ++s.flipped_front_back; break;
      case FlipClass::kUpDown: ++s.flipped_up_down; break;
      case FlipClass::kNone: break;
    }
    const std::string side = p.RefineSide();
    if (side == "to_symmetric") ++s.refine_to_symmetric;
    if (side == "to_direct") ++s.refine_to_direct;
  }
  s.total_points = static_cast<long>(direct.size());
  s.mean_direct = Mean(direct);
  s.median_direct = Median(direct);
  s.mean_flip_tolerant = Mean(tolerant);
  s.median_flip_tolerant = Median(tolerant);
  for (size_t k = 0; k < kErrorThresholds.size(); ++k) {
    s.pct_direct[k] = PercentAtMost(direct, kErrorThresholds[k]);
    s.pct_flip_tolerant[k] = PercentAtMost(tolerant, kErrorThresholds[k]);
  }
  s.mean_of_pair_means_direct = Mean(pair_means_direct);
  s.mean_of_pair_means_flip_tolerant = Mean(pair_means_tolerant);
  s.thresholds = CurveThresholds(options.max_error, options.step);
  s.curve_direct = CumulativeCurve(direct, s.thresholds);
  s.curve_flip_tolerant = CumulativeCurve(tolerant, s.thresholds);
  s.auc_direct = CurveArea(s.thresholds, s.curve_direct);
  s.auc_flip_tolerant = CurveArea(s.thresholds, s.curve_flip_tolerant);

  s.time_total_s = timings.total_seconds;
  s.time_per_pair_s = pairs.empty() ? 0.0 : pair_seconds / static_cast<double>(pairs.size());
  double shape_seconds = 0.0;
  for (const auto& [shape, stages] : timings.shape_stage_seconds) {
    shape_seconds += SumSeconds(stages);
  }
  s.time_per_shape_s = timings.shape_stage_seconds.empty()
                           ? 0.0
                           : shape_seconds / static_cast<double>(timings.shape_stage_seconds.size());
  s.peak_rss_mb = timings.peak_rss_mb;
  return s;
}

}  // namespace symembed
