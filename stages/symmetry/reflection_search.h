// Reflective symmetry search on a point set in 2D or 3D: reflect / nearest neighbour / refit
// iterations with a trimmed score, and an intrinsic check of the induced self map.
//
// A reflection is p -> p - 2 (n . p - c) n with unit normal n and offset c (plane n . p = c).
// Shared by the `plane2d` and `plane3d` symmetry stages.
// [Mitra et al. 2006] Partial and approximate symmetry detection for 3D geometry;
// [Yoshiyasu et al. 2016] Symmetry-aware embedding for shape correspondence.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/knn.h"
#include "core/range.h"
#include "registry/types.h"

namespace symembed {

struct ReflectionSearchOptions {
  // Maximum reflect / NN / refit iterations per starting reflection.
  int max_iterations = 30;
  static constexpr Range kMaxIterations = Range::AtLeast(1);
  // Fraction of points (smallest residuals) kept in the refit; the rest is treated as
  // unmatched (missing parts, imperfect symmetry).
  double trim_fraction = 0.8;
  static constexpr Range kTrimFraction = Range::Closed(0.05, 1.0);
  // Residuals are truncated at outlier_distance * size in the score, so an unmatched point
  // costs a fixed amount whatever its distance (and a plane that leaves more points unmatched
  // scores worse).
  double outlier_distance = 0.1;
  static constexpr Range kOutlierDistance = Range::Closed(1e-6, 10.0);
  // Reflections mapping more than this fraction of points to themselves are rejected (a flat
  // point set is "symmetric" about its own plane with the identity as self map).
  double max_fixed_fraction = 0.5;
  static constexpr Range kMaxFixedFraction = Range::Closed(0.0, 1.0);
  // Converged when the normal turns by less than this (radians) and the offset moves by less
  // than this times the size.
  double tolerance = 1e-6;
  static constexpr Range kTolerance = Range::Above(0.0);

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("max_iterations", self.max_iterations, kMaxIterations);
    visit("trim_fraction", self.trim_fraction, kTrimFraction);
    visit("outlier_distance", self.outlier_distance, kOutlierDistance);
    visit("max_fixed_fraction", self.max_fixed_fraction, kMaxFixedFraction);
  }
  bool IsValid(std::string* error) const;
};

// The intrinsic check of candidate planes (IntrinsicCheck below), weighed against their
// extrinsic score in the choice among them.
struct IntrinsicCheckOptions {
  // Weight of the intrinsic distortion in the choice among candidates (0: off).
  double weight = 2.0;
  static constexpr Range kWeight = Range::AtLeast(0.0);
  // Sample pairs used by the check.
  int pairs = 4000;
  static constexpr Range kPairs = Range::AtLeast(1);
  // Seed of the pair sampling.
  int seed = 1;

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("intrinsic_weight", self.weight, kWeight);
    visit("intrinsic_pairs", self.pairs, kPairs);
    visit("seed", self.seed, Range::Any());
  }
};

struct ReflectionFit {
  Eigen::VectorXd normal;     // d, unit
  double offset = 0.0;
  std::vector<int> sigma;     // #N: point -> nearest point to its mirror image
  Eigen::VectorXd residual;   // #N: ||reflect(p_i) - p_sigma(i)||
  double score = 0.0;         // mean of min(residual, outlier_distance * size) / size; +inf
                              // when rejected
  double fixed_fraction = 0.0;
  int iterations = 0;
  bool converged = false;
};

// Fraction of points that sigma maps to themselves.
double FixedFraction(const std::vector<int>& sigma);

// The score of a self map's residuals (#N) in a point set of RMS radius size: the mean of
// min(residual, outlier_distance * size) / size.
double TruncatedScore(const Eigen::VectorXd& residual, double size, double outlier_distance);

// Rows of P reflected about the plane normal . p = offset.
Eigen::MatrixXd Reflect(const Eigen::MatrixXd& P, const Eigen::VectorXd& normal, double offset);

// The reflection that maps p_i to p_sigma(i) best, weighted by w (#N, >= 0): its plane passes
// through the weighted mean of the midpoints (p_i + p_sigma(i)) / 2 and its normal is the
// principal direction of the differences p_i - p_sigma(i). Exact for an exactly symmetric set.
// Returns false (normal unchanged) when no weighted pair has a non-zero difference.
bool FitReflection(const Eigen::MatrixXd& P, const std::vector<int>& sigma,
                   const Eigen::VectorXd& w, Eigen::VectorXd* normal, double* offset);

// Iterates from the reflection (normal, offset): sigma = NN of the reflected points, refit on the
// trimmed inliers, until the plane stops moving. index: KnnIndex built on P.
ReflectionFit RefineReflection(const Eigen::MatrixXd& P, const KnnIndex& index,
                               const Eigen::VectorXd& normal, double offset,
                               const ReflectionSearchOptions& options);

// Scores the reflection (normal, offset) without iterating (one NN pass).
ReflectionFit EvaluateReflection(const Eigen::MatrixXd& P, const KnnIndex& index,
                                 const Eigen::VectorXd& normal, double offset,
                                 const ReflectionSearchOptions& options);

// Intrinsic distortion of self maps of one point set: trimmed mean over sampled pairs (i, j) of
// |D(i, j) - D(sigma i, sigma j)|, divided by the mean of D(i, j) over the same pairs; 0 means
// distances are preserved exactly. The pairs and their distances are drawn once, so checking
// each of many self maps costs one lookup per pair.
class IntrinsicCheck {
 public:
  // Dss: #S x #S distances between the points, kept by reference (it must outlive the check);
  // num_pairs (>= 1) random pairs (fixed seed), or all pairs when there are fewer. Throws
  // InvalidInputError when Dss is not square.
  IntrinsicCheck(const Eigen::MatrixXd& Dss, int num_pairs, unsigned seed);

  // sigma: #S, a point of Dss for each point. Throws InvalidInputError when its size is not #S.
  // Thread-safe.
  double Distortion(const std::vector<int>& sigma, double trim_fraction) const;

 private:
  const Eigen::MatrixXd& Dss_;
  std::vector<int> first_, second_;  // the pairs (i, j), in the order drawn
  std::vector<double> distance_;     // D(i, j) of each pair
  double distance_sum_ = 0.0;        // their sum, in the order drawn
};

// Per-point confidence in [0, 1]: exp(-(r / h)^2) with h = max(2 median(r), 1e-3 size), halved
// where sigma is not an involution (sigma(sigma(i)) != i).
Eigen::VectorXd SymmetryConfidence(const Eigen::VectorXd& residual, const std::vector<int>& sigma,
                                   double size);

// The symmetry stages' output from a plane in the 3D embedding: refined by up to
// `iterations_3d` iterations on the 3D sample positions Y3s (#S x 3; index built on them),
// sigma = NN of the mirrored samples, confidence from the residuals, score as in ReflectionFit. `message` goes into the status.
SymmetryResult MakeSymmetryResult(const Eigen::MatrixXd& Y3s, const KnnIndex& index,
                                  const Eigen::VectorXd& normal, double offset,
                                  const ReflectionSearchOptions& options, int iterations_3d,
                                  const std::string& message);

// Sample-to-sample distances D(:, samples), symmetrized: #S x #S. D: #S x #V.
Eigen::MatrixXd SampleDistances(const Eigen::MatrixXd& D, const std::vector<int>& samples);

}  // namespace symembed
