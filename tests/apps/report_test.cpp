// `symembed report` on a small run: the page's data matches the run's files, every pair has
// its 3D data, and bad input (no results, a run in progress, a truncated mesh, a map of the
// wrong length, a missing dataset) is named in errors without losing the rest of the report.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>

#include "core/errors.h"
#include "core/map_io.h"
#include "eval/json.h"
#include "harness/html/html_report.h"
#include "harness/html/report_data.h"
#include "registry/registry.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

using testing::Symembed;

namespace fs = std::filesystem;
using testing::ReadText;
using testing::TempDir;
using testing::WriteText;

// The JSON of a report's data.js, each variant's pairs expanded from {columns, rows} to objects.
JsonValue ReportJson(const std::string& report_dir) {
  const std::string text = ReadText(report_dir + "/data.js");
  const std::string prefix = "window.SYMEMBED_REPORT = ";
  EXPECT_EQ(text.rfind(prefix, 0), 0u);
  const size_t end = text.rfind(';');
  JsonValue report =
      ParseJson(text.substr(prefix.size(), end - prefix.size()), report_dir + "/data.js");
  JsonValue variants = JsonValue::Array();
  for (JsonValue variant : report.Get("variants").items()) {
    const JsonValue& table = variant.Get("pairs");
    JsonValue pairs = JsonValue::Array();
    for (const JsonValue& row : table.Get("rows").items()) {
      JsonValue pair = JsonValue::Object();
      for (size_t c = 0; c < row.items().size(); ++c) {
        if (!row.items()[c].IsNull()) {
          pair.Set(table.Get("columns").items()[c].AsString(), row.items()[c]);
        }
      }
      pairs.Push(pair);
    }
    variant.Set("pairs", pairs);
    variants.Push(variant);
  }
  report.Set("variants", variants);
  return report;
}

const JsonValue* FindPair(const JsonValue& variant, const std::string& source,
                          const std::string& target) {
  for (const JsonValue& p : variant.Get("pairs").items()) {
    if (p.Get("source").AsString() == source && p.Get("target").AsString() == target) return &p;
  }
  return nullptr;
}

// One run shared by the tests: 4 poses of the synthetic humanoid (6 pairs), two variants.
class ReportTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = std::make_unique<TempDir>();
    std::string log;
    ASSERT_EQ(Symembed("synth --poses 4 --vertices 600 --out " + tmp_->File("data"), &log), 0)
        << log;
    WriteText(tmp_->File("config.yaml"),
              "name: small\n"
              "description: a small report test\n"
              "dataset: {format: pairs_vts, root: " +
                  tmp_->File("data") +
                  "}\n"
                  "pipeline:\n"
                  "  sampling: {type: farthest_point, count: 80}\n"
                  "  symmetry: {type: plane3d}\n"
                  "evaluation: {geodesics: dijkstra}\n"
                  "variants:\n"
                  "  - {name: oracle, set: {pipeline.flip.type: oracle}}\n");
    ASSERT_EQ(Symembed("run " + tmp_->File("config.yaml") + " --quiet --jobs 2 --cache " +
                           tmp_->File("cache") + " --out " + tmp_->File("run"),
                       &log),
              0)
        << log;
    run_log_ = log;
  }
  static void TearDownTestSuite() { tmp_.reset(); }

  // A copy of the run to damage.
  std::string CopyOfRun(const std::string& name) {
    const std::string dir = tmp_->File(name);
    fs::remove_all(dir);
    fs::copy(tmp_->File("run"), dir, fs::copy_options::recursive);
    fs::remove_all(dir + "/report");
    return dir;
  }

  // A copy of the run's data at tmp_/NAME, with the configs of `variants` in `run` pointed at it.
  std::string CopyOfDataFor(const std::string& run, const std::string& name,
                            std::initializer_list<const char*> variants) {
    const std::string data = tmp_->File(name);
    fs::remove_all(data);
    fs::copy(tmp_->File("data"), data, fs::copy_options::recursive);
    const std::string from = tmp_->File("data");
    for (const char* variant : variants) {
      const std::string config = run + "/" + variant + "/config.yaml";
      std::string text = ReadText(config);
      for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at)) {
        text.replace(at, from.size(), data);
        at += data.size();
      }
      WriteText(config, text);
    }
    return data;
  }

  HtmlReportResult Report(const std::string& results, const std::string& out) {
    Registry registry;
    RegisterBuiltinStages(registry);
    HtmlReportOptions options;
    options.out_dir = out;
    return WriteHtmlReport(results, options, registry);
  }

  static std::unique_ptr<TempDir> tmp_;
  static std::string run_log_;
};

