#include "harness/pair_pipeline.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <limits>
#include <optional>
#include <type_traits>
#include <sstream>

#include "core/clock.h"
#include "core/laplacian.h"
#include "core/mesh_graph.h"
#include "registry/hash.h"

namespace symembed {
namespace {

void CheckMap(const MatchResult& result, int source_vertices, int target_vertices,
              const char* stage) {
  if (static_cast<int>(result.map.size()) != source_vertices) {
    throw SolverError(std::string(stage) + " returned a map of " +
                      std::to_string(result.map.size()) + " entries for " +
                      std::to_string(source_vertices) + " source vertices");
  }
  for (int t : result.map) {
    if (t < 0 || t >= target_vertices) {
      throw SolverError(std::string(stage) + " returned target vertex " + std::to_string(t) +
                        " outside [0, " + std::to_string(target_vertices) + ")");
    }
  }
}

}  // namespace

std::vector<int> MapFromGroundTruth(const Surface& source, int target_vertices,
                                    const PreprocessedGroundTruth& ground_truth) {
  const int n = source.NumVertices();
  if (ground_truth.source_ids.empty() ||
      ground_truth.source_ids.size() != ground_truth.target_ids.size()) {
    throw InvalidInputError("the pair has no ground truth to start from (" +
                            std::to_string(ground_truth.source_ids.size()) + " source and " +
                            std::to_string(ground_truth.target_ids.size()) + " target ids)");
  }
  std::vector<int> map(n, -1);
  for (size_t i = 0; i < ground_truth.source_ids.size(); ++i) {
    const int s = ground_truth.source_ids[i], t = ground_truth.target_ids[i];
    if (s < 0 || s >= n || t < 0 || t >= target_vertices) {
      throw InvalidInputError("ground truth line " + std::to_string(i + 1) + " (" +
                              std::to_string(s) + " -> " + std::to_string(t) +
                              ") is outside the meshes (" + std::to_string(n) + " and " +
                              std::to_string(target_vertices) + " vertices)");
    }
    if (map[s] < 0) map[s] = t;
  }
  std::vector<int> lined;
  for (int v = 0; v < n; ++v) {
    if (map[v] >= 0) lined.push_back(v);
  }
  // Nearest along the edges, which keeps a vertex on its own part where a touching part is
  // nearer in space; where no lined vertex is reachable, the nearest in space.
  const std::vector<int> seed = NearestSeeds(BuildMeshGraph(source), lined);
  std::vector<int> kept_of_lined, nearest_lined;
  if (std::find(seed.begin(), seed.end(), -1) != seed.end()) {
    InputToKept(source.V, lined, &kept_of_lined, &nearest_lined);
  }
  std::vector<int> out(n);
  for (int v = 0; v < n; ++v) out[v] = map[lined[seed[v] >= 0 ? seed[v] : nearest_lined[v]]];
  return out;
}

uint64_t PairKey(const ShapeOutcome& source, const ShapeOutcome& target, const Pipeline& pipeline,
                 const InputGroundTruth& ground_truth) {
  Hasher h;
  h.AddString("symembed-pair-cache-7").AddString(source.name).AddU64(source.key);
  h.AddString(target.name).AddU64(target.key);
  // The per-shape kinds' options are in the shapes' keys.
  for (const StageKind& kind : kPipelineStageKinds) {
    if (kind.scope == StageScope::kPair) h.AddString(OptionsText(pipeline.StageOf(kind.name)));
  }
  h.AddString(OptionsText(*pipeline.evaluation_geodesics));
  char numbers[128];
  std::snprintf(numbers, sizeof numbers, "%.17g %.17g %d", pipeline.evaluation.max_error,
                pipeline.evaluation.step, pipeline.evaluation.points);
  h.AddString(numbers);
  // Only when set, so that the keys of pairs computed without it stay valid.
  if (pipeline.evaluation.refine_start != EvaluationOptions().refine_start) {
    h.AddString("refine_start " + pipeline.evaluation.refine_start);
  }
  for (const std::vector<int>* ids :
       {&ground_truth.source_ids, &ground_truth.target_ids, &ground_truth.target_sym_ids}) {
    h.AddU64(ids->size()).AddBytes(ids->data(), ids->size() * sizeof(int));
  }
  return h.Digest();
}

PreprocessedGroundTruth ToPreprocessedIds(const InputGroundTruth& ground_truth,
                                          const ShapeOutcome& source, const ShapeOutcome& target) {
  PreprocessedGroundTruth out;
  const bool sym = ground_truth.target_sym_ids.size() == ground_truth.target_ids.size();
  auto kept = [](const std::vector<int>& of_input, int v) {
    return v >= 0 && v < static_cast<int>(of_input.size()) ? of_input[v] : -1;
  };
  for (size_t i = 0; i < ground_truth.source_ids.size(); ++i) {
    const int s = kept(source.kept_of_input, ground_truth.source_ids[i]);
    const int t = kept(target.kept_of_input, ground_truth.target_ids[i]);
    const int t_sym = sym ? kept(target.kept_of_input, ground_truth.target_sym_ids[i]) : 0;
    if (s < 0 || t < 0 || t_sym < 0) continue;
    out.source_ids.push_back(s);
    out.target_ids.push_back(t);
    if (sym) out.target_sym_ids.push_back(t_sym);
  }
  return out;
}

namespace {

// What the per-pair chain has computed of one pair: each kind's step (RunPairStep) reads what the
// steps before it wrote and adds its kind's output and time.
struct PairChain {
  PairChain(const ShapeOutcome& source, const ShapeOutcome& target, const Pipeline& pipeline,
            const InputGroundTruth* ground_truth, StageCounters* counters, PairOutcome& out)
      : source(source),
        target(target),
        pipeline(pipeline),
        ground_truth(ground_truth),
        counters(counters),
        out(out) {
    if (ground_truth) truth_pre = ToPreprocessedIds(*ground_truth, source, target);
  }

