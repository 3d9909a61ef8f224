#include "core/files.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.h"

namespace fs = std::filesystem;

namespace symembed {

void WriteFileAtomically(const std::string& path, const std::string& bytes) {
  static std::atomic<uint64_t> counter{0};
  const fs::path target(path);
  std::error_code ec;
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  // Unique per process and call, so concurrent writers never share a temporary file.
  const std::string temp =
      path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1));
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw IoError(path + ": cannot create " + temp);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) {
      out.close();
      fs::remove(temp, ec);
      throw IoError(path + ": write failed");
    }
  }
  fs::rename(temp, target, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw IoError(path + ": cannot rename the temporary file into place");
  }
}

std::optional<std::string> ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return text.str();
}

std::string ReadFileOrThrow(const std::string& path) {
  std::optional<std::string> bytes = ReadFileBytes(path);
  if (!bytes) throw IoError(path + ": cannot read");
  return std::move(*bytes);
}

bool FolderIsWritable(const std::string& folder) {
  static std::atomic<uint64_t> counter{0};
  const std::string probe = (fs::path(folder) / (".write_probe." + std::to_string(::getpid()) +
                                                 "." + std::to_string(counter.fetch_add(1))))
                                .string();
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return false;
  ::close(fd);
  ::unlink(probe.c_str());
  return true;
}

FolderLock FolderLock::Acquire(const std::string& folder, const std::string& command) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  const std::string path = (fs::path(folder) / ".symembed.lock").string();
  // The holder removes the file when it is done. One that opened the file just before that
  // would lock a removed file, so a lock counts only on the file the path still names.
  for (;;) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      throw IoError(folder + ": cannot create the lock file " + path + ": " + std::strerror(errno));
    }
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      std::string holder = ReadFileBytes(path).value_or("");
      while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' ')) holder.pop_back();
      ::close(fd);
      if (error == EWOULDBLOCK) {
        throw IoError(folder + ": in use by another symembed command" +
                      (holder.empty() ? std::string() : " (" + holder + ")") +
                      "; wait for it to finish, or write to another folder");
      }
      throw IoError(folder + ": cannot lock " + path + ": " + std::strerror(error));
    }
    struct stat held {
    }, named{};
    if (::fstat(fd, &held) != 0 || ::stat(path.c_str(), &named) != 0 ||
        held.st_ino != named.st_ino || held.st_dev != named.st_dev) {
      ::close(fd);
      continue;
    }
    // Who holds it, for the message of the next one; the lock itself is the flock.
    char when[32] = "";
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    if (gmtime_r(&now, &utc)) std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S UTC", &utc);
    const std::string text =
        "pid " + std::to_string(::getpid()) + ", started " + when + ": " + command + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, text.data(), text.size(), 0) < 0) {
      // The lock holds without the note; only the next message would lack the holder.
    }
    return FolderLock(fd, path);
  }
}

FolderLock::~FolderLock() {
  if (fd_ < 0) return;
  // Removed while still locked, so that no one locks it between the removal and the close.
  ::unlink(path_.c_str());
  ::close(fd_);
}

}  // namespace symembed