std::unique_ptr<TempDir> ReportTest::tmp_;
std::string ReportTest::run_log_;

TEST_F(ReportTest, RunWritesItsReportAndSaysWhere) {
  EXPECT_NE(run_log_.find("report: " + tmp_->File("run") + "/report/index.html"), std::string::npos)
      << run_log_;
  for (const char* file :
       {"index.html", "data.js", "report.css", "page.js", "plot.js", "viewer.js", "transfer.js",
        "sidefiles.js", "experiment.js", "pairs.js", "report.js"}) {
    EXPECT_TRUE(fs::exists(tmp_->File("run/report/") + file)) << file;
  }
}

TEST_F(ReportTest, DataMatchesSummaryJsonAndPairsCsv) {
  const JsonValue report = ReportJson(tmp_->File("run/report"));
  EXPECT_EQ(report.Get("title").AsString(), "small");
  EXPECT_EQ(report.Get("description").AsString(), "a small report test");
  const auto& variants = report.Get("variants").items();
  ASSERT_EQ(variants.size(), 2u);
  const char* names[] = {"base", "oracle"};
  for (size_t i = 0; i < variants.size(); ++i) {
    const JsonValue& v = variants[i];
    EXPECT_EQ(v.Get("name").AsString(), names[i]);
    const std::string summary = tmp_->File("run/") + names[i] + "/summary.json";
    // Same keys, same order, same numbers (written back exactly).
    EXPECT_EQ(WriteJson(v.Get("summary")), WriteJson(ParseJson(ReadText(summary), summary)));
    EXPECT_EQ(v.Get("pairs").items().size(), 6u);
    EXPECT_EQ(v.Get("curve").Get("threshold").items().size(),
              v.Get("curve").Get("direct").items().size());
    EXPECT_TRUE(v.Get("config").IsString());
    EXPECT_TRUE(v.Get("stage_seconds").Get("pair").Has("flip"));
    for (const JsonValue& p : v.Get("pairs").items()) {
      EXPECT_EQ(p.Get("status").AsString(), "ok");
      EXPECT_EQ(p.Get("class").AsString(), "humanoid");
      EXPECT_TRUE(p.Get("mean_direct").IsNumber());
      EXPECT_EQ(p.Get("candidate_errors").items().size(), 4u);
      EXPECT_TRUE(p.Get("seconds").Has("matching"));
      ASSERT_TRUE(p.Get("view").IsString()) << p.Get("unavailable").IsString();
      EXPECT_TRUE(fs::exists(tmp_->File("run/report/pairs/") + p.Get("view").AsString() + ".js"));
    }
  }
  // The oracle variant differs from base in its flip stage.
  const auto& changes = variants[1].Get("config_changes").items();
  ASSERT_FALSE(changes.empty());
  bool flip_type = false;
  for (const JsonValue& c : changes) flip_type |= c.AsString().rfind("pipeline.flip.type:", 0) == 0;
  EXPECT_TRUE(flip_type);
  // One side file per shape, shared by both variants.
  EXPECT_EQ(report.Get("shapes").members().size(), 4u);
  for (const auto& [name, shape] : report.Get("shapes").members()) {
    EXPECT_TRUE(fs::exists(tmp_->File("run/report/") + shape.Get("file").AsString())) << name;
  }
  EXPECT_TRUE(report.Get("warnings").items().empty());
}

