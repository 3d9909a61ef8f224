#include "eval/synthetic/synthetic.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.h"
#include "core/mesh_io.h"
#include "core/parallel.h"
#include "eval/synthetic/dataset_writer.h"
#include "eval/synthetic/posing.h"
#include "eval/synthetic/random.h"

namespace symembed {

namespace fs = std::filesystem;

bool SynthOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& what) {
    if (error) *error = what;
    return false;
  };
  if (kinds.empty()) return fail("kinds: at least one figure kind is needed");
  for (size_t i = 0; i < kinds.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      if (kinds[i] == kinds[j]) return fail("kinds: '" + FigureKindName(kinds[i]) + "' twice");
    }
  }
  const std::string bounds = FieldViolation(*this);
  if (!bounds.empty()) return fail(bounds);
  if (remesh > 0 && remesh < 50) return fail("remesh: a target below 50 vertices is degenerate");
  if (remesh_anisotropy > 1.0 && remesh == 0) {
    return fail("remesh_anisotropy: needs remesh > 0 (the anisotropy is the remeshing's)");
  }
  return true;
}

std::string SynthOptionsText(const SynthOptions& o) {
  std::ostringstream out;
  out << "kinds: [";
  for (size_t i = 0; i < o.kinds.size(); ++i) out << (i ? ", " : "") << FigureKindName(o.kinds[i]);
  char buffer[64];
  out << "]\nposes: " << o.poses << "\nvertices: " << o.vertices << "\nseed: " << o.seed
      << "\nremesh: " << o.remesh;
  // Written only when set, so that the text (and the cache folders named by its hash) of every
  // option set without it stays what it was.
  if (o.remesh_anisotropy != 1.0) {
    std::snprintf(buffer, sizeof buffer, "%.17g", o.remesh_anisotropy);
    out << "\nremesh_anisotropy: " << buffer;
  }
  std::snprintf(buffer, sizeof buffer, "%.17g", o.nonisometric);
  out << "\nnonisometric: " << buffer;
  std::snprintf(buffer, sizeof buffer, "%.17g", o.noise);
  out << "\nnoise: " << buffer;
  std::snprintf(buffer, sizeof buffer, "%.17g", o.partial);
  out << "\npartial: " << buffer << "\npairs: " << o.pairs << "\n";
  // Also written only when set (see remesh_anisotropy).
  auto optional = [&](const char* key, double value) {
    if (value == 0.0) return;
    std::snprintf(buffer, sizeof buffer, "%.17g", value);
    out << key << ": " << buffer << "\n";
  };
  optional("plane_cuts", o.plane_cuts);
  optional("holes", o.holes);
  optional("glue", o.glue);
  if (o.glue > 0.0 && o.glue_bridges != 8) out << "glue_bridges: " << o.glue_bridges << "\n";
  optional("cross_class", o.cross_class);
  return out.str();
}

