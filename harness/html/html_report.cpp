#include "harness/html/html_report.h"

#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <set>

#include "core/errors.h"
#include "core/files.h"
#include "core/parallel.h"
#include "harness/eval_setup.h"
#include "harness/html/assets.h"
#include "harness/html/pair_views.h"
#include "harness/html/report_data.h"
#include "harness/run_outputs.h"
#include "registry/hash.h"

namespace symembed {

namespace fs = std::filesystem;

namespace {

// What the page needs of one variant, and how to reach its meshes and maps.
struct VariantInputs {
  ReportVariant variant;
  JsonValue data;
  std::unique_ptr<Dataset> dataset;  // null when it could not be opened (see reason)
  DatasetIndex index;
  MapSource maps;      // its names: those of the pairs.csv rows (WritePairs)
  std::string reason;  // why this variant's pairs have no 3D view; empty when they have one
};

// A file stem safe in any file system and URL: the name itself when it is plain, else the
// name with other characters replaced and a hash of the original, so distinct names stay
// distinct.
std::string SafeFileStem(const std::string& name) {
  std::string stem;
  for (char c : name) {
    const bool plain = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' ||
                       (c == '.' && !stem.empty());
    stem += plain ? c : '_';
  }
  if (stem == name && !stem.empty()) return stem;
  return stem + "-" + HexDigest(HashBytes(name.data(), name.size())).substr(0, 8);
}

// The class of a shape name without a dataset index: the name without its trailing digits,
// as scripts/results-table does.
std::string ClassFromName(const std::string& name) {
  size_t end = name.size();
  while (end > 0 && std::isdigit(static_cast<unsigned char>(name[end - 1]))) --end;
  return end == 0 ? name : name.substr(0, end);
}

void OpenDataset(VariantInputs& v, const Registry& registry) {
  const std::string dir = v.variant.dir;
  const std::string config = VariantConfigPath(dir);
  const std::string eval = EvalSourcePath(dir);
  try {
    EvalSetup setup;
    if (fs::exists(config)) {
      setup = MakeEvalSetup(config, registry);
      v.maps = MapSource{dir + "/maps", 1, false, dir + "/pairs", PairNames()};
    } else if (fs::exists(eval)) {
      const EvalSource source = ReadEvalSource(eval);
      setup = MakeEvalSetup(source.dataset, registry);
      v.maps = MapSource{source.maps_dir, source.base, source.reverse, "", PairNames()};
    } else {
      v.reason = dir + ": neither config.yaml nor eval.json, so the meshes and maps are unknown";
      return;
    }
    v.index = setup.dataset->Load();
    v.dataset = std::move(setup.dataset);
  } catch (const std::exception& e) {
    v.reason = std::string("the dataset cannot be opened: ") + e.what() +
               " (relative paths are read from the working directory, as the run read them)";
  }
}

void WriteFile(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw IoError(path.string() + ": cannot write");
}

int64_t FolderBytes(const fs::path& dir) {
  int64_t bytes = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) bytes += static_cast<int64_t>(e.file_size());
  }
  return bytes;
}

// The report folder may replace `out` only when that is empty or an earlier report.
void CheckReplaceable(const fs::path& out) {
  if (!fs::exists(out)) return;
  if (!fs::is_directory(out) || (!fs::is_empty(out) && !fs::exists(out / "index.html"))) {
    throw IoError(out.string() +
                  ": exists and is not a report folder (no index.html); "
                  "choose another --out");
  }
}

// Rows of objects as {"columns": [keys in order of first appearance], "rows": [[values]]},
// null where a row lacks a key: the keys of thousands of pair rows would be a third of data.js.
JsonValue Columnar(const JsonValue& rows) {
  std::vector<std::string> columns;
  std::map<std::string, size_t> index;
  for (const JsonValue& row : rows.items()) {
    for (const auto& [key, value] : row.members()) {
      if (index.emplace(key, columns.size()).second) columns.push_back(key);
    }
  }
  JsonValue table = JsonValue::Object();
  JsonValue names = JsonValue::Array();
  for (const std::string& c : columns) names.Push(JsonValue::String(c));
  table.Set("columns", names);
  JsonValue values = JsonValue::Array();
  for (const JsonValue& row : rows.items()) {
    JsonValue line = JsonValue::Array();
    for (const std::string& c : columns) line.Push(row.Get(c));
    values.Push(line);
  }
  table.Set("rows", values);
  return table;
}