TEST_F(ReportTest, MissingOrUnfinishedResultsAreErrorsNamingThePath) {
  const std::string missing = tmp_->File("no_such_results");
  try {
    Report(missing, tmp_->File("out_missing"));
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  // A run that has started: variants.txt and a variant folder, no summary.json yet.
  const std::string started = tmp_->File("started");
  WriteText(started + "/variants.txt", "base\n");
  WriteText(started + "/base/config.yaml", "name: x\n");
  try {
    Report(started, tmp_->File("out_started"));
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(started), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("in progress"), std::string::npos) << e.what();
  }
  std::string out;
  EXPECT_EQ(Symembed("report " + missing, &out), 1);
  EXPECT_NE(out.find(missing), std::string::npos) << out;
  EXPECT_EQ(Symembed("report", &out), 2) << out;
}

// `symembed run --variant base` lists every variant in variants.txt but writes one folder: the
// others are left out without a warning; a folder without summary.json is still running.
TEST_F(ReportTest, VariantsNotRunAreLeftOutAndUnfinishedOnesWarned) {
  const std::string run = CopyOfRun("one_variant");
  fs::remove_all(run + "/oracle");
  HtmlReportResult result = Report(run, run + "/report");
  EXPECT_EQ(result.variants, 1);
  EXPECT_TRUE(result.warnings.empty()) << result.warnings.front();
  fs::copy(tmp_->File("run/oracle"), run + "/oracle", fs::copy_options::recursive);
  fs::remove(run + "/oracle/summary.json");
  result = Report(run, run + "/report");
  EXPECT_EQ(result.variants, 1);
  ASSERT_EQ(result.warnings.size(), 1u);
  EXPECT_NE(result.warnings[0].find(run + "/oracle/summary.json"), std::string::npos);
}

TEST_F(ReportTest, AMapOfTheWrongLengthMakesOnlyItsPairUnavailable) {
  const std::string run = CopyOfRun("bad_map");
  const JsonValue good = ReportJson(tmp_->File("run/report"));
  const JsonValue& first = good.Get("variants").items()[0].Get("pairs").items()[0];
  const std::string source = first.Get("source").AsString();
  const std::string target = first.Get("target").AsString();
  const std::string map = run + "/base/maps/" + source + "_" + target + ".map";
  WriteText(map, "1\n2\n3\n");
  const HtmlReportResult result = Report(run, run + "/report");
  EXPECT_EQ(result.pairs_unavailable, 1);
  EXPECT_EQ(result.pairs_viewable, 11);
  const JsonValue report = ReportJson(run + "/report");
  const JsonValue* pair = FindPair(report.Get("variants").items()[0], source, target);
  ASSERT_NE(pair, nullptr);
  ASSERT_TRUE(pair->Get("unavailable").IsString());
  EXPECT_NE(pair->Get("unavailable").AsString().find(map), std::string::npos)
      << pair->Get("unavailable").AsString();
  // The other variant's map of the same pair is intact.
  EXPECT_TRUE(FindPair(report.Get("variants").items()[1], source, target)->Get("view").IsString());
}

TEST_F(ReportTest, AnUnreadableMeshMakesItsPairsUnavailableNamingTheFile) {
  const std::string run = CopyOfRun("bad_mesh");
  // Point the run's configs at a copy of the data, then truncate one mesh there.
  const std::string data = CopyOfDataFor(run, "data_bad_mesh", {"base", "oracle"});
  std::string mesh;
  for (const auto& e : fs::directory_iterator(data + "/shapes")) mesh = e.path().string();
  WriteText(mesh, "OFF\n3 1 0\n0 0 0\n");
  const HtmlReportResult result = Report(run, run + "/report");
  // The shape is in 3 of the 6 pairs of each variant.
  EXPECT_EQ(result.pairs_unavailable, 6);
  EXPECT_EQ(result.pairs_viewable, 6);
  bool named = false;
  for (const std::string& w : result.warnings) named |= w.find(mesh) != std::string::npos;
  EXPECT_TRUE(named) << "no warning names " << mesh;
  // The tables are all there.
  EXPECT_EQ(ReportJson(run + "/report").Get("variants").items().size(), 2u);
}

