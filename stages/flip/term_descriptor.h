// The descriptor term of the flip stage `extrinsic`, pipeline.flip.terms.descriptor: adds
// weight * (1 - a_k) / 2 for candidate k's agreement a_k with the functional map of wave kernel
// signatures (descriptor_map.h).
//   descriptor: {weight: 1, k: 30, eigenpairs: 60, energies: 100, sigma: 7, mu: 0.01,
//                samples: 300, axes: 1}
// Per shape it needs the signature products (WksProducts) of the first `eigenpairs` eigenpairs
// of the stage's basis. Status message: "; descriptor a0 a1 a2 a3".
#pragma once

#include <memory>

#include "registry/options.h"
#include "stages/flip/descriptor_map.h"
#include "stages/flip/flip_term.h"

namespace symembed {

class DescriptorTerm : public FlipTerm {
 public:
  // Throws ConfigError for invalid options.
  DescriptorTerm(double weight, const DescriptorMapOptions& options);
  void AddNeeds(int stage_basis, ShapeNeeds* needs) const override;
  int BasisSize() const override { return options_.eigenpairs; }
  void Score(const FlipTermContext& context, std::array<double, 4>* total,
             std::ostringstream* detail) const override;
  const DescriptorMapOptions& options() const { return options_; }
  // The key of its products of a shape.
  ProductKey<WksProducts> ProductsKey() const;

 private:
  DescriptorMapOptions options_;
};

// The term from its options besides `weight` (read by the stage). Throws ConfigError.
std::unique_ptr<FlipTerm> ReadDescriptorTerm(OptionReader& options, double weight);

}  // namespace symembed