namespace {

// The poses (of n) that a variation applied to `fraction` of them touches: a seeded subset.
std::vector<bool> ChosenPoses(int n, double fraction, uint32_t seed);

// Fisher-Yates shuffle with the platform-independent generator.
template <typename T>
void Shuffle(std::vector<T>& items, SynthRandom& random) {
  for (int i = static_cast<int>(items.size()) - 1; i > 0; --i) {
    std::swap(items[i], items[random.Index(i + 1)]);
  }
}

std::vector<bool> ChosenPoses(int n, double fraction, uint32_t seed) {
  std::vector<bool> chosen(n, false);
  const int count = static_cast<int>(std::floor(fraction * n + 0.5));
  if (count == 0) return chosen;
  SynthRandom random(seed);
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  Shuffle(order, random);
  for (int i = 0; i < count; ++i) chosen[order[i]] = true;
  return chosen;
}

// Keeps a seeded subset of `count` of the pairs (all when count is 0 or not below their
// number), in their order.
void KeepSeededSubset(std::vector<std::pair<int, int>>* pairs, int count, uint32_t seed) {
  if (count <= 0 || count >= static_cast<int>(pairs->size())) return;
  SynthRandom random(seed);
  Shuffle(*pairs, random);
  pairs->resize(count);
  std::sort(pairs->begin(), pairs->end());
}

// Offset of a cross class's stream index from its kind's (FigureKind values are small).
constexpr uint64_t kCrossStreams = 64;

// The cross class's body plan (SynthOptions::cross_class): per-bone length and thickness
// factors, equal on mirrored bones, and the forward bend applied to the rest shape.
struct CrossBody {
  std::vector<double> length, thickness;
};

CrossBody DrawCrossBody(const std::vector<Bone>& bones, double spread, uint32_t seed) {
  CrossBody body;
  body.length.assign(bones.size(), 1.0);
  body.thickness.assign(bones.size(), 1.0);
  SynthRandom random(seed);
  for (size_t b = 0; b < bones.size(); ++b) {
    const size_t m = static_cast<size_t>(bones[b].mirror);
    if (m < b) {
      body.length[b] = body.length[m];
      body.thickness[b] = body.thickness[m];
      continue;
    }
    body.length[b] = random.Uniform(1.0 - spread, 1.0 + spread);
    body.thickness[b] = random.Uniform(1.0 - spread, 1.0 + spread);
  }
  return body;
}

void BendForwards(Surface* rest, double spread) {
  const double y0 = rest->V.col(1).minCoeff();
  const double height = rest->V.col(1).maxCoeff() - y0;
  for (int i = 0; i < rest->NumVertices(); ++i) {
    const double y = rest->V(i, 1) - y0;
    rest->V(i, 2) += 0.5 * spread * y * y / height;
  }
}

}  // namespace

std::vector<std::pair<int, int>> CrossClassPairs(FigureKind kind, const SynthOptions& options) {
  const int n = options.poses;
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) pairs.push_back({i, j});
  }
  KeepSeededSubset(&pairs, options.pairs,
                   DeriveSeed(static_cast<uint64_t>(options.seed), "cross_pairs",
                              static_cast<uint64_t>(kind)));
  return pairs;
}

