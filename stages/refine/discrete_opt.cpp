#include "stages/refine/discrete_opt.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <utility>

#include "core/errors.h"
#include "core/fmap/descriptors.h"
#include "core/fmap/functional_map.h"
#include "core/fmap/spectral_knn.h"
#include "core/fmap/zoomout.h"
#include "stages/refine/discrete_terms.h"

namespace symembed {

bool DiscreteOptOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  const DiscreteOptWeights& w = weights;
  out << FieldViolation(*this);
  if (out.str().empty() && k_end < k_start) {
    out << "k_end (" << k_end << ") must be >= k_start (" << k_start << ")";
  }
  const std::string weight = FieldViolation(w);
  if (out.str().empty() && !weight.empty()) out << "weights." << weight;
  // The descriptor and embedding terms alone do not depend on the functional maps: the
  // iterations would repeat one query.
  if (out.str().empty() && !(w.orthogonality + w.bijectivity + w.proper + w.laplacian > 0)) {
    out << "one of the weights orthogonality, bijectivity, proper, laplacian must be > 0";
  }
  return NoViolation(out.str(), error);
}

WksProducts DiscreteWksProducts(const LaplaceBasis& basis, int k_end) {
  return ComputeWksProducts(basis, k_end, k_end);
}

namespace {

// What one shape contributes to the iterations: the vertices that query (their weights, basis
// rows and Gram matrix, for fitting the functional map of this shape's point map) and the
// vertices the other shape's points may land on (those of them with area).
struct Side {
  const LaplaceBasis* basis = nullptr;
  std::vector<int> active;
  Eigen::VectorXd weights;
  Eigen::MatrixXd rows;  // basis rows of `active`, k_end columns
  Eigen::MatrixXd gram;  // A^T W A of rows
  std::vector<int> candidates;
  Eigen::MatrixXd candidate_rows;  // basis rows of `candidates`, k_end columns
  std::vector<int> candidate_row;  // per vertex: its row in candidate_rows, or -1
  Eigen::MatrixXd points;          // embedding term: points of `active`, or empty
  Eigen::MatrixXd candidate_points;  // embedding term: points of `candidates`, or empty

  // The basis rows (first k columns) at vertex ids of this shape.
  Eigen::MatrixXd RowsAt(const std::vector<int>& ids, int k) const {
    std::vector<int> r(ids.size());
    for (size_t i = 0; i < ids.size(); ++i) {
      r[i] = candidate_row[ids[i]];
      if (r[i] < 0) return BasisRows(basis->evecs, ids, k);
    }
    return BasisRows(candidate_rows, r, k);
  }
};

Side MakeSide(const LaplaceBasis& basis, const std::vector<int>& samples, int k_end,
              bool sample_candidates, const Eigen::MatrixXd* points, const char* which) {
  Side side;
  side.basis = &basis;
  const int n = basis.NumVertices();
  side.active = samples;
  if (samples.empty()) {
    side.active.resize(n);
    std::iota(side.active.begin(), side.active.end(), 0);
    side.weights = basis.mass;
  } else {
    for (int i : samples) {
      if (i < 0 || i >= n) {
        std::ostringstream out;
        out << "discrete: " << which << " sample id " << i << " out of range 0.." << n - 1;
        throw InvalidInputError(out.str());
      }
    }
    side.weights = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(samples.size()));
  }
  side.rows = BasisRows(basis.evecs, side.active, k_end);
  side.gram = WeightedGram(side.rows, side.weights);
  side.candidates = MatchableTargets(basis.mass, sample_candidates ? samples : std::vector<int>{});
  side.candidate_rows = BasisRows(basis.evecs, side.candidates, k_end);
  side.candidate_row.assign(n, -1);
  for (size_t r = 0; r < side.candidates.size(); ++r) {
    side.candidate_row[side.candidates[r]] = static_cast<int>(r);
  }
  if (points != nullptr) {
    side.points = BasisRows(*points, side.active);
    side.candidate_points = BasisRows(*points, side.candidates);
  }
  return side;
}

