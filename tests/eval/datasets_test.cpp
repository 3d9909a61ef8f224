#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>

#include "core/errors.h"
#include "core/mesh_io.h"
#include "eval/datasets/dataset_files.h"
#include "eval/datasets/kim2011.h"
#include "eval/datasets/pairs_vts.h"
#include "eval/datasets/remeshed_dataset.h"
#include "eval/datasets/same_connectivity.h"
#include "eval/datasets/synthetic_dataset.h"
#include "eval/synthetic/synthetic.h"
#include "registry/registry.h"
#include "tests/eval/dataset_test_util.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;
using testing::WriteText;

const auto Create = testing::CreateDataset;
using testing::ExpectError;
using testing::Tetrahedron;

// --- pairs_vts -------------------------------------------------------------------------------

// cat0, cat1 (4 vertices), dog0, dog1 (5 vertices), TOSCA-like quirks: non-bijective ground
// truth, a trailing blank line in test_pairs.txt, .sym.vts only for the cats.
void WritePairsVtsTree(const std::string& root) {
  WriteText(root + "/shapes/cat0.off", Tetrahedron());
  WriteText(root + "/shapes/cat1.off", Tetrahedron());
  WriteText(root + "/shapes/dog0.off", Tetrahedron(1));
  WriteText(root + "/shapes/dog1.off", Tetrahedron(1));
  WriteText(root + "/corres/cat0.vts", "1\n2\n3\n");
  WriteText(root + "/corres/cat1.vts", "2\n2\n4\n");  // vertex 2 twice: not a bijection
  WriteText(root + "/corres/cat0.sym.vts", "1\n3\n2\n");
  WriteText(root + "/corres/cat1.sym.vts", "2\n4\n2\n");
  WriteText(root + "/corres/dog0.vts", "5\n1\n");
  WriteText(root + "/corres/dog1.vts", "0\n1\n");  // 0: the shape does not have line 1
  WriteText(root + "/corres/cat_sampleID.vts", "1\n");  // ignored
  WriteText(root + "/test_pairs.txt", "cat0\tcat1\ndog0\tdog1\ndog1\tdog0\n\n");
}

TEST(PairsVts, ReadsShapesPairsAndOneBasedGroundTruth) {
  TempDir dir;
  WritePairsVtsTree(dir.path());
  auto dataset = Create("{type: pairs_vts, root: " + dir.path() + "}");
  const DatasetIndex index = dataset->Load();
  ASSERT_EQ(index.shapes.size(), 4u);
  ASSERT_EQ(index.pairs.size(), 3u);
  EXPECT_EQ(index.pairs[2].source, "dog1");
  const DatasetShape* cat1 = index.Find("cat1");
  ASSERT_NE(cat1, nullptr);
  EXPECT_EQ(cat1->class_name, "cat");
  EXPECT_EQ(cat1->mesh_path, dir.path() + "/shapes/cat1.off");
  const ShapeGroundTruth gt = dataset->GroundTruth(*cat1, 4);
  EXPECT_EQ(gt.ids, (std::vector<int>{1, 1, 3}));
  EXPECT_EQ(gt.sym_ids, (std::vector<int>{1, 3, 1}));
  const ShapeGroundTruth dog1 = dataset->GroundTruth(*index.Find("dog1"), 5);
  EXPECT_EQ(dog1.ids, (std::vector<int>{-1, 0}));
  EXPECT_TRUE(dog1.sym_ids.empty());
  const InputGroundTruth pair = PairLines(dataset->GroundTruth(*index.Find("dog0"), 5), dog1);
  EXPECT_EQ(pair.source_ids, (std::vector<int>{0}));
  EXPECT_EQ(pair.target_ids, (std::vector<int>{0}));
}

TEST(PairsVts, RestrictionsSelectClassesPairsAndPairsFile) {
  TempDir dir;
  WritePairsVtsTree(dir.path());
  auto dogs = Create("{type: pairs_vts, root: " + dir.path() + ", classes: [dog], max_pairs: 1}");
  const DatasetIndex index = dogs->Load();
  ASSERT_EQ(index.pairs.size(), 1u);
  EXPECT_EQ(index.pairs[0].source, "dog0");
  EXPECT_EQ(index.shapes.size(), 2u);
  WriteText(dir.File("mine.txt"), "cat1 cat0\n");
  const DatasetIndex own =
      Create("{type: pairs_vts, root: " + dir.path() + ", pairs_file: mine.txt}")->Load();
  ASSERT_EQ(own.pairs.size(), 1u);
  EXPECT_EQ(own.pairs[0].source, "cat1");
  // Without test_pairs.txt: all unordered pairs within each class.
  fs::remove(dir.File("test_pairs.txt"));
  EXPECT_EQ(Create("{type: pairs_vts, root: " + dir.path() + "}")->Load().pairs.size(), 2u);
  ExpectError<InvalidInputError>(
      [&] { Create("{type: pairs_vts, root: " + dir.path() + ", classes: [horse]}")->Load(); },
      {"no shape of class 'horse'", "cat, dog"});
  ExpectError<ConfigError>([&] { Create("{type: pairs_vts}"); }, {"missing required key 'root'"});
  ExpectError<ConfigError>([&] { Create("{type: pairs_vts, root: x, max_pair: 3}"); },
                           {"unknown key 'max_pair'"});
}

