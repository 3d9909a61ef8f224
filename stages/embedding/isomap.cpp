#include "stages/embedding/isomap.h"

#include <sstream>

#include "core/errors.h"
#include "core/mds/smacof.h"
#include "stages/embedding/embedding_common.h"

namespace symembed {

bool IsomapOptions::IsValid(std::string* error) const {
  std::string why;
  if (dims != 2 && dims != 3)
    why = "dims must be 2 or 3, got " + std::to_string(dims);
  else if (!mds.IsValid(&why))
    why = "mds: " + why;
  if (why.empty()) return true;
  if (error) *error = why;
  return false;
}

EmbeddingResult IsomapEmbedding(const EmbeddingInput& input, const IsomapOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw ConfigError("isomap: " + why);
  CheckEmbeddingInput(input);
  const Eigen::MatrixXd Dss = SampleDistances(input);
  ClassicalMdsOptions mds_options = options.mds;
  mds_options.dims = options.dims;
  ClassicalMdsResult mds = ClassicalMds(Dss, mds_options);

  EmbeddingResult result;
  ReflectionState reflection = EmbeddingReflection(input, mds.X);
  if (options.fix_orientation && reflection.sign < 0) {
    // Negating one eigenvector keeps the decomposition valid and turns det -1 into +1.
    mds.X.col(options.dims - 1) *= -1.0;
    mds.eigenvectors.col(options.dims - 1) *= -1.0;
    reflection = EmbeddingReflection(input, mds.X);
  }
  result.reflection = reflection.sign;
  const int ns = static_cast<int>(input.samples.size());
  result.Y.resize(input.surface.NumVertices(), options.dims);
  for (int i = 0; i < ns; ++i) result.Y.row(input.samples[i]) = mds.X.row(i);
  const std::vector<int> rest = NonSampleVertices(input);
  if (!rest.empty()) {
    const Eigen::MatrixXd placed = LandmarkMds(mds, input.D, rest);
    for (size_t r = 0; r < rest.size(); ++r) result.Y.row(rest[r]) = placed.row(r);
  }
  result.normalized_stress = NormalizedStress(Dss, mds.X);
  result.status.iterations = mds.solver_iterations;
  result.status.residual = result.normalized_stress;
  std::ostringstream msg;
  msg << "classical MDS, eigenvalues";
  for (int k = 0; k < options.dims; ++k) msg << " " << mds.eigenvalues(k);
  msg << ", normalized stress " << result.normalized_stress << ", " << ReflectionText(reflection);
  result.status.message = msg.str();
  return result;
}

}  // namespace symembed
