#include "core/files.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "core/errors.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

namespace fs = std::filesystem;

// The message of the IoError that acquiring the lock of folder throws ("" when it is taken).
std::string LockError(const std::string& folder) {
  try {
    FolderLock::Acquire(folder, "second");
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(FolderLock, ASecondHolderIsRefusedNamingTheFolderAndTheFirst) {
  testing::TempDir dir;
  const std::string folder = dir.File("out/exp");
  {
    const FolderLock held = FolderLock::Acquire(folder, "symembed run a.yaml");
    EXPECT_TRUE(fs::is_directory(folder));
    const std::string message = LockError(folder);
    EXPECT_EQ(message.find(folder + ": in use by another symembed command (pid " +
                           std::to_string(getpid()) + ", started "),
              0u)
        << message;
    EXPECT_NE(message.find(": symembed run a.yaml)"), std::string::npos) << message;
  }
  // Released with its holder, which removes the file.
  EXPECT_FALSE(fs::exists(folder + "/.symembed.lock"));
  EXPECT_EQ(LockError(folder), "");
}

TEST(FolderLock, TheKernelReleasesTheLockOfAKilledHolder) {
  testing::TempDir dir;
  const std::string folder = dir.File("exp");
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  const pid_t child = fork();
  if (child == 0) {
    try {
      const FolderLock held = FolderLock::Acquire(folder, "child");
      const char byte = 1;
      if (write(ready[1], &byte, 1) != 1) _exit(2);
      pause();
    } catch (...) {
      _exit(3);
    }
    _exit(0);
  }
  char byte = 0;
  ASSERT_EQ(read(ready[0], &byte, 1), 1);
  EXPECT_NE(LockError(folder).find("(pid " + std::to_string(child) + ", "), std::string::npos);
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_EQ(LockError(folder), "");
  close(ready[0]);
  close(ready[1]);
}

TEST(FolderLock, AFolderThatCannotHoldTheLockFileIsNamed) {
  testing::TempDir dir;
  testing::WriteText(dir.File("file"), "x");
  try {
    FolderLock::Acquire(dir.File("file"), "run");
    ADD_FAILURE() << "a lock in a regular file's place";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()).find(dir.File("file") + ": cannot create the lock file"), 0u)
        << e.what();
  }
}

}  // namespace
}  // namespace symembed
