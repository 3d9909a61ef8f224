#include "harness/html/pair_views.h"

#include <filesystem>

#include "core/files.h"
#include "core/map_io.h"
#include "core/mesh_io.h"
#include "eval/report.h"
#include "harness/html/side_files.h"
#include "registry/hash.h"

namespace symembed {

ShapeView BuildShapeView(const Dataset& dataset, const DatasetShape& shape,
                         const std::string& key) {
  ShapeView view;
  view.key = key.empty() ? shape.name : key;
  view.name = shape.name;
  view.class_name = shape.class_name;
  Surface surface;
  try {
    surface = LoadSurface(shape.mesh_path);
  } catch (const std::exception& e) {
    view.error = e.what();
    return view;
  }
  view.vertices = surface.NumVertices();
  JsonValue payload = JsonValue::Object();
  payload.Set("name", JsonValue::String(shape.name));
  payload.Set("class", JsonValue::String(shape.class_name));
  payload.Set("vertices", JsonValue::Number(view.vertices));
  try {
    payload.Set("positions", EncodePositions(surface.V));
  } catch (const std::exception& e) {
    view.error = shape.mesh_path + ": " + e.what();
    return view;
  }
  // Eigen stores F column-major; the page wants the vertices of each face together.
  view.faces.resize(3 * static_cast<size_t>(surface.NumFaces()));
  for (int f = 0; f < surface.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) view.faces[3 * f + k] = surface.F(f, k);
  }
  payload.Set("faces", EncodeIds(view.faces));
  try {
    view.truth = dataset.GroundTruth(shape, view.vertices);
  } catch (const std::exception& e) {
    // A shape without ground truth is still shown; its pairs then lack the ground truth view.
    view.truth = ShapeGroundTruth();
    payload.Set("gt_note", JsonValue::String(e.what()));
  }
  if (!view.truth.ids.empty()) payload.Set("gt", EncodeIds(view.truth.ids));
  if (!view.truth.sym_ids.empty()) payload.Set("gt_sym", EncodeIds(view.truth.sym_ids));
  view.script = SideFileScript("shape", view.key, payload);
  return view;
}

std::string MapSource::Stem(const std::string& source, const std::string& target) const {
  return reverse ? names.Stem(target, source) : names.Stem(source, target);
}

std::string MapSource::MapPath(const std::string& source, const std::string& target) const {
  return maps_dir + "/" + Stem(source, target) + ".map";
}

std::string MapSource::RecordPath(const std::string& source, const std::string& target) const {
  return records_dir + "/" + Stem(source, target) + ".rec";
}

namespace {

// The pair's per-point errors, or the reason there are none (*note).
std::vector<double> RecordErrors(const ShapeView& source, const ShapeView& target,
                                 const MapSource& maps, std::string* note) {
  if (maps.records_dir.empty()) {
    *note = "no per-point errors: this folder has no per-pair records (symembed eval keeps none)";
    return {};
  }
  const std::string path = maps.RecordPath(source.name, target.name);
  PairEvaluation record;
  try {
    record = ParsePairRecord(ReadFileOrThrow(path), path);
  } catch (const std::exception& e) {
    *note = std::string("no per-point errors: ") + e.what();
    return {};
  }
  const size_t lines = PairGroundTruth(source.truth, source.name, target.truth, target.name).source_ids.size();
  if (record.errors_direct.size() != lines) {
    *note = "no per-point errors: " + path + " has " + std::to_string(record.errors_direct.size()) +
            " errors, the ground truth " + std::to_string(lines) +
            " lines (evaluation.points selects a subset; the heat map needs all)";
    return {};
  }
  return record.errors_direct;
}

}  // namespace

PairView BuildPairView(const ShapeView& source, const ShapeView& target, const MapSource& maps,
                       double max_error) {
  PairView view;
  for (const ShapeView* shape : {&source, &target}) {
    if (!shape->error.empty()) {
      view.error = "shape " + shape->name + ": " + shape->error;
      return view;
    }
  }
  JsonValue payload = JsonValue::Object();
  try {
    const std::vector<int> map = ReadMapFile(maps.MapPath(source.name, target.name), maps.base,
                                             source.vertices, target.vertices);
    payload.Set("map",
                EncodeVertexMap(map, source.vertices, source.faces, target.vertices, target.faces));
  } catch (const std::exception& e) {
    view.error = e.what();
    return view;
  }
  std::string note;
  const std::vector<double> errors = source.truth.ids.empty() || target.truth.ids.empty()
                                         ? std::vector<double>()
                                         : RecordErrors(source, target, maps, &note);
  if (source.truth.ids.empty() || target.truth.ids.empty()) {
    note = "no per-point errors: the dataset has no ground truth for this pair";
  }
  if (note.empty()) {
    payload.Set("errors", EncodeUnitValues(errors, max_error));
  } else {
    payload.Set("errors_note", JsonValue::String(note));
  }
  const std::string body = WriteJson(payload, 0);
  // Side files are named by their content: pairs whose plain stems collide differ in the hash,
  // and pairs with equal payloads may share one file.
  view.key = PlainPairStem(source.name, target.name) + "-" +
             HexDigest(HashBytes(body.data(), body.size())).substr(0, 8);
  view.script = SideFileScript("pair", view.key, payload);
  return view;
}

}  // namespace symembed
