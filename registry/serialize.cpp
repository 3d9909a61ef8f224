#include "registry/serialize.h"

#include <cstring>
#include <limits>

#include "registry/hash.h"

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "registry/serialize.cpp stores numbers in native order and expects a little-endian target"
#endif

namespace symembed {
namespace {

// The magic of frames checksummed with ChecksumBytes, and of the older ones with HashBytes.
constexpr char kMagic[8] = {'S', 'Y', 'M', 'A', 'R', 'C', 'H', '2'};
constexpr char kMagicFnv[8] = {'S', 'Y', 'M', 'A', 'R', 'C', 'H', '1'};

void AppendU64(std::string* out, uint64_t value) { out->append(reinterpret_cast<char*>(&value), 8); }

uint64_t LoadU64(const std::string& bytes, size_t pos) {
  uint64_t value;
  std::memcpy(&value, bytes.data() + pos, 8);
  return value;
}

}  // namespace

void ArchiveWriter::U64(uint64_t value) { Raw(&value, 8); }
void ArchiveWriter::I64(int64_t value) { Raw(&value, 8); }
void ArchiveWriter::F64(double value) { Raw(&value, 8); }

void ArchiveWriter::String(const std::string& text) {
  U64(text.size());
  Raw(text.data(), text.size());
}

void ArchiveWriter::Ints(const std::vector<int>& values) {
  U64(values.size());
  Raw(values.data(), values.size() * sizeof(int));
}

void ArchiveWriter::Doubles(const std::vector<double>& values) {
  U64(values.size());
  Raw(values.data(), values.size() * sizeof(double));
}

void ArchiveWriter::Matrix(const Eigen::Ref<const Eigen::MatrixXd>& M) {
  U64(static_cast<uint64_t>(M.rows()));
  U64(static_cast<uint64_t>(M.cols()));
  for (Eigen::Index c = 0; c < M.cols(); ++c) Raw(M.col(c).data(), M.rows() * sizeof(double));
}

void ArchiveWriter::IntMatrix(const Eigen::Ref<const Eigen::MatrixXi>& M) {
  U64(static_cast<uint64_t>(M.rows()));
  U64(static_cast<uint64_t>(M.cols()));
  for (Eigen::Index c = 0; c < M.cols(); ++c) Raw(M.col(c).data(), M.rows() * sizeof(int));
}

void ArchiveWriter::FloatMatrix(const Eigen::Ref<const Eigen::MatrixXd>& M) {
  U64(static_cast<uint64_t>(M.rows()));
  U64(static_cast<uint64_t>(M.cols()));
  Eigen::VectorXf column(M.rows());
  for (Eigen::Index c = 0; c < M.cols(); ++c) {
    column = M.col(c).cast<float>();
    Raw(column.data(), column.size() * sizeof(float));
  }
}

std::string ArchiveWriter::Finish(const std::string& tag) const {
  std::string out(kMagic, sizeof kMagic);
  AppendU64(&out, kArchiveVersion);
  AppendU64(&out, tag.size());
  out += tag;
  AppendU64(&out, payload_.size());
  AppendU64(&out, ChecksumBytes(payload_.data(), payload_.size()));
  out += payload_;
  return out;
}

ArchiveReader::ArchiveReader(std::string bytes, const std::string& tag) : bytes_(std::move(bytes)) {
  const size_t fixed = sizeof kMagic + 8 + 8;
  if (bytes_.size() < fixed) throw ArchiveError("not a symembed archive");
  const bool fnv = std::memcmp(bytes_.data(), kMagicFnv, sizeof kMagicFnv) == 0;
  if (!fnv && std::memcmp(bytes_.data(), kMagic, sizeof kMagic) != 0) {
    throw ArchiveError("not a symembed archive");
  }
  const uint64_t version = LoadU64(bytes_, sizeof kMagic);
  if (version != kArchiveVersion) {
    throw ArchiveError("archive version " + std::to_string(version) + ", expected " +
                       std::to_string(kArchiveVersion));
  }
  const uint64_t tag_size = LoadU64(bytes_, sizeof kMagic + 8);
  if (tag_size != tag.size() || bytes_.size() < fixed + tag_size + 16 ||
      bytes_.compare(fixed, tag_size, tag) != 0) {
    throw ArchiveError("archive is not a '" + tag + "' entry");
  }
  const size_t header = fixed + tag_size + 16;
  const uint64_t payload_size = LoadU64(bytes_, fixed + tag_size);
  const uint64_t checksum = LoadU64(bytes_, fixed + tag_size + 8);
  if (bytes_.size() - header != payload_size) throw ArchiveError("archive payload is truncated");
  const char* payload = bytes_.data() + header;
  if ((fnv ? HashBytes(payload, payload_size) : ChecksumBytes(payload, payload_size)) != checksum) {
    throw ArchiveError("archive checksum mismatch");
  }
  pos_ = header;
}

void ArchiveReader::Raw(void* data, size_t size) {
  if (size > bytes_.size() - pos_) throw ArchiveError("archive payload ends early");
  if (size > 0) std::memcpy(data, bytes_.data() + pos_, size);
  pos_ += size;
}

uint64_t ArchiveReader::Count(size_t element_size) {
  const uint64_t n = U64();
  if (element_size > 0 && n > (bytes_.size() - pos_) / element_size) {
    throw ArchiveError("archive length field exceeds the payload");
  }
  return n;
}

uint64_t ArchiveReader::U64() {
  uint64_t v;
  Raw(&v, 8);
  return v;
}

int64_t ArchiveReader::I64() {
  int64_t v;
  Raw(&v, 8);
  return v;
}

double ArchiveReader::F64() {
  double v;
  Raw(&v, 8);
  return v;
}

std::string ArchiveReader::String() {
  std::string text(Count(1), '\0');
  Raw(text.data(), text.size());
  return text;
}

std::vector<int> ArchiveReader::Ints() {
  std::vector<int> values(Count(sizeof(int)));
  Raw(values.data(), values.size() * sizeof(int));
  return values;
}

std::vector<double> ArchiveReader::Doubles() {
  std::vector<double> values(Count(sizeof(double)));
  Raw(values.data(), values.size() * sizeof(double));
  return values;
}

Eigen::MatrixXd ArchiveReader::Matrix() {
  const uint64_t rows = U64();
  const uint64_t cols = U64();
  if (cols != 0 && rows > (bytes_.size() - pos_) / sizeof(double) / cols) {
    throw ArchiveError("archive matrix exceeds the payload");
  }
  Eigen::MatrixXd M(rows, cols);
  Raw(M.data(), rows * cols * sizeof(double));
  return M;
}

Eigen::MatrixXi ArchiveReader::IntMatrix() {
  const uint64_t rows = U64();
  const uint64_t cols = U64();
  if (cols != 0 && rows > (bytes_.size() - pos_) / sizeof(int) / cols) {
    throw ArchiveError("archive matrix exceeds the payload");
  }
  Eigen::MatrixXi M(rows, cols);
  Raw(M.data(), rows * cols * sizeof(int));
  return M;
}

Eigen::MatrixXd ArchiveReader::FloatMatrix() {
  const uint64_t rows = U64();
  const uint64_t cols = U64();
  if (cols != 0 && rows > (bytes_.size() - pos_) / sizeof(float) / cols) {
    throw ArchiveError("archive matrix exceeds the payload");
  }
  Eigen::MatrixXf M(rows, cols);
  Raw(M.data(), rows * cols * sizeof(float));
  return M.cast<double>();
}

void ArchiveReader::ExpectEnd() const {
  if (pos_ != bytes_.size()) throw ArchiveError("archive has unread trailing bytes");
}

}  // namespace symembed
