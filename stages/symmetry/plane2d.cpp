#include "stages/symmetry/plane2d.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "core/errors.h"
#include "core/mds/classical_mds.h"
#include "core/mds/smacof.h"
#include "core/parallel.h"
#include "core/procrustes.h"
#include "stages/symmetry/plane3d.h"

namespace symembed {

Eigen::MatrixXd EmbedSamples2d(const Eigen::MatrixXd& Dss, int smacof_iterations, int threads) {
  ClassicalMdsOptions mds;
  mds.dims = 2;
  Eigen::MatrixXd X = ClassicalMds(Dss, mds).X;
  if (smacof_iterations > 0) {
    SmacofOptions options;
    options.max_iterations = smacof_iterations;
    options.threads = threads;
    X = Smacof(Dss, X, options).X;
  }
  return X;
}

namespace {

// A near tie is looked for among the candidates whose self map moves the samples at least this
// many times as much as the chosen one's: another symmetry, not a variant of the same.
constexpr double kClearlyMore = 1.5;

// One candidate symmetry: plane in the 3D embedding, self map, confidence, and its criterion.
struct Candidate {
  Eigen::VectorXd normal;
  double offset = 0.0;
  std::vector<int> sigma;
  Eigen::VectorXd confidence;
  double score = 0.0, intrinsic = 0.0, consistency = 1.0, displacement = 0.0;
  double total = std::numeric_limits<double>::infinity();
  bool converged = true;
  std::string origin;
};

// The input checks of DetectSymmetryPlane2d.
void CheckPlane2dInputs(const std::vector<int>& samples, const Eigen::MatrixXd& Y,
                        const Plane2dOptions& options, const Eigen::MatrixXd& G,
                        const Eigen::VectorXd& evals) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("symmetry plane2d: " + error);
  if (Y.cols() != 3) throw InvalidInputError("symmetry plane2d: the embedding must be 3D");
  if (samples.size() < 4) throw InvalidInputError("symmetry plane2d: fewer than 4 samples");
  if (G.size() > 0 && G.rows() != static_cast<Eigen::Index>(samples.size())) {
    throw InvalidInputError("symmetry plane2d: spectral coordinates have " +
                            std::to_string(G.rows()) + " rows for " +
                            std::to_string(samples.size()) + " samples");
  }
  if (evals.size() != 0 && evals.size() != G.cols()) {
    throw InvalidInputError("symmetry plane2d: " + std::to_string(evals.size()) +
                            " eigenvalues for " + std::to_string(G.cols()) +
                            " spectral coordinates");
  }
}

// The samples' rows of the 3D embedding (#S x 3).
Eigen::MatrixXd SamplePoints(const Eigen::MatrixXd& Y, const std::vector<int>& samples) {
  Eigen::MatrixXd P(samples.size(), 3);
  for (size_t i = 0; i < samples.size(); ++i) {
    if (samples[i] < 0 || samples[i] >= Y.rows()) {
      throw InvalidInputError("symmetry plane2d: sample id out of range");
    }
    P.row(i) = Y.row(samples[i]);
  }
  return P;
}

}  // namespace

// One detection: the samples in 2D (X) and in the 3D embedding (P), and the candidates found.
// Candidates are added in a fixed order (lines of the 2D embedding by angle, the 3D search, the
// sign flips of the eigenfunctions), so the choice does not depend on the threads. The lines and
// the 3D search do not depend on min_self_map_displacement; Choose, which adds the sign flips
// when the choice so far needs them and picks the plane, does, and leaves the search as it was.
class Plane2dCandidates {
 public:
  Plane2dCandidates(const Eigen::MatrixXd& D, const std::vector<int>& samples,
                    const Eigen::MatrixXd& Y, const Plane2dOptions& options,
                    const Eigen::MatrixXd& G, const Eigen::VectorXd& evals)
      : options_(options),
        G_(G),
        evals_(evals),
        Dss_(SampleDistances(D, samples)),
        X_(EmbedSamples2d(Dss_, options.smacof_iterations, options.threads)),
        index2_(X_),
        centroid_(X_.colwise().mean().transpose()),
        P_(SamplePoints(Y, samples)),
        index3_(P_),
        size2_(RmsRadius(X_)),
        size3_(RmsRadius(P_)),
        intrinsic_check_(Dss_, options.intrinsic.pairs,
                         static_cast<unsigned>(options.intrinsic.seed)) {}
  // intrinsic_check_ refers to Dss_.
  Plane2dCandidates(const Plane2dCandidates&) = delete;
  Plane2dCandidates& operator=(const Plane2dCandidates&) = delete;

