// The `lsmds` embedding: SMACOF on the sample geodesic distances, then out-of-sample placement
// of every other vertex.
//
// With init `original` the iteration starts from the samples' own surface coordinates (scaled
// to the distances), so the embedding keeps the surface's orientation: SMACOF only descends
// stress from there and never passes through a reflected configuration in practice [Yoshiyasu
// et al. 2016]. `isomap` starts from classical MDS (arbitrary signs), `random` from seeded
// Gaussian points.
//
// [Yoshiyasu et al. 2016] Symmetry-aware embedding for shape correspondence.
// [Borg & Groenen 2005] Modern Multidimensional Scaling.
#pragma once

#include <string>

#include "core/mds/smacof.h"
#include "registry/stages.h"
#include "stages/embedding/out_of_sample.h"

namespace symembed {

enum class LsmdsInit { kOriginal, kIsomap, kRandom };

struct LsmdsOptions {
  int dims = 3;  // 2 or 3
  LsmdsInit init = LsmdsInit::kOriginal;
  unsigned seed = 1;  // for init kRandom
  SmacofOptions smacof;
  OutOfSampleOptions out_of_sample;

  // The options as the config names them (core/range.h), besides dims and init.
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("seed", self.seed, Range::AtLeast(0));
    SmacofOptions::Fields(self.smacof, visit);
    using P = OutOfSampleOptions;
    visit("neighbors", self.out_of_sample.neighbors, P::kNeighbors);
    visit("out_of_sample_weight_power", self.out_of_sample.weight_power, P::kWeightPower);
    visit("out_of_sample_iterations", self.out_of_sample.max_iterations, P::kMaxIterations);
  }
  bool IsValid(std::string* error) const;
};

// The samples' initial configuration (#S x dims) for the given init. With dims 2, `original`
// projects the input coordinates onto their two principal axes.
Eigen::MatrixXd LsmdsInitialConfiguration(const EmbeddingInput& input,
                                          const Eigen::MatrixXd& sample_distances,
                                          const LsmdsOptions& options);

// Y (#V x dims) with sample rows exactly the SMACOF result; stress history, normalised stress
// and reflection (see EmbeddingReflection) filled in; status.converged/iterations from SMACOF,
// status.residual = normalised stress. Throws InvalidInputError on bad input (see
// CheckEmbeddingInput), ConfigError on invalid options.
EmbeddingResult LsmdsEmbedding(const EmbeddingInput& input, const LsmdsOptions& options = {});

}  // namespace symembed