TEST(PairsVts, RejectsMalformedInputNamingFileAndLine) {
  TempDir dir;
  const std::string root = dir.path();
  WritePairsVtsTree(root);
  PairsVtsDataset dataset(PairsVtsOptions{root, {}});
  const DatasetShape cat1{"cat1", "cat", root + "/shapes/cat1.off"};

  WriteText(root + "/test_pairs.txt", "cat0\tcat1\ncat0\tcat7\n");
  ExpectError<InvalidInputError>([&] { dataset.Load(); },
                                 {"test_pairs.txt:2: unknown shape 'cat7'", "shapes/cat7.off"});
  WriteText(root + "/test_pairs.txt", "cat0\tcat1\ncat0 cat1 dog0\n");
  ExpectError<InvalidInputError>([&] { dataset.Load(); }, {"test_pairs.txt:2: expected two"});
  WriteText(root + "/test_pairs.txt", "\n");
  ExpectError<InvalidInputError>([&] { dataset.Load(); }, {"test_pairs.txt: no pairs"});
  WriteText(root + "/test_pairs.txt", "cat0\tcat1\n");

  // Ground truth of a different length than its partner's.
  WriteText(root + "/corres/cat1.vts", "2\n2\n4\n1\n");
  WriteText(root + "/corres/cat1.sym.vts", "2\n4\n2\n1\n");
  ExpectError<InvalidInputError>([&] { dataset.Load(); },
                                 {"corres/cat1.vts: 4 lines", "partner", "corres/cat0.vts has 3",
                                  "test_pairs.txt:1"});
  // .sym.vts of a different length than its .vts.
  WriteText(root + "/corres/cat1.vts", "2\n2\n4\n");
  ExpectError<InvalidInputError>([&] { dataset.Load(); },
                                 {"cat1.sym.vts: 4 lines", "cat1.vts has 3"});
  WriteText(root + "/corres/cat1.sym.vts", "2\n4\n2\n");
  EXPECT_NO_THROW(dataset.Load());

  // Ids out of range, not numbers, blank lines inside.
  WriteText(root + "/corres/cat1.vts", "2\n2\n9\n");
  ExpectError<InvalidInputError>([&] { dataset.GroundTruth(cat1, 4); },
                                 {"corres/cat1.vts:3: vertex id 9 out of range [1, 4]"});
  WriteText(root + "/corres/cat1.vts", "2\n-1\n3\n");
  ExpectError<InvalidInputError>([&] { dataset.GroundTruth(cat1, 4); },
                                 {"cat1.vts:2: vertex id -1 out of range"});
  WriteText(root + "/corres/cat1.vts", "2\nx\n3\n");
  ExpectError<InvalidInputError>([&] { dataset.Load(); },
                                 {"cat1.vts:2: expected one integer vertex id, got 'x'"});
  WriteText(root + "/corres/cat1.vts", "2\n\n3\n");
  ExpectError<InvalidInputError>([&] { dataset.Load(); }, {"cat1.vts:2: blank line"});

  // Missing ground truth, missing mesh.
  fs::remove(root + "/corres/cat1.vts");
  ExpectError<InvalidInputError>([&] { dataset.Load(); },
                                 {"missing ground truth", "corres/cat1.vts", "test_pairs.txt:1"});
  WriteText(root + "/corres/cat1.vts", "2\n2\n4\n");
  fs::remove(root + "/shapes/cat0.off");
  ExpectError<InvalidInputError>([&] { dataset.Load(); },
                                 {"test_pairs.txt:1: unknown shape 'cat0'"});
  ExpectError<IoError>([&] { PairsVtsDataset(PairsVtsOptions{root + "/nope", {}}).Load(); },
                       {"not a directory", "nope"});
}

// --- same_connectivity -----------------------------------------------------------------------

// A symbolic link in a loop (or to nothing) among the meshes is a shape that fails when read,
// naming its file, not an error that stops the listing of every other shape.
TEST(ListMeshes, LinksThatResolveToNoFileAreListedToFailAlone) {
  testing::TempDir dir;
  fs::create_directories(dir.File("shapes"));
  testing::WriteText(dir.File("shapes/a.off"), "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  fs::create_symlink("loop.off", dir.File("shapes/loop.off"));
  fs::create_symlink("missing.off", dir.File("shapes/gone.off"));
  fs::create_directories(dir.File("shapes/folder.off"));
  const auto meshes = ListMeshes(dir.File("shapes"));
  ASSERT_EQ(meshes.size(), 3u);
  EXPECT_EQ(meshes[0].first, "a");
  EXPECT_EQ(meshes[1].first, "gone");
  EXPECT_EQ(meshes[2].first, "loop");
  EXPECT_EQ(LoadSurface(meshes[0].second).NumVertices(), 3);
  for (int i : {1, 2}) {
    try {
      LoadSurface(meshes[i].second);
      ADD_FAILURE() << meshes[i].second;
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find(meshes[i].second), std::string::npos) << e.what();
    }
  }
}