SynthClass GenerateClass(FigureKind kind, const SynthOptions& options, ClassBody body) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("synthetic options: " + error);
  const bool cross = body == ClassBody::kCross;
  if (cross && options.cross_class == 0.0) {
    throw ConfigError("synthetic options: a cross class needs cross_class > 0");
  }
  const uint64_t seed = static_cast<uint64_t>(options.seed);
  const uint64_t k = static_cast<uint64_t>(kind) + (cross ? kCrossStreams : 0);
  SynthClass out;
  out.name = FigureKindName(kind) + (cross ? "_cross" : "");
  out.rest = MakeRestFigure(kind, options.vertices);
  CrossBody cross_body;
  if (cross) {
    cross_body = DrawCrossBody(out.rest.figure.bones, options.cross_class,
                               DeriveSeed(seed, "cross_body", k));
    BendForwards(&out.rest.surface, options.cross_class);
  }
  const RestFigure& rest = out.rest;
  const int n = options.poses;

  // Which poses lose which part.
  std::vector<int> cut_bone(n, -1);
  const int num_cut = static_cast<int>(std::floor(options.partial * n + 0.5));
  if (num_cut > 0) {
    SynthRandom random(DeriveSeed(seed, "partial", k));
    std::vector<int> order(n);
    for (int i = 0; i < n; ++i) order[i] = i;
    Shuffle(order, random);
    for (int i = 0; i < num_cut; ++i) {
      const auto& parts = rest.figure.cuttable;
      cut_bone[order[i]] = parts[random.Index(static_cast<int>(parts.size()))];
    }
  }

  const std::vector<bool> glued = ChosenPoses(n, options.glue, DeriveSeed(seed, "glue", k));
  const std::vector<bool> plane_cut =
      ChosenPoses(n, options.plane_cuts, DeriveSeed(seed, "plane_cuts", k));
  const std::vector<bool> holed = ChosenPoses(n, options.holes, DeriveSeed(seed, "holes", k));

  out.shapes.resize(n);
  ParallelFor(n, [&](int p) {
    SynthShape& shape = out.shapes[p];
    shape.name = out.name + std::to_string(p);
    shape.shape.rest_ids.resize(rest.surface.V.rows());
    for (int i = 0; i < rest.surface.NumVertices(); ++i) shape.shape.rest_ids[i] = i;
    std::vector<std::string> notes;
    auto posed = [&](uint64_t draw) {
      // Draw 0 is the pose's own; the others come from streams of their own, so that no
      // contact pose repeats another pose of the class.
      const uint64_t index = draw == 0 ? p : static_cast<uint64_t>(p) * kContactDraws + draw;
      const std::string prefix = draw == 0 ? "" : "contact_";
      Pose pose = RandomPose(rest.figure.bones, DeriveSeed(seed, prefix + "angles", k, index),
                             options.nonisometric, DeriveSeed(seed, prefix + "scales", k, index));
      for (size_t b = 0; cross && b < pose.length_scale.size(); ++b) {
        pose.length_scale[b] *= cross_body.length[b];
        pose.thickness_scale[b] *= cross_body.thickness[b];
      }
      return Surface{SkinVertices(rest, pose), rest.surface.F};
    };
    shape.shape.surface = posed(0);
    if (glued[p]) {
      // The draw whose parts come closest to touching.
      double best_gap = GlueGap(shape.shape, rest.weights, rest.figure.bones);
      for (int draw = 1; draw < kContactDraws; ++draw) {
        TrackedSurface candidate{posed(draw), shape.shape.rest_ids};
        const double gap = GlueGap(candidate, rest.weights, rest.figure.bones);
        if (gap < best_gap) {
          best_gap = gap;
          shape.shape = std::move(candidate);
        }
      }
      shape.shape = PullIntoContact(shape.shape, rest.weights, rest.figure.bones);
      std::ostringstream note;
      note << "contact pose (gap " << best_gap << " closed)";
      if (options.glue_bridges > 0) {
        shape.shape = GlueParts(shape.shape, rest.weights, rest.figure.bones, options.glue_bridges);
        note << ", glued by " << (shape.shape.surface.NumFaces() - rest.surface.NumFaces()) / 4
             << " tubes";
      }
      notes.push_back(note.str());
    }
    if (cut_bone[p] >= 0) {
      shape.shape = CutPart(shape.shape, rest.weights, rest.figure.bones, cut_bone[p]);
      notes.push_back("cut " + rest.figure.bones[cut_bone[p]].name);
    }
    if (plane_cut[p]) {
      SynthRandom random(DeriveSeed(seed, "plane_cut", k, p));
      const Eigen::Vector3d normal = RandomUnitVector(DeriveSeed(seed, "plane_normal", k, p));
      const double removed = random.Uniform(0.1, 0.4);
      shape.shape = CutByPlane(shape.shape, normal, removed);
      std::ostringstream note;
      note << "plane cut (" << static_cast<int>(100 * removed + 0.5) << "% of the vertices)";
      notes.push_back(note.str());
    }
    if (holed[p]) {
      SynthRandom random(DeriveSeed(seed, "hole", k, p));
      const int count = 1 + random.Index(3);
      const double scale = std::sqrt(FaceAreas(shape.shape.surface).sum());
      for (int h = 0; h < count; ++h) {
        const int center = random.Index(shape.shape.surface.NumVertices());
        shape.shape = CutHole(shape.shape, center, random.Uniform(0.03, 0.12) * scale);
      }
      notes.push_back(std::to_string(count) + (count == 1 ? " hole" : " holes"));
    }
    if (options.remesh > 0 && options.remesh < shape.shape.surface.NumVertices()) {
      Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
      std::string anisotropic;
      if (options.remesh_anisotropy > 1.0) {
        direction = RandomUnitVector(DeriveSeed(seed, "remesh_direction", k, p));
        std::ostringstream note;
        note << ", anisotropy " << options.remesh_anisotropy;
        anisotropic = note.str();
      }
      shape.shape = Remesh(shape.shape, options.remesh, DeriveSeed(seed, "remesh", k, p),
                           options.remesh_anisotropy, direction);
      notes.push_back("remeshed to " + std::to_string(shape.shape.surface.NumVertices()) +
                      " vertices" + anisotropic);
    }
    if (options.noise > 0.0) {
      AddNormalNoise(&shape.shape.surface, options.noise, DeriveSeed(seed, "noise", k, p));
      notes.push_back("noise");
    }
    for (size_t i = 0; i < notes.size(); ++i) shape.note += (i ? ", " : "") + notes[i];
  });

  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) out.pairs.push_back({i, j});
  }
  KeepSeededSubset(&out.pairs, options.pairs, DeriveSeed(seed, "pairs", k));
  return out;
}

