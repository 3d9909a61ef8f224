// Correspondence error measures: per-pair records, cumulative error curves and per-variant
// summaries.
//
// Errors are geodesic distances on the target normalised by sqrt(area) of the target, per
// ground-truth point [Kim et al. 2011] Blended intrinsic maps; the cumulative curve gives, for
// each threshold t in [0, max_error], the fraction of points with error <= t, and its
// normalised area (AUC) is the trapezoidal integral divided by max_error (1 = perfect). Means
// and curves of a variant pool all ground-truth points of all evaluated pairs, as the TOSCA
// literature does [Ren et al. 2018] Continuous and orientation-preserving correspondences
// via functional maps.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace symembed {

struct EvaluationOptions;  // eval/evaluation_options.h

// The thresholds of the "% <= t" measures, and their keys in summary.json and CSV headers.
constexpr std::array<double, 3> kErrorThresholds = {0.05, 0.10, 0.25};
const std::array<std::string, 3>& ErrorThresholdKeys();  // {"0.05", "0.10", "0.25"}

// How a map is flipped relative to the ground truth.
enum class FlipClass { kNone, kLeftRight, kFrontBack, kUpDown };
const char* FlipClassName(FlipClass flip);  // "none", "left_right", "front_back", "up_down"
// Throws InvalidInputError for an unknown name.
FlipClass ParseFlipClass(const std::string& name);

// What a run computed a pair's outputs from: the cache keys of both shapes' per-shape data (mesh
// bytes and every per-shape stage's resolved options) and the pair's key (both shape keys, the
// per-pair stages' and the evaluation's options, the ground truth). --resume keeps a pair only
// when its record carries the inputs of the current run.
struct PairInputs {
  uint64_t source = 0;
  uint64_t target = 0;
  uint64_t pair = 0;
  bool operator==(const PairInputs& other) const {
    return source == other.source && target == other.target && pair == other.pair;
  }
};

// The evaluation of one map A -> B; also the pair's record in a run (pairs/STEM.rec).
struct PairEvaluation {
  // What a run computed the pair from (the first member of its record); none for the pairs
  // of `symembed eval` and for a record without an `inputs` member.
  std::optional<PairInputs> inputs;
  std::string source, target;
  bool ok = false;              // false: failed, see message; no errors recorded
  std::string message;          // why it failed (empty when ok)
  int points = 0;               // ground-truth points evaluated
  double mean_direct = 0.0, median_direct = 0.0, max_direct = 0.0;
  std::array<double, 3> pct_direct{};   // % of points with error <= kErrorThresholds (0..100)
  bool has_sym = false;         // symmetric ground truth known
  double mean_sym = 0.0;        // mean against the symmetric ground truth (when has_sym)
  double mean_flip_tolerant = 0.0;      // min(mean_direct, mean_sym)
  FlipClass flip = FlipClass::kNone;
  int chosen = -1;              // candidate rotation chosen by the pipeline (-1: none)
  int oracle = -1;              // the oracle's candidate (-1: unknown)
  std::vector<double> errors_direct;    // #points, in ground-truth line order
  std::vector<double> errors_sym;       // #points when has_sym, else empty
  std::map<std::string, double> stage_seconds;  // wall time per stage ("evaluation", ...)
  // Status message of each pair stage that reported one ("flip": its scores and terms,
  // "refine": e.g. ZoomOut's energy per basis size).
  std::map<std::string, std::string> stage_messages;
  // Mean direct error of each candidate rotation (the oracle's measure), when it was computed.
  std::vector<double> candidate_errors;
  // When a refine stage changed the map: the means of the map before refinement.
  bool refined = false;
  double initial_mean_direct = 0.0, initial_mean_sym = 0.0;

  // Which ground truth the map is nearer to, before and after refinement: "" (not refined, or no
  // symmetric ground truth), "kept", "to_symmetric" (refinement moved the map onto the mirrored
  // solution: a flip it introduced) or "to_direct" (a flip it repaired).
  std::string RefineSide() const;

  // The error vector of whichever ground truth gave the lower mean.
  const std::vector<double>& FlipTolerantErrors() const;
};