// A variant whose dataset has another mesh under a name (here a copy of the data elsewhere; in
// practice a remeshed variant) gets its own entries in the shape table, and its pair rows name
// them, so its maps are drawn on the meshes they map.
TEST_F(ReportTest, AVariantWithOtherMeshesUnderTheSameNamesIsDrawnOnItsOwn) {
  const std::string run = CopyOfRun("other_meshes");
  const std::string data = CopyOfDataFor(run, "data_other_meshes", {"oracle"});
  const HtmlReportResult result = Report(run, run + "/report");
  EXPECT_EQ(result.pairs_viewable, 12);
  EXPECT_EQ(result.pairs_unavailable, 0);
  EXPECT_TRUE(result.warnings.empty());
  const JsonValue report = ReportJson(run + "/report");
  const JsonValue& shapes = report.Get("shapes");
  EXPECT_EQ(shapes.members().size(), 8u);  // 4 names, 2 meshes each
  const auto& variants = report.Get("variants").items();
  ASSERT_EQ(variants.size(), 2u);
  for (const JsonValue& pair : variants[0].Get("pairs").items()) {
    EXPECT_FALSE(pair.Has("source_shape"));
    EXPECT_FALSE(pair.Has("target_shape"));
  }
  for (const JsonValue& pair : variants[1].Get("pairs").items()) {
    for (const char* end : {"source", "target"}) {
      const std::string id = pair.Get(std::string(end) + "_shape").AsString();
      const JsonValue& shape = shapes.Get(id);
      EXPECT_EQ(shape.Get("name").AsString(), pair.Get(end).AsString()) << id;
      // The side file holds the copy's mesh under the id.
      const std::string side = ReadText(run + "/report/" + shape.Get("file").AsString());
      EXPECT_NE(side.find("\"" + id + "\""), std::string::npos) << id;
    }
  }
}

// A remeshed variant: the page draws each variant's maps on its own meshes (vertex counts of the
// shape entries and of the maps agree), whatever the order of the variants.
TEST(ReportMeshes, ARemeshedVariantIsDrawnOnItsOwnMeshes) {
  TempDir tmp;
  WriteText(tmp.File("config.yaml"),
            "name: remeshed\n"
            "dataset: {format: synthetic, kinds: [humanoid], poses: 3, vertices: 600, seed: 3}\n"
            "pipeline:\n"
            "  sampling: {type: farthest_point, count: 80}\n"
            "  symmetry: {type: plane3d}\n"
            "  flip: {type: oracle}\n"
            "evaluation: {geodesics: dijkstra}\n"
            "variants:\n"
            "  - {name: remeshed, set: {dataset.remesh: 400}}\n");
  std::string log;
  ASSERT_EQ(Symembed("run " + tmp.File("config.yaml") + " --quiet --jobs 2 --cache " +
                         tmp.File("cache") + " --out " + tmp.File("run"),
                     &log),
            0)
      << log;
  const JsonValue report = ReportJson(tmp.File("run/report"));
  // Nothing left out: no shape or pair of either variant is unavailable.
  EXPECT_TRUE(report.Get("warnings").items().empty()) << log;
  const JsonValue& shapes = report.Get("shapes");
  EXPECT_EQ(shapes.members().size(), 6u);
  const auto& variants = report.Get("variants").items();
  ASSERT_EQ(variants.size(), 2u);
  for (size_t vi = 0; vi < 2; ++vi) {
    ASSERT_FALSE(variants[vi].Get("pairs").items().empty());
    for (const JsonValue& pair : variants[vi].Get("pairs").items()) {
      ASSERT_TRUE(pair.Get("view").IsString()) << variants[vi].Get("name").AsString();
      const std::string id = pair.Has("source_shape") ? pair.Get("source_shape").AsString()
                                                      : pair.Get("source").AsString();
      EXPECT_EQ(pair.Has("source_shape"), vi == 1);
      const int vertices = static_cast<int>(shapes.Get(id).Get("vertices").AsNumber());
      if (vi == 0) {
        EXPECT_GT(vertices, 500) << id;
      } else {
        EXPECT_LE(vertices, 400) << id;
      }
      // The variant's own map of the pair has one entry per vertex of the mesh drawn.
      const std::string map =
          tmp.File("run/" + variants[vi].Get("name").AsString() + "/maps/" +
                   pair.Get("source").AsString() + "_" + pair.Get("target").AsString() + ".map");
      EXPECT_EQ(static_cast<int>(ReadMapFile(map, 1, -1, -1).size()), vertices) << map;
    }
  }
}

