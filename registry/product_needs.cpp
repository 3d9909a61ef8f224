#include "registry/product_needs.h"

#include <algorithm>

#include "core/errors.h"

namespace symembed {

void ThrowMissingProduct(const std::string& shape, const std::string& id) {
  throw InvalidInputError("shape '" + shape + "' has no product '" + id +
                          "' (the stage that reads it did not declare it in Needs)");
}

void ShapeNeeds::Add(ShapeNeeds other) {
  basis = std::max(basis, other.basis);
  for (ProductNeed& need : other.products) {
    const bool listed = std::any_of(products.begin(), products.end(),
                                    [&](const ProductNeed& p) { return p.id == need.id; });
    if (!listed) products.push_back(std::move(need));
  }
}

void ComputeNeeds(const ShapeNeeds& needs, ShapeData* shape) {
  SYMEMBED_CHECK(shape != nullptr, "shape is null");
  auto basis_of = [&](int k) {
    LaplaceBasisOptions options;
    options.k = k;
    return ComputeLaplaceBasis(shape->surface, options);
  };
  if (needs.basis > shape->basis.NumEigenpairs()) shape->basis = basis_of(needs.basis);
  for (const ProductNeed& need : needs.products) {
    if (shape->products.Has(need.id)) continue;
    LaplaceBasis own;
    const bool shared = need.basis_size == 0 || need.basis_size == shape->basis.NumEigenpairs();
    if (!shared) own = basis_of(need.basis_size);
    const std::any value = need.compute(*shape, shared ? shape->basis : own);
    shape->products.PutAny(need.id, std::make_shared<const std::any>(value));
  }
}

void ShapeBasis(const ShapeData& shape, int k, LaplaceBasis* out) {
  try {
    LeadingEigenpairs(shape.basis, k, out);
  } catch (const InvalidInputError& e) {
    throw InvalidInputError("shape '" + shape.name + "': " + e.what() +
                            " (the stage that reads it did not declare it in Needs)");
  }
}

const LaplaceBasis& ShapeBasisWithAtLeast(const ShapeData& shape, int k) {
  if (shape.basis.NumEigenpairs() < k) {
    LaplaceBasis unused;
    ShapeBasis(shape, k, &unused);  // throws, naming the shape
  }
  return shape.basis;
}

}  // namespace symembed
