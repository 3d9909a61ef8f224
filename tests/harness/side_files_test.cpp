// The side-file encoding of the HTML report (harness/html/side_files.h): what the page decodes
// (harness/html/assets/sidefiles.js, transfer.js).
#include "harness/html/side_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/errors.h"
#include "core/primitives.h"

namespace symembed {
namespace {

TEST(SideFiles, Base64MatchesTheRfc4648Vectors) {
  const std::pair<std::string, std::string> vectors[] = {{"", ""},
                                                         {"f", "Zg=="},
                                                         {"fo", "Zm8="},
                                                         {"foo", "Zm9v"},
                                                         {"foob", "Zm9vYg=="},
                                                         {"fooba", "Zm9vYmE="},
                                                         {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : vectors) {
    EXPECT_EQ(Base64Encode(plain), encoded);
    EXPECT_EQ(Base64Decode(encoded), plain);
  }
  std::string all_bytes;
  for (int b = 0; b < 256; ++b) all_bytes += static_cast<char>(b);
  EXPECT_EQ(Base64Decode(Base64Encode(all_bytes)), all_bytes);
  EXPECT_THROW(Base64Decode("Zm9"), InvalidInputError);
  EXPECT_THROW(Base64Decode("Zm*v"), InvalidInputError);
  EXPECT_THROW(Base64Decode("Zg==Zg=="), InvalidInputError);
}

TEST(SideFiles, ZlibRoundTripsAndChecksTheSize) {
  const std::string text(10000, 'x');
  const std::string packed = ZlibDeflate(text);
  EXPECT_LT(packed.size(), 100u);  // a run of one byte compresses to almost nothing
  EXPECT_EQ(ZlibInflate(packed, text.size()), text);
  EXPECT_THROW(ZlibInflate(packed, text.size() - 1), InvalidInputError);
  EXPECT_THROW(ZlibInflate(packed, text.size() + 1), InvalidInputError);
  EXPECT_THROW(ZlibInflate("not zlib", 8), InvalidInputError);
}

// The narrowest type that holds max id + 1 (the shift that lets -1 mean none).
TEST(SideFiles, IdsUseTheNarrowestTypeAndRoundTrip) {
  const std::vector<std::pair<std::vector<int>, std::string>> cases = {{{-1, 0, 254}, "u8"},
                                                                       {{-1, 0, 255}, "u16"},
                                                                       {{3, 65534}, "u16"},
                                                                       {{65535, -1}, "u32"},
                                                                       {{}, "u8"}};
  for (const auto& [ids, type] : cases) {
    const JsonValue encoded = EncodeIds(ids);
    EXPECT_EQ(encoded.Get("type").AsString(), type);
    EXPECT_EQ(encoded.Get("count").AsNumber(), ids.size());
    EXPECT_EQ(encoded.Get("shift").AsNumber(), 1);
    const std::vector<int64_t> decoded = DecodeArray(encoded);
    EXPECT_EQ(std::vector<int64_t>(ids.begin(), ids.end()), decoded);
  }
  EXPECT_THROW(EncodeIds({0, -2}), InvalidInputError);
}

TEST(SideFiles, PositionsAreQuantizedWithinHalfAStepOfTheBox) {
  Eigen::MatrixX3d V(4, 3);
  V << -1.0, 0.0, 5.0,     //
      2.0, 0.25, 5.0,      //
      0.123456, 0.1, 5.0,  //
      1.5, 0.2, 5.0;       // z is constant: a flat box side
  const JsonValue encoded = EncodePositions(V);
  EXPECT_EQ(encoded.Get("type").AsString(), "u16");
  const std::vector<int64_t> q = DecodeArray(encoded);
  ASSERT_EQ(q.size(), 12u);
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 3; ++k) {
      const double lo = encoded.Get("lo").items()[k].AsNumber();
      const double hi = encoded.Get("hi").items()[k].AsNumber();
      const double x = lo + static_cast<double>(q[3 * i + k]) * (hi - lo) / 65535.0;
      // Rounding to the nearest of 65536 levels: at most half a level off.
      EXPECT_NEAR(x, V(i, k), 0.5 * (hi - lo) / 65535.0 + 1e-12) << i << "," << k;
    }
  }
  V(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(EncodePositions(V), InvalidInputError);
}

TEST(SideFiles, UnitValuesClampAndMarkUnknown) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const JsonValue encoded = EncodeUnitValues({0.0, 0.125, 0.25, 1.0, nan, -1.0}, 0.25);
  EXPECT_EQ(encoded.Get("max").AsNumber(), 0.25);
  EXPECT_EQ(DecodeArray(encoded), (std::vector<int64_t>{0, 127, 254, 254, 255, 255}));
}

std::vector<int> RowMajorFaces(const Surface& s) {
  std::vector<int> faces;
  for (int f = 0; f < s.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) faces.push_back(s.F(f, k));
  }
  return faces;
}

