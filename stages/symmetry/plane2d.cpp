#include "stages/symmetry/plane2d.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "core/errors.h"
#include "core/parallel.h"
#include "core/procrustes.h"
#include "stages/embedding/classical_mds.h"
#include "stages/embedding/smacof.h"
#include "stages/symmetry/plane3d.h"

namespace symembed {

bool Plane2dOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  std::string sub;
  if (!search.IsValid(&sub)) out << sub;
  else if (!spectral.IsValid(&sub)) out << sub;
  else if (num_angles < 1) out << "num_angles must be >= 1, got " << num_angles;
  else if (!(intrinsic_weight >= 0.0)) out << "intrinsic_weight must be >= 0, got " << intrinsic_weight;
  else if (intrinsic_pairs < 1) out << "intrinsic_pairs must be >= 1, got " << intrinsic_pairs;
  else if (smacof_iterations < 0) out << "smacof_iterations must be >= 0, got " << smacof_iterations;
  else if (refine_3d_iterations < 0)
    out << "refine_3d_iterations must be >= 0, got " << refine_3d_iterations;
  else if (num_directions < 0) out << "num_directions must be >= 0, got " << num_directions;
  else if (threads < 0) out << "threads must be >= 0, got " << threads;
  if (error) *error = out.str();
  return out.str().empty();
}

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

// One candidate symmetry: plane in the 3D embedding, self map, confidence, and its criterion.
struct Candidate {
  Eigen::VectorXd normal;
  double offset = 0.0;
  std::vector<int> sigma;
  Eigen::VectorXd confidence;
  double score = 0.0, intrinsic = 0.0, consistency = 1.0;
  double total = std::numeric_limits<double>::infinity();
  bool converged = true;
  std::string origin;
};

}  // namespace

