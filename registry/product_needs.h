// What a per-pair stage needs of each shape beyond the per-shape stages' outputs: the size of
// the Laplace-Beltrami basis it reads, and its products (registry/shape_products.h).
//
// Each product is computed from one declared input: the surface (after preprocessing), the
// samples (and the surface), the canonical embedding (and everything before it), or the basis
// of a given size. The shape pipeline (shape_pipeline.h) caches a product on disk under
// H(key of its input, product id), so the key follows from what the product is computed from
// and the options it names; nothing is versioned by hand. A product of a new kind or with new
// options has a new id, hence a new key.
#pragma once

#include <any>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/spectral.h"
#include "registry/serialize.h"
#include "registry/types.h"

namespace symembed {

enum class ProductInput { kSurface, kSamples, kEmbedding, kBasis };

struct ProductNeed {
  std::string id;    // ProductKey::Id()
  std::string name;  // ProductKey::name: the cache folder and the timing column
  ProductInput input = ProductInput::kSurface;
  int basis_size = 0;  // eigenpairs of the basis it is computed from (input kBasis)
  // basis: the shape's basis of basis_size eigenpairs (input kBasis), else empty.
  std::function<std::any(const ShapeData& shape, const LaplaceBasis& basis)> compute;
  std::function<void(ArchiveWriter& out, const std::any& value)> write;
  std::function<std::any(ArchiveReader& in)> read;
};

// The need of product `key` computed by compute(const ShapeData&, const LaplaceBasis&) -> T,
// stored with the Write/Read overloads of T (registry/serialize.h).
template <typename T, typename Compute>
ProductNeed NeedProduct(const ProductKey<T>& key, ProductInput input, int basis_size,
                        Compute compute) {
  ProductNeed need;
  need.id = key.Id();
  need.name = key.name;
  need.input = input;
  need.basis_size = input == ProductInput::kBasis ? basis_size : 0;
  need.compute = [compute](const ShapeData& shape, const LaplaceBasis& basis) -> std::any {
    return T(compute(shape, basis));
  };
  need.write = [](ArchiveWriter& out, const std::any& value) {
    Write(out, *std::any_cast<T>(&value));
  };
  need.read = [](ArchiveReader& in) -> std::any {
    T value;
    Read(in, &value);
    return value;
  };
  return need;
}

struct ShapeNeeds {
  int basis = 0;  // eigenpairs of the Laplace-Beltrami basis the stage reads (0: none)
  std::vector<ProductNeed> products;

  // Adds other's needs: the larger basis, and the products not already listed (by id).
  void Add(ShapeNeeds other);
};

// Computes what `needs` declares into *shape, without a cache (tests, benchmarks, and a stage
// run outside the runner): the basis when shape->basis holds fewer eigenpairs, then each product
// not already there, a product from a basis of another size than shape->basis computing that
// basis for itself. Throws what the products' functions throw.
void ComputeNeeds(const ShapeNeeds& needs, ShapeData* shape);

// The first k eigenpairs of shape.basis into *out (LeadingEigenpairs). Throws InvalidInputError
// naming the shape when it holds fewer.
void ShapeBasis(const ShapeData& shape, int k, LaplaceBasis* out);
// shape.basis itself, for a reader of its first k eigenpairs that takes no copy (it may hold
// more). Throws as ShapeBasis when it holds fewer.
const LaplaceBasis& ShapeBasisWithAtLeast(const ShapeData& shape, int k);

}  // namespace symembed
