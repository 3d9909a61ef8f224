// The on-disk cache of per-shape stage outputs, and atomic file writing.
//
// One file per entry: DIR/<kind>/<16 hex digits of the key>.bin, holding an archive
// (registry/serialize.h) tagged with the kind. Keys are chained content hashes (the runner
// hashes the mesh bytes and the resolved options of a stage and of every stage before it), so
// an entry never goes stale: a changed input or option gives a different key. A missing,
// truncated, damaged or foreign file is a miss. Writes go to a temporary file that is renamed
// into place, so concurrent writers and killed processes never leave a partial entry.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/files.h"
#include "registry/serialize.h"

namespace symembed {

class DiskCache {
 public:
  // dir empty: the cache is disabled (every lookup misses, stores do nothing).
  explicit DiskCache(std::string dir = "");

  bool enabled() const { return !dir_.empty(); }
  const std::string& dir() const { return dir_; }
  std::string Path(const std::string& kind, uint64_t key) const;

  // Reads the entry into *value with Read(ArchiveReader&, T*); false on a miss. A damaged
  // entry is a miss.
  template <typename T>
  bool Load(const std::string& kind, uint64_t key, T* value) const {
    std::optional<std::string> bytes = LoadBytes(kind, key);
    if (!bytes) return false;
    try {
      ArchiveReader in(std::move(*bytes), kind);
      Read(in, value);
      in.ExpectEnd();
      return true;
    } catch (const ArchiveError&) {
      return false;
    }
  }

  // Stores the entry written with Write(ArchiveWriter&, const T&). A failed write is not an
  // error of the run (the entry is recomputed next time); it returns false.
  template <typename T>
  bool Store(const std::string& kind, uint64_t key, const T& value) const {
    if (!enabled()) return false;
    ArchiveWriter out;
    Write(out, value);
    return StoreBytes(kind, key, out.Finish(kind));
  }

  std::optional<std::string> LoadBytes(const std::string& kind, uint64_t key) const;
  bool StoreBytes(const std::string& kind, uint64_t key, const std::string& bytes) const;

 private:
  std::string dir_;
};

}  // namespace symembed
