// A small versioned binary archive for cache entries: scalars, strings, int/double vectors,
// Eigen matrices (double, int, or double stored as float), and the per-shape results of
// registry/types.h, each stored as the members it lists.
//
// Frame: magic, layout version (u64), tag (string), payload size (u64), checksum of the payload
// (u64), payload. The magic names the checksum: "SYMARCH2" (written) ChecksumBytes, "SYMARCH1"
// (still read) HashBytes, byte-wise FNV-1a (registry/hash.h). A reader rejects a frame whose
// magic, version, tag, size or checksum does not match (a truncated or foreign file), so a cache
// treats it as a miss.
// Numbers are stored little-endian (the only byte order this project builds for).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
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

// One member of a result, by its type (a type with its own Write and Read below, such as
// Eigen::MatrixXd or Surface, goes through them). ReadMember throws ArchiveError on malformed
// data (a matrix of the wrong shape).
void WriteMember(ArchiveWriter& out, bool value);
void WriteMember(ArchiveWriter& out, int value);
void WriteMember(ArchiveWriter& out, double value);
void WriteMember(ArchiveWriter& out, const std::string& value);
void WriteMember(ArchiveWriter& out, const std::vector<int>& values);
void WriteMember(ArchiveWriter& out, const std::vector<double>& values);
void WriteMember(ArchiveWriter& out, const Eigen::MatrixX3d& M);
void WriteMember(ArchiveWriter& out, const Eigen::VectorXd& v);
void WriteMember(ArchiveWriter& out, const Eigen::Vector3d& v);
void ReadMember(ArchiveReader& in, bool* value);
void ReadMember(ArchiveReader& in, int* value);
void ReadMember(ArchiveReader& in, double* value);
void ReadMember(ArchiveReader& in, std::string* value);
void ReadMember(ArchiveReader& in, std::vector<int>* values);
void ReadMember(ArchiveReader& in, std::vector<double>* values);
void ReadMember(ArchiveReader& in, Eigen::MatrixX3d* M);
void ReadMember(ArchiveReader& in, Eigen::VectorXd* v);
void ReadMember(ArchiveReader& in, Eigen::Vector3d* v);

// Types that are not a list of members. Read throws ArchiveError on malformed data.
void Write(ArchiveWriter& out, const Report& report);
void Read(ArchiveReader& in, Report* report);
void Write(ArchiveWriter& out, const Surface& surface);
void Read(ArchiveReader& in, Surface* surface);
void Write(ArchiveWriter& out, const Eigen::MatrixXd& M);
void Read(ArchiveReader& in, Eigen::MatrixXd* M);
void Write(ArchiveWriter& out, const LaplaceBasis& basis);
void Read(ArchiveReader& in, LaplaceBasis* basis);

// A member of another type: its own Write and Read.
template <typename T>
void WriteMember(ArchiveWriter& out, const T& value) {
  Write(out, value);
}
template <typename T>
void ReadMember(ArchiveReader& in, T* value) {
  Read(in, value);
}

// A type that lists its members (`static constexpr auto Members()`, a tuple of pointers to
// members: the stage results of registry/types.h, StageStatus) is stored as its members in
// that order, so its layout is declared once, beside its fields.
template <typename T, typename = decltype(T::Members())>
void Write(ArchiveWriter& out, const T& value) {
  std::apply([&](auto... member) { (WriteMember(out, value.*member), ...); }, T::Members());
}
template <typename T, typename = decltype(T::Members())>
void Read(ArchiveReader& in, T* value) {
  std::apply([&](auto... member) { (ReadMember(in, &(value->*member)), ...); }, T::Members());
}

}  // namespace symembed