  const ShapeOutcome& source;
  const ShapeOutcome& target;
  const Pipeline& pipeline;
  const InputGroundTruth* ground_truth;
  StageCounters* counters;
  PairOutcome& out;
  PreprocessedGroundTruth truth_pre;
  const std::array<Eigen::Matrix3d, 4> rotations = CandidateRotations();

  // The planes the flip step chose (each shape's first, or its second hypothesis).
  const ShapeData* a = nullptr;
  const ShapeData* b = nullptr;
  std::optional<PairInput> input;
  // The normals of both embedded surfaces, once per pair (the oracle rotates the target's).
  EmbeddedPoints source_points, target_points;
  EmbeddedPoints chosen_target;  // target_points under the chosen rotation
  MatchResult matched;
  bool on_surfaces = false;  // the matching stage's map on the surfaces replaced matched
  MatchResult refined;

  const PreprocessedGroundTruth* Truth() const { return ground_truth ? &truth_pre : nullptr; }
  // Per candidate, the source's points as the matching stage compares them with the target so
  // rotated (its Align), once each: the oracle reuses the chosen candidate's.
  const EmbeddedPoints& Aligned(int c, const EmbeddedPoints& rotated_target) {
    if (alignment[c] == 0) {
      alignment[c] =
          pipeline.matching->Align(*input, source_points, rotated_target, &moved[c]) ? 1 : 2;
    }
    return alignment[c] == 1 ? moved[c] : source_points;
  }

