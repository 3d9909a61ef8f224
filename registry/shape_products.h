// Per-shape products: values a per-pair stage computes once per shape and reads in every pair
// (curvature features, distances from samples, descriptor products), each named by a typed key.
//
// A ProductKey<T> names one value of type T: `name` says what it is (one function computes it)
// and `options` the parameters it was computed with, as text. Two stages that declare the same
// key share one value. Stages declare the products they need in PairStage::Needs
// (registry/product_needs.h); the shape pipeline computes them into ShapeData::products, and the
// stages read them back with ProductOf, which checks the type.
#pragma once

#include <any>
#include <map>
#include <memory>
#include <string>
#include <utility>

namespace symembed {

template <typename T>
struct ProductKey {
  std::string name;     // "curvature_features"
  std::string options;  // "smoothing_rings=2"
  // The product's identity among a shape's products and in its cache key.
  std::string Id() const { return options.empty() ? name : name + "{" + options + "}"; }
};

class ShapeProducts {
 public:
  bool Has(const std::string& id) const { return values_.count(id) > 0; }
  size_t size() const { return values_.size(); }
  // The value of `key`, or null when there is none or it has another type.
  template <typename T>
  const T* Find(const ProductKey<T>& key) const {
    const auto it = values_.find(key.Id());
    return it == values_.end() ? nullptr : std::any_cast<T>(it->second.get());
  }
  // Shares a value (products are immutable once computed).
  void PutAny(const std::string& id, std::shared_ptr<const std::any> value) {
    values_[id] = std::move(value);
  }
  void Erase(const std::string& id) { values_.erase(id); }
  void Clear() { values_.clear(); }

 private:
  std::map<std::string, std::shared_ptr<const std::any>> values_;
};

// Throws InvalidInputError naming the shape and the product (product_needs.cpp).
[[noreturn]] void ThrowMissingProduct(const std::string& shape, const std::string& id);

}  // namespace symembed