// What the terms of one direction X -> Y need at one basis size besides the basis rows.
struct DirectionMaps {
  const Eigen::MatrixXd* C_xy;
  const Eigen::MatrixXd* C_yx;
  const Eigen::VectorXd* lambda_x;
  const Eigen::VectorXd* lambda_y;
  const Eigen::MatrixXd* A_x;  // descriptor coefficients, k_end rows (first k used)
  const Eigen::MatrixXd* A_y;
  const Eigen::MatrixXd* Z_x;  // embedding term: points at the query rows
  const Eigen::MatrixXd* Z_y;  // embedding term: points at the candidates
};

// The terms of positive weight for queries X and candidates Y (basis rows, first k columns),
// reduced to k coordinates and the embedding's (ReduceTerms): the linear terms' maps are their
// rows at identity bases.
ReducedTerms Stacked(const BasisRef& X, const BasisRef& Y, const DirectionMaps& m,
                     const DiscreteOptWeights& w) {
  const int k = static_cast<int>(X.cols());
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(k, k);
  std::vector<TermRows> terms;
  std::vector<double> weights;
  auto add = [&](double weight, auto make) {
    if (weight <= 0.0) return;
    terms.push_back(make());
    weights.push_back(weight);
  };
  add(w.orthogonality, [&] { return OrthogonalityRows(I, I, *m.C_xy); });
  add(w.bijectivity, [&] { return BijectivityRows(I, I, *m.C_yx); });
  add(w.proper, [&] { return ProperRows(I, I, *m.C_xy); });
  add(w.laplacian, [&] { return LaplacianRows(I, I, *m.lambda_x, *m.lambda_y, *m.C_xy); });
  add(w.descriptor, [&] { return DescriptorRows(I, I, m.A_x->topRows(k), m.A_y->topRows(k)); });
  const bool embedded = w.embedding > 0.0;
  return ReduceTerms(X, Y, StackTerms(terms, weights), embedded ? m.Z_x : nullptr,
                     embedded ? m.Z_y : nullptr, w.embedding);
}

// The minimiser over maps into `candidates` of the stacked energy: per query row, the nearest
// candidate. Adds the weighted energy of the result to *energy.
std::vector<int> Query(const TermRows& rows, const std::vector<int>& candidates,
                       const Eigen::VectorXd& weights, double* energy) {
  const SpectralNearest nearest(rows.points, candidates);
  std::vector<int> map;
  std::vector<double> sq;
  nearest.Query(rows.query, &map, &sq);
  for (size_t r = 0; r < sq.size(); ++r) *energy += weights(r) * sq[r];
  return map;
}

// The same for reduced terms; gram: the weighted Gram matrix of the query rows (at least k x k,
// its top-left block read), which gives the part of the energy the reduction leaves out.
std::vector<int> Query(const ReducedTerms& terms, const std::vector<int>& candidates,
                       const Eigen::VectorXd& weights, const Eigen::MatrixXd& gram,
                       double* energy) {
  const Eigen::Index k = terms.G.rows();
  *energy += std::max(0.0, terms.G.cwiseProduct(gram.topLeftCorner(k, k)).sum());
  return Query(terms.rows, candidates, weights, energy);
}

// Descriptor coefficients (k_end x count) of both shapes: wave kernel signatures at energies
// shared by the pair, in the first k_end eigenfunctions. products: each shape's
// DiscreteWksProducts (computed here when null).
void Descriptors(const LaplaceBasis& source, const LaplaceBasis& target, int k_end, int count,
                 const WksProducts* source_products, const WksProducts* target_products,
                 Eigen::MatrixXd* A_s, Eigen::MatrixXd* A_t) {
  double sigma = 0.0;
  const Eigen::VectorXd energies =
      WksEnergies(source.evals.head(k_end), target.evals.head(k_end), count, 2.0, &sigma);
  *A_s = WksCoefficients(source_products ? *source_products : DiscreteWksProducts(source, k_end),
                         EnergyWeights(source.evals.head(k_end), energies, sigma));
  *A_t = WksCoefficients(target_products ? *target_products : DiscreteWksProducts(target, k_end),
                         EnergyWeights(target.evals.head(k_end), energies, sigma));
}