TEST(SameConnectivity, IdentityGroundTruthSymmetryFileAndPairs) {
  TempDir dir;
  const std::string root = dir.path();
  WriteText(root + "/scape/mesh000.off", Tetrahedron());
  WriteText(root + "/scape/mesh001.off", Tetrahedron());
  WriteText(root + "/scape/mesh002.off", Tetrahedron());
  WriteText(root + "/scape/sym.txt", "2\n1\n3\n4\n");
  WriteText(root + "/cat/cat0.off", Tetrahedron(1));
  WriteText(root + "/cat/cat1.off", Tetrahedron(1));
  WriteText(root + "/cat/pairs.txt", "cat1\tcat0\n");
  auto dataset = Create("{type: same_connectivity, root: " + root + "}");
  const DatasetIndex index = dataset->Load();
  ASSERT_EQ(index.pairs.size(), 4u);  // cat: listed; scape: all 3 unordered pairs
  EXPECT_EQ(index.pairs[0].source, "cat1");
  EXPECT_EQ(index.Find("mesh001")->class_name, "scape");
  const ShapeGroundTruth gt = dataset->GroundTruth(*index.Find("mesh001"), 4);
  EXPECT_EQ(gt.ids, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(gt.sym_ids, (std::vector<int>{1, 0, 2, 3}));
  EXPECT_TRUE(dataset->GroundTruth(*index.Find("cat0"), 5).sym_ids.empty());
  const DatasetIndex restricted =
      Create("{type: same_connectivity, root: " + root + ", classes: [scape], max_pairs: 2}")
          ->Load();
  EXPECT_EQ(restricted.pairs.size(), 2u);
}

TEST(SameConnectivity, RejectsMalformedInputNamingFileAndLine) {
  TempDir dir;
  const std::string root = dir.path();
  WriteText(root + "/scape/mesh000.off", Tetrahedron());
  WriteText(root + "/scape/mesh001.off", Tetrahedron());
  SameConnectivityDataset dataset(SameConnectivityOptions{root, {}});
  WriteText(root + "/scape/sym.txt", "2\n1\n3\n");
  ExpectError<InvalidInputError>([&] { dataset.Load(); },
                                 {"scape/sym.txt: 3 lines", "have 4 vertices"});
  WriteText(root + "/scape/sym.txt", "2\n1\n3\n5\n");
  ExpectError<InvalidInputError>([&] { dataset.Load(); },
                                 {"scape/sym.txt:4: vertex id 5 out of range [1, 4]"});
  WriteText(root + "/scape/sym.txt", "2\n1\n3\n");  // changed after Load
  ExpectError<InvalidInputError>(
      [&] { dataset.GroundTruth({"mesh000", "scape", root + "/scape/mesh000.off"}, 4); },
      {"sym.txt: 3 lines", "mesh000.off has 4 vertices"});
  WriteText(root + "/scape/sym.txt", "2\n1\n3\n4\n");
  WriteText(root + "/scape/pairs.txt", "mesh000 mesh001\nmesh000 mesh009\n");
  ExpectError<InvalidInputError>([&] { dataset.Load(); },
                                 {"scape/pairs.txt:2: unknown shape 'mesh009'"});
  fs::remove(root + "/scape/pairs.txt");
  WriteText(root + "/other/mesh001.off", Tetrahedron());
  ExpectError<InvalidInputError>([&] { dataset.Load(); }, {"shape name 'mesh001' is used twice"});
  fs::remove_all(root + "/other");
  WriteText(root + "/all_pairs.txt", "mesh000\tmesh001\nmesh001\tmeshX\n");
  SameConnectivityDataset listed(SameConnectivityOptions{root, {{}, 0, "all_pairs.txt"}});
  ExpectError<InvalidInputError>([&] { listed.Load(); },
                                 {"all_pairs.txt:2: unknown shape 'meshX'"});
}

TEST(SameConnectivity, AMeshThatBreaksItsClassTemplateFailsAloneNotTheDataset) {
  TempDir dir;
  const std::string root = dir.path();
  // The first mesh in name order is the odd one: the template is what most meshes have.
  WriteText(root + "/scape/mesh000.off", Tetrahedron(2));
  WriteText(root + "/scape/mesh001.off", Tetrahedron());
  WriteText(root + "/scape/mesh002.off", Tetrahedron());
  WriteText(root + "/scape/sym.txt", "2\n1\n3\n4\n");
  SameConnectivityDataset dataset(SameConnectivityOptions{root, {}});
  const DatasetIndex index = dataset.Load();
  EXPECT_EQ(index.pairs.size(), 3u);
  EXPECT_EQ(dataset.GroundTruth(*index.Find("mesh001"), 4).sym_ids,
            (std::vector<int>{1, 0, 2, 3}));
  ExpectError<InvalidInputError>(
      [&] { dataset.GroundTruth(*index.Find("mesh000"), 6); },
      {root + "/scape/mesh000.off: 6 vertices", "template of class scape", "has 4",
       "2 of its 3 meshes", "mesh001.off"});
  // A tie keeps the count of the first mesh in name order.
  fs::remove(root + "/scape/mesh002.off");
  fs::remove(root + "/scape/sym.txt");
  EXPECT_NO_THROW(dataset.GroundTruth(*index.Find("mesh000"), 6));
  ExpectError<InvalidInputError>([&] { dataset.GroundTruth(*index.Find("mesh001"), 4); },
                                 {"mesh001.off: 4 vertices", "has 6"});
}

// --- kim2011 ---------------------------------------------------------------------------------

// The benchmark's layout in small: SCAPE (one class file for all meshes; mesh003 breaks the
// 6-vertex template), TOSCA (a class file per class; gorilla0 has none), Watertight (a landmark
// file per numbered mesh, classes of 20), and query files for SCAPE and TOSCA.
void WriteKimTree(const std::string& root) {
  const std::string scape = root + "/Data/SCAPE/";
  for (const char* name : {"mesh000", "mesh001", "mesh002"}) {
    WriteText(scape + "Meshes/" + name + ".off", Tetrahedron(2));
  }
  WriteText(scape + "Meshes/mesh003.off", Tetrahedron(1));
  WriteText(scape + "Meshes/mesh000.hks.off", "not a mesh\n");
  WriteText(scape + "Meshes/camera0.txt", "not a mesh\n");
  WriteText(scape + "Corrs/1.pid", "0 0.5 1 2\n5 0.5 1 2\n2 0 0 0\n3 0 0 0\n\n");
  WriteText(scape + "Corrs/1.info", "0: left hand\n1: right hand\n2: nose\n3: navel\n");
  WriteText(scape + "Corrs/1.sym.info", "0 1\n2\n");  // 2 on the plane, 3 not listed
  const std::string tosca = root + "/Data/TOSCA/";
  for (const char* name : {"cat0", "cat1", "cat2", "cat10", "gorilla0"}) {
    WriteText(tosca + "Meshes/" + name + ".off", Tetrahedron());
  }
  WriteText(tosca + "Meshes/david0.off", Tetrahedron(1));
  WriteText(tosca + "Meshes/david1.off", Tetrahedron(1));
  WriteText(tosca + "Corrs/cat.pid", "0 1 1 1\n1 1 1 1\n");
  WriteText(tosca + "Corrs/cat.sym.info", "1 0\n");
  WriteText(tosca + "Corrs/david.pid", "4 0 0 0\n");
  const std::string watertight = root + "/Data/Watertight/";
  for (const char* name : {"1", "2", "21", "22"}) {
    WriteText(watertight + "Meshes/" + name + ".off", Tetrahedron());
  }
  WriteText(watertight + "Corrs/1.vts", "0 0 0 0\n1 0 0 0\n2 0 0 0\n");
  WriteText(watertight + "Corrs/2.vts", "3\n2\n1\n");
  WriteText(watertight + "Corrs/1.sym.info", "0 1\n2\n");
  WriteText(watertight + "Corrs/21.vts", "0\n");
  WriteText(watertight + "Corrs/22.vts", "1\n");
  // Indices in natural name order: SCAPE mesh000..mesh003 = 0..3 (not the .hks.off); TOSCA
  // cat0 cat1 cat2 cat10 david0 david1 gorilla0 = 0..6.
  WriteText(root + "/Results/Corr_SCAPE.query", "SCAPE\n1\n2\nSCAPE\n1\n0\nSCAPE\n1\n3\n");
  WriteText(root + "/Results/Corr_Tosca.query",
            "tosca\n1\n3\n\ntosca\n1\n2\ntosca\n1\n4\ntosca\n1\n5\ntosca\n1\n6\n");
}

std::vector<std::string> PairNames(const DatasetIndex& index) {
  std::vector<std::string> out;
  for (const auto& p : index.pairs) out.push_back(p.source + ">" + p.target);
  return out;
}

TEST(Kim2011, ReadsTheBenchmarkLayoutQueriesAndMirrors) {
  TempDir dir;
  WriteKimTree(dir.path());
  auto dataset = Create("{type: kim2011, root: " + dir.path() + "}");
  const DatasetIndex index = dataset->Load();  // mesh003 breaks its template: not the dataset
  // SCAPE and TOSCA: queried meshes of one class, first queried is the source; Watertight (no
  // query file): all pairs within each class of 20.
  EXPECT_EQ(PairNames(index),
            (std::vector<std::string>{"mesh002>mesh000", "mesh002>mesh003", "mesh000>mesh003",
                                      "cat10>cat2", "david0>david1", "1>2", "21>22"}));
  EXPECT_EQ(index.Find("mesh003")->class_name, "SCAPE/1");
  EXPECT_EQ(index.Find("cat10")->class_name, "TOSCA/cat");
  EXPECT_EQ(index.Find("21")->class_name, "Watertight/21-40");
  EXPECT_EQ(index.Find("cat2")->mesh_path, dir.path() + "/Data/TOSCA/Meshes/cat2.off");
  EXPECT_EQ(index.Find("mesh001"), nullptr);  // in no pair

  const ShapeGroundTruth m0 = dataset->GroundTruth(*index.Find("mesh000"), 6);
  EXPECT_EQ(m0.ids, (std::vector<int>{0, 5, 2, 3}));
  EXPECT_EQ(m0.sym_ids, (std::vector<int>{5, 0, 2, -1}));
  ExpectError<InvalidInputError>(
      [&] { dataset->GroundTruth(*index.Find("mesh003"), 5); },
      {"SCAPE/Meshes/mesh003.off: 5 vertices", "template of class SCAPE/1", "Corrs/1.pid",
       "has 6 (3 of its 4 meshes"});
  const ShapeGroundTruth cat = dataset->GroundTruth(*index.Find("cat10"), 4);
  EXPECT_EQ(cat.ids, (std::vector<int>{0, 1}));
  EXPECT_EQ(cat.sym_ids, (std::vector<int>{1, 0}));
  const ShapeGroundTruth david = dataset->GroundTruth(*index.Find("david1"), 5);
  EXPECT_EQ(david.ids, (std::vector<int>{4}));
  EXPECT_TRUE(david.sym_ids.empty());  // no david.sym.info
  const ShapeGroundTruth w1 = dataset->GroundTruth(*index.Find("1"), 4);
  EXPECT_EQ(w1.ids, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(w1.sym_ids, (std::vector<int>{1, 0, 2}));
  EXPECT_EQ(dataset->GroundTruth(*index.Find("2"), 4).ids, (std::vector<int>{3, 2, 1}));
  ExpectError<InvalidInputError>(
      [&] { dataset->GroundTruth({"gorilla0", "TOSCA/gorilla", dir.path() + "/g.off"}, 4); },
      {"g.off: no landmarks", "Corrs/gorilla0.vts", "Corrs/gorilla.pid"});
}

TEST(Kim2011, RestrictionsSelectSetsClassesAndPairs) {
  TempDir dir;
  WriteKimTree(dir.path());
  const std::string base = "{type: kim2011, root: " + dir.path();
  EXPECT_EQ(PairNames(Create(base + ", classes: [TOSCA]}")->Load()),
            (std::vector<std::string>{"cat10>cat2", "david0>david1"}));
  EXPECT_EQ(PairNames(Create(base + ", classes: [TOSCA/david, Watertight]}")->Load()),
            (std::vector<std::string>{"david0>david1", "1>2", "21>22"}));
  EXPECT_EQ(Create(base + ", max_pairs: 2}")->Load().pairs.size(), 2u);
  WriteText(dir.File("mine.txt"), "cat1 cat0\n");
  EXPECT_EQ(PairNames(Create(base + ", pairs_file: mine.txt}")->Load()),
            (std::vector<std::string>{"cat1>cat0"}));
  ExpectError<InvalidInputError>([&] { Create(base + ", classes: [FAUST]}")->Load(); },
                                 {"classes: 'FAUST' names no set", "SCAPE, TOSCA, Watertight"});
  ExpectError<InvalidInputError>([&] { Create(base + ", classes: [TOSCA/horse]}")->Load(); },
                                 {"no shape of class 'TOSCA/horse'", "TOSCA/cat"});
  ExpectError<ConfigError>([&] { Create(base + ", id_base: 1}"); }, {"unknown key 'id_base'"});
}

TEST(Kim2011, RejectsMalformedInputNamingFileAndLine) {
  TempDir dir;
  const std::string root = dir.path();
  WriteKimTree(root);
  Kim2011Dataset dataset(Kim2011Options{root, {}});
  auto load = [&] { dataset.Load(); };
  const std::string query = root + "/Results/Corr_SCAPE.query";
  const std::vector<std::pair<std::string, std::string>> bad_queries = {
      {"FAUST\n1\n0\n", "Corr_SCAPE.query:1: unknown set 'FAUST'"},
      {"SCAPE\n2\n0\n", "Corr_SCAPE.query:2: expected 1"},
      {"SCAPE\n1\nx\n", "Corr_SCAPE.query:3: expected a mesh index"},
      {"SCAPE\n1\n0\nSCAPE\n1\n", "Corr_SCAPE.query:4: the file ends inside this group"},
      {"SCAPE\n1\n4\n", "Corr_SCAPE.query:3: mesh index 4 of set SCAPE has no mesh"},
      {"SCAPE\n1\n0\n\nSCAPE\n1\n0\n", "Corr_SCAPE.query:7: mesh mesh000 (index 0) is already "
                                       "queried at " + query + ":3"}};
  for (const auto& [text, message] : bad_queries) {
    WriteText(query, text);
    ExpectError<InvalidInputError>(load, {message});
  }
  WriteText(query, "SCAPE\n1\n0\nSCAPE\n1\n1\n");
  EXPECT_NO_THROW(load());

  const std::string pid = root + "/Data/SCAPE/Corrs/1.pid";
  const std::vector<std::pair<std::string, std::string>> bad_pids = {
      {"0\n\n5\n", "1.pid:2: blank line before the last landmark"},
      {"0\nnose 1 2 3\n", "1.pid:2: expected a line starting with a vertex id, got 'nose'"},
      {"0\n-1 0 0 0\n", "1.pid:2: vertex id -1 is negative"},
      {"\n", "1.pid:1: no landmark lines"}};
  for (const auto& [text, message] : bad_pids) {
    WriteText(pid, text);
    ExpectError<InvalidInputError>(load, {message});
  }
  WriteText(pid, "0\n9\n2\n3\n");
  EXPECT_NO_THROW(load());
  const DatasetShape mesh000{"mesh000", "SCAPE/1", root + "/Data/SCAPE/Meshes/mesh000.off"};
  ExpectError<InvalidInputError>([&] { dataset.GroundTruth(mesh000, 6); },
                                 {"1.pid:2: vertex id 9 out of range [0, 5]", "mesh000.off"});

  const std::string sym = root + "/Data/SCAPE/Corrs/1.sym.info";
  const std::vector<std::pair<std::string, std::string>> bad_mirrors = {
      {"0 1 2\n", "1.sym.info:1: expected one or two landmark lines"},
      {"0 1\n3 7\n", "1.sym.info:2: '7' is not a landmark line of " + pid + " (0 to 3)"},
      {"0 1\n1 2\n", "1.sym.info:2: landmark line 1 already listed on line 1"}};
  for (const auto& [text, message] : bad_mirrors) {
    WriteText(sym, text);
    ExpectError<InvalidInputError>(load, {message});
  }
  WriteText(sym, "0 1\n");

  WriteText(root + "/Data/Watertight/Corrs/2.vts", "3\n2\n");
  ExpectError<InvalidInputError>(load, {"pair 1 -> 2 has landmark files of different lengths",
                                        "Corrs/1.vts has 3 lines", "Corrs/2.vts has 2"});
  WriteText(root + "/Data/Watertight/Corrs/2.vts", "3\n2\n1\n");

  WriteText(root + "/pairs.txt", "cat0 cat1\ncat0 horse0\n");
  Kim2011Dataset listed(Kim2011Options{root, {{}, 0, "pairs.txt"}});
  ExpectError<InvalidInputError>([&] { listed.Load(); },
                                 {"pairs.txt:2: unknown shape 'horse0'"});
  WriteText(root + "/pairs.txt", "cat0 david0\n");
  ExpectError<InvalidInputError>([&] { listed.Load(); },
                                 {"pairs.txt:1: shapes 'cat0' (TOSCA/cat) and 'david0' "
                                  "(TOSCA/david) are in different classes"});

  WriteText(root + "/Data/Other/Meshes/cat0.off", Tetrahedron());
  ExpectError<InvalidInputError>(load, {"shape name 'cat0' is used twice"});
  ExpectError<IoError>([&] { Kim2011Dataset(Kim2011Options{root + "/x", {}}).Load(); },
                       {"not a directory", "/x/Data"});
}

// --- synthetic -------------------------------------------------------------------------------

TEST(SyntheticDataset, OnePoseCannotFormAPair) {
  try {
    Create("{type: synthetic, poses: 1}");
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(
        std::string(e.what()).find("poses: pairs are formed between poses: needs >= 2, got 1"),
        std::string::npos)
        << e.what();
  }
}

TEST(SyntheticDataset, AnAnisotropicRemeshingNeedsARemeshing) {
  ExpectError<ConfigError>([&] { Create("{type: synthetic, remesh_anisotropy: 3}"); },
                           {"remesh_anisotropy: needs remesh > 0"});
  ExpectError<ConfigError>(
      [&] { Create("{type: synthetic, remesh: 500, remesh_anisotropy: 0.5}"); },
      {"remesh_anisotropy"});
  EXPECT_NO_THROW(Create("{type: synthetic, remesh: 500, remesh_anisotropy: 3}"));
}

TEST(SyntheticDataset, GeneratesIntoTheCacheOnceAndReadsIt) {
  TempDir dir;
  const std::string yaml = "{type: synthetic, kinds: [humanoid, quadruped], poses: 3, vertices: 800, "
                           "partial: 0.34, cache: " + dir.File("cache") + "}";
  auto dataset = Create(yaml);
  const DatasetIndex index = dataset->Load();
  ASSERT_EQ(index.shapes.size(), 6u);
  ASSERT_EQ(index.pairs.size(), 6u);
  EXPECT_EQ(index.Find("quadruped2")->class_name, "quadruped");
  const std::string readme = dir.File("cache/README.md");
  const auto written = fs::last_write_time(readme);
  const DatasetShape& s = *index.Find("humanoid1");
  const int n = CountMeshVertices(s.mesh_path);
  const ShapeGroundTruth gt = dataset->GroundTruth(s, n);
  EXPECT_FALSE(gt.ids.empty());
  EXPECT_EQ(gt.sym_ids.size(), gt.ids.size());
  // A second dataset with the same cache reads it without generating again.
  auto again = Create(yaml);
  EXPECT_EQ(again->Load().pairs.size(), 6u);
  EXPECT_EQ(fs::last_write_time(readme), written);
  // Restrictions apply to the generated data.
  auto restricted = Create("{type: synthetic, kinds: [humanoid, quadruped], poses: 3, "
                           "vertices: 800, partial: 0.34, classes: [quadruped], max_pairs: 2, "
                           "cache: " + dir.File("cache") + "}");
  EXPECT_EQ(restricted->Load().pairs.size(), 2u);
}

TEST(SyntheticDataset, DefaultCacheIsKeyedByTheGeneratorOptions) {
  auto a = Create("{type: synthetic, poses: 3}");
  auto b = Create("{type: synthetic, poses: 3, seed: 2}");
  auto c = Create("{type: synthetic, poses: 3, max_pairs: 1}");
  const auto* sa = dynamic_cast<SyntheticDataset*>(a.get());
  const auto* sb = dynamic_cast<SyntheticDataset*>(b.get());
  const auto* sc = dynamic_cast<SyntheticDataset*>(c.get());
  ASSERT_TRUE(sa && sb && sc);
  EXPECT_EQ(sa->cache().rfind("results/.cache/synthetic/", 0), 0u) << sa->cache();
  EXPECT_NE(sa->cache(), sb->cache());
  EXPECT_EQ(sa->cache(), sc->cache());  // restrictions do not change what is generated
  ExpectError<ConfigError>([&] { Create("{type: synthetic, kinds: [horse]}"); },
                           {"dataset.kinds", "invalid kind 'horse'"});
  ExpectError<ConfigError>([&] { Create("{type: synthetic, noise: 2}"); },
                           {"dataset.noise", "must be in [0, 1], got 2"});
  ExpectError<ConfigError>([&] { Create("{type: synthetic, pose: 3}"); }, {"unknown key 'pose'"});
}

// --- pairs_vts through a remeshing ------------------------------------------------------------

TEST(RemeshedPairsVts, RemeshesIntoTheCacheOnceAndReadsIt) {
  TempDir dir;
  SynthOptions o;
  o.kinds = {FigureKind::kHumanoid};
  o.poses = 3;
  o.vertices = 900;
  WriteSyntheticDataset(dir.File("in"), o);
  WriteText(dir.File("in/two_pairs.txt"), "humanoid0 humanoid1\nhumanoid1 humanoid2\n");
  const std::string yaml = "{type: pairs_vts, root: " + dir.File("in") +
                           ", remesh: 400, remesh_anisotropy: 3, cache: " + dir.File("cache") + "}";
  auto dataset = Create(yaml);
  ASSERT_NE(dynamic_cast<RemeshedDataset*>(dataset.get()), nullptr);
  const DatasetIndex index = dataset->Load();
  ASSERT_EQ(index.shapes.size(), 3u);
  ASSERT_EQ(index.pairs.size(), 3u);
  const DatasetShape& s = *index.Find("humanoid1");
  EXPECT_EQ(s.mesh_path.rfind(dir.File("cache"), 0), 0u) << s.mesh_path;
  const int n = CountMeshVertices(s.mesh_path);
  EXPECT_LE(n, 420);
  const ShapeGroundTruth gt = dataset->GroundTruth(s, n);
  EXPECT_EQ(gt.sym_ids.size(), gt.ids.size());
  EXPECT_EQ(std::count_if(gt.ids.begin(), gt.ids.end(), [](int v) { return v >= 0; }), n);
  // Read again without remeshing; restrictions apply, a pairs file is the input's.
  const std::string readme = dir.File("cache/README.md");
  const auto written = fs::last_write_time(readme);
  auto restricted = Create("{type: pairs_vts, root: " + dir.File("in") +
                           ", remesh: 400, remesh_anisotropy: 3, pairs_file: two_pairs.txt, "
                           "max_pairs: 1, cache: " +
                           dir.File("cache") + "}");
  const DatasetIndex one = restricted->Load();
  ASSERT_EQ(one.pairs.size(), 1u);
  EXPECT_EQ(one.pairs[0].source, "humanoid0");
  EXPECT_EQ(fs::last_write_time(readme), written);
}

TEST(RemeshedPairsVts, DefaultCacheFollowsTheOptionsAndTheInputFiles) {
  TempDir dir;
  WritePairsVtsTree(dir.File("in"));
  auto key = [&](const std::string& extra) {
    auto d = Create("{type: pairs_vts, root: " + dir.File("in") + ", remesh: 100" + extra + "}");
    const auto* r = dynamic_cast<RemeshedDataset*>(d.get());
    EXPECT_NE(r, nullptr);
    return r ? r->cache() : std::string();
  };
  const std::string a = key("");
  EXPECT_EQ(a.rfind("results/.cache/remeshed/", 0), 0u) << a;
  EXPECT_EQ(key(""), a);
  EXPECT_EQ(key(", max_pairs: 1"), a);  // restrictions do not change what is remeshed
  EXPECT_NE(key(", remesh_seed: 2"), a);
  EXPECT_NE(key(", remesh_anisotropy: 2"), a);
  EXPECT_NE(key(", remesh_subdivide: 1"), a);
  WriteText(dir.File("in/corres/dog1.vts"), "1\n2\n3\n");  // an edited ground truth
  EXPECT_NE(key(""), a);
  // Without remesh the loader reads the files themselves; remeshing options alone are errors.
  EXPECT_NE(dynamic_cast<PairsVtsDataset*>(
                Create("{type: pairs_vts, root: " + dir.File("in") + "}").get()),
            nullptr);
  ExpectError<ConfigError>(
      [&] { Create("{type: pairs_vts, root: " + dir.File("in") + ", remesh_anisotropy: 3}"); },
      {"remesh_anisotropy", "needs remesh > 0"});
  ExpectError<ConfigError>(
      [&] { Create("{type: pairs_vts, root: " + dir.File("in") + ", remesh_subdivide: 1}"); },
      {"remesh_subdivide", "needs remesh > 0"});
  ExpectError<ConfigError>(
      [&] { Create("{type: pairs_vts, root: " + dir.File("in") + ", remesh: 20}"); },
      {"dataset.remesh", "below 50"});
}

TEST(RemeshedPairsVts, BadInputIsNamedAndLeavesNoCache) {
  TempDir dir;
  WritePairsVtsTree(dir.File("in"));
  // Tetrahedra have 4 and 5 vertices, fewer than the target: copied as they are.
  auto dataset = Create("{type: pairs_vts, root: " + dir.File("in") +
                        ", remesh: 60, cache: " + dir.File("cache") + "}");
  EXPECT_EQ(dataset->Load().pairs.size(), 3u);
  // A broken ground-truth file is reported with its path.
  WriteText(dir.File("in/corres/cat1.vts"), "2\n2\n99\n");
  auto broken = Create("{type: pairs_vts, root: " + dir.File("in") +
                       ", remesh: 60, cache: " + dir.File("cache2") + "}");
  ExpectError<InvalidInputError>([&] { broken->Load(); }, {"cat1.vts"});
  EXPECT_FALSE(fs::exists(dir.File("cache2")));
  // So is a mesh the decimation cannot take: a face on an edge that has two already.
  SynthOptions o;
  o.poses = 2;
  o.vertices = 900;
  WriteSyntheticDataset(dir.File("synth"), o);
  Surface s = LoadSurface(dir.File("synth/shapes/humanoid1.off"));
  s.V.conservativeResize(s.V.rows() + 1, 3);
  s.V.row(s.V.rows() - 1) << 5.0, 5.0, 5.0;
  s.F.conservativeResize(s.F.rows() + 1, 3);
  s.F.row(s.F.rows() - 1) << s.F(0, 0), s.F(0, 1), static_cast<int>(s.V.rows() - 1);
  SaveMesh(dir.File("synth/shapes/humanoid1.off"), s);
  auto bad_mesh = Create("{type: pairs_vts, root: " + dir.File("synth") +
                         ", remesh: 400, cache: " + dir.File("cache3") + "}");
  ExpectError<InvalidInputError>([&] { bad_mesh->Load(); },
                                 {"humanoid1.off", "cannot be remeshed"});
  EXPECT_FALSE(fs::exists(dir.File("cache3")));
  // With a subdivision first, the subdivision is what refuses it.
  auto bad_subdivided =
      Create("{type: pairs_vts, root: " + dir.File("synth") +
             ", remesh: 4000, remesh_subdivide: 1, cache: " + dir.File("cache4") + "}");
  ExpectError<InvalidInputError>([&] { bad_subdivided->Load(); },
                                 {"humanoid1.off", "cannot be subdivided"});
  EXPECT_FALSE(fs::exists(dir.File("cache4")));
}

}  // namespace
}  // namespace symembed
