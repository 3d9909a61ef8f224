// `symembed validate`: report format and exit codes.
#include <gtest/gtest.h>

#include "core/mesh_io.h"
#include "core/primitives.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

using testing::RunShell;
using testing::TempDir;

std::string Validate(const std::string& args, int* code) {
  std::string output;
  *code = RunShell(std::string(SYMEMBED_BINARY) + " validate " + args, &output);
  return output;
}

TEST(ValidateCommand, ReportsEveryMeshAndContinuesPastBrokenFiles) {
  TempDir dir;
  SaveMesh(dir.File("sphere.off"), Icosphere(1));
  SaveMesh(dir.File("grid.obj"), GridMesh(3, 3));
  testing::WriteText(dir.File("broken.ply"), "ply\nformat ascii 1.0\n");
  int code = 0;
  const std::string out = Validate(dir.File("sphere.off") + " " + dir.File("broken.ply") + " " +
                                       dir.File("grid.obj"),
                                   &code);
  EXPECT_EQ(code, 1) << out;  // a file failed to load
  EXPECT_NE(out.find(dir.File("sphere.off") + ": 42 vertices, 80 faces"), std::string::npos)
      << out;
  EXPECT_NE(out.find("closed, genus 0: clean\n"), std::string::npos) << out;
  EXPECT_NE(out.find(dir.File("broken.ply") + ": cannot load: line 3: truncated header"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find(dir.File("grid.obj") + ": 9 vertices, 8 faces"), std::string::npos) << out;
  EXPECT_NE(out.find("\n  boundary edges: 8 in 1 loop\n"), std::string::npos) << out;
  EXPECT_NE(out.find("3 meshes: 1 clean, 1 with defects, 1 failed to load"), std::string::npos)
      << out;
}

TEST(ValidateCommand, DefectsExitZeroUnlessStrict) {
  TempDir dir;
  SaveMesh(dir.File("grid.off"), GridMesh(3, 3));
  int code = -1;
  Validate(dir.File("grid.off"), &code);
  EXPECT_EQ(code, 0);
  Validate("--strict " + dir.File("grid.off"), &code);
  EXPECT_EQ(code, 1);
  SaveMesh(dir.File("sphere.off"), Icosphere(1));
  const std::string out = Validate("--quiet " + dir.File("sphere.off"), &code);
  EXPECT_EQ(code, 0);
  EXPECT_EQ(out, "1 mesh: 1 clean, 0 with defects, 0 failed to load\n");
}

TEST(ValidateCommand, UsageErrors) {
  int code = 0;
  Validate("", &code);
  EXPECT_EQ(code, 2);
  Validate("--bogus x.off", &code);
  EXPECT_EQ(code, 2);
  const std::string help = Validate("--help", &code);
  EXPECT_EQ(code, 0);
  EXPECT_NE(help.find("--strict"), std::string::npos) << help;
}

}  // namespace
}  // namespace symembed