void CheckDiscreteOptInputs(const LaplaceBasis& source, const LaplaceBasis& target,
                            const std::vector<int>& initial_map, const std::vector<int>& samples,
                            const std::vector<int>& target_samples,
                            const DiscreteOptOptions& options, const DiscreteOptPoints* points) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("discrete: " + error);
  CheckBasesReach("discrete", source, target, options.k_end);
  if (samples.empty() != target_samples.empty()) {
    throw InvalidInputError("discrete: give samples of both shapes or of neither");
  }
  CheckPointMap(initial_map, source.NumVertices(), target.NumVertices());
  if (options.weights.embedding > 0.0) {
    if (points == nullptr) {
      throw InvalidInputError("discrete: the embedding term needs the embedded points of the pair");
    }
    if (points->source.rows() != source.NumVertices() ||
        points->target.rows() != target.NumVertices() ||
        points->source.cols() != points->target.cols()) {
      std::ostringstream out;
      out << "discrete: embedded points " << points->source.rows() << " x " << points->source.cols()
          << " and " << points->target.rows() << " x " << points->target.cols() << " for shapes of "
          << source.NumVertices() << " and " << target.NumVertices() << " vertices";
      throw InvalidInputError(out.str());
    }
  }
}

// The status message: the schedule, the samples, the weights, and per basis size the energy
// and the defects of the functional maps.
std::string DiscreteOptMessage(const DiscreteOptResult& result, const DiscreteOptOptions& options,
                               int source_active, int target_active, bool sampled, int ns) {
  const DiscreteOptWeights& w = options.weights;
  std::ostringstream message;
  message << "discrete k " << options.k_start << ".." << options.k_end << " step "
          << options.step;
  if (sampled) message << " on " << source_active << " / " << target_active << " samples";
  message << "; weights orthogonality " << w.orthogonality << " bijectivity " << w.bijectivity
          << " proper " << w.proper << " laplacian " << w.laplacian << " descriptor "
          << w.descriptor << " embedding " << w.embedding;
  message.precision(3);
  message << "; changed " << result.changed << "/" << ns
          << "; per k: energy per point, ||C12^T C12 - I||^2/k, ||C12 C21 - I||^2/k:";
  for (size_t it = 0; it < result.k.size(); ++it) {
    message << " " << result.k[it] << ":" << result.energy[it] << "," << result.orthogonality[it]
            << "," << result.bijectivity[it];
  }
  return message.str();
}

}  // namespace

