#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "core/errors.h"
#include "eval/evaluator.h"
#include "eval/metrics.h"
#include "harness/run_evaluation.h"
#include "python/src/arrays.h"
#include "python/src/bindings.h"
#include "python/src/match.h"

namespace symembed::python {
namespace {

using namespace pybind11::literals;

// Direct errors of `map` on `target` (the evaluator's view of the target), in ground-truth
// line order. Needs no Python.
std::vector<double> Errors(const LoadedPipeline& pipeline, const EvalShape& target,
                           const std::vector<int>& map, const std::vector<int>& gt_a,
                           const std::vector<int>& gt_b) {
  if (gt_a.size() != gt_b.size()) {
    throw InvalidInputError("gt_a and gt_b differ in length (" + std::to_string(gt_a.size()) +
                            " and " + std::to_string(gt_b.size()) + ")");
  }
  InputGroundTruth truth;
  truth.source_ids = gt_a;
  truth.target_ids = gt_b;
  const Evaluator evaluator(pipeline.pipeline.evaluation, *pipeline.pipeline.evaluation_geodesics);
  PairEvaluation evaluation = evaluator.Evaluate("source", "target", target, map, truth);
  if (!evaluation.ok) throw InvalidInputError(evaluation.message);
  return std::move(evaluation.errors_direct);
}

constexpr char kErrorsDoc[] = R"doc(
Geodesic errors of a map A -> B at ground-truth points, as `symembed run` and `symembed eval`
measure them: for each line i, the geodesic distance on B between map[gt_a[i]] and gt_b[i],
over sqrt(area of B), both measured on B after the preprocess stage.

geodesic_errors(VB, FB, map, gt_a, gt_b, config=None, *, set=None, variant="base")
geodesic_errors(shape_b, map, gt_a, gt_b)

map: 0-based B vertex id per A vertex (any integer array, e.g. from another method); gt_a, gt_b:
the ground-truth lines (0-based vertex ids of A and B). The config's preprocess stage and
evaluation options (evaluation.geodesics, evaluation.points) apply; a Shape brings its own.
Returns a float64 array, one error per line (per selected line with evaluation.points = N).
Raises symembed.InvalidInputError for ids out of range, ConfigError for a bad config.)doc";

}  // namespace

void BindEvaluation(py::module_& m) {
  m.def(
      "geodesic_errors",
      [](const std::shared_ptr<Shape>& target, const py::array& map, const py::array& gt_a,
         const py::array& gt_b) {
        const std::vector<int> ids = IdsFromArray(map, "map");
        const std::vector<int> a = IdsFromArray(gt_a, "gt_a"), b = IdsFromArray(gt_b, "gt_b");
        std::vector<double> errors;
        {
          py::gil_scoped_release release;
          errors = Errors(*target->pipeline, EvalShapeOf(*target->outcome), ids, a, b);
        }
        return ToNumpy(std::move(errors));
      },
      "shape_b"_a, "map"_a, "gt_a"_a, "gt_b"_a);
  m.def(
      "geodesic_errors",
      [](const py::array& VB, const py::array& FB, const py::array& map, const py::array& gt_a,
         const py::array& gt_b, const py::object& config, const py::object& set,
         const std::string& variant) {
        const auto pipeline = LoadPipeline(config, set, variant);
        Surface input = SurfaceFromArrays(VB, FB, "VB", "FB");
        const std::vector<int> ids = IdsFromArray(map, "map");
        const std::vector<int> a = IdsFromArray(gt_a, "gt_a"), b = IdsFromArray(gt_b, "gt_b");
        std::vector<double> errors;
        {
          py::gil_scoped_release release;
          const PreprocessResult pre = pipeline->pipeline.preprocess->Run(input);
          errors = Errors(*pipeline, MakeEvalShape(pre, input), ids, a, b);
        }
        return ToNumpy(std::move(errors));
      },
      "VB"_a, "FB"_a, "map"_a, "gt_a"_a, "gt_b"_a, "config"_a = py::none(), py::kw_only(),
      "set"_a = py::none(), "variant"_a = "base", kErrorsDoc);

  m.def(
      "error_curve",
      [](const std::vector<double>& errors, double max_error, double step) {
        if (!(max_error > 0.0) || !(step > 0.0) || step > max_error) {
          throw InvalidInputError("error_curve: need 0 < step <= max_error");
        }
        std::vector<double> thresholds = CurveThresholds(max_error, step);
        std::vector<double> curve = CumulativeCurve(errors, thresholds);
        const double area = CurveArea(thresholds, curve);
        return py::make_tuple(ToNumpy(std::move(thresholds)), ToNumpy(std::move(curve)), area);
      },
      "errors"_a, "max_error"_a = 0.25, "step"_a = 0.0025, R"doc(
The cumulative error curve of errors, as curve.csv gives it: (thresholds, fraction, auc) with
thresholds 0, step, ..., max_error, fraction[k] the fraction of errors <= thresholds[k], and auc
the normalised area under the curve (1 = every error 0).)doc");
}

}  // namespace symembed::python
