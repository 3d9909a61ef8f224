// symembed.Shape and symembed.match: the per-shape stages of one mesh given as arrays, held for
// every pair it is matched in, and the per-pair stages of two shapes, as `symembed run` computes
// them (harness/shape_pipeline.h ComputeMeshOutcome, harness/pair_pipeline.h ComputePair).
#pragma once

#include <pybind11/pybind11.h>

#include <map>
#include <memory>
#include <string>

#include "harness/pair_pipeline.h"
#include "harness/shape_pipeline.h"
#include "python/src/pipeline.h"

namespace symembed::python {

namespace py = pybind11;

// One mesh with its per-shape stage outputs (and what the pipeline's per-pair stages need of
// it), computed once with the pipeline it holds. Immutable, so pairs may share it across threads.
struct Shape {
  std::shared_ptr<const LoadedPipeline> pipeline;
  std::shared_ptr<const ShapeOutcome> outcome;
  std::string cache_dir;                  // "" without a cache
  std::map<std::string, int> computed;    // stage -> computations (cache misses)
  std::map<std::string, int> from_cache;  // stage -> cache hits
};

// Runs (or loads from cache_dir, when not empty) the per-shape stages of `pipeline` on `input`,
// named `name` in messages. load_seconds: the time taken to copy the arrays (the first time
// entry, "load"). Throws what the stages throw (InvalidInputError, SolverError, ...). Needs no
// Python: call it with the GIL released.
std::shared_ptr<Shape> ComputeShape(Surface input, double load_seconds,
                                    std::shared_ptr<const LoadedPipeline> pipeline,
                                    const std::string& cache_dir, const std::string& name);

// The pair source -> target with the shapes' pipeline. Throws ConfigError when the two shapes
// were computed with different stage options, and what a stage throws. Needs no Python.
PairOutcome MatchShapes(const Shape& source, const Shape& target);

}  // namespace symembed::python
