#include "stages/embedding/embedding_common.h"

#include <sstream>

#include "core/errors.h"
#include "core/procrustes.h"

namespace symembed {

void CheckEmbeddingInput(const EmbeddingInput& input) {
  const int nv = input.surface.NumVertices();
  const int ns = static_cast<int>(input.samples.size());
  std::ostringstream why;
  if (ns < 2)
    why << "need at least 2 samples, got " << ns;
  else if (input.D.rows() != ns || input.D.cols() != nv)
    why << "distances are " << input.D.rows() << "x" << input.D.cols() << ", expected " << ns << "x"
        << nv << " (#samples x #vertices)";
  else if (!input.D.allFinite() || (input.D.array() < 0.0).any())
    why << "distances must be finite and non-negative (is the surface connected?)";
  if (why.str().empty()) {
    std::vector<char> seen(nv, 0);
    for (int s : input.samples) {
      if (s < 0 || s >= nv) {
        why << "sample id " << s << " out of range [0, " << nv << ")";
        break;
      }
      if (seen[s]) {
        why << "sample id " << s << " appears twice";
        break;
      }
      seen[s] = 1;
    }
  }
  if (!why.str().empty()) throw InvalidInputError("embedding: " + why.str());
}

Eigen::MatrixXd SampleDistances(const EmbeddingInput& input) {
  const int ns = static_cast<int>(input.samples.size());
  Eigen::MatrixXd A(ns, ns);
  for (int j = 0; j < ns; ++j) A.col(j) = input.D.col(input.samples[j]);
  Eigen::MatrixXd S = 0.5 * (A + A.transpose());
  S.diagonal().setZero();
  return S;
}

Eigen::MatrixXd SampleCoordinates(const EmbeddingInput& input) {
  const int ns = static_cast<int>(input.samples.size());
  Eigen::MatrixXd X(ns, 3);
  for (int i = 0; i < ns; ++i) X.row(i) = input.surface.V.row(input.samples[i]);
  return X;
}

ReflectionState EmbeddingReflection(const EmbeddingInput& input, const Eigen::MatrixXd& Ys) {
  if (Ys.cols() != 3) return {};
  const ProcrustesFit fit = FitProcrustes(SampleCoordinates(input), Ys);
  return {fit.det_sign, fit.conditioning};
}

std::string ReflectionText(const ReflectionState& state) {
  std::ostringstream out;
  out << "reflection " << (state.sign < 0 ? "-1" : "+1") << " (Procrustes conditioning "
      << state.conditioning << ")";
  return out.str();
}

std::vector<int> NonSampleVertices(const EmbeddingInput& input) {
  std::vector<char> is_sample(input.surface.NumVertices(), 0);
  for (int s : input.samples) is_sample[s] = 1;
  std::vector<int> rest;
  for (int v = 0; v < input.surface.NumVertices(); ++v) {
    if (!is_sample[v]) rest.push_back(v);
  }
  return rest;
}

}  // namespace symembed
