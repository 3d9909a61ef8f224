// The parts of the flip stage `extrinsic` (extrinsic_stage.h): terms, each adding a score per
// candidate rotation (lower is better), and a decision that picks the candidate from the sum.
//
// A term is one file (term_<name>.h) with its options, its reader and its FlipTerm; it becomes
// part of the stage through one line of the term table in extrinsic_stage.cpp, under its name in
// the stage's `terms` map. The stage runs the terms in table order, each on the totals of those
// before it (the orientation term measures only candidates that can still win), then the
// decision.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <sstream>
#include <string>

#include "core/spectral.h"
#include "registry/product_needs.h"
#include "registry/types.h"
#include "stages/flip/extrinsic.h"
#include "stages/flip/flip_common.h"

namespace symembed {

// What the stage computes once per pair for its parts.
struct FlipTermContext {
  const PairInput& pair;
  const CandidateMaps& maps;          // ComputeCandidateMaps of the canonical embeddings
  // The first BasisSize() eigenpairs of each shape, the largest any part asks for (empty when
  // none asks).
  const LaplaceBasis& source_basis;
  const LaplaceBasis& target_basis;
  // The shapes' curvature features (ExtrinsicFeatures, extrinsic.h) of the last term that reads
  // them (Features), or null when none does.
  const Eigen::MatrixXd* source_features;
  const Eigen::MatrixXd* target_features;
  int threads;                        // the stage's threads (0: all cores)
};

class FlipTerm {
 public:
  // weight: the term's weight in the sum (> 0; a term of weight 0 is not built into the stage).
  explicit FlipTerm(double weight) : weight_(weight) {}
  virtual ~FlipTerm() = default;
  double weight() const { return weight_; }

  // Adds the products the term reads to *needs; stage_basis: the eigenpairs of the basis the
  // stage declares (the largest any part reads), which products of the basis are computed from.
  virtual void AddNeeds(int /*stage_basis*/, ShapeNeeds* /*needs*/) const {}
  // Laplace-Beltrami eigenpairs the term reads (0: none).
  virtual int BasisSize() const { return 0; }
  // The smoothing of the curvature features the term reads (CurvatureFeaturesKey), which the
  // stage then passes to every part in the context, or none when it reads none.
  virtual std::optional<FeatureSmoothing> Features() const { return std::nullopt; }
  // Adds the term to *total (per candidate of CandidateRotations()) and its values to *detail
  // ("; <name> v0 v1 v2 v3", the status message of the stage).
  virtual void Score(const FlipTermContext& context, std::array<double, 4>* total,
                     std::ostringstream* detail) const = 0;

 private:
  double weight_;
};

class FlipDecision {
 public:
  virtual ~FlipDecision() = default;
  // Laplace-Beltrami eigenpairs the decision reads (0: none).
  virtual int BasisSize() const { return 0; }
  // Whether it reads the features of the context (a term must prepare them).
  virtual bool ReadsFeatures() const { return false; }
  // The chosen candidate given the terms' totals, or -1 for the lowest total (MakeFlipResult);
  // appends what it measured to *detail.
  virtual int Decide(const FlipTermContext& context, const std::array<double, 4>& total,
                     std::ostringstream* detail) const = 0;
};

// The curvature features of a shape (ExtrinsicFeatures, extrinsic.h), #V x 3, a product of its
// surface.
ProductKey<Eigen::MatrixXd> CurvatureFeaturesKey(const FeatureSmoothing& smoothing);
ProductNeed CurvatureFeaturesNeed(const FeatureSmoothing& smoothing);

// Those features diffused by heat for `time` (DiffuseFeatures, extrinsic.h), #V x 3, a product
// of its surface.
ProductKey<Eigen::MatrixXd> DiffusedFeaturesKey(const FeatureSmoothing& smoothing, double time);
ProductNeed DiffusedFeaturesNeed(const FeatureSmoothing& smoothing, double time);

}  // namespace symembed