 private:
  std::array<EmbeddedPoints, 4> moved;
  std::array<int, 4> alignment{};  // 0: not computed, 1: moved[c], 2: the points as they are
};

// One overload per per-pair kind's interface: ComputePair calls them in the order of the
// stage-kind table, so a per-pair kind without its step does not compile.
//
// With a second plane hypothesis for either shape, the flip stage scores every combination of
// planes and the pair goes on with the one whose chosen rotation scores lowest (the first plane
// on ties): which of a shape's planes holds is told by the partner's frame.
void RunPairStep(const std::string& kind, const FlipStage& stage, PairChain& chain) {
  const auto start = std::chrono::steady_clock::now();
  PairOutcome& out = chain.out;
  const ShapeOutcome& source = chain.source;
  const ShapeOutcome& target = chain.target;
  std::string chosen_planes;
  std::ostringstream planes;  // each combination's score of its chosen rotation
  for (const ShapeData* sa : {source.data.get(), source.alternative.get()}) {
    for (const ShapeData* sb : {target.data.get(), target.alternative.get()}) {
      if (!sa || !sb) continue;
      FlipResult flip = stage.Run(PairInput{*sa, *sb, chain.Truth()});
      chain.counters->Executed(kind);
      if (flip.chosen < 0 || flip.chosen > 3) {
        throw SolverError("flip scorer chose candidate " + std::to_string(flip.chosen) +
                          " outside [0, 3]");
      }
      const std::string name = std::string(sa == source.data.get() ? "first" : "second") + "/" +
                               (sb == target.data.get() ? "first" : "second");
      planes << (planes.tellp() > 0 ? ", " : "") << name << " " << flip.scores[flip.chosen];
      if (!chain.a || flip.scores[flip.chosen] < out.flip.scores[out.flip.chosen]) {
        out.flip = std::move(flip);
        chain.a = sa;
        chain.b = sb;
        chosen_planes = name;
      }
    }
  }
  if (source.alternative || target.alternative) {
    out.flip.status.message +=
        "; planes (source/target): " + planes.str() + "; chosen " + chosen_planes;
  }
  out.times.push_back({kind, SecondsSince(start), false});
  chain.input.emplace(PairInput{*chain.a, *chain.b, chain.Truth()});
}

// The embeddings' map under the chosen rotation; for a partial pair also the map on the
// surfaces, kept when it keeps the part's distances better.
void RunPairStep(const std::string& kind, const MatchingStage& stage, PairChain& chain) {
  const auto start = std::chrono::steady_clock::now();
  const ShapeData& a = *chain.a;
  const ShapeData& b = *chain.b;
  const int nb = b.surface.NumVertices();
  chain.source_points = EmbeddedShape(a);
  chain.target_points = EmbeddedShape(b);
  const int chosen = chain.out.flip.chosen;
  chain.chosen_target = Rotated(chain.target_points, chain.rotations[chosen]);
  MatchResult matched = stage.Run(chain.Aligned(chosen, chain.chosen_target), chain.chosen_target);
  CheckMap(matched, a.surface.NumVertices(), nb, kind.c_str());
  SurfaceMatch on_surfaces_map;
  const bool partial = stage.MatchSurfaces(*chain.input, matched.map, &on_surfaces_map);
  if (partial) {
    CheckMap(on_surfaces_map.result, a.surface.NumVertices(), nb, kind.c_str());
    // Of the map on the surfaces and the one in the embeddings, the one that keeps the part's
    // distances better: a part that lacks little (a few holes) keeps its embedding and frame.
    const double surfaces = on_surfaces_map.distortion;
    const double embeddings = on_surfaces_map.seed_distortion;
    chain.on_surfaces = surfaces < embeddings;
    std::ostringstream note;
    note << "the matching stage mapped the surfaces (" << on_surfaces_map.result.status.message
         << "); landmark distortion " << surfaces << " on the surfaces, " << embeddings
         << " in the embeddings";
    if (chain.on_surfaces) {
      chain.out.flip.status.message += "; not used: " + note.str();
      matched = std::move(on_surfaces_map.result);
    } else {
      chain.out.flip.status.message += "; " + note.str() + ": the embeddings' map kept";
    }
  }
  chain.out.times.push_back({kind, SecondsSince(start), false});
  chain.counters->Executed(kind);
  chain.out.matching_status = matched.status;
  chain.matched = std::move(matched);
}

// The refined map, from the matching stage's map or, with `evaluation.refine_start:
// ground_truth`, from the ground truth.
void RunPairStep(const std::string& kind, const RefineStage& stage, PairChain& chain) {
  const ShapeData& a = *chain.a;
  const int nb = chain.b->surface.NumVertices();
  if (chain.pipeline.evaluation.refine_start == "ground_truth") {
    if (!chain.ground_truth) {
      throw InvalidInputError(
          "evaluation.refine_start: ground_truth: the dataset gives this pair no ground truth");
    }
    chain.matched.map = MapFromGroundTruth(a.surface, nb, chain.truth_pre);
  }
  const auto start = std::chrono::steady_clock::now();
  // A part's map on the surfaces is refined as a part's; the embeddings' points do not
  // describe it.
  const int chosen = chain.out.flip.chosen;
  const bool part = chain.on_surfaces;
  MatchResult refined = stage.Run(RefineInput{
      *chain.input, chain.matched.map, part ? nullptr : &chain.Aligned(chosen, chain.chosen_target),
      part ? nullptr : &chain.chosen_target, part});
  chain.counters->Executed(kind);
  chain.out.times.push_back({kind, SecondsSince(start), false});
  CheckMap(refined, a.surface.NumVertices(), nb, kind.c_str());
  chain.out.refine_status = refined.status;
  chain.refined = std::move(refined);
}

}  // namespace

PairOutcome ComputePair(const ShapeOutcome& source, const ShapeOutcome& target,
                        const Pipeline& pipeline, const InputGroundTruth* ground_truth,
                        const MeanErrorFunction& mean_error, StageCounters* counters) {
  PairOutcome out;
  PairChain chain(source, target, pipeline, ground_truth, counters, out);
  Pipeline::ForEachStage(pipeline, [&](const char* kind, const auto& stage) {
    using T = typename std::decay_t<decltype(stage)>::element_type;
    if constexpr (std::is_base_of_v<PairStage, T>) RunPairStep(kind, *stage, chain);
  });
  const ShapeData& b = *chain.b;
  const int nb = b.surface.NumVertices();
  const auto& rotations = chain.rotations;
  const MatchResult& matched = chain.matched;
  const MatchResult& refined = chain.refined;

  auto to_input_ids = [&](const std::vector<int>& map) {
    std::vector<int> ids(source.nearest_kept.size());
    for (size_t v = 0; v < ids.size(); ++v) ids[v] = b.input_ids[map[source.nearest_kept[v]]];
    return ids;
  };
  out.map = to_input_ids(refined.map);
  if (refined.map != matched.map) out.initial_map = to_input_ids(matched.map);

  if (ground_truth && !ground_truth->source_ids.empty() && mean_error) {
    const auto start = std::chrono::steady_clock::now();
    for (int v : ground_truth->source_ids) {
      if (v < 0 || v >= static_cast<int>(source.nearest_kept.size())) {
        throw InvalidInputError("ground truth names source vertex " + std::to_string(v) +
                                " of a mesh with " + std::to_string(source.nearest_kept.size()) +
                                " vertices");
      }
    }
    double best = std::numeric_limits<double>::infinity();
    // The target's ground-truth distance rows are computed by the first call that lacks them;
    // they are the evaluation's, timed apart from the oracle's own work.
    double distance_seconds = 0.0;
    for (int c = 0; c < 4; ++c) {
      // The chosen candidate's rotated target is the matching stage's.
      EmbeddedPoints other;
      const EmbeddedPoints& rotated_target =
          c == out.flip.chosen ? chain.chosen_target
                               : (other = Rotated(chain.target_points, rotations[c]));
      const EmbeddedPoints& from = chain.Aligned(c, rotated_target);
      EmbeddedPoints points;
      points.Y.resize(ground_truth->source_ids.size(), 3);
      points.N.resize(ground_truth->source_ids.size(), 3);
      for (size_t i = 0; i < ground_truth->source_ids.size(); ++i) {
        const int v = source.nearest_kept[ground_truth->source_ids[i]];
        points.Y.row(i) = from.Y.row(v);
        points.N.row(i) = from.N.row(v);
      }
      MatchResult m = pipeline.matching->Run(points, rotated_target);
      CheckMap(m, static_cast<int>(points.Y.rows()), nb, "matching");
      std::vector<int> predicted(m.map.size());
      for (size_t i = 0; i < m.map.size(); ++i) predicted[i] = b.input_ids[m.map[i]];
      double seconds = 0.0;
      out.oracle_errors[c] = mean_error(predicted, &seconds);
      distance_seconds += seconds;
      if (out.oracle_errors[c] < best) {
        best = out.oracle_errors[c];
        out.oracle = c;
      }
    }
    out.times.push_back({"oracle", SecondsSince(start) - distance_seconds, false});
    out.times.push_back({"ground_truth_distances", distance_seconds, false});
    counters->Executed("oracle");
  }
  return out;
}

}  // namespace symembed
