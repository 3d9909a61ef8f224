// The `isomap` embedding: classical MDS on the sample geodesic distances, landmark MDS for every
// other vertex.
//
// Eigenvector signs are arbitrary, so the embedding can be a reflection of the surface; by
// default that is kept (and reported through `reflection`) because it is what the LS-MDS
// embedding started from the input coordinates avoids [Yoshiyasu et al. 2016]. With
// fix_orientation (dims 3 only) the last axis is negated when the Procrustes fit from the input
// coordinates needs a reflection.
//
// [Tenenbaum et al. 2000] A global geometric framework for nonlinear dimensionality reduction.
// [de Silva & Tenenbaum 2004] Sparse multidimensional scaling using landmark points.
// [Yoshiyasu et al. 2016] Symmetry-aware embedding for shape correspondence.
#pragma once

#include <string>

#include "core/mds/classical_mds.h"
#include "registry/stages.h"

namespace symembed {

struct IsomapOptions {
  int dims = 3;                  // 2 or 3
  bool fix_orientation = false;  // see above; no effect for dims 2
  ClassicalMdsOptions mds;       // mds.dims is overridden by dims

  bool IsValid(std::string* error) const;
};

// Y (#V x dims), sample rows exactly the classical MDS coordinates; normalised stress of the
// sample embedding; reflection after the optional fix; status.iterations = eigensolver
// iterations. Throws InvalidInputError on bad input, ConfigError on invalid options,
// SolverError when the eigensolver fails.
EmbeddingResult IsomapEmbedding(const EmbeddingInput& input, const IsomapOptions& options = {});

}  // namespace symembed