SymmetryResult DetectSymmetryPlane2d(const Eigen::MatrixXd& D, const std::vector<int>& samples,
                                     const Eigen::MatrixXd& Y, const Plane2dOptions& options,
                                     const Eigen::MatrixXd& G, const Eigen::VectorXd& evals) {
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
  auto consistency = [&](const std::vector<int>& sigma) {
    return SpectralConsistency(G, sigma, evals, options.spectral.eigenvalue_tolerance);
  };
  const Eigen::MatrixXd Dss = SampleDistances(D, samples);
  const Eigen::MatrixXd X = EmbedSamples2d(Dss, options.smacof_iterations, options.threads);
  const KnnIndex index2(X);
  const Eigen::Vector2d centroid = X.colwise().mean().transpose();
  Eigen::MatrixXd P(samples.size(), 3);
  for (size_t i = 0; i < samples.size(); ++i) {
    if (samples[i] < 0 || samples[i] >= Y.rows()) {
      throw InvalidInputError("symmetry plane2d: sample id out of range");
    }
    P.row(i) = Y.row(samples[i]);
  }
  const KnnIndex index3(P);
  const double size2 = RmsRadius(X), size3 = RmsRadius(P);
  auto intrinsic = [&](const std::vector<int>& sigma) {
    return options.intrinsic_weight > 0.0
               ? IntrinsicDistortion(Dss, sigma, options.search.trim_fraction,
                                     options.intrinsic_pairs, static_cast<unsigned>(options.seed))
               : 0.0;
  };
  // A candidate from a fit in 3D: its plane, self map, confidence and score on the samples P.
  auto from_fit_3d = [&](const ReflectionFit& fit, double intrinsic_distortion,
                         std::string origin) {
    Candidate c;
    c.normal = fit.normal;
    c.offset = fit.offset;
    c.sigma = fit.sigma;
    c.confidence = SymmetryConfidence(fit.residual, fit.sigma, size3);
    c.score = fit.score;
    c.intrinsic = intrinsic_distortion;
    c.converged = fit.converged;
    c.origin = std::move(origin);
    return c;
  };
  // The plane (normal, offset) refined in 3D for refine_3d_iterations, as a candidate; none when
  // that refinement is off or rejects the plane. Adds its iterations to *iterations.
  auto refined_in_3d = [&](const Eigen::VectorXd& normal, double offset, const std::string& origin,
                           int* iterations) -> std::optional<Candidate> {
    if (options.refine_3d_iterations <= 0) return std::nullopt;
    ReflectionSearchOptions o = options.search;
    o.max_iterations = options.refine_3d_iterations;
    const ReflectionFit fit3 = RefineReflection(P, index3, normal, offset, o);
    *iterations += fit3.iterations;
    if (!std::isfinite(fit3.score)) return std::nullopt;
    return from_fit_3d(fit3, intrinsic(fit3.sigma), origin + ", refined in 3D");
  };
  std::vector<Candidate> candidates;
  auto consider = [&](Candidate c) {
    c.total = c.score + options.intrinsic_weight * c.intrinsic;
    if (std::isfinite(c.total)) candidates.push_back(std::move(c));
  };

  // Each line direction refined on its own (in parallel) into up to two candidates, then taken in
  // order, so the candidates and the choice do not depend on the threads.
  std::vector<std::vector<Candidate>> per_angle(options.num_angles);
  std::vector<int> angle_iterations(options.num_angles, 0);
  ParallelFor(
      options.num_angles,
      [&](int k) {
        const double angle = M_PI * k / options.num_angles;
        const Eigen::Vector2d n(std::cos(angle), std::sin(angle));
        const ReflectionFit fit = RefineReflection(X, index2, n, n.dot(centroid), options.search);
        angle_iterations[k] += fit.iterations;
        if (!std::isfinite(fit.score)) return;
        // The 2D self map with the plane lifted to 3D.
        Candidate lifted;
        lifted.sigma = fit.sigma;
        lifted.confidence = SymmetryConfidence(fit.residual, fit.sigma, size2);
        if (!FitReflection(P, fit.sigma, lifted.confidence, &lifted.normal, &lifted.offset)) {
          return;
        }
        lifted.score = fit.score;
        lifted.intrinsic = intrinsic(fit.sigma);
        lifted.converged = fit.converged;
        std::ostringstream origin;
        origin << "2D line from " << angle * 180.0 / M_PI << " deg";
        lifted.origin = origin.str();
        std::optional<Candidate> refined =
            refined_in_3d(lifted.normal, lifted.offset, lifted.origin, &angle_iterations[k]);
        per_angle[k].push_back(std::move(lifted));
        if (refined) per_angle[k].push_back(std::move(*refined));
      },
      options.threads);
  int iterations = 0;
  for (int k = 0; k < options.num_angles; ++k) {
    iterations += angle_iterations[k];
    for (Candidate& c : per_angle[k]) consider(std::move(c));
  }
  if (options.candidates_3d) {
    Plane3dOptions o3;
    o3.search = options.search;
    o3.num_directions = options.num_directions;
    o3.intrinsic_weight = options.intrinsic_weight;
    o3.intrinsic_pairs = options.intrinsic_pairs;
    o3.seed = options.seed;
    o3.threads = options.threads;
    double total = 0.0, distortion = 0.0;
    const ReflectionFit fit3 = SearchPlanes3d(P, index3, Dss, o3, &total, &distortion, &iterations);
    if (std::isfinite(total)) consider(from_fit_3d(fit3, distortion, "3D search"));
  }
  auto best_of = [&]() {
    return std::min_element(candidates.begin(), candidates.end(),
                            [](const Candidate& a, const Candidate& b) { return a.total < b.total; });
  };
  if (candidates.empty()) {
    throw InvalidInputError("symmetry plane2d: every candidate symmetry was rejected");
  }
  Candidate& chosen = *best_of();
  if (G.size() > 0) chosen.consistency = consistency(chosen.sigma);
  if (G.size() > 0 && chosen.consistency < options.spectral.min_consistency) {
    // Step 5: the choice by distances is not an intrinsic symmetry of the eigenfunctions. Self
    // maps from sign flips of the eigenfunctions join the candidates, lifted to 3D, and the
    // spectral inconsistency joins the criterion.
    const double sizeG = RmsRadius(G);
    for (const SignFlipCandidate& flip :
         SignFlipCandidates(G, options.spectral.num_candidates, options.search.outlier_distance)) {
      if (flip.fixed_fraction > options.search.max_fixed_fraction) continue;
      Candidate c;
      c.sigma = flip.sigma;
      c.confidence = SymmetryConfidence(flip.residual, flip.sigma, sizeG);
      if (!FitReflection(P, flip.sigma, c.confidence, &c.normal, &c.offset)) continue;
      // Scored like the other candidates, by the lifted plane's fit in 3D.
      c.score = EvaluateReflection(P, index3, c.normal, c.offset, options.search).score;
      if (!std::isfinite(c.score)) continue;
      c.intrinsic = intrinsic(flip.sigma);
      std::ostringstream origin;
      origin << "sign flip of eigenfunctions";
      for (int j = 0; j < G.cols(); ++j) {
        if (flip.pattern >> j & 1u) origin << " " << j + 1;
      }
      c.origin = origin.str();
      // The sign-flip self map is coarse (nearest neighbours in a few eigenfunctions); the
      // lifted plane refined in 3D gives the same symmetry's self map point by point where the
      // 3D embedding has it, and another symmetry, which the criterion then weighs, where not.
      std::optional<Candidate> refined = refined_in_3d(c.normal, c.offset, c.origin, &iterations);
      if (refined) consider(std::move(*refined));
      consider(std::move(c));
    }
    for (Candidate& c : candidates) {
      c.consistency = consistency(c.sigma);
      c.total += options.spectral.weight * (1.0 - c.consistency);
    }
  }
  const Candidate& best = *best_of();
  SymmetryResult result;
  result.normal = best.normal;
  result.offset = best.offset;
  result.sigma = best.sigma;
  result.confidence = best.confidence;
  result.score = best.score;
  result.status.converged = best.converged;
  result.status.iterations = iterations;
  result.status.residual = best.total;
  std::ostringstream message;
  message << "plane2d: " << best.origin << ", score " << best.score << ", intrinsic distortion "
          << best.intrinsic;
  if (G.size() > 0) message << ", spectral consistency " << best.consistency;
  result.status.message = message.str();
  return result;
}

}  // namespace symembed
