// Stable 64-bit content hashing for cache keys: FNV-1a (Fowler, Noll & Vo), byte-wise, so the
// value depends only on the bytes fed in, never on the platform, the process or the run.
//
// Fields are length-prefixed when fed through AddString, so ("ab", "c") and ("a", "bc") differ.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace symembed {

class Hasher {
 public:
  Hasher() = default;
  // Continues from an earlier digest (to chain keys: stage key = H(previous key, stage)).
  explicit Hasher(uint64_t seed);

  Hasher& AddBytes(const void* data, size_t size);
  Hasher& AddU64(uint64_t value);             // 8 bytes, little-endian
  Hasher& AddString(const std::string& text);  // length, then bytes

  uint64_t Digest() const { return state_; }

 private:
  static constexpr uint64_t kOffsetBasis = 0xcbf29ce484222325ULL;
  static constexpr uint64_t kPrime = 0x100000001b3ULL;
  uint64_t state_ = kOffsetBasis;
};

uint64_t HashBytes(const void* data, size_t size);
// A checksum of bytes, several times faster than HashBytes on long inputs (archive payloads;
// cache keys use Hasher): four FNV-1a lanes over the 8-byte little-endian words, word k into
// lane k mod 4, then the size, the lanes and the last size mod 8 bytes through one Hasher.
// Changing one word changes the checksum (each lane's step is a bijection of its state). Like
// HashBytes it depends only on the bytes.
uint64_t ChecksumBytes(const void* data, size_t size);
// The hash of a file's bytes. Throws IoError when it cannot be read.
uint64_t HashFile(const std::string& path);
// 16 lowercase hex digits.
std::string HexDigest(uint64_t digest);
// The digest HexDigest wrote; std::nullopt for any other text.
std::optional<uint64_t> ParseHexDigest(const std::string& text);

}  // namespace symembed