void WriteSyntheticDataset(const std::string& dir, const SynthOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("synthetic options: " + error);
  const fs::path root(dir);
  CreateDatasetFolders(root);
  std::string pairs_text, shapes_text;
  auto write_class = [&](const SynthClass& c) {
    const int num_rest = c.rest.surface.NumVertices();
    shapes_text += "## " + c.name + "\n\nRest shape: " + std::to_string(num_rest) + " vertices (" +
                   std::to_string(c.rest.levels) + " Catmull-Clark levels, " +
                   std::to_string(c.rest.rings_per_segment) + " rings per segment), " +
                   std::to_string(c.rest.figure.bones.size()) +
                   " bones.\n\n| shape | vertices | what |\n| --- | --- | --- |\n";
    std::vector<int> direct(num_rest);
    for (int i = 0; i < num_rest; ++i) direct[i] = i;
    for (const SynthShape& s : c.shapes) {
      SaveMesh((root / "shapes" / (s.name + ".off")).string(), s.shape.surface);
      WriteDatasetFile(root / "corres" / (s.name + ".vts"),
                       VtsText(s.shape.rest_ids, direct, num_rest));
      WriteDatasetFile(root / "corres" / (s.name + ".sym.vts"),
                       VtsText(s.shape.rest_ids, c.rest.mirror, num_rest));
      shapes_text += "| " + s.name + " | " + std::to_string(s.shape.surface.NumVertices()) + " | " +
                     (s.note.empty() ? "posed" : "posed, " + s.note) + " |\n";
    }
    shapes_text += "\n";
  };
  for (FigureKind kind : options.kinds) {
    const SynthClass c = GenerateClass(kind, options);
    write_class(c);
    if (options.cross_class == 0.0) {
      for (const auto& [a, b] : c.pairs) {
        pairs_text += c.shapes[a].name + "\t" + c.shapes[b].name + "\n";
      }
      continue;
    }
    const SynthClass cross = GenerateClass(kind, options, ClassBody::kCross);
    write_class(cross);
    for (const auto& [a, b] : CrossClassPairs(kind, options)) {
      pairs_text += c.shapes[a].name + "\t" + cross.shapes[b].name + "\n";
    }
  }
  WriteDatasetFile(root / "test_pairs.txt", pairs_text);
  std::ostringstream readme;
  readme << "# Synthetic ground-truth dataset (symembed synth)\n\n"
         << "Generator options (the same options give byte-identical files):\n\n```yaml\n"
         << SynthOptionsText(options) << "```\n\n"
         << "Layout (pairs_vts): `shapes/NAME.off`; `corres/NAME.vts`: line i is the 1-based "
            "id in NAME of rest vertex i, 0 when NAME does not have it (remeshed away or cut "
            "off); `corres/NAME.sym.vts`: the same for the mirror image of rest vertex i; "
            "`test_pairs.txt`: tab-separated pairs, within a class or, with cross_class, from "
            "each kind's class onto its cross class KIND_cross (another body plan on the same "
            "mesh). The class of a shape is its name without the trailing digits.\n\n"
         << shapes_text;
  WriteDatasetFile(root / "README.md", readme.str());
}

}  // namespace symembed