// Fills mean/median/max/pct/mean_sym/mean_flip_tolerant of a pair from its error vectors.
void ComputePairStatistics(PairEvaluation& pair);

// Flip class rule: with both candidates known (>= 0) and different, the relative rotation
// R_chosen * R_oracle^T of CandidateRotations() decides: it negates y (Rx or Rz) -> up_down,
// else (Ry: negates x and z) -> front_back. Otherwise left_right when the symmetric mean is
// lower than the direct mean, else none.
FlipClass ClassifyFlip(int chosen, int oracle, bool has_sym, double mean_direct, double mean_sym);

// Statistics of a sample (NaN for an empty one). Median: mean of the two middle values.
double Mean(const std::vector<double>& x);
double Median(std::vector<double> x);
// Percentage (0..100) of values <= t.
double PercentAtMost(const std::vector<double>& x, double t);

// Thresholds 0, step, ..., max_error (round(max_error / step) + 1 values).
std::vector<double> CurveThresholds(double max_error, double step);
// Fraction of errors <= each threshold (0 for no errors).
std::vector<double> CumulativeCurve(const std::vector<double>& errors,
                                    const std::vector<double>& thresholds);
// Trapezoidal area under the curve divided by the threshold range; 0..1.
double CurveArea(const std::vector<double>& thresholds, const std::vector<double>& curve);

// Wall times the runner measured outside the per-pair records.
struct VariantTimings {
  double total_seconds = 0.0;                     // wall time of the whole variant
  // Per shape: shape name -> stage -> seconds (per-shape stages; 0 when taken from cache).
  std::map<std::string, std::map<std::string, double>> shape_stage_seconds;
  double peak_rss_mb = 0.0;                       // PeakRssMb() of the process(es)
};

// Peak resident set size of this process in MiB (VmHWM of /proc/self/status; 0 if unknown).
double PeakRssMb();

struct VariantSummary {
  std::string variant;
  std::string evaluation_geodesics;
  double max_error = 0.25, step = 0.0025;
  int points_option = 0;                 // evaluation.points (0 = all)
  int pairs = 0;                         // pairs evaluated, failed ones included
  int failed_pairs = 0;
  long total_points = 0;                 // ground-truth points pooled over the pairs
  // Pooled over all points of all successful pairs.
  double mean_direct = 0.0, median_direct = 0.0;
  double mean_flip_tolerant = 0.0, median_flip_tolerant = 0.0;
  std::array<double, 3> pct_direct{}, pct_flip_tolerant{};   // 0..100
  double auc_direct = 0.0, auc_flip_tolerant = 0.0;
  // Unweighted mean over pairs of each pair's mean.
  double mean_of_pair_means_direct = 0.0, mean_of_pair_means_flip_tolerant = 0.0;
  int flipped_left_right = 0, flipped_front_back = 0, flipped_up_down = 0;
  // Refined pairs whose map refinement moved to the symmetric / to the direct ground truth.
  int refine_to_symmetric = 0, refine_to_direct = 0;
  int FlippedTotal() const { return flipped_left_right + flipped_front_back + flipped_up_down; }
  // Shapes whose preprocessing removed components (some of their area); -1: not known (eval).
  int shapes_lost_area = -1;
  double time_total_s = 0.0, time_per_shape_s = 0.0, time_per_pair_s = 0.0;
  double peak_rss_mb = 0.0;
  std::vector<double> thresholds, curve_direct, curve_flip_tolerant;
};

// Summarises the pairs of one variant. The result does not depend on the order of `pairs`
// (they are sorted by source, target first), so shards merged give a single run's numbers.
// time_per_pair_s: mean over pairs of the sum of their stage_seconds; time_per_shape_s: mean
// over timings' shapes of the sum of their stage seconds.
VariantSummary Summarize(const std::string& variant, std::vector<PairEvaluation> pairs,
                         const EvaluationOptions& options, const VariantTimings& timings);

// Sorts by (source, target).
void SortPairs(std::vector<PairEvaluation>& pairs);

}  // namespace symembed
