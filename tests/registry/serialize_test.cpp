#include "registry/serialize.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "registry/hash.h"

namespace symembed {
namespace {

TEST(Hash, MatchesTheFnv1aReferenceValues) {
  // Published FNV-1a 64-bit test vectors.
  EXPECT_EQ(HashBytes("", 0), 0xcbf29ce484222325ULL);
  EXPECT_EQ(HashBytes("a", 1), 0xaf63dc4c8601ec8cULL);
  EXPECT_EQ(HashBytes("foobar", 6), 0x85944171f73967e8ULL);
  EXPECT_EQ(HexDigest(0xaf63dc4c8601ec8cULL), "af63dc4c8601ec8c");
}

TEST(Hash, LengthPrefixSeparatesFields) {
  EXPECT_NE(Hasher().AddString("ab").AddString("c").Digest(),
            Hasher().AddString("a").AddString("bc").Digest());
  EXPECT_EQ(Hasher(7).AddString("x").Digest(), Hasher(7).AddString("x").Digest());
  EXPECT_NE(Hasher(7).AddString("x").Digest(), Hasher(8).AddString("x").Digest());
}

TEST(Hash, ChecksumKeepsItsValuesAndSeesEveryByte) {
  // The checksums of stored archives: these values must not change.
  std::string bytes(77, '\0');
  for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 37 + 11);
  EXPECT_EQ(HexDigest(ChecksumBytes("", 0)), "6596806ac622e65d");
  EXPECT_EQ(HexDigest(ChecksumBytes("foobar", 6)), "3f87a34742ac934a");
  EXPECT_EQ(HexDigest(ChecksumBytes(bytes.data(), bytes.size())), "4fbf02ae10fc13cb");
  const uint64_t whole = ChecksumBytes(bytes.data(), bytes.size());
  for (size_t i = 0; i < bytes.size(); ++i) {
    std::string changed = bytes;
    changed[i] ^= static_cast<char>(0x80 >> (i % 8));
    EXPECT_NE(ChecksumBytes(changed.data(), changed.size()), whole) << i;
  }
  // Words trading places, and a zero byte more.
  std::string swapped = bytes;
  std::swap_ranges(swapped.begin(), swapped.begin() + 8, swapped.begin() + 8);
  EXPECT_NE(ChecksumBytes(swapped.data(), swapped.size()), whole);
  EXPECT_NE(ChecksumBytes((bytes + '\0').data(), bytes.size() + 1), whole);
}

TEST(Archive, ReadsTheFramesOfTheByteWiseChecksum) {
  ArchiveWriter out;
  out.Doubles({1, 2, 3});
  const std::string bytes = out.Finish("a");
  // A frame as written before ChecksumBytes: magic SYMARCH1, the payload's FNV-1a.
  const size_t header = 8 + 8 + 8 + 1 + 8 + 8;
  const std::string payload = bytes.substr(header);
  std::string old = bytes.substr(0, header - 8);
  old[7] = '1';
  const uint64_t fnv = HashBytes(payload.data(), payload.size());
  old.append(reinterpret_cast<const char*>(&fnv), 8);
  old += payload;
  ArchiveReader in(old, "a");
  EXPECT_EQ(in.Doubles(), std::vector<double>({1, 2, 3}));
  in.ExpectEnd();
  // Each checksum only with its own magic.
  std::string mixed = bytes;
  mixed[7] = '1';
  EXPECT_THROW(ArchiveReader(mixed, "a"), ArchiveError);
  old[7] = '2';
  EXPECT_THROW(ArchiveReader(old, "a"), ArchiveError);
  EXPECT_EQ(bytes.substr(0, 8), "SYMARCH2");
}

TEST(Archive, RoundTripsEveryFieldExactly) {
  ArchiveWriter out;
  out.U64(42);
  out.I64(-3);
  out.F64(std::numeric_limits<double>::quiet_NaN());
  out.F64(0.1);
  out.String(std::string("a\0b", 3));
  out.Ints({1, -2, 3});
  out.Doubles({});
  Eigen::MatrixXd M(2, 3);
  M << 1, 2, 3, 4, 5, 6.25;
  out.Matrix(M);
  Eigen::MatrixXi I(1, 2);
  I << 7, -8;
  out.IntMatrix(I);
  out.FloatMatrix(M * 0.1);
  ArchiveReader in(out.Finish("tag"), "tag");
  EXPECT_EQ(in.U64(), 42u);
  EXPECT_EQ(in.I64(), -3);
  EXPECT_TRUE(std::isnan(in.F64()));
  EXPECT_EQ(in.F64(), 0.1);
  EXPECT_EQ(in.String(), std::string("a\0b", 3));
  EXPECT_EQ(in.Ints(), (std::vector<int>{1, -2, 3}));
  EXPECT_TRUE(in.Doubles().empty());
  EXPECT_EQ(in.Matrix(), M);
  EXPECT_EQ(in.IntMatrix(), I);
  const Eigen::MatrixXd F = in.FloatMatrix();
  // Float storage: relative rounding of 2^-24.
  EXPECT_LT((F - M * 0.1).cwiseAbs().maxCoeff(), 1e-7);
  in.ExpectEnd();
}

TEST(Archive, RejectsWrongTagTruncationAndCorruption) {
  ArchiveWriter out;
  out.Doubles({1, 2, 3});
  const std::string bytes = out.Finish("a");
  EXPECT_THROW(ArchiveReader(bytes, "b"), ArchiveError);
  EXPECT_THROW(ArchiveReader(bytes.substr(0, bytes.size() - 1), "a"), ArchiveError);
  EXPECT_THROW(ArchiveReader(bytes.substr(0, 5), "a"), ArchiveError);
  EXPECT_THROW(ArchiveReader("", "a"), ArchiveError);
  std::string flipped = bytes;
  flipped.back() ^= 1;
  EXPECT_THROW(ArchiveReader(flipped, "a"), ArchiveError);
  // Reading past the payload or leaving bytes unread is an error.
  ArchiveReader in(bytes, "a");
  EXPECT_THROW(in.ExpectEnd(), ArchiveError);
  in.Doubles();
  EXPECT_THROW(in.U64(), ArchiveError);
}

TEST(Archive, LengthFieldsCannotAllocateBeyondThePayload) {
  ArchiveWriter out;
  out.U64(1ULL << 60);  // read as a vector length
  ArchiveReader in(out.Finish("x"), "x");
  EXPECT_THROW(in.Ints(), ArchiveError);
}

TEST(Archive, RoundTripsShapeResults) {
  PreprocessResult pre;
  pre.surface.V = Eigen::MatrixX3d::Random(4, 3);
  pre.surface.F.resize(2, 3);
  pre.surface.F << 0, 1, 2, 0, 2, 3;
  pre.input_ids = {0, 2, 3, 5};
  pre.scale = 1.5;
  pre.report = {{"flipped_faces", 3}, {"components_removed", 1}};
  pre.status.converged = false;
  pre.status.message = "note";
  SymmetryResult sym;
  sym.normal = Eigen::Vector3d(0, 1, 0);
  sym.offset = -0.5;
  sym.sigma = {1, 0};
  sym.confidence = Eigen::Vector2d(0.5, 1.0);
  EmbeddingResult emb;
  emb.Y = Eigen::MatrixXd::Random(4, 3);
  emb.reflection = -1;
  emb.stress_history = {3, 2, 1};
  LaplaceBasis basis{Eigen::VectorXd::LinSpaced(2, 0.0, 1.0), Eigen::MatrixXd::Random(4, 2),
                     Eigen::VectorXd::Ones(4)};

  ArchiveWriter out;
  Write(out, pre);
  Write(out, sym);
  Write(out, emb);
  Write(out, basis);
  ArchiveReader in(out.Finish("shape"), "shape");
  PreprocessResult pre2;
  SymmetryResult sym2;
  EmbeddingResult emb2;
  LaplaceBasis basis2;
  Read(in, &pre2);
  Read(in, &sym2);
  Read(in, &emb2);
  Read(in, &basis2);
  in.ExpectEnd();
  EXPECT_EQ(pre2.surface.V, pre.surface.V);
  EXPECT_EQ(pre2.surface.F, pre.surface.F);
  EXPECT_EQ(pre2.input_ids, pre.input_ids);
  EXPECT_EQ(pre2.report, pre.report);
  EXPECT_FALSE(pre2.status.converged);
  EXPECT_EQ(pre2.status.message, "note");
  EXPECT_EQ(sym2.normal, sym.normal);
  EXPECT_EQ(sym2.sigma, sym.sigma);
  EXPECT_EQ(sym2.confidence, sym.confidence);
  EXPECT_EQ(emb2.Y, emb.Y);
  EXPECT_EQ(emb2.reflection, -1);
  EXPECT_EQ(emb2.stress_history, emb.stress_history);
  EXPECT_EQ(basis2.evals, basis.evals);
  EXPECT_EQ(basis2.evecs, basis.evecs);
  EXPECT_EQ(basis2.mass, basis.mass);
}

// A result is stored as the members its Members() lists, in that order: the same bytes as its
// fields written one by one (the layout the cache's entries have), and a member of the wrong
// shape is refused.
TEST(Archive, AResultIsStoredAsItsMembersInOrder) {
  SymmetrizeResult result;
  result.Y = Eigen::MatrixX3d::Random(5, 3);
  result.asymmetry_before = 0.25;
  result.asymmetry_after = 0.125;
  result.status.iterations = 7;
  result.status.message = "done";
  ArchiveWriter by_members, by_hand;
  Write(by_members, result);
  by_hand.Matrix(result.Y);
  by_hand.F64(0.25);
  by_hand.F64(0.125);
  by_hand.Bool(true);
  by_hand.I64(7);
  by_hand.F64(0.0);
  by_hand.String("done");
  EXPECT_EQ(by_members.Finish("r"), by_hand.Finish("r"));

  ArchiveWriter two_columns;
  two_columns.Matrix(Eigen::MatrixXd::Zero(5, 2));
  ArchiveReader y_in(two_columns.Finish("r"), "r");
  SymmetrizeResult read;
  EXPECT_THROW(Read(y_in, &read), ArchiveError);
  ArchiveWriter short_normal;
  short_normal.Matrix(Eigen::Vector2d(1.0, 0.0));
  ArchiveReader normal_in(short_normal.Finish("r"), "r");
  SymmetryResult symmetry;
  EXPECT_THROW(Read(normal_in, &symmetry), ArchiveError);
}

}  // namespace
}  // namespace symembed