// Smooth maps (neighbours to neighbours) cost about a byte per vertex before compression;
// arbitrary maps round-trip too, through the escape ids.
TEST(SideFiles, VertexMapsRoundTripThroughRanks) {
  const Surface source = GridMesh(30, 20);
  Surface target = Icosphere(3);
  // Two components and an isolated vertex: each component starts with an id.
  const Surface extra = Icosphere(1);
  const int offset = target.NumVertices();
  target.V.conservativeResize(offset + extra.NumVertices() + 1, 3);
  target.V.bottomRows(extra.NumVertices() + 1).setZero();
  target.F.conservativeResize(target.NumFaces() + extra.NumFaces(), 3);
  target.F.bottomRows(extra.NumFaces()) = (extra.F.array() + offset).matrix();
  const std::vector<int> sf = RowMajorFaces(source), tf = RowMajorFaces(target);
  const int ns = source.NumVertices(), nt = target.NumVertices();

  std::vector<int> smooth(ns), arbitrary(ns), constant(ns, nt - 1);
  std::mt19937 rng(7);
  for (int v = 0; v < ns; ++v) {
    // Nearest target vertex to the source point lifted onto the sphere: a smooth map.
    const Eigen::RowVector3d p(source.V(v, 0) - 0.5, source.V(v, 1) - 0.5, 0.6);
    int best = 0;
    for (int t = 0; t < offset; ++t) {
      if ((target.V.row(t) - p.normalized()).squaredNorm() <
          (target.V.row(best) - p.normalized()).squaredNorm()) {
        best = t;
      }
    }
    smooth[v] = best;
    arbitrary[v] = static_cast<int>(rng() % nt);
  }
  for (const auto* map : {&smooth, &arbitrary, &constant}) {
    const JsonValue encoded = EncodeVertexMap(*map, ns, sf, nt, tf);
    EXPECT_EQ(DecodeVertexMap(encoded, ns, sf, nt, tf), *map);
  }
  const JsonValue encoded = EncodeVertexMap(smooth, ns, sf, nt, tf);
  EXPECT_EQ(encoded.Get("ids").Get("count").AsNumber(), 1);  // only the source's first vertex
  EXPECT_THROW(EncodeVertexMap({0, 1}, ns, sf, nt, tf), InvalidInputError);
  std::vector<int> out_of_range = smooth;
  out_of_range[3] = nt;
  EXPECT_THROW(EncodeVertexMap(out_of_range, ns, sf, nt, tf), InvalidInputError);
}

TEST(SideFiles, AdjacencyListsFollowTheFaces) {
  const VertexAdjacency a = BuildVertexAdjacency(4, {0, 1, 2, 2, 1, 3});
  EXPECT_EQ(a.start, (std::vector<int>{0, 2, 6, 10, 12}));
  EXPECT_EQ(a.index, (std::vector<int>{1, 2, 2, 0, 3, 2, 0, 1, 1, 3, 2, 1}));
  EXPECT_THROW(BuildVertexAdjacency(3, {0, 1, 3}), InvalidInputError);
}

TEST(SideFiles, ScriptRegistersThePayloadUnderItsKindAndKey) {
  JsonValue payload = JsonValue::Object();
  payload.Set("vertices", JsonValue::Number(3));
  EXPECT_EQ(SideFileScript("shape", "cat\"0", payload),
            "symembedData(\"shape\", \"cat\\\"0\", {\"vertices\": 3});\n");
}

}  // namespace
}  // namespace symembed
