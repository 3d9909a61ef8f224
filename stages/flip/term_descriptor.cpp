#include "stages/flip/term_descriptor.h"

#include "core/errors.h"
#include "stages/products.h"

namespace symembed {

DescriptorTerm::DescriptorTerm(double weight, const DescriptorMapOptions& options)
    : FlipTerm(weight), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw ConfigError("flip descriptor: " + error);
}

ProductKey<WksProducts> DescriptorTerm::ProductsKey() const {
  return {"flip_descriptor_products",
          "k=" + std::to_string(options_.k) + " eigenpairs=" + std::to_string(options_.eigenpairs)};
}

void DescriptorTerm::AddNeeds(int stage_basis, ShapeNeeds* needs) const {
  // Over the shape's vertices, once per shape.
  const int k = options_.k, eigenpairs = options_.eigenpairs;
  needs->products.push_back(NeedProduct(
      ProductsKey(), ProductInput::kBasis, stage_basis,
      [k, eigenpairs](const ShapeData&, const LaplaceBasis& basis) {
        return ComputeWksProducts(LeadingEigenpairs(basis, eigenpairs), k, eigenpairs);
      }));
}

void DescriptorTerm::Score(const FlipTermContext& context, std::array<double, 4>* total,
                           std::ostringstream* detail) const {
  const PairInput& pair = context.pair;
  const DescriptorAgreement d = DescriptorMapAgreement(
      pair.source.Y, pair.target.Y, context.source_basis, context.target_basis,
      ProductOf(pair.source, ProductsKey()), ProductOf(pair.target, ProductsKey()),
      pair.source.samples, options_);
  for (int k = 0; k < 4; ++k) (*total)[k] += weight() * (1.0 - d.agreement[k]) / 2.0;
  *detail << "; descriptor";
  for (double v : d.agreement) *detail << " " << v;
}

std::unique_ptr<FlipTerm> ReadDescriptorTerm(OptionReader& o, double weight) {
  DescriptorMapOptions d;
  ReadValidFields(o, &d);
  return std::make_unique<DescriptorTerm>(weight, d);
}

}  // namespace symembed
