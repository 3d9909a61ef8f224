// Helpers of the dataset loader tests: tiny meshes, error expectations, loaders from YAML.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "registry/dataset.h"
#include "registry/registry.h"

namespace symembed {
namespace testing {

// A tetrahedron (4 faces) with `extra` isolated vertices appended (vertex count 4 + extra), as
// OFF text.
inline std::string Tetrahedron(int extra = 0) {
  std::string off = "OFF\n" + std::to_string(4 + extra) + " 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
  for (int i = 0; i < extra; ++i) off += "2 2 2\n";
  return off + "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
}

// Expects `fn` to throw E whose message contains every fragment.
template <typename E>
void ExpectError(const std::function<void()>& fn, const std::vector<std::string>& fragments) {
  try {
    fn();
    ADD_FAILURE() << "no exception; expected one containing '" << fragments[0] << "'";
  } catch (const E& e) {
    const std::string msg = e.what();
    for (const auto& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << msg;
  }
}

// A built-in dataset loader from its YAML options (file "test.yaml", path "dataset").
inline std::unique_ptr<Dataset> CreateDataset(const std::string& yaml) {
  Registry registry;
  RegisterBuiltinStages(registry);
  return registry.CreateAs<Dataset>("dataset", YAML::Load(yaml), "test.yaml", "dataset");
}

}  // namespace testing
}  // namespace symembed
