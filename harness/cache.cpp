#include "harness/cache.h"

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.h"
#include "core/files.h"
#include "registry/hash.h"

namespace fs = std::filesystem;

namespace symembed {

DiskCache::DiskCache(std::string dir) : dir_(std::move(dir)) {}

std::string DiskCache::Path(const std::string& kind, uint64_t key) const {
  return dir_ + "/" + kind + "/" + HexDigest(key) + ".bin";
}

std::optional<std::string> DiskCache::LoadBytes(const std::string& kind, uint64_t key) const {
  if (!enabled()) return std::nullopt;
  return ReadFileBytes(Path(kind, key));
}

bool DiskCache::StoreBytes(const std::string& kind, uint64_t key, const std::string& bytes) const {
  if (!enabled()) return false;
  try {
    WriteFileAtomically(Path(kind, key), bytes);
    return true;
  } catch (const IoError&) {
    return false;
  }
}

}  // namespace symembed