  // Each line direction of the 2D embedding refined on its own (in parallel) into the lifted
  // candidate and its refinement in 3D.
  void AddLineCandidates() {
    std::vector<std::vector<Candidate>> per_angle(options_.num_angles);
    std::vector<int> angle_iterations(options_.num_angles, 0);
    ParallelFor(
        options_.num_angles,
        [&](int k) { per_angle[k] = LineCandidates(k, &angle_iterations[k]); },
        options_.threads);
    for (int k = 0; k < options_.num_angles; ++k) {
      iterations_ += angle_iterations[k];
      for (Candidate& c : per_angle[k]) Consider(std::move(c), &candidates_);
    }
  }

  // The best plane of the 3D search over directions (SearchPlanes3d).
  void AddSearch3dCandidate() {
    Plane3dOptions o3;
    o3.search = options_.search;
    o3.num_directions = options_.num_directions;
    o3.intrinsic = options_.intrinsic;
    o3.threads = options_.threads;
    double total = 0.0, distortion = 0.0;
    const ReflectionFit fit3 =
        SearchPlanes3d(P_, index3_, intrinsic_check_, o3, &total, &distortion, &iterations_);
    if (std::isfinite(total)) Consider(FromFit3d(fit3, distortion, "3D search"), &candidates_);
  }

  // The plane chosen with the bound min_self_map_displacement. Step 5: when the choice by
  // distances is not an intrinsic symmetry of the eigenfunctions, self maps from sign flips of the
  // eigenfunctions join the candidates, lifted to 3D, and the spectral inconsistency joins the
  // criterion.
  SymmetryResult Choose(double min_self_map_displacement) const {
    if (candidates_.empty()) {
      throw InvalidInputError("symmetry plane2d: every candidate symmetry was rejected");
    }
    std::vector<Candidate> candidates = candidates_;
    int iterations = iterations_;
    Candidate& chosen = Best(candidates, min_self_map_displacement);
    if (G_.size() > 0) chosen.consistency = Consistency(chosen.sigma);
    if (G_.size() > 0 && chosen.consistency < options_.spectral.min_consistency) {
      const double sizeG = RmsRadius(G_);
      for (const SignFlipCandidate& flip :
           SignFlipCandidates(G_, options_.spectral.num_candidates,
                              options_.search.outlier_distance, options_.threads)) {
        if (flip.fixed_fraction > options_.search.max_fixed_fraction) continue;
        AddSignFlipCandidate(flip, sizeG, &candidates, &iterations);
      }
      for (Candidate& c : candidates) {
        c.consistency = Consistency(c.sigma);
        c.total += options_.spectral.weight * (1.0 - c.consistency);
      }
    }
    return Result(candidates, iterations, min_self_map_displacement);
  }

  SymmetryResult Result(std::vector<Candidate>& candidates, int iterations,
                        double min_self_map_displacement) const {
    const Candidate& best = Best(candidates, min_self_map_displacement);
    SymmetryResult result;
    result.normal = best.normal;
    result.offset = best.offset;
    result.sigma = best.sigma;
    result.confidence = best.confidence;
    if (options_.distance_confidence > 0.0) {
      // Redistribute the symmetrization's pull towards the pairs the self map is sure of,
      // keeping its overall strength: a coarse self map (a sign flip of eigenfunctions on a
      // shape whose eigenfunctions are not quite symmetric) pairs some samples wrongly, and
      // pressing those into mirror images bends the whole embedding.
      if (result.confidence.size() != Dss_.rows()) {
        result.confidence = Eigen::VectorXd::Ones(Dss_.rows());
      }
      const double before = result.confidence.mean();
      result.confidence.array() *=
          DistanceConsistencyWeights(Dss_, best.sigma, options_.distance_confidence).array();
      const double after = result.confidence.mean();
      if (after > 0.0) result.confidence *= before / after;
    }
    result.score = best.score;
    result.status.converged = best.converged;
    result.status.iterations = iterations;
    result.status.residual = best.total;
    std::ostringstream message;
    message << "plane2d: " << best.origin << ", score " << best.score
            << ", intrinsic distortion " << best.intrinsic;
    if (G_.size() > 0) message << ", spectral consistency " << best.consistency;
    message << ", self map displacement " << best.displacement;
    // A near tie with a candidate that moves the samples clearly more: RunAlternative proposes
    // it as the second plane.
    const double moves_more = kClearlyMore * best.displacement;
    if (options_.second_plane_below > 0.0 && options_.second_plane_tie > 1.0 &&
        best.displacement >= options_.second_plane_below) {
      const Candidate* tied = nullptr;
      for (const Candidate& c : candidates) {
        if (c.displacement >= moves_more && (tied == nullptr || c.total < tied->total)) tied = &c;
      }
      if (tied != nullptr && tied->total <= options_.second_plane_tie * best.total) {
        result.tie_displacement = moves_more;
        message << "; near tie (" << tied->total << ") with a self map moving the samples "
                << tied->displacement;
      }
    }
    result.status.message = message.str();
    return result;
  }

