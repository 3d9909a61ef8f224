#include "python/src/match.h"

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <array>
#include <chrono>

#include "core/clock.h"
#include "core/errors.h"
#include "core/parallel.h"
#include "harness/cache.h"
#include "python/src/arrays.h"
#include "python/src/bindings.h"

namespace symembed::python {
namespace {

using namespace pybind11::literals;

py::dict StatusDict(const StageStatus& status) {
  return py::dict("converged"_a = status.converged, "iterations"_a = status.iterations,
                  "residual"_a = status.residual, "message"_a = status.message);
}

// The pair's result beside its map.
struct MatchResult {
  PairOutcome outcome;
  std::shared_ptr<Shape> source, target;
  py::object map;          // the map array returned with the result
  py::object initial_map;  // None when the refine stage kept the map
};

// A read-only numpy view of a column-major Eigen matrix owned by `owner`.
template <typename Matrix>
py::array View(const Matrix& M, py::handle owner) {
  using T = typename Matrix::Scalar;
  py::array view(
      py::dtype::of<T>(), {M.rows(), M.cols()},
      {static_cast<py::ssize_t>(sizeof(T)), static_cast<py::ssize_t>(sizeof(T) * M.rows())},
      M.data(), owner);
  view.attr("setflags")("write"_a = false);
  return view;
}

// Per-shape stage times in pipeline order, each {stage, seconds, cached}; the embedding's and
// the symmetry's with their status.
py::list ShapeStages(const ShapeOutcome& outcome) {
  py::list stages;
  for (const StageTime& t : outcome.times) {
    py::dict entry("stage"_a = t.stage, "seconds"_a = t.seconds, "cached"_a = t.cached);
    if (t.stage == "embedding") entry["status"] = StatusDict(outcome.data->embedding.status);
    if (t.stage == "symmetry") entry["status"] = StatusDict(outcome.data->symmetry.status);
    stages.append(entry);
  }
  return stages;
}

// The per-pair stages, {stage: {seconds, cached, status...}}, in pipeline order.
py::dict PairStages(const PairOutcome& outcome) {
  py::dict stages;
  const std::map<std::string, const StageStatus*> status = {{"flip", &outcome.flip.status},
                                                            {"matching", &outcome.matching_status},
                                                            {"refine", &outcome.refine_status}};
  for (const StageTime& t : outcome.times) {
    py::dict entry("seconds"_a = t.seconds, "cached"_a = t.cached);
    const auto it = status.find(t.stage);
    if (it != status.end()) entry.attr("update")(StatusDict(*it->second));
    stages[py::str(t.stage)] = entry;
  }
  return stages;
}

std::shared_ptr<Shape> ShapeFromArrays(const py::array& V, const py::array& F,
                                       std::shared_ptr<const LoadedPipeline> pipeline,
                                       const std::string& cache_dir, const std::string& name,
                                       const std::string& v_name, const std::string& f_name) {
  const auto start = std::chrono::steady_clock::now();
  Surface input = SurfaceFromArrays(V, F, v_name, f_name);
  const double load_seconds = SecondsSince(start);
  py::gil_scoped_release release;
  return ComputeShape(std::move(input), load_seconds, std::move(pipeline), cache_dir, name);
}

py::tuple MatchResultTuple(PairOutcome outcome, std::shared_ptr<Shape> source,
                           std::shared_ptr<Shape> target) {
  auto result = std::make_shared<MatchResult>();
  result->source = std::move(source);
  result->target = std::move(target);
  result->map = IdsToNumpy(std::move(outcome.map));
  result->initial_map = outcome.initial_map.empty()
                            ? py::none()
                            : py::object(IdsToNumpy(std::move(outcome.initial_map)));
  outcome.map.clear();
  outcome.initial_map.clear();
  result->outcome = std::move(outcome);
  py::object map = result->map;
  return py::make_tuple(map, py::cast(result));
}

std::string CacheDir(const py::object& cache) { return cache.is_none() ? "" : PathOf(cache); }

}  // namespace

std::shared_ptr<Shape> ComputeShape(Surface input, double load_seconds,
                                    std::shared_ptr<const LoadedPipeline> pipeline,
                                    const std::string& cache_dir, const std::string& name) {
  const uint64_t mesh_key = SurfaceMeshKey(input);
  const DiskCache cache(cache_dir);
  StageCounters counters;
  const ShapeContext context{&cache, &counters};
  ShapeOutcome content =
      ComputeMeshOutcome(std::move(input), load_seconds, mesh_key, pipeline->pipeline, context);
  auto shape = std::make_shared<Shape>();
  shape->outcome = std::make_shared<const ShapeOutcome>(
      OutcomeOfShape(std::move(content), DatasetShape{name, "", ""}, ShapeGroundTruth{}, false));
  shape->pipeline = std::move(pipeline);
  shape->cache_dir = cache_dir;
  shape->computed = counters.executed();
  shape->from_cache = counters.hits();
  return shape;
}

PairOutcome MatchShapes(const Shape& source, const Shape& target) {
  if (source.pipeline->stages != target.pipeline->stages) {
    throw ConfigError("match: the two shapes were computed with different stage options (" +
                      source.outcome->name + ":\n" + source.pipeline->stages +
                      target.outcome->name + ":\n" + target.pipeline->stages +
                      "); make both with the same config (a cache makes that cheap)");
  }
  StageCounters counters;
  return ComputePair(*source.outcome, *target.outcome, source.pipeline->pipeline, nullptr,
                     MeanErrorFunction(), &counters);
}

void BindMatch(py::module_& m) {
  py::class_<Shape, std::shared_ptr<Shape>>(m, "Shape", R"doc(
A mesh with its per-shape stage outputs, computed once and reused by every match.

Shape(V, F, config=None, *, set=None, variant="base", cache=None, name="shape")

V: (n, 3) vertex positions (any real dtype, any memory order); F: (m, 3) 0-based vertex ids
(any integer dtype). Both are copied once into the shape. config, set, variant: as for match.
cache: a folder for the on-disk cache of per-shape stages (as `symembed run --cache`), or None.
Raises symembed.ConfigError, InvalidInputError (bad arrays, a mesh the stages reject),
SolverError.)doc")
      .def(py::init([](const py::array& V, const py::array& F, const py::object& config,
                       const py::object& set, const std::string& variant, const py::object& cache,
                       const std::string& name) {
             return ShapeFromArrays(V, F, LoadPipeline(config, set, variant), CacheDir(cache), name,
                                    "V", "F");
           }),
           "V"_a, "F"_a, "config"_a = py::none(), py::kw_only(), "set"_a = py::none(),
           "variant"_a = "base", "cache"_a = py::none(), "name"_a = "shape")
      .def_property_readonly("name", [](const Shape& s) { return s.outcome->name; })
      .def_property_readonly(
          "vertices",
          [](py::object self) { return View(self.cast<const Shape&>().outcome->input.V, self); },
          "the input positions as held (a read-only view, (n, 3) float64)")
      .def_property_readonly(
          "faces",
          [](py::object self) { return View(self.cast<const Shape&>().outcome->input.F, self); },
          "the input faces as held (a read-only view, (m, 3) int32)")
      .def_property_readonly(
          "config", [](const Shape& s) { return s.pipeline->resolved; },
          "the resolved config (YAML) the shape was computed with")
      .def_property_readonly(
          "stages", [](const Shape& s) { return ShapeStages(*s.outcome); },
          "per-shape stages in order: [{stage, seconds, cached[, status]}]")
      .def_property_readonly(
          "computed", [](const Shape& s) { return s.computed; },
          "{stage: computations} (not found in the cache)")
      .def_property_readonly(
          "from_cache", [](const Shape& s) { return s.from_cache; },
          "{stage: loads} from the on-disk cache")
      .def_property_readonly(
          "report",
          [](const Shape& s) {
            py::dict report;
            for (const auto& [k, v] : s.outcome->report) report[py::str(k)] = v;
            return report;
          },
          "the preprocess report and the stages' measures (shapes.csv's columns)")
      .def_property_readonly("warnings", [](const Shape& s) { return s.outcome->warnings; })
      .def_property_readonly(
          "surface",
          [](const Shape& s) {
            return py::make_tuple(Eigen::MatrixX3d(s.outcome->data->surface.V),
                                  Eigen::MatrixX3i(s.outcome->data->surface.F));
          },
          "the preprocessed surface (V, F): consistently oriented, cleaned, unit area")
      .def_property_readonly(
          "input_ids", [](const Shape& s) { return IdsToNumpy(s.outcome->data->input_ids); },
          "input vertex id of each preprocessed vertex (int32 array)")
      .def_property_readonly(
          "samples", [](const Shape& s) { return IdsToNumpy(s.outcome->data->samples); },
          "sample vertex ids, preprocessed ids (int32 array)")
      .def_property_readonly(
          "embedding", [](const Shape& s) { return Eigen::MatrixX3d(s.outcome->data->Y); },
          "the canonical symmetric embedding, one row per preprocessed vertex")
      .def("__repr__", [](const Shape& s) {
        return "<symembed.Shape '" + s.outcome->name +
               "': " + std::to_string(s.outcome->input.NumVertices()) + " vertices, " +
               std::to_string(s.outcome->input.NumFaces()) + " faces>";
      });

  py::class_<MatchResult, std::shared_ptr<MatchResult>>(m, "MatchResult",
                                                        "What match computed besides the map.")
      .def_readonly("map", &MatchResult::map, "0-based target vertex id per source vertex")
      .def_readonly("initial_map", &MatchResult::initial_map,
                    "the map before the refine stage, or None when it kept the map")
      .def_readonly("source", &MatchResult::source)
      .def_readonly("target", &MatchResult::target)
      .def_property_readonly(
          "chosen", [](const MatchResult& r) { return r.outcome.flip.chosen; },
          "index of the chosen rotation in candidates")
      .def_property_readonly(
          "rotation",
          [](const MatchResult& r) {
            return Eigen::Matrix3d(CandidateRotations()[r.outcome.flip.chosen]);
          },
          "the chosen rotation R of the target's canonical embedding (y' = R y), 3 x 3")
      .def_property_readonly(
          "candidates",
          [](const MatchResult&) {
            py::list rotations;
            for (const Eigen::Matrix3d& R : CandidateRotations())
              rotations.append(Eigen::Matrix3d(R));
            return py::module_::import("numpy").attr("array")(rotations);
          },
          "the four candidate rotations {I, Rx(pi), Ry(pi), Rz(pi)}, 4 x 3 x 3")
      .def_property_readonly(
          "scores",
          [](const MatchResult& r) {
            return ToNumpy({r.outcome.flip.scores.begin(), r.outcome.flip.scores.end()});
          },
          "the flip scorer's score of each candidate (lower is better)")
      .def_property_readonly(
          "stages", [](const MatchResult& r) { return PairStages(r.outcome); },
          "per-pair stages: {stage: {seconds, cached, converged, iterations, "
          "residual, message}}")
      .def("__repr__", [](const MatchResult& r) {
        return "<symembed.MatchResult " + r.source->outcome->name + " -> " +
               r.target->outcome->name + ": candidate " + std::to_string(r.outcome.flip.chosen) +
               ">";
      });

  m.def(
      "match",
      [](const std::shared_ptr<Shape>& a, const std::shared_ptr<Shape>& b) {
        PairOutcome outcome;
        {
          py::gil_scoped_release release;
          outcome = MatchShapes(*a, *b);
        }
        return MatchResultTuple(std::move(outcome), a, b);
      },
      "shape_a"_a, "shape_b"_a);
  m.def(
      "match",
      [](const py::array& VA, const py::array& FA, const py::array& VB, const py::array& FB,
         const py::object& config, const py::object& set, const std::string& variant,
         const py::object& cache) {
        const auto pipeline = LoadPipeline(config, set, variant);
        const std::string cache_dir = CacheDir(cache);
        std::array<Surface, 2> inputs;
        std::array<double, 2> seconds{};
        const auto start = std::chrono::steady_clock::now();
        inputs[0] = SurfaceFromArrays(VA, FA, "VA", "FA");
        seconds[0] = SecondsSince(start);
        inputs[1] = SurfaceFromArrays(VB, FB, "VB", "FB");
        seconds[1] = SecondsSince(start) - seconds[0];
        std::array<std::shared_ptr<Shape>, 2> shapes;
        PairOutcome outcome;
        {
          py::gil_scoped_release release;
          // As the runner computes shapes: in parallel, one per thread.
          const char* names[] = {"source", "target"};
          ParallelFor(
              2,
              [&](int i) {
                shapes[i] =
                    ComputeShape(std::move(inputs[i]), seconds[i], pipeline, cache_dir, names[i]);
              },
              0, 1);
          outcome = MatchShapes(*shapes[0], *shapes[1]);
        }
        return MatchResultTuple(std::move(outcome), shapes[0], shapes[1]);
      },
      "VA"_a, "FA"_a, "VB"_a, "FB"_a, "config"_a = py::none(), py::kw_only(), "set"_a = py::none(),
      "variant"_a = "base", "cache"_a = py::none(), R"doc(
Matches shape A onto shape B: returns (map, result).

match(VA, FA, VB, FB, config=None, *, set=None, variant="base", cache=None)
match(shape_a, shape_b)

map: for each vertex of A, the 0-based id of its image vertex of B (int32 array). result: a
MatchResult (chosen rotation, candidates' scores, per-pair stages' status and seconds, and the
two Shapes, reusable in further matches). VA, VB: (n, 3) positions; FA, FB: (m, 3) 0-based
vertex ids; each copied once. config: None (every stage at its default), a dict of options by
their dotted names as in a config file ({"pipeline.flip.type": "extrinsic"}), or the path of a
config file, whose `variant` is used with `set` (a dict) applied as `symembed run --set` does.
cache: a folder for the on-disk cache of per-shape stages, or None. The map equals the one
`symembed run` writes for the same meshes and config. Raises symembed.ConfigError (the messages
of `symembed run`), InvalidInputError, SolverError, IoError.)doc");
}

}  // namespace symembed::python