JsonValue StringArray(const std::vector<std::string>& items) {
  JsonValue a = JsonValue::Array();
  for (const std::string& s : items) a.Push(JsonValue::String(s));
  return a;
}

// Title and description from the first variant's config.yaml (name, description), else the
// name of a single variant (a `symembed eval` folder) or the folder's.
void SetTitle(const std::string& results_dir, const std::vector<VariantInputs>& variants,
              JsonValue* report) {
  std::string title = fs::absolute(results_dir).lexically_normal().filename().string();
  if (title.empty()) {
    title = fs::absolute(results_dir).lexically_normal().parent_path().filename().string();
  }
  if (variants.size() == 1 && fs::exists(EvalSourcePath(variants.front().variant.dir))) {
    title = variants.front().variant.name;
  }
  std::string description;
  const JsonValue& config = variants.front().data.Get("config");
  if (config.IsString()) {
    try {
      const YAML::Node node = YAML::Load(config.AsString());
      if (node["name"] && node["name"].IsScalar()) title = node["name"].as<std::string>();
      if (node["description"] && node["description"].IsScalar()) {
        description = node["description"].as<std::string>();
      }
    } catch (const YAML::Exception&) {
      // The variant's data already carries the text; a title is not worth failing for.
    }
  }
  report->Set("title", JsonValue::String(title));
  report->Set("description", JsonValue::String(description));
}

class ReportWriter {
 public:
  ReportWriter(const fs::path& dir, int threads) : dir_(dir), threads_(threads) {}

  // Builds and writes the side file of every mesh the variants' pairs name; returns the page's
  // shape table, keyed by MeshKey.
  JsonValue WriteShapes(const std::vector<VariantInputs>& variants,
                        std::vector<std::string>* warnings) {
    std::map<std::string, std::pair<const Dataset*, const DatasetShape*>> wanted;  // by key
    for (const VariantInputs& v : variants) {
      if (!v.dataset) continue;
      for (const JsonValue& row : v.data.Get("pairs").items()) {
        for (const char* end : {"source", "target"}) {
          const DatasetShape* shape = v.index.Find(row.Get(end).AsString());
          if (!shape) continue;
          const std::string key = MeshKey(*shape);
          if (!wanted.count(key)) wanted[key] = {v.dataset.get(), shape};
        }
      }
    }
    std::vector<std::pair<std::string, std::pair<const Dataset*, const DatasetShape*>>> jobs(
        wanted.begin(), wanted.end());
    std::vector<ShapeView> views(jobs.size());
    fs::create_directories(dir_ / "shapes");
    ParallelFor(
        static_cast<int>(jobs.size()),
        [&](int i) {
          const auto& [key, job] = jobs[i];
          views[i] = BuildShapeView(*job.first, *job.second, key);
          if (views[i].error.empty()) {
            WriteFile(dir_ / "shapes" / (SafeFileStem(key) + ".js"), views[i].script);
            views[i].script.clear();  // written; only the ground truth and size are needed now
          }
        },
        threads_);
    JsonValue table = JsonValue::Object();
    for (ShapeView& view : views) {
      JsonValue entry = JsonValue::Object();
      entry.Set("class", JsonValue::String(view.class_name));
      if (view.key != view.name) entry.Set("name", JsonValue::String(view.name));
      if (view.error.empty()) {
        entry.Set("vertices", JsonValue::Number(view.vertices));
        entry.Set("file", JsonValue::String("shapes/" + SafeFileStem(view.key) + ".js"));
        ++shapes_written_;
      } else {
        entry.Set("unavailable", JsonValue::String(view.error));
        warnings->push_back("shape " + view.name + ": " + view.error);
      }
      table.Set(view.key, entry);
      shapes_[view.key] = std::move(view);
    }
    return table;
  }

