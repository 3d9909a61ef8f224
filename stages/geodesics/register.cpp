// The geodesics stages: each prepares one of the solvers of this folder per shape.
#include "stages/register.h"

#include <memory>

#include "stages/geodesics/dijkstra.h"
#include "stages/geodesics/fast_marching.h"
#include "stages/geodesics/heat.h"

namespace symembed {

namespace {

// A stage that builds a Solver (a GeodesicSolver constructed from a surface and Options) per
// shape.
template <typename Solver, typename Options>
class SolverStage : public GeodesicsStage {
 public:
  explicit SolverStage(const Options& options) : options_(options) {}
  std::unique_ptr<GeodesicSolver> Prepare(const Surface& surface) const override {
    return std::make_unique<Solver>(surface, options_);
  }

 private:
  Options options_;
};

// `threads` and `precision`, shared by every solver.
GeodesicsCommonOptions ReadCommonOptions(OptionReader& reader) {
  GeodesicsCommonOptions o;
  o.threads = reader.GetInt("threads", o.threads, GeodesicsCommonOptions::kThreads);
  o.precision = reader.GetEnum<GeodesicPrecision>(
      "precision", o.precision,
      {{"double", GeodesicPrecision::kDouble}, {"float", GeodesicPrecision::kFloat}});
  return o;
}

}  // namespace

void RegisterGeodesicsStages(Registry& registry) {
  registry.Add(
      "geodesics", "dijkstra",
      "shortest paths on the mesh edge graph (fast, overestimates by up to ~8%)",
      [](OptionReader& reader) -> std::unique_ptr<Stage> {
        DijkstraGeodesicsOptions options;
        options.common = ReadCommonOptions(reader);
        return std::make_unique<SolverStage<DijkstraGeodesicSolver, DijkstraGeodesicsOptions>>(
            options);
      });
  registry.Add(
      "geodesics", "fast_marching",
      "fast marching on triangles, obtuse angles split by unfolding (Kimmel & Sethian "
      "1998); first-order accurate",
      [](OptionReader& reader) -> std::unique_ptr<Stage> {
        FastMarchingOptions options;
        options.common = ReadCommonOptions(reader);
        options.max_unfold_steps = reader.GetInt("max_unfold_steps", options.max_unfold_steps,
                                                 FastMarchingOptions::kMaxUnfoldSteps);
        return std::make_unique<SolverStage<FastMarchingGeodesicSolver, FastMarchingOptions>>(
            options);
      });
  registry.Add(
      "geodesics", "heat",
      "heat method (Crane et al. 2013), one sparse factorisation per shape, "
      "t = time_factor * h^2",
      [](OptionReader& reader) -> std::unique_ptr<Stage> {
        HeatOptions options;
        options.common = ReadCommonOptions(reader);
        options.time_factor =
            reader.GetDouble("time_factor", options.time_factor, HeatOptions::kTimeFactor);
        options.boundary = reader.GetEnum<HeatBoundary>("boundary", options.boundary,
                                                        {{"average", HeatBoundary::kAverage},
                                                         {"neumann", HeatBoundary::kNeumann},
                                                         {"dirichlet", HeatBoundary::kDirichlet}});
        options.intrinsic_delaunay =
            reader.GetBool("intrinsic_delaunay", options.intrinsic_delaunay);
        return std::make_unique<SolverStage<HeatGeodesicSolver, HeatOptions>>(options);
      });
}

}  // namespace symembed
