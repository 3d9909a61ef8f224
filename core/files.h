// Whole-file reads and atomic writes, for everything the harness writes: the per-shape cache,
// the run folders (maps, records, summaries) and the baselines.
#pragma once

#include <optional>
#include <string>
#include <utility>

namespace symembed {

// Writes bytes to path through a temporary file in the same folder (unique per process and
// call, so concurrent writers never share one) and a rename, so that a reader sees the old
// file or the new one, never a part; creates the parent folders. Throws IoError naming path.
void WriteFileAtomically(const std::string& path, const std::string& bytes);

// The bytes of a file, or std::nullopt when it cannot be opened or read.
std::optional<std::string> ReadFileBytes(const std::string& path);

// The bytes of a file. Throws IoError "<path>: cannot read" when it cannot be opened or read.
std::string ReadFileOrThrow(const std::string& path);

// Whether a file can be created in folder (a probe file, removed at once): permissions, a
// read-only mount or a pseudo file system (/proc) all say no.
bool FolderIsWritable(const std::string& folder);

// An advisory lock on an output folder (flock on FOLDER/.symembed.lock), held while a command
// writes there, so that a second command into a folder in use fails at once instead of mixing
// its outputs with the first's. The kernel releases it when the holder exits or dies. The lock
// file holds the holder's pid, start time and command line (for the message); the holder
// removes it when done (one left by a killed holder is taken over by the next command).
class FolderLock {
 public:
  // Creates the folder when needed and takes the lock. Throws IoError naming the folder and the
  // holder when another process holds it, or when the lock file cannot be created.
  static FolderLock Acquire(const std::string& folder, const std::string& command);
  FolderLock(FolderLock&& other) noexcept
      : fd_(std::exchange(other.fd_, -1)), path_(std::move(other.path_)) {}
  FolderLock& operator=(FolderLock&&) = delete;
  FolderLock(const FolderLock&) = delete;
  ~FolderLock();

 private:
  FolderLock(int fd, std::string path) : fd_(fd), path_(std::move(path)) {}
  int fd_ = -1;
  std::string path_;
};

}  // namespace symembed
