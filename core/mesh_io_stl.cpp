// STL reader (ASCII and binary). STL stores every triangle with its own three positions;
// vertices are welded by exact position so that the mesh has connectivity.
#include <cstring>
#include <unordered_map>

#include "core/mesh_io_internal.h"

namespace symembed::mesh_io {
namespace {

// Welds positions by exact value (+0 and -0 are the same position); ids in order of first use.
class Welder {
 public:
  explicit Welder(RawMesh* mesh) : mesh_(mesh) {}
  int Add(const double p[3]) {
    Key key;
    for (int k = 0; k < 3; ++k) {
      const double v = p[k] == 0.0 ? 0.0 : p[k];
      std::memcpy(&key.bits[k], &v, sizeof(double));
    }
    const auto [it, inserted] = ids_.emplace(key, mesh_->NumVertices());
    if (inserted) mesh_->positions.insert(mesh_->positions.end(), p, p + 3);
    return it->second;
  }

 private:
  struct Key {
    uint64_t bits[3];
    bool operator==(const Key& o) const {
      return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
    }
  };
  struct KeyHash {
    size_t operator()(const Key& k) const {
      uint64_t h = 1469598103934665603ull;
      for (uint64_t b : k.bits) h = (h ^ b) * 1099511628211ull ^ (b >> 29);
      return static_cast<size_t>(h);
    }
  };
  RawMesh* mesh_;
  std::unordered_map<Key, int, KeyHash> ids_;
};

void ReadBinaryStl(std::string_view data, RawMesh* mesh) {
  uint32_t n = 0;
  std::memcpy(&n, data.data() + 80, 4);  // little-endian, as on every supported host
  Welder welder(mesh);
  mesh->triangles.reserve(3 * static_cast<size_t>(n));
  for (uint32_t t = 0; t < n; ++t) {
    const char* rec = data.data() + 84 + 50 * static_cast<size_t>(t);
    for (int k = 0; k < 3; ++k) {
      float xyz[3];
      std::memcpy(xyz, rec + 12 + 12 * k, 12);
      const double p[3] = {xyz[0], xyz[1], xyz[2]};
      mesh->triangles.push_back(welder.Add(p));
    }
  }
}

void ReadAsciiStl(std::string_view data, const std::string& name, RawMesh* mesh) {
  TextCursor c(data, name, 0);
  auto expect = [&](const char* keyword) {
    if (!c.SkipToContent()) c.Fail(std::string("truncated: expected '") + keyword + "'");
    const std::string_view t = c.Token();
    if (t != keyword) c.Fail(std::string("expected '") + keyword + "', found " + Quote(t));
  };
  Welder welder(mesh);
  bool in_solid = false;
  while (c.SkipToContent()) {
    const std::string_view kw = c.Token();
    if (!in_solid) {
      if (kw != "solid") c.Fail("expected 'solid', found " + Quote(kw));
      in_solid = true;
      c.NextLine();  // the rest of the line is the solid's name
      continue;
    }
    if (kw == "endsolid") {
      in_solid = false;
      c.NextLine();
      continue;
    }
    if (kw != "facet") c.Fail("expected 'facet' or 'endsolid', found " + Quote(kw));
    expect("normal");
    for (int k = 0; k < 3; ++k) c.Double("facet normal");
    expect("outer");
    expect("loop");
    for (int v = 0; v < 3; ++v) {
      expect("vertex");
      double p[3];
      for (int k = 0; k < 3; ++k) p[k] = c.Double("vertex coordinate");
      mesh->triangles.push_back(welder.Add(p));
    }
    expect("endloop");
    expect("endfacet");
  }
  if (in_solid) c.Fail("truncated: missing 'endsolid'");
}

}  // namespace

void ReadStl(std::string_view data, const std::string& name, RawMesh* mesh) {
  // A binary file may also start with "solid", so the size check decides first.
  if (data.size() >= 84) {
    uint32_t n = 0;
    std::memcpy(&n, data.data() + 80, 4);
    if (84 + 50 * static_cast<uint64_t>(n) == data.size()) {
      ReadBinaryStl(data, mesh);
      return;
    }
  }
  size_t start = 0;
  while (start < data.size() && std::strchr(" \t\r\n", data[start]) && data[start] != 0) ++start;
  if (data.substr(start, 5) == "solid") {
    ReadAsciiStl(data, name, mesh);
    return;
  }
  if (data.size() < 84) {
    Fail(name, 0, "not an STL file: no 'solid' header and too short (" +
                      std::to_string(data.size()) + " bytes) for binary STL");
  }
  uint32_t n = 0;
  std::memcpy(&n, data.data() + 80, 4);
  Fail(name, 0, "binary STL of " + std::to_string(data.size()) + " bytes declares " +
                    std::to_string(n) + " triangles, which need " +
                    std::to_string(84 + 50 * static_cast<uint64_t>(n)) +
                    " bytes (truncated or not an STL file)");
}

}  // namespace symembed::mesh_io