TEST_F(ReportTest, AMissingDatasetLeavesTheTablesAndSaysWhy) {
  const std::string run = CopyOfRun("no_data");
  for (const char* variant : {"base", "oracle"}) {
    const std::string config = run + "/" + variant + "/config.yaml";
    std::string text = ReadText(config);
    const std::string from = tmp_->File("data");
    text.replace(text.find(from), from.size(), tmp_->File("moved_data"));
    WriteText(config, text);
  }
  const HtmlReportResult result = Report(run, run + "/report");
  EXPECT_EQ(result.pairs_viewable, 0);
  EXPECT_EQ(result.pairs_unavailable, 12);
  const JsonValue report = ReportJson(run + "/report");
  const JsonValue& base = report.Get("variants").items()[0];
  ASSERT_TRUE(base.Get("views_note").IsString());
  EXPECT_NE(base.Get("views_note").AsString().find(tmp_->File("moved_data")), std::string::npos)
      << base.Get("views_note").AsString();
  EXPECT_EQ(base.Get("pairs").items().size(), 6u);
}

// symembed eval keeps its inputs (eval.json), so its report finds the meshes and maps; it keeps
// no per-pair records, so the views have no heat map and say why.
TEST_F(ReportTest, AnEvalFolderHasItsMapsButNoPerPointErrors) {
  const std::string out = tmp_->File("eval_out");
  std::string log;
  ASSERT_EQ(
      Symembed("eval --dataset " + tmp_->File("config.yaml") + " --maps " +
                   tmp_->File("run/oracle/maps") + " --base 1 --name scored --jobs 2 --out " + out,
               &log),
      0)
      << log;
  EXPECT_NE(log.find("report: " + out + "/report/index.html"), std::string::npos) << log;
  const JsonValue report = ReportJson(out + "/report");
  EXPECT_EQ(report.Get("title").AsString(), "scored");
  const auto& variants = report.Get("variants").items();
  ASSERT_EQ(variants.size(), 1u);
  EXPECT_EQ(variants[0].Get("name").AsString(), "scored");
  EXPECT_FALSE(variants[0].Get("has_records").AsBool());
  ASSERT_EQ(variants[0].Get("pairs").items().size(), 6u);
  const JsonValue& pair = variants[0].Get("pairs").items()[0];
  ASSERT_TRUE(pair.Get("view").IsString());
  const std::string side = ReadText(out + "/report/pairs/" + pair.Get("view").AsString() + ".js");
  const JsonValue payload =
      ParseJson(side.substr(side.find('{'), side.rfind('}') - side.find('{') + 1), "side file");
  EXPECT_TRUE(payload.Get("map").IsObject());
  EXPECT_FALSE(payload.Has("errors"));
  EXPECT_NE(payload.Get("errors_note").AsString().find("symembed eval"), std::string::npos);
}

TEST_F(ReportTest, RefusesToReplaceAFolderThatIsNotAReport) {
  const std::string out = tmp_->File("not_a_report");
  WriteText(out + "/notes.txt", "mine\n");
  EXPECT_THROW(Report(tmp_->File("run"), out), IoError);
  EXPECT_TRUE(fs::exists(out + "/notes.txt"));
}

TEST(ConfigDifferences, ListsChangedAddedAndRemovedLeaves) {
  const std::vector<std::string> d = ConfigDifferences(
      "pipeline: {flip: {type: extrinsic, k: 3}, matching: {type: nearest}}\nlist: [1, 2]\n",
      "pipeline: {flip: {type: oracle}, matching: {type: nearest}}\nlist: [1, 3]\nnew: 1\n",
      "test");
  EXPECT_EQ(d, (std::vector<std::string>{"list: [1, 2] -> [1, 3]", "new: (none) -> 1",
                                         "pipeline.flip.k: 3 -> (none)",
                                         "pipeline.flip.type: extrinsic -> oracle"}));
}

}  // namespace
}  // namespace symembed
