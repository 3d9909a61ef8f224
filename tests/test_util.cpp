#include "tests/test_util.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "core/knn.h"
#include "core/primitives.h"

namespace fs = std::filesystem;

namespace symembed::testing {

TempDir::TempDir() {
  std::random_device rd;
  for (int attempt = 0; attempt < 100; ++attempt) {
    fs::path p = fs::temp_directory_path() / ("symembed_test_" + std::to_string(rd()));
    if (fs::create_directories(p)) {
      path_ = p.string();
      return;
    }
  }
  throw std::runtime_error("cannot create a temporary directory");
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

void WriteText(const std::string& path, const std::string& text) {
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) fs::create_directories(parent);
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path);
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string SourceDir() { return SYMEMBED_SOURCE_DIR; }

int Symembed(const std::string& args, std::string* output) {
  return RunShell(std::string(SYMEMBED_BINARY) + " " + args, output);
}

std::string DataRoot() {
  std::string root;
  if (const char* env = std::getenv("SYMEMBED_DATA")) {
    root = env;
  } else {
    root = SourceDir() + "/../shared/data";
  }
  return fs::is_directory(root) ? root : "";
}

int RunShell(const std::string& command, std::string* output) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::string text;
  char buffer[4096];
  size_t n;
  while ((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) text.append(buffer, n);
  const int status = pclose(pipe);
  if (output) *output = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

Surface BumpyBlob(int n, unsigned seed) {
  Surface s = BoxMesh(n);
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  struct Bump {
    Eigen::Vector3d centre;
    double height, width;
  };
  std::vector<Bump> bumps(7);
  for (auto& b : bumps) {
    b.centre = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    b.height = 0.1 + 0.25 * uniform(rng);
    b.width = 0.3 + 0.3 * uniform(rng);
  }
  for (int i = 0; i < s.NumVertices(); ++i) {
    const Eigen::Vector3d p = s.V.row(i).transpose().normalized();
    double r = 1.0;
    for (const auto& b : bumps) {
      r += b.height * std::exp(-(p - b.centre).squaredNorm() / (2.0 * b.width * b.width));
    }
    s.V.row(i) << 1.3 * r * p.x(), 1.0 * r * p.y(), 0.8 * r * p.z();
  }
  return s;
}

Surface TwistedShuffledCopy(const Surface& surface, double twist, unsigned seed,
                            std::vector<int>* ground_truth) {
  const int n = surface.NumVertices();
  std::vector<int> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  std::mt19937 rng(seed);
  std::shuffle(perm.begin(), perm.end(), rng);
  Surface out;
  out.V.resize(n, 3);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d p = surface.V.row(i);
    const double a = twist * p.z(), c = std::cos(a), s = std::sin(a);
    out.V.row(perm[i]) << c * p.x() - s * p.y(), s * p.x() + c * p.y(), p.z();
  }
  out.F.resize(surface.NumFaces(), 3);
  for (int f = 0; f < surface.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) out.F(f, k) = perm[surface.F(f, k)];
  }
  if (ground_truth != nullptr) *ground_truth = perm;
  return out;
}

}  // namespace symembed::testing

namespace symembed::testing {
namespace {

// Appends part (rotated by R, moved by t, then mirrored x -> -x when mirror) to out.
void AppendPart(const Surface& part, const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                bool mirror, Surface* out) {
  const int v0 = out->NumVertices(), f0 = out->NumFaces();
  out->V.conservativeResize(v0 + part.NumVertices(), 3);
  out->F.conservativeResize(f0 + part.NumFaces(), 3);
  for (int i = 0; i < part.NumVertices(); ++i) {
    Eigen::Vector3d p = R * part.V.row(i).transpose() + t;
    if (mirror) p.x() = -p.x();
    out->V.row(v0 + i) = p.transpose();
  }
  for (int f = 0; f < part.NumFaces(); ++f) {
    Eigen::RowVector3i face = part.F.row(f).array() + v0;
    if (mirror) std::swap(face(1), face(2));  // keep faces counter-clockwise from outside
    out->F.row(f0 + f) = face;
  }
}

Surface BuildFigure(int detail, bool with_left_arm, double arm_angle, double leg_angle) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  auto along = [](const Eigen::Vector3d& d) {
    return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), d).toRotationMatrix();
  };
  Surface out;
  out.V.resize(0, 3);
  out.F.resize(0, 3);
  AppendPart(BoxMesh(3 * detail, 0.5, 0.8, 0.25), I, Eigen::Vector3d::Zero(), false, &out);
  AppendPart(Icosphere(2, 0.15), I, Eigen::Vector3d(0, 0.58, 0), false, &out);
  AppendPart(Icosphere(1, 0.06), I, Eigen::Vector3d(0, 0.58, 0.16), false, &out);
  AppendPart(BoxMesh(2 * detail, 0.3, 0.4, 0.12), I, Eigen::Vector3d(0, 0.05, -0.19), false, &out);
  const Eigen::Vector3d arm_dir(std::cos(arm_angle), -std::sin(arm_angle), 0.0);
  const Eigen::Vector3d leg_dir(std::sin(leg_angle), -std::cos(leg_angle), 0.0);
  const Eigen::Vector3d shoulder(0.27, 0.32, 0.0), hip(0.14, -0.42, 0.0);
  const Surface arm = Cylinder(8, 8 * detail, 0.06, 0.6);
  const Surface leg = Cylinder(8, 10 * detail, 0.08, 0.8);
  const Surface foot = BoxMesh(2 * detail, 0.12, 0.06, 0.32);
  const Eigen::Vector3d foot_at = hip + 0.8 * leg_dir + Eigen::Vector3d(0, -0.04, 0.12);
  for (bool mirror : {false, true}) {
    if (!mirror || with_left_arm) AppendPart(arm, along(arm_dir), shoulder, mirror, &out);
    AppendPart(leg, along(leg_dir), hip, mirror, &out);
    AppendPart(foot, I, foot_at, mirror, &out);
  }
  return out;
}

}  // namespace

Surface SymmetricFigure(int detail, bool with_left_arm, std::vector<int>* mirror) {
  Surface s = BuildFigure(detail, with_left_arm, 0.0, 0.0);
  if (mirror) {
    Eigen::MatrixX3d reflected = s.V;
    reflected.col(0) *= -1.0;
    Eigen::VectorXd dist;
    *mirror = KnnIndex(s.V).Nearest(reflected, &dist, 1);
    for (int i = 0; i < s.NumVertices(); ++i) {
      if (dist(i) > 1e-9) (*mirror)[i] = -1;
    }
  }
  return s;
}

Surface PosedSymmetricFigure(int detail, double arm_angle, double leg_angle) {
  return BuildFigure(detail, true, arm_angle, leg_angle);
}

double EdgeExtentRatio(const Surface& s, const Eigen::Vector3d& d) {
  double along = 0.0, across = 0.0;
  for (int f = 0; f < s.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e = s.V.row(s.F(f, (k + 1) % 3)) - s.V.row(s.F(f, k));
      along += std::abs(e.dot(d));
      across += e.cross(d).norm();
    }
  }
  return along / across;
}

}  // namespace symembed::testing
