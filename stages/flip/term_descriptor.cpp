#include "stages/flip/term_descriptor.h"

#include "core/errors.h"

namespace symembed {
namespace {

// The products in ShapeData::aux.
constexpr const char* kWksPKey = "extrinsic_wks_P";
constexpr const char* kWksQKey = "extrinsic_wks_Q";

WksProducts WksProductsOf(const ShapeData& shape) {
  return {AuxOf(shape, kWksPKey), AuxOf(shape, kWksQKey)};
}

}  // namespace

DescriptorTerm::DescriptorTerm(double weight, const DescriptorMapOptions& options)
    : FlipTerm(weight), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw ConfigError("flip descriptor: " + error);
}

void DescriptorTerm::PrepareShape(ShapeData& shape) const {
  // Over the shape's vertices, once per shape.
  const WksProducts products = ComputeWksProducts(GetLaplaceBasis(shape.aux, options_.eigenpairs),
                                                  options_.k, options_.eigenpairs);
  shape.aux[kWksPKey] = products.P;
  shape.aux[kWksQKey] = products.Q;
}

void DescriptorTerm::Score(const FlipTermContext& context, std::array<double, 4>* total,
                           std::ostringstream* detail) const {
  const PairInput& pair = context.pair;
  const DescriptorAgreement d = DescriptorMapAgreement(
      pair.source.Y, pair.target.Y, context.source_basis, context.target_basis,
      WksProductsOf(pair.source), WksProductsOf(pair.target), pair.source.samples, options_);
  for (int k = 0; k < 4; ++k) (*total)[k] += weight() * (1.0 - d.agreement[k]) / 2.0;
  *detail << "; descriptor";
  for (double v : d.agreement) *detail << " " << v;
}

std::unique_ptr<FlipTerm> ReadDescriptorTerm(OptionReader& o, double weight) {
  DescriptorMapOptions d;
  d.k = o.GetInt("k", d.k, 2, 1000);
  d.eigenpairs = o.GetInt("eigenpairs", d.eigenpairs, 2, 1000);
  d.energies = o.GetInt("energies", d.energies, 1, 10000);
  d.sigma = o.GetDouble("sigma", d.sigma, 0.0);
  d.mu = o.GetDouble("mu", d.mu, 0.0);
  d.samples = o.GetInt("samples", d.samples, 1, 100000);
  d.axes = o.GetInt("axes", d.axes, 1, 2);
  std::string error;
  if (!d.IsValid(&error)) o.Fail("", error);
  return std::make_unique<DescriptorTerm>(weight, d);
}

}  // namespace symembed
