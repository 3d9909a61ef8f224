#include "stages/embedding/lsmds.h"

#include <Eigen/Eigenvalues>
#include <random>
#include <sstream>

#include "core/errors.h"
#include "core/mds/classical_mds.h"
#include "stages/embedding/embedding_common.h"

namespace symembed {

bool LsmdsOptions::IsValid(std::string* error) const {
  std::string why;
  if (dims != 2 && dims != 3)
    why = "dims must be 2 or 3, got " + std::to_string(dims);
  else if (!smacof.IsValid(&why))
    why = "smacof: " + why;
  else if (!out_of_sample.IsValid(&why))
    why = "out_of_sample: " + why;
  if (why.empty()) return true;
  if (error) *error = why;
  return false;
}

Eigen::MatrixXd LsmdsInitialConfiguration(const EmbeddingInput& input,
                                          const Eigen::MatrixXd& sample_distances,
                                          const LsmdsOptions& options) {
  const int ns = static_cast<int>(sample_distances.rows());
  switch (options.init) {
    case LsmdsInit::kOriginal: {
      Eigen::MatrixXd X = SampleCoordinates(input);
      X.rowwise() -= X.colwise().mean();
      if (options.dims == 2) {
        // Principal axes, largest first (the eigensolver sorts ascending).
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(X.transpose() * X);
        X = (X * eig.eigenvectors().rightCols(2).rowwise().reverse()).eval();
      }
      return ScaleToDistances(sample_distances, X);
    }
    case LsmdsInit::kIsomap: {
      ClassicalMdsOptions mds;
      mds.dims = options.dims;
      return ClassicalMds(sample_distances, mds).X;
    }
    case LsmdsInit::kRandom: {
      std::mt19937 rng(options.seed);
      std::normal_distribution<double> normal(0.0, 1.0);
      Eigen::MatrixXd X(ns, options.dims);
      for (int i = 0; i < ns; ++i) {
        for (int c = 0; c < options.dims; ++c) X(i, c) = normal(rng);
      }
      return ScaleToDistances(sample_distances, X);
    }
  }
  SYMEMBED_CHECK(false, "unknown LsmdsInit");
}

EmbeddingResult LsmdsEmbedding(const EmbeddingInput& input, const LsmdsOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw ConfigError("lsmds: " + why);
  CheckEmbeddingInput(input);
  const Eigen::MatrixXd Dss = SampleDistances(input);
  const Eigen::MatrixXd init = LsmdsInitialConfiguration(input, Dss, options);
  SmacofResult smacof = Smacof(Dss, init, options.smacof);

  EmbeddingResult result;
  const int ns = static_cast<int>(input.samples.size());
  result.Y.resize(input.surface.NumVertices(), options.dims);
  for (int i = 0; i < ns; ++i) result.Y.row(input.samples[i]) = smacof.X.row(i);
  const std::vector<int> rest = NonSampleVertices(input);
  if (!rest.empty()) {
    const Eigen::MatrixXd placed = PlaceOutOfSample(smacof.X, input.D, rest, options.out_of_sample);
    for (size_t r = 0; r < rest.size(); ++r) result.Y.row(rest[r]) = placed.row(r);
  }
  result.normalized_stress = smacof.normalized_stress;
  const ReflectionState reflection = EmbeddingReflection(input, smacof.X);
  result.reflection = reflection.sign;
  result.stress_history = std::move(smacof.stress_history);
  result.status.converged = smacof.converged;
  result.status.iterations = smacof.iterations;
  result.status.residual = smacof.normalized_stress;
  std::ostringstream msg;
  msg << "SMACOF " << (smacof.converged ? "converged" : "stopped at max_iterations") << " after "
      << smacof.iterations << " iterations (" << smacof.evaluations
      << " stress evaluations), normalized stress " << smacof.normalized_stress << ", "
      << ReflectionText(reflection);
  result.status.message = msg.str();
  return result;
}

}  // namespace symembed
