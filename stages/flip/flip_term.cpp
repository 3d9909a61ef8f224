#include "stages/flip/flip_term.h"

#include "core/errors.h"

namespace symembed {

const Eigen::MatrixXd& AuxOf(const ShapeData& shape, const std::string& key) {
  auto it = shape.aux.find(key);
  if (it == shape.aux.end()) {
    throw InvalidInputError("flip extrinsic: shape '" + shape.name + "' has no '" + key +
                            "' (PrepareShape was not called)");
  }
  return it->second;
}

}  // namespace symembed
