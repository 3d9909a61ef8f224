#include "registry/hash.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <vector>

#include "core/errors.h"

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "registry/hash.cpp reads 8-byte words in native order and expects a little-endian target"
#endif

namespace symembed {

Hasher::Hasher(uint64_t seed) { AddU64(seed); }

Hasher& Hasher::AddBytes(const void* data, size_t size) {
  const unsigned char* bytes = static_cast<const unsigned char*>(data);
  uint64_t h = state_;
  for (size_t i = 0; i < size; ++i) {
    h ^= bytes[i];
    h *= kPrime;
  }
  state_ = h;
  return *this;
}

Hasher& Hasher::AddU64(uint64_t value) {
  unsigned char bytes[8];
  for (int i = 0; i < 8; ++i) bytes[i] = static_cast<unsigned char>(value >> (8 * i));
  return AddBytes(bytes, 8);
}

Hasher& Hasher::AddString(const std::string& text) {
  AddU64(text.size());
  return AddBytes(text.data(), text.size());
}

uint64_t HashBytes(const void* data, size_t size) { return Hasher().AddBytes(data, size).Digest(); }

uint64_t ChecksumBytes(const void* data, size_t size) {
  constexpr uint64_t kOffsetBasis = 0xcbf29ce484222325ULL;
  constexpr uint64_t kPrime = 0x100000001b3ULL;
  const unsigned char* bytes = static_cast<const unsigned char*>(data);
  // Lanes start apart, so that words trading places between lanes change the result.
  uint64_t lanes[4] = {kOffsetBasis, kOffsetBasis ^ 1, kOffsetBasis ^ 2, kOffsetBasis ^ 3};
  auto word = [&](size_t k) {
    uint64_t w;
    std::memcpy(&w, bytes + 8 * k, 8);  // little-endian (checked above)
    return w;
  };
  const size_t words = size / 8;
  size_t k = 0;
  for (; k + 4 <= words; k += 4) {
    for (int l = 0; l < 4; ++l) lanes[l] = (lanes[l] ^ word(k + l)) * kPrime;
  }
  for (; k < words; ++k) lanes[k % 4] = (lanes[k % 4] ^ word(k)) * kPrime;
  Hasher tail;
  tail.AddU64(size);
  for (const uint64_t lane : lanes) tail.AddU64(lane);
  return tail.AddBytes(bytes + 8 * words, size - 8 * words).Digest();
}

uint64_t HashFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open for reading");
  Hasher hasher;
  std::vector<char> buffer(1 << 16);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    hasher.AddBytes(buffer.data(), static_cast<size_t>(in.gcount()));
  }
  if (in.bad()) throw IoError(path + ": read error");
  return hasher.Digest();
}

std::string HexDigest(uint64_t digest) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(digest));
  return text;
}

std::optional<uint64_t> ParseHexDigest(const std::string& text) {
  if (text.size() != 16 || text.find_first_not_of("0123456789abcdef") != std::string::npos) {
    return std::nullopt;
  }
  return std::strtoull(text.c_str(), nullptr, 16);
}

}  // namespace symembed