  // Replaces each variant's pair rows by rows with "class" and either "view" (the key of its
  // map's side file pairs/KEY.js) or "unavailable" (why not), writing the side files.
  void WritePairs(std::vector<VariantInputs>& variants, HtmlReportResult* result) {
    struct Job {
      size_t variant, row;
      std::string source, target;
      std::string source_key, target_key;  // of the meshes in shapes_ (MeshKey)
      PairView view;
    };
    std::vector<Job> jobs;
    for (size_t vi = 0; vi < variants.size(); ++vi) {
      VariantInputs& v = variants[vi];
      const auto& rows = v.data.Get("pairs").items();
      // The folder's files are named among the pairs of its pairs.csv (in the files' orientation).
      std::vector<DatasetPair> named;
      for (const JsonValue& row : rows) {
        const std::string source = row.Get("source").AsString();
        const std::string target = row.Get("target").AsString();
        named.push_back(v.maps.reverse ? DatasetPair{target, source} : DatasetPair{source, target});
      }
      v.maps.names = PairNames(named);
      for (size_t r = 0; r < rows.size(); ++r) {
        if (rows[r].Get("status").AsString() != "ok") continue;
        Job job{
            vi, r,         rows[r].Get("source").AsString(), rows[r].Get("target").AsString(), "",
            "", PairView()};
        // Empty keys: the shape is not in the variant's dataset (or it has none).
        if (v.dataset) {
          for (auto [name, key] :
               {std::pair{&job.source, &job.source_key}, std::pair{&job.target, &job.target_key}}) {
            if (const DatasetShape* shape = v.index.Find(*name)) *key = MeshKey(*shape);
          }
        }
        jobs.push_back(std::move(job));
      }
    }
    fs::create_directories(dir_ / "pairs");
    std::mutex mutex;
    std::set<std::string> written;
    ParallelFor(
        static_cast<int>(jobs.size()),
        [&](int i) {
          Job& job = jobs[i];
          const VariantInputs& v = variants[job.variant];
          if (!v.dataset) {
            job.view.error = v.reason;
            return;
          }
          for (auto [name, key] :
               {std::pair{&job.source, &job.source_key}, std::pair{&job.target, &job.target_key}}) {
            if (!shapes_.count(*key)) {
              job.view.error = "shape " + *name + " is not in the dataset of " +
                               VariantConfigPath(v.variant.dir);
              return;
            }
          }
          const double max_error = v.data.Get("summary").Get("max_error").NumberOr(0.25);
          job.view = BuildPairView(shapes_.at(job.source_key), shapes_.at(job.target_key), v.maps,
                                   max_error > 0 ? max_error : 0.25);
          if (!job.view.error.empty()) return;
          job.view.key = SafeFileStem(job.view.key);
          bool fresh = false;
          {
            std::lock_guard<std::mutex> lock(mutex);
            fresh = written.insert(job.view.key).second;
          }
          if (fresh) WriteFile(dir_ / "pairs" / (job.view.key + ".js"), job.view.script);
          job.view.script.clear();
        },
        threads_);
    result->pair_files = static_cast<int>(written.size());

    std::map<std::pair<size_t, size_t>, const Job*> by_row;
    for (const Job& job : jobs) by_row[{job.variant, job.row}] = &job;
    std::set<std::string> reported;  // one warning per distinct reason of a variant
    for (size_t vi = 0; vi < variants.size(); ++vi) {
      JsonValue& data = variants[vi].data;
      JsonValue rows = JsonValue::Array();
      const auto& old_rows = data.Get("pairs").items();
      for (size_t r = 0; r < old_rows.size(); ++r) {
        JsonValue row = old_rows[r];
        const std::string source = row.Get("source").AsString();
        const auto it = by_row.find({vi, r});
        const Job* job = it != by_row.end() ? it->second : nullptr;
        const auto shape = shapes_.find(job && !job->source_key.empty() ? job->source_key : source);
        row.Set("class",
                JsonValue::String(shape != shapes_.end() && !shape->second.class_name.empty()
                                      ? shape->second.class_name
                                      : ClassFromName(source)));
        if (job) {
          const PairView& view = job->view;
          if (view.error.empty()) {
            row.Set("view", JsonValue::String(view.key));  // its file: pairs/KEY.js
            // The meshes' ids in the shape table where they are not the names (another mesh
            // under the same name in an earlier variant).
            if (job->source_key != job->source) {
              row.Set("source_shape", JsonValue::String(job->source_key));
            }
            if (job->target_key != job->target) {
              row.Set("target_shape", JsonValue::String(job->target_key));
            }
            ++result->pairs_viewable;
          } else {
            row.Set("unavailable", JsonValue::String(view.error));
            ++result->pairs_unavailable;
            const std::string warning = variants[vi].variant.name + ": " + source + " -> " +
                                        row.Get("target").AsString() + ": " + view.error;
            if (reported.insert(variants[vi].variant.name + "\n" + view.error).second) {
              result->warnings.push_back(warning);
            }
          }
        }
        rows.Push(row);
      }
      data.Set("pairs", rows);
    }
  }

  int shapes_written() const { return shapes_written_; }