 private:
  double Consistency(const std::vector<int>& sigma) const {
    return SpectralConsistency(G_, sigma, evals_, options_.spectral.eigenvalue_tolerance);
  }

  double Intrinsic(const std::vector<int>& sigma) const {
    return options_.intrinsic.weight > 0.0
               ? intrinsic_check_.Distortion(sigma, options_.search.trim_fraction)
               : 0.0;
  }

  // A candidate from a fit in 3D: its plane, self map, confidence and score on the samples P.
  Candidate FromFit3d(const ReflectionFit& fit, double intrinsic_distortion,
                      std::string origin) const {
    Candidate c;
    c.normal = fit.normal;
    c.offset = fit.offset;
    c.sigma = fit.sigma;
    c.confidence = SymmetryConfidence(fit.residual, fit.sigma, size3_);
    c.score = fit.score;
    c.intrinsic = intrinsic_distortion;
    c.converged = fit.converged;
    c.origin = std::move(origin);
    return c;
  }

  // The plane (normal, offset) refined in 3D for refine_3d_iterations, as a candidate; none when
  // that refinement is off or rejects the plane. Adds its iterations to *iterations.
  std::optional<Candidate> RefinedIn3d(const Eigen::VectorXd& normal, double offset,
                                       const std::string& origin, int* iterations) const {
    if (options_.refine_3d_iterations <= 0) return std::nullopt;
    ReflectionSearchOptions o = options_.search;
    o.max_iterations = options_.refine_3d_iterations;
    const ReflectionFit fit3 = RefineReflection(P_, index3_, normal, offset, o);
    *iterations += fit3.iterations;
    if (!std::isfinite(fit3.score)) return std::nullopt;
    return FromFit3d(fit3, Intrinsic(fit3.sigma), origin + ", refined in 3D");
  }

  // The line of angle pi k / num_angles refined in 2D, its self map with the plane lifted to
  // 3D, and that plane refined in 3D: up to two candidates.
  std::vector<Candidate> LineCandidates(int k, int* iterations) const {
    std::vector<Candidate> out;
    const double angle = M_PI * k / options_.num_angles;
    const Eigen::Vector2d n(std::cos(angle), std::sin(angle));
    const ReflectionFit fit = RefineReflection(X_, index2_, n, n.dot(centroid_), options_.search);
    *iterations += fit.iterations;
    if (!std::isfinite(fit.score)) return out;
    Candidate lifted;
    lifted.sigma = fit.sigma;
    lifted.confidence = SymmetryConfidence(fit.residual, fit.sigma, size2_);
    if (!FitReflection(P_, fit.sigma, lifted.confidence, &lifted.normal, &lifted.offset)) {
      return out;
    }
    lifted.score = fit.score;
    lifted.intrinsic = Intrinsic(fit.sigma);
    lifted.converged = fit.converged;
    std::ostringstream origin;
    origin << "2D line from " << angle * 180.0 / M_PI << " deg";
    lifted.origin = origin.str();
    std::optional<Candidate> refined =
        RefinedIn3d(lifted.normal, lifted.offset, lifted.origin, iterations);
    out.push_back(std::move(lifted));
    if (refined) out.push_back(std::move(*refined));
    return out;
  }

  // A sign-flip self map lifted to a plane in 3D, scored like the other candidates by the plane's
  // fit in 3D, after its refinement in 3D: the sign-flip self map is coarse (nearest neighbours
  // in a few eigenfunctions); the lifted plane refined in 3D gives the same symmetry's self map
  // point by point where the 3D embedding has it, and another symmetry, which the criterion then
  // weighs, where not.
  void AddSignFlipCandidate(const SignFlipCandidate& flip, double sizeG,
                            std::vector<Candidate>* candidates, int* iterations) const {
    Candidate c;
    c.sigma = flip.sigma;
    c.confidence = SymmetryConfidence(flip.residual, flip.sigma, sizeG);
    if (!FitReflection(P_, flip.sigma, c.confidence, &c.normal, &c.offset)) return;
    c.score = EvaluateReflection(P_, index3_, c.normal, c.offset, options_.search).score;
    if (!std::isfinite(c.score)) return;
    c.intrinsic = Intrinsic(flip.sigma);
    std::ostringstream origin;
    origin << "sign flip of eigenfunctions";
    for (int j = 0; j < G_.cols(); ++j) {
      if (flip.pattern >> j & 1u) origin << " " << j + 1;
    }
    c.origin = origin.str();
    std::optional<Candidate> refined = RefinedIn3d(c.normal, c.offset, c.origin, iterations);
    if (refined) Consider(std::move(*refined), candidates);
    Consider(std::move(c), candidates);
  }

  void Consider(Candidate c, std::vector<Candidate>* candidates) const {
    c.total = c.score + options_.intrinsic.weight * c.intrinsic;
    c.displacement = SelfMapDisplacement(P_, c.sigma);
    if (std::isfinite(c.total)) candidates->push_back(std::move(c));
  }

