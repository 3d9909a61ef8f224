// symembed_fuzz_seeds OUT SOURCE_DIR: writes the seed inputs of every fuzz target into
// OUT/<target>/, all made by the project itself (nothing downloaded): meshes of the synthetic
// generator and small primitives in OFF, OBJ, ASCII and binary PLY, ASCII and binary STL; the
// generator's ground truth and pairs files; maps; Kim 2011 benchmark files; the configs under
// SOURCE_DIR/configs.
// Exit code 0, or 1 with a message when something cannot be written.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/mesh_io.h"
#include "core/primitives.h"
#include "core/map_io.h"
#include "eval/synthetic/synthetic.h"

namespace {

namespace fs = std::filesystem;
using symembed::Surface;

void Write(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out << bytes;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

std::string Read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

template <typename T>
void Append(std::string* out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out->append(bytes, sizeof(T));
}

std::string BinaryPly(const Surface& s) {
  std::string out = "ply\nformat binary_little_endian 1.0\nelement vertex " +
                    std::to_string(s.NumVertices()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                    std::to_string(s.NumFaces()) +
                    "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int v = 0; v < s.NumVertices(); ++v) {
    for (int k = 0; k < 3; ++k) Append(&out, static_cast<float>(s.V(v, k)));
  }
  for (int f = 0; f < s.NumFaces(); ++f) {
    Append(&out, static_cast<uint8_t>(3));
    for (int k = 0; k < 3; ++k) Append(&out, static_cast<int32_t>(s.F(f, k)));
  }
  return out;
}

Eigen::Vector3d Normal(const Surface& s, int f) {
  const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
  return (b - a).cross(c - a).normalized();
}

std::string BinaryStl(const Surface& s) {
  std::string out(80, ' ');
  Append(&out, static_cast<uint32_t>(s.NumFaces()));
  for (int f = 0; f < s.NumFaces(); ++f) {
    const Eigen::Vector3d n = Normal(s, f);
    for (int k = 0; k < 3; ++k) Append(&out, static_cast<float>(n(k)));
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k) Append(&out, static_cast<float>(s.V(s.F(f, j), k)));
    }
    Append(&out, static_cast<uint16_t>(0));
  }
  return out;
}

std::string AsciiStl(const Surface& s) {
  std::ostringstream out;
  out.precision(9);
  out << "solid seed\n";
  for (int f = 0; f < s.NumFaces(); ++f) {
    const Eigen::Vector3d n = Normal(s, f);
    out << "facet normal " << n(0) << " " << n(1) << " " << n(2) << "\nouter loop\n";
    for (int j = 0; j < 3; ++j) {
      const auto p = s.V.row(s.F(f, j));
      out << "vertex " << p(0) << " " << p(1) << " " << p(2) << "\n";
    }
    out << "endloop\nendfacet\n";
  }
  out << "endsolid seed\n";
  return out.str();
}

// The mesh in every format, as OUT/mesh_<format>/<name>.<ext>.
void WriteMeshSeeds(const fs::path& out, const fs::path& scratch, const std::string& name,
                    const Surface& s) {
  for (const char* ext : {"off", "obj", "ply"}) {
    const fs::path file = scratch / (name + "." + ext);
    symembed::SaveMesh(file.string(), s);
    Write(out / (std::string("mesh_") + ext) / file.filename(), Read(file));
  }
  Write(out / "mesh_ply" / (name + "_binary.ply"), BinaryPly(s));
  Write(out / "mesh_stl" / (name + "_ascii.stl"), AsciiStl(s));
  Write(out / "mesh_stl" / (name + "_binary.stl"), BinaryStl(s));
}

// A map seed: the selector byte of fuzz_map.cpp, then the ids.
void WriteMapSeed(const fs::path& path, int base, const std::vector<int>& map) {
  int max_id = 0;
  for (int id : map) max_id = std::max(max_id, id);
  const int selector = std::min(127, max_id / 128 + 1);
  std::string text(1, static_cast<char>((selector << 1) | base));
  for (int id : map) text += std::to_string(id + base) + "\n";
  Write(path, text);
}

void WriteSeeds(const fs::path& out, const fs::path& source) {
  const fs::path scratch = out / "scratch";
  fs::create_directories(scratch);
  WriteMeshSeeds(out, scratch, "icosphere", symembed::Icosphere(1));
  WriteMeshSeeds(out, scratch, "grid", symembed::GridMesh(3, 3));

  symembed::SynthOptions synth;
  synth.kinds = {symembed::FigureKind::kHumanoid, symembed::FigureKind::kQuadruped};
  synth.poses = 2;
  synth.vertices = 300;
  const fs::path dataset = scratch / "synthetic";
  symembed::WriteSyntheticDataset(dataset.string(), synth);
  for (const auto& e : fs::directory_iterator(dataset / "shapes")) {
    const Surface s = symembed::LoadSurface(e.path().string());
    WriteMeshSeeds(out, scratch, e.path().stem().string(), s);
    std::vector<int> identity(s.NumVertices());
    for (int v = 0; v < s.NumVertices(); ++v) identity[v] = v;
    WriteMapSeed(out / "map" / (e.path().stem().string() + ".map"), 1, identity);
  }
  for (const auto& e : fs::directory_iterator(dataset / "corres")) {
    Write(out / "ground_truth" / e.path().filename(), std::string(1, '\x05') + Read(e.path()));
  }
  Write(out / "ground_truth" / "small.vts", std::string(1, '\x00') + "1\n0\n");
  Write(out / "pairs" / "test_pairs.txt", Read(dataset / "test_pairs.txt"));
  Write(out / "pairs" / "tabs.txt", "# comment\ncat0\tcat1\n\ndog0 dog1\n");
  WriteMapSeed(out / "map" / "small0.map", 0, {0, 1, 2, 1});
  WriteMapSeed(out / "map" / "small1.map", 1, {0, 1, 2, 1});
  Write(out / "map" / "floats.map", std::string(1, '\x03') + "1.0\n2e0\n3\n");
  // Kim 2011 benchmark files, behind the reader-selecting byte of fuzz_kim2011.cpp.
  Write(out / "kim2011" / "cat.pid", std::string(1, '\x00') +
                                         "12 0.1 0.2 0.3\n7 1 2 3\n3 -1 0 1\n40 0 0 0\n");
  Write(out / "kim2011" / "cat.sym.info", std::string(1, '\x0a') + "0 1\n2\n\n");
  Write(out / "kim2011" / "Corr_TOSCA.query",
        std::string(1, '\x02') + "TOSCA\n1\n0\nTOSCA\n1\n3\nSCAPE\n1\n12\n");
  for (const fs::path& dir : {source / "configs", source / "configs" / "bench"}) {
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.path().extension() == ".yaml") {
        Write(out / "config" / (dir.filename().string() + "_" + e.path().filename().string()),
              Read(e.path()));
      }
    }
  }
  fs::remove_all(scratch);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: symembed_fuzz_seeds OUT SOURCE_DIR\n";
    return 2;
  }
  try {
    WriteSeeds(argv[1], argv[2]);
  } catch (const std::exception& e) {
    std::cerr << "symembed_fuzz_seeds: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