 private:
  fs::path dir_;
  int threads_;
  // The page's id of a mesh: the shape's name for the first mesh seen under the name, the name
  // and a digest of the mesh file's path for another one (a variant that remeshes its shapes).
  // Called in variant order, outside the parallel loops, so the first mesh is the first variant's.
  std::string MeshKey(const DatasetShape& shape) {
    const auto [first, fresh] = first_mesh_.emplace(shape.name, shape.mesh_path);
    if (fresh || first->second == shape.mesh_path) return shape.name;
    return shape.name + "@" +
           HexDigest(HashBytes(shape.mesh_path.data(), shape.mesh_path.size())).substr(0, 8);
  }

  std::map<std::string, ShapeView> shapes_;        // by MeshKey
  std::map<std::string, std::string> first_mesh_;  // mesh path of the first mesh of each name
  int shapes_written_ = 0;
};

// The page's data: title, the variants (with their config changes against the first one and
// why their pairs may lack views), shapes and warnings.
JsonValue ReportData(const std::string& results_dir, std::vector<VariantInputs>& variants,
                     JsonValue shapes, const std::vector<std::string>& warnings) {
  JsonValue report = JsonValue::Object();
  SetTitle(results_dir, variants, &report);
  report.Set("results_dir",
             JsonValue::String(fs::absolute(results_dir).lexically_normal().string()));
  report.Set("rotations", StringArray({"I", "Rx(pi)", "Ry(pi)", "Rz(pi)"}));
  JsonValue list = JsonValue::Array();
  const JsonValue& first_config = variants.front().data.Get("config");
  for (VariantInputs& v : variants) {
    JsonValue data = v.data;
    const JsonValue& config = data.Get("config");
    if (&v != &variants.front() && config.IsString() && first_config.IsString()) {
      data.Set("config_changes",
               StringArray(ConfigDifferences(first_config.AsString(), config.AsString(),
                                             VariantConfigPath(v.variant.dir))));
    }
    data.Set("pairs", Columnar(data.Get("pairs")));
    data.Set("has_records", JsonValue::Bool(!v.maps.records_dir.empty()));
    data.Set("views_note", v.reason.empty() ? JsonValue() : JsonValue::String(v.reason));
    list.Push(data);
  }
  report.Set("variants", list);
  report.Set("shapes", std::move(shapes));
  report.Set("warnings", StringArray(warnings));
  return report;
}

}  // namespace

HtmlReportResult WriteHtmlReport(const std::string& results_dir, const HtmlReportOptions& options,
                                 const Registry& registry) {
  HtmlReportResult result;
  const fs::path out =
      options.out_dir.empty() ? fs::path(results_dir) / "report" : fs::path(options.out_dir);
  std::vector<std::string> found_warnings;
  const std::vector<ReportVariant> found = FindReportVariants(results_dir, &found_warnings);
  result.warnings = found_warnings;
  CheckReplaceable(out);

  std::vector<VariantInputs> variants;
  for (const ReportVariant& variant : found) {
    VariantInputs v;
    v.variant = variant;
    try {
      v.data = VariantReportData(variant);
    } catch (const std::exception& e) {
      result.warnings.push_back(variant.dir + ": left out of the report: " + e.what());
      continue;
    }
    OpenDataset(v, registry);
    if (!v.reason.empty()) result.warnings.push_back(variant.dir + ": " + v.reason);
    variants.push_back(std::move(v));
  }
  if (variants.empty()) {
    throw IoError(results_dir + ": no variant could be read (see the messages above)");
  }

  const fs::path tmp = out.string() + ".tmp-" + std::to_string(getpid());
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  try {
    ReportWriter writer(tmp, options.threads);
    JsonValue shapes = writer.WriteShapes(variants, &result.warnings);
    writer.WritePairs(variants, &result);
    result.shapes = writer.shapes_written();
    const JsonValue data = ReportData(results_dir, variants, std::move(shapes), result.warnings);
    WriteFile(tmp / "data.js", "window.SYMEMBED_REPORT = " + WriteJson(data, 0) + ";\n");
    for (const ReportAsset& asset : ReportAssets()) WriteFile(tmp / asset.name, asset.bytes);
    CheckReplaceable(out);
    fs::remove_all(out);
    if (out.has_parent_path()) fs::create_directories(out.parent_path());
    fs::rename(tmp, out);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(tmp, ignored);
    throw;
  }
  result.variants = static_cast<int>(variants.size());
  result.index_path = (out / "index.html").string();
  result.bytes = FolderBytes(out);
  return result;
}

}  // namespace symembed
