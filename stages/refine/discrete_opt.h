// Discrete optimisation of a point map and its functional maps in both directions, grown over
// basis sizes: the `discrete` refine stage.
//
// [Ren, Melzi, Wonka & Ovsjanikov 2021] Discrete optimization for shape matching. The state is
// a pair of point maps, T12 from source to target and T21 back, and their functional maps
// C12 = Phi_s^+ Pi12 Phi_t and C21 = Phi_t^+ Pi21 Phi_s (the "proper" maps the point maps
// induce, core/fmap/functional_map.h). At each basis size k (k_start, k_start + step, ...,
// k_end, as in ZoomOut) the two functional maps are fitted to the point maps by least squares,
// then each point map is set to the exact minimiser, for those functional maps, of the weighted
// sum of the terms of discrete_terms.h (orthogonality, bijectivity through the other
// direction's map, properness, Laplacian commutativity, descriptor preservation, and the
// embedding term that keeps each point near its image in the pipeline's aligned embeddings):
// one nearest-neighbour query in the stacked embeddings. The bijectivity term ties the two
// directions together, which keeps the map close to a bijection where ZoomOut, one direction
// alone, lets many source points collapse onto one target region on non-isometric pairs.
//
// With samples, the iterations run between the source samples and the target samples; only the
// last query (at k_end, after the last fit) maps every source vertex onto every target vertex.
// Descriptors are wave kernel signatures of each shape computed from its basis
// (core/fmap/descriptors.h), at energies shared by the pair.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/fmap/descriptors.h"
#include "core/fmap/zoomout.h"
#include "core/range.h"
#include "core/spectral.h"
#include "registry/types.h"

namespace symembed {

// Weights of the terms (>= 0, at least one of the first four positive).
struct DiscreteOptWeights {
  double orthogonality = 1.0;
  double bijectivity = 1.0;
  double proper = 1.0;
  double laplacian = 1.0;
  double descriptor = 1.0;
  // Needs the pair's embedded points (DiscreteOptPoints); the refine stage's default is 100.
  double embedding = 0.0;
  static constexpr Range kWeight = Range::AtLeast(0.0);  // of each weight above

  // The weights as the config's `weights` map names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("orthogonality", self.orthogonality, kWeight);
    visit("bijectivity", self.bijectivity, kWeight);
    visit("proper", self.proper, kWeight);
    visit("laplacian", self.laplacian, kWeight);
    visit("descriptor", self.descriptor, kWeight);
    visit("embedding", self.embedding, kWeight);
  }
};

struct DiscreteOptOptions {
  int k_start = 20;  // first basis size
  static constexpr Range kKStart = Range::Closed(1, 1000);
  int k_end = 120;  // last basis size (>= k_start; both bases need k_end eigenpairs)
  static constexpr Range kKEnd = Range::Closed(1, 1000);
  int step = 5;  // increment of k; k_end is always the last size
  static constexpr Range kStep = Range::Closed(1, 1000);
  DiscreteOptWeights weights;
  int descriptors = 50;  // wave kernel energies of the descriptor term
  static constexpr Range kDescriptors = Range::Closed(1, 1000);
  // With samples: true lands the iterations' maps on the other shape's samples; false on every
  // vertex of the other shape (costlier queries, no rounding of the images to the samples).
  bool sample_candidates = true;
  // With samples: true maps every source vertex in the last query; false maps only the samples
  // (the other entries of the result keep the initial map).
  bool dense_result = true;

  // The options as the config names them (core/range.h), besides `candidates` and `weights`.
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    BasisSizeFields(self, visit);
    visit("descriptors", self.descriptors, kDescriptors);
  }
  bool IsValid(std::string* error) const;
};

// The embedding term's points of every vertex of both shapes in one frame (#Vs x d, #Vt x d):
// the pipeline's embeddings, the source's moved onto the target's by the matching stage.
struct DiscreteOptPoints {
  Eigen::MatrixXd source;
  Eigen::MatrixXd target;
};

struct DiscreteOptResult {
  std::vector<int> map;               // #Vs: target vertex of each source vertex
  std::vector<int> k;                 // per iteration: basis size
  std::vector<double> energy;         // per iteration: weighted energy of both directions'
                                      // point maps after the query, per query point
  std::vector<double> orthogonality;  // per iteration: ||C12^T C12 - I||^2 / k before it
  std::vector<double> bijectivity;    // per iteration: ||C12 C21 - I||^2 / k before it
  int changed = 0;                    // source vertices whose target changed
  StageStatus status;
};

// source, target: bases with at least k_end eigenpairs. initial_map: #Vs entries in [0, #Vt).
// samples, target_samples: the vertices the iterations run on (both empty: every vertex, with
// the lumped areas as weights; else both non-empty, uniform weights, each enough well-spread
// vertices to determine k_end coefficients). Throws ConfigError for invalid options,
// InvalidInputError for inconsistent inputs.
// source_products, target_products (optional): each shape's DiscreteWksProducts for k_end,
// which depend on the shape alone (the refine stage prepares them per shape); computed here when
// null. points: the embedding term's (required when its weight is positive; rows must match
// the vertex counts).
DiscreteOptResult DiscreteOpt(const LaplaceBasis& source, const LaplaceBasis& target,
                              const std::vector<int>& initial_map, const std::vector<int>& samples,
                              const std::vector<int>& target_samples,
                              const DiscreteOptOptions& options,
                              const WksProducts* source_products = nullptr,
                              const WksProducts* target_products = nullptr,
                              const DiscreteOptPoints* points = nullptr);

// What the descriptor term needs of one shape, whatever the pair: the wave kernel signature
// products (core/fmap/descriptors.h) of the first k_end eigenpairs.
WksProducts DiscreteWksProducts(const LaplaceBasis& basis, int k_end);

}  // namespace symembed