DiscreteOptResult DiscreteOpt(const LaplaceBasis& source, const LaplaceBasis& target,
                              const std::vector<int>& initial_map, const std::vector<int>& samples,
                              const std::vector<int>& target_samples,
                              const DiscreteOptOptions& options, const WksProducts* source_products,
                              const WksProducts* target_products, const DiscreteOptPoints* points) {
  CheckDiscreteOptInputs(source, target, initial_map, samples, target_samples, options, points);
  const int ns = source.NumVertices(), k_end = options.k_end;
  const bool sampled = !samples.empty();
  const DiscreteOptWeights& w = options.weights;
  const bool embedded = w.embedding > 0.0;
  const Side S = MakeSide(source, samples, k_end, options.sample_candidates,
                          embedded ? &points->source : nullptr, "source");
  const Side T = MakeSide(target, target_samples, k_end, options.sample_candidates,
                          embedded ? &points->target : nullptr, "target");
  Eigen::MatrixXd A_s, A_t;
  if (w.descriptor > 0.0) {
    Descriptors(source, target, k_end, options.descriptors, source_products, target_products, &A_s,
                &A_t);
  }

  std::vector<int> sizes;
  for (int k = options.k_start; k < k_end; k += options.step) sizes.push_back(k);
  sizes.push_back(k_end);

  // T12 on the source's active points; T21 on the target's, started from the first functional
  // map as ZoomOut recovers a map from it (C21 taken as C12^T, exact for an orthogonal C12).
  std::vector<int> t12(S.active.size());
  for (size_t r = 0; r < S.active.size(); ++r) t12[r] = initial_map[S.active[r]];
  const int k0 = sizes.front();
  auto fit12 = [&](int k) {
    return FitFunctionalMapFromRows(S.rows.leftCols(k), T.RowsAt(t12, k), S.weights, &S.gram);
  };
  std::vector<int> t21;
  {
    const Eigen::MatrixXd C21 = fit12(k0).transpose();
    double unused = 0.0;
    t21 = Query(OrthogonalityRows(T.rows.leftCols(k0), S.candidate_rows.leftCols(k0), C21),
                S.candidates, T.weights, &unused);
  }

  DiscreteOptResult result;
  Eigen::MatrixXd C12, C21;
  Eigen::VectorXd lambda_s, lambda_t;
  for (size_t it = 0; it < sizes.size(); ++it) {
    const int k = sizes[it];
    C12 = fit12(k);
    C21 = FitFunctionalMapFromRows(T.rows.leftCols(k), S.RowsAt(t21, k), T.weights, &T.gram);
    if (w.laplacian > 0.0) ScaledEigenvalues(source.evals, target.evals, k, &lambda_s, &lambda_t);
    result.k.push_back(k);
    result.orthogonality.push_back(OrthogonalityDefect(C12));
    result.bijectivity.push_back(BijectivityDefect(C12, C21));
    const bool last = it + 1 == sizes.size();
    if (last && sampled && options.dense_result) break;  // the dense query below
    const DirectionMaps forward{&C12, &C21, &lambda_s, &lambda_t,
                                &A_s, &A_t, &S.points, &T.candidate_points};
    const DirectionMaps backward{&C21, &C12, &lambda_t, &lambda_s,
                                 &A_t, &A_s, &T.points, &S.candidate_points};
    double energy = 0.0;
    t12 = Query(Stacked(S.rows.leftCols(k), T.candidate_rows.leftCols(k), forward, w), T.candidates,
                S.weights, S.gram, &energy);
    t21 = Query(Stacked(T.rows.leftCols(k), S.candidate_rows.leftCols(k), backward, w),
                S.candidates, T.weights, T.gram, &energy);
    result.energy.push_back(energy / static_cast<double>(S.active.size() + T.active.size()));
  }

  if (sampled && options.dense_result) {
    // Every source vertex onto every target vertex with area, with the last functional maps.
    const std::vector<int> all_targets = MatchableTargets(target.mass);
    Eigen::MatrixXd Z_s, Z_t;
    if (embedded) {
      Z_s = points->source;
      Z_t = BasisRows(points->target, all_targets);
    }
    const DirectionMaps forward{&C12, &C21, &lambda_s, &lambda_t, &A_s, &A_t, &Z_s, &Z_t};
    double energy = 0.0;
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(ns);
    result.map =
        Query(Stacked(source.evecs.leftCols(k_end), BasisRows(target.evecs, all_targets, k_end),
                      forward, w),
              all_targets, ones, WeightedGram(source.evecs.leftCols(k_end), ones), &energy);
    result.energy.push_back(energy / ns);
  } else if (sampled) {
    result.map = initial_map;
    for (size_t r = 0; r < S.active.size(); ++r) result.map[S.active[r]] = t12[r];
  } else {
    result.map = t12;
  }
  for (int i = 0; i < ns; ++i) result.changed += result.map[i] != initial_map[i];

  result.status.converged = true;
  result.status.iterations = static_cast<int>(result.k.size());
  result.status.residual = result.energy.back();
  result.status.message =
      DiscreteOptMessage(result, options, static_cast<int>(S.active.size()),
                         static_cast<int>(T.active.size()), sampled, ns);
  return result;
}

}  // namespace symembed
