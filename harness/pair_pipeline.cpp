#include "harness/pair_pipeline.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <limits>
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
  h.AddString("symembed-pair-cache-5").AddString(source.name).AddU64(source.key);
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

PairOutcome ComputePair(const ShapeOutcome& source, const ShapeOutcome& target,
                        const Pipeline& pipeline, const InputGroundTruth* ground_truth,
                        const MeanErrorFunction& mean_error, StageCounters* counters) {
  PairOutcome out;
  PreprocessedGroundTruth truth_pre;
  if (ground_truth) truth_pre = ToPreprocessedIds(*ground_truth, source, target);

  // With a second plane hypothesis for either shape, the flip stage scores every combination
  // of planes and the pair goes on with the one whose chosen rotation scores lowest (the first
  // plane on ties): which of a shape's planes holds is told by the partner's frame.
  auto start = std::chrono::steady_clock::now();
  const ShapeData* a_ptr = nullptr;
  const ShapeData* b_ptr = nullptr;
  std::string chosen_planes;
  std::ostringstream planes;  // each combination's score of its chosen rotation
  for (const ShapeData* sa : {source.data.get(), source.alternative.get()}) {
    for (const ShapeData* sb : {target.data.get(), target.alternative.get()}) {
      if (!sa || !sb) continue;
      FlipResult flip =
          pipeline.flip->Run(PairInput{*sa, *sb, ground_truth ? &truth_pre : nullptr});
      counters->Executed("flip");
      if (flip.chosen < 0 || flip.chosen > 3) {
        throw SolverError("flip scorer chose candidate " + std::to_string(flip.chosen) +
                          " outside [0, 3]");
      }
      const std::string name = std::string(sa == source.data.get() ? "first" : "second") + "/" +
                               (sb == target.data.get() ? "first" : "second");
      planes << (planes.tellp() > 0 ? ", " : "") << name << " " << flip.scores[flip.chosen];
      if (!a_ptr || flip.scores[flip.chosen] < out.flip.scores[out.flip.chosen]) {
        out.flip = std::move(flip);
        a_ptr = sa;
        b_ptr = sb;
        chosen_planes = name;
      }
    }
  }
  if (source.alternative || target.alternative) {
    out.flip.status.message +=
        "; planes (source/target): " + planes.str() + "; chosen " + chosen_planes;
  }
  out.times.push_back({"flip", SecondsSince(start), false});
  const ShapeData& a = *a_ptr;
  const ShapeData& b = *b_ptr;
  const int nb = b.surface.NumVertices();
  const PairInput input{a, b, ground_truth ? &truth_pre : nullptr};
  const auto rotations = CandidateRotations();

  start = std::chrono::steady_clock::now();
  // The normals of both embedded surfaces, once per pair (the oracle below rotates the target's).
  const EmbeddedPoints source_points = EmbeddedShape(a), target_points = EmbeddedShape(b);
  // Per candidate, the source's points as the matching stage compares them with the target so
  // rotated (its Align), once each: the oracle below reuses the chosen candidate's.
  std::array<EmbeddedPoints, 4> moved;
  std::array<int, 4> alignment{};  // 0: not computed, 1: moved[c], 2: the points as they are
  auto aligned = [&](int c, const EmbeddedPoints& rotated_target) -> const EmbeddedPoints& {
    if (alignment[c] == 0) {
      alignment[c] =
          pipeline.matching->Align(input, source_points, rotated_target, &moved[c]) ? 1 : 2;
    }
    return alignment[c] == 1 ? moved[c] : source_points;
  };
  const EmbeddedPoints chosen_target = Rotated(target_points, rotations[out.flip.chosen]);
  MatchResult matched =
      pipeline.matching->Run(aligned(out.flip.chosen, chosen_target), chosen_target);
  CheckMap(matched, a.surface.NumVertices(), nb, "matching");
  SurfaceMatch on_surfaces_map;
  const bool partial = pipeline.matching->MatchSurfaces(input, matched.map, &on_surfaces_map);
  bool on_surfaces = false;
  if (partial) {
    CheckMap(on_surfaces_map.result, a.surface.NumVertices(), nb, "matching");
    // Of the map on the surfaces and the one in the embeddings, the one that keeps the part's
    // distances better: a part that lacks little (a few holes) keeps its embedding and frame.
    const double surfaces = on_surfaces_map.distortion;
    const double embeddings = on_surfaces_map.seed_distortion;
    on_surfaces = surfaces < embeddings;
    std::ostringstream note;
    note << "the matching stage mapped the surfaces (" << on_surfaces_map.result.status.message
         << "); landmark distortion " << surfaces << " on the surfaces, " << embeddings
         << " in the embeddings";
    if (on_surfaces) {
      out.flip.status.message += "; not used: " + note.str();
      matched = std::move(on_surfaces_map.result);
    } else {
      out.flip.status.message += "; " + note.str() + ": the embeddings' map kept";
    }
  }
  out.times.push_back({"matching", SecondsSince(start), false});
  counters->Executed("matching");
  out.matching_status = matched.status;

  if (pipeline.evaluation.refine_start == "ground_truth") {
    if (!ground_truth) {
      throw InvalidInputError(
          "evaluation.refine_start: ground_truth: the dataset gives this pair no ground truth");
    }
    matched.map = MapFromGroundTruth(a.surface, nb, truth_pre);
  }

  start = std::chrono::steady_clock::now();
  MatchResult refined;
  if (on_surfaces) {
    // The refine stages pull a map towards one that covers the whole target, which a part's
    // map must not; the surfaces' map is refined by its own rounds.
    refined.map = matched.map;
    refined.status.message = "not run: the matching stage mapped the surfaces";
  } else {
    refined = pipeline.refine->Run(RefineInput{
        input, matched.map, &aligned(out.flip.chosen, chosen_target), &chosen_target});
    counters->Executed("refine");
  }
  out.times.push_back({"refine", SecondsSince(start), false});
  CheckMap(refined, a.surface.NumVertices(), nb, "refine");
  out.refine_status = refined.status;

  auto to_input_ids = [&](const std::vector<int>& map) {
    std::vector<int> ids(source.nearest_kept.size());
    for (size_t v = 0; v < ids.size(); ++v) ids[v] = b.input_ids[map[source.nearest_kept[v]]];
    return ids;
  };
  out.map = to_input_ids(refined.map);
  if (refined.map != matched.map) out.initial_map = to_input_ids(matched.map);

  if (ground_truth && !ground_truth->source_ids.empty() && mean_error) {
    start = std::chrono::steady_clock::now();
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
      const EmbeddedPoints rotated_target = Rotated(target_points, rotations[c]);
      const EmbeddedPoints& from = aligned(c, rotated_target);
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