  // The candidate of the lowest total (the first on ties) among those whose self map moves the
  // samples at least `bound`, or among all when none does.
  static Candidate& Best(std::vector<Candidate>& candidates, double bound) {
    const bool any_moves = std::any_of(candidates.begin(), candidates.end(),
                                       [&](const Candidate& c) { return c.displacement >= bound; });
    return *std::min_element(candidates.begin(), candidates.end(),
                             [&](const Candidate& a, const Candidate& b) {
                               if (any_moves) {
                                 const bool a_moves = a.displacement >= bound;
                                 const bool b_moves = b.displacement >= bound;
                                 if (a_moves != b_moves) return a_moves;
                               }
                               return a.total < b.total;
                             });
  }

  const Plane2dOptions options_;
  const Eigen::MatrixXd G_;
  const Eigen::VectorXd evals_;
  const Eigen::MatrixXd Dss_;  // #S x #S
  const Eigen::MatrixXd X_;    // #S x 2
  const KnnIndex index2_;
  const Eigen::Vector2d centroid_;
  const Eigen::MatrixXd P_;  // #S x 3
  const KnnIndex index3_;
  const double size2_, size3_;
  const IntrinsicCheck intrinsic_check_;  // of Dss_
  std::vector<Candidate> candidates_;  // the lines' and the 3D search's
  int iterations_ = 0;
};

Eigen::VectorXd DistanceConsistencyWeights(const Eigen::MatrixXd& Dss,
                                           const std::vector<int>& sigma, double scale) {
  const Eigen::Index S = Dss.rows();
  if (Dss.cols() != S || static_cast<Eigen::Index>(sigma.size()) != S) {
    throw InvalidInputError("symmetry plane2d: a self map of " + std::to_string(sigma.size()) +
                            " entries for " + std::to_string(S) + " x " +
                            std::to_string(Dss.cols()) + " sample distances");
  }
  for (int j : sigma) {
    if (j < 0 || j >= S) {
      throw InvalidInputError("symmetry plane2d: self map entry " + std::to_string(j) +
                              " out of range 0.." + std::to_string(S - 1));
    }
  }
  const Eigen::Index A = std::min<Eigen::Index>(S, 128);
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(S);
  if (S == 0) return weights;
  std::vector<double> d(S), r(A);
  for (Eigen::Index i = 0; i < S; ++i) {
    for (Eigen::Index a = 0; a < A; ++a) {
      r[a] = std::abs(Dss(i, a) - Dss(sigma[i], sigma[a]));
    }
    std::nth_element(r.begin(), r.begin() + A / 2, r.end());
    d[i] = r[A / 2];
  }
  std::vector<double> sorted = d;
  std::nth_element(sorted.begin(), sorted.begin() + S / 2, sorted.end());
  const double unit = scale * sorted[S / 2];
  if (!(unit > 0.0)) return weights;
  for (Eigen::Index i = 0; i < S; ++i) {
    const double x = d[i] / unit;
    weights(i) = 1.0 / (1.0 + x * x);
  }
  return weights;
}

double SampleSelfMapDisplacement(const Eigen::MatrixXd& Y, const std::vector<int>& samples,
                                 const std::vector<int>& sigma) {
  if (sigma.size() != samples.size()) {
    throw InvalidInputError("symmetry plane2d: a self map of " + std::to_string(sigma.size()) +
                            " entries for " + std::to_string(samples.size()) + " samples");
  }
  return SelfMapDisplacement(SamplePoints(Y, samples), sigma);
}

std::shared_ptr<const Plane2dCandidates> SearchPlane2d(
    const Eigen::MatrixXd& D, const std::vector<int>& samples, const Eigen::MatrixXd& Y,
    const Plane2dOptions& options, const Eigen::MatrixXd& G, const Eigen::VectorXd& evals) {
  CheckPlane2dInputs(samples, Y, options, G, evals);
  auto search = std::make_shared<Plane2dCandidates>(D, samples, Y, options, G, evals);
  search->AddLineCandidates();
  if (options.candidates_3d) search->AddSearch3dCandidate();
  return search;
}

SymmetryResult ChoosePlane2d(const Plane2dCandidates& candidates,
                             double min_self_map_displacement) {
  return candidates.Choose(min_self_map_displacement);
}

SymmetryResult DetectSymmetryPlane2d(const Eigen::MatrixXd& D, const std::vector<int>& samples,
                                     const Eigen::MatrixXd& Y, const Plane2dOptions& options,
                                     const Eigen::MatrixXd& G, const Eigen::VectorXd& evals) {
  return SearchPlane2d(D, samples, Y, options, G, evals)->Choose(options.min_self_map_displacement);
}

}  // namespace symembed
