#include "registry/hash.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <vector>

#include "core/errors.h"

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
