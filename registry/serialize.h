// A small versioned binary archive for cache entries: scalars, strings, int/double vectors,
// Eigen matrices (double, int, or double stored as float), and the per-shape results of
// registry/types.h.
//
// Frame: "SYMARCH1" magic, format version (u32), tag (string), payload size (u64), FNV-1a
// checksum of the payload (u64), payload. A reader rejects a frame whose magic, version, tag,
// size or checksum does not match (a truncated or foreign file), so a cache treats it as a miss.
// Numbers are stored little-endian (the only byte order this project builds for).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/errors.h"
#include "registry/types.h"

namespace symembed {

// A frame or payload that cannot be read (wrong magic/version/tag, truncated, bad checksum).
class ArchiveError : public IoError {
 public:
  using IoError::IoError;
};

inline constexpr uint32_t kArchiveVersion = 1;

class ArchiveWriter {
 public:
  void U64(uint64_t value);
  void I64(int64_t value);
  void F64(double value);
  void Bool(bool value) { U64(value ? 1 : 0); }
  void String(const std::string& text);
  void Ints(const std::vector<int>& values);
  void Doubles(const std::vector<double>& values);
  void Matrix(const Eigen::Ref<const Eigen::MatrixXd>& M);
  void IntMatrix(const Eigen::Ref<const Eigen::MatrixXi>& M);
  // Stored as 32-bit floats (half the size; values are rounded to float precision).
  void FloatMatrix(const Eigen::Ref<const Eigen::MatrixXd>& M);

  // The framed bytes (header + payload).
  std::string Finish(const std::string& tag) const;

 private:
  void Raw(const void* data, size_t size) { payload_.append(static_cast<const char*>(data), size); }
  std::string payload_;
};

class ArchiveReader {
 public:
  // Validates the frame; throws ArchiveError when it does not match `tag` or is damaged.
  ArchiveReader(std::string bytes, const std::string& tag);

  uint64_t U64();
  int64_t I64();
  double F64();
  bool Bool() { return U64() != 0; }
  std::string String();
  std::vector<int> Ints();
  std::vector<double> Doubles();
  Eigen::MatrixXd Matrix();
  Eigen::MatrixXi IntMatrix();
  Eigen::MatrixXd FloatMatrix();
  // Throws ArchiveError unless every payload byte was read.
  void ExpectEnd() const;

 private:
  void Raw(void* data, size_t size);
  uint64_t Count(size_t element_size);  // a length, checked against the bytes left
  std::string bytes_;
  size_t pos_ = 0;
};

// Results of registry/types.h. Read* throws ArchiveError on malformed data.
void Write(ArchiveWriter& out, const StageStatus& status);
void Read(ArchiveReader& in, StageStatus* status);
void Write(ArchiveWriter& out, const Report& report);
void Read(ArchiveReader& in, Report* report);
void Write(ArchiveWriter& out, const Surface& surface);
void Read(ArchiveReader& in, Surface* surface);
void Write(ArchiveWriter& out, const PreprocessResult& result);
void Read(ArchiveReader& in, PreprocessResult* result);
void Write(ArchiveWriter& out, const SamplingResult& result);
void Read(ArchiveReader& in, SamplingResult* result);
void Write(ArchiveWriter& out, const EmbeddingResult& result);
void Read(ArchiveReader& in, EmbeddingResult* result);
void Write(ArchiveWriter& out, const SymmetryResult& result);
void Read(ArchiveReader& in, SymmetryResult* result);
void Write(ArchiveWriter& out, const SymmetrizeResult& result);
void Read(ArchiveReader& in, SymmetrizeResult* result);
void Write(ArchiveWriter& out, const Eigen::MatrixXd& M);
void Read(ArchiveReader& in, Eigen::MatrixXd* M);
void Write(ArchiveWriter& out, const LaplaceBasis& basis);
void Read(ArchiveReader& in, LaplaceBasis* basis);

}  // namespace symembed
