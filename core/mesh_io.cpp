#include "core/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

#include "core/errors.h"
#include "core/mesh_io_internal.h"

namespace symembed {
namespace {

std::string LowerExtension(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

std::string ReadWholeFile(const std::string& path) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) throw IoError("cannot open " + path + ": " + std::strerror(errno));
  std::string data;
  char buffer[1 << 16];
  while (true) {
    const size_t n = std::fread(buffer, 1, sizeof(buffer), file.get());
    data.append(buffer, n);
    if (n < sizeof(buffer)) break;
  }
  if (std::ferror(file.get())) throw IoError("cannot read " + path + ": " + std::strerror(errno));
  return data;
}

// Shortest decimal form that reads back to the same double ("1", "0.1", "nan").
void AppendNumber(double v, std::string* out) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
  out->append(buffer, result.ptr);
}

void AppendInt(int64_t v, std::string* out) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), v);
  out->append(buffer, result.ptr);
}

int ColorByte(double c) { return static_cast<int>(std::lround(mesh_io::Clamp01(c) * 255.0)); }

void AppendPosition(const Surface& s, int i, std::string* out) {
  for (int k = 0; k < 3; ++k) {
    if (k > 0) out->push_back(' ');
    AppendNumber(s.V(i, k), out);
  }
}

void AppendColorBytes(const Eigen::MatrixX3d& colors, int i, std::string* out) {
  for (int k = 0; k < 3; ++k) {
    out->push_back(' ');
    AppendInt(ColorByte(colors(i, k)), out);
  }
}

// One line "3 a b c" per face, 0-based (the face lines of OFF and PLY).
void AppendCountedFaces(const Surface& s, std::string* out) {
  for (int f = 0; f < s.NumFaces(); ++f) {
    out->push_back('3');
    for (int k = 0; k < 3; ++k) {
      out->push_back(' ');
      AppendInt(s.F(f, k), out);
    }
    out->push_back('\n');
  }
}

std::string FormatOff(const Surface& s, const Eigen::MatrixX3d* colors) {
  std::string out = colors ? "COFF\n" : "OFF\n";
  AppendInt(s.NumVertices(), &out);
  out += ' ';
  AppendInt(s.NumFaces(), &out);
  out += " 0\n";
  for (int i = 0; i < s.NumVertices(); ++i) {
    AppendPosition(s, i, &out);
    if (colors) {
      AppendColorBytes(*colors, i, &out);
      out += " 255";
    }
    out += '\n';
  }
  AppendCountedFaces(s, &out);
  return out;
}

std::string FormatObj(const Surface& s, const Eigen::MatrixX3d* colors) {
  std::string out;
  for (int i = 0; i < s.NumVertices(); ++i) {
    out += "v ";
    AppendPosition(s, i, &out);
    for (int k = 0; colors && k < 3; ++k) {
      out += ' ';
      AppendNumber(mesh_io::Clamp01((*colors)(i, k)), &out);
    }
    out += '\n';
  }
  for (int f = 0; f < s.NumFaces(); ++f) {
    out += 'f';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      AppendInt(int64_t{s.F(f, k)} + 1, &out);
    }
    out += '\n';
  }
  return out;
}

std::string FormatPly(const Surface& s, const Eigen::MatrixX3d* colors) {
  std::string out = "ply\nformat ascii 1.0\nelement vertex ";
  AppendInt(s.NumVertices(), &out);
  out += "\nproperty double x\nproperty double y\nproperty double z\n";
  if (colors) out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out += "element face ";
  AppendInt(s.NumFaces(), &out);
  out += "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int i = 0; i < s.NumVertices(); ++i) {
    AppendPosition(s, i, &out);
    if (colors) AppendColorBytes(*colors, i, &out);
    out += '\n';
  }
  AppendCountedFaces(s, &out);
  return out;
}

}  // namespace

Surface ParseMesh(const std::string& data, const std::string& format, const std::string& name,
                  Eigen::MatrixX3d* colors) {
  if (data.empty()) mesh_io::Fail(name, 0, "empty file");
  mesh_io::RawMesh raw;
  if (format == "off") {
    mesh_io::ReadOff(data, name, &raw);
  } else if (format == "obj") {
    mesh_io::ReadObj(data, name, &raw);
  } else if (format == "ply") {
    mesh_io::ReadPly(data, name, &raw);
  } else if (format == "stl") {
    mesh_io::ReadStl(data, name, &raw);
  } else {
    mesh_io::Fail(name, 0, "unsupported mesh format '" + format +
                               "' (expected .off, .obj, .ply or .stl)");
  }
  const int nv = raw.NumVertices();
  if (nv == 0) mesh_io::Fail(name, 0, "the mesh has no vertices");
  if (raw.triangles.empty()) mesh_io::Fail(name, 0, "the mesh has no faces");
  Surface surface;
  surface.V = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      raw.positions.data(), nv, 3);
  surface.F = Eigen::Map<const Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      raw.triangles.data(), static_cast<Eigen::Index>(raw.triangles.size() / 3), 3);
  if (colors) {
    if (raw.colors.size() == raw.positions.size()) {
      *colors = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
          raw.colors.data(), nv, 3);
    } else {
      colors->resize(0, 3);
    }
  }
  return surface;
}

Surface LoadSurface(const std::string& path, Eigen::MatrixX3d* colors) {
  const std::string ext = LowerExtension(path);
  if (ext != "off" && ext != "obj" && ext != "ply" && ext != "stl") {
    throw InvalidInputError(path + ": unsupported mesh file extension '" + ext +
                            "' (expected .off, .obj, .ply or .stl)");
  }
  return ParseMesh(ReadWholeFile(path), ext, path, colors);
}

Surface LoadSurface(const std::string& path) { return LoadSurface(path, nullptr); }

TriMesh LoadMesh(const std::string& path) {
  const Surface surface = LoadSurface(path);
  for (int f = 0; f < surface.NumFaces(); ++f) {
    const auto& t = surface.F.row(f);
    if (t(0) == t(1) || t(1) == t(2) || t(0) == t(2)) {
      throw InvalidInputError(path + ": face " + std::to_string(f) +
                              " repeats a vertex and cannot be stored in the half-edge mesh "
                              "(see 'symembed validate')");
    }
  }
  int skipped = 0;
  TriMesh mesh = FromSurface(surface, &skipped);
  if (skipped > 0) {
    throw InvalidInputError(path + ": " + std::to_string(skipped) + " of " +
                            std::to_string(surface.NumFaces()) +
                            " faces are non-manifold or inconsistently oriented and cannot be "
                            "stored in the half-edge mesh (see 'symembed validate')");
  }
  return mesh;
}

void SaveMesh(const std::string& path, const Surface& surface, const Eigen::MatrixX3d* colors) {
  const std::string ext = LowerExtension(path);
  const int nv = surface.NumVertices();
  if (surface.F.size() > 0 && (surface.F.minCoeff() < 0 || surface.F.maxCoeff() >= nv)) {
    throw InvalidInputError("cannot write " + path + ": face vertex ids out of range [0, " +
                            std::to_string(nv) + ")");
  }
  if (colors && colors->rows() != nv) {
    throw InvalidInputError("cannot write " + path + ": " + std::to_string(colors->rows()) +
                            " colour rows for " + std::to_string(nv) + " vertices");
  }
  if (colors && !colors->allFinite()) {
    throw InvalidInputError("cannot write " + path + ": non-finite colour values");
  }
  std::string text;
  if (ext == "off") {
    text = FormatOff(surface, colors);
  } else if (ext == "obj") {
    text = FormatObj(surface, colors);
  } else if (ext == "ply") {
    text = FormatPly(surface, colors);
  } else {
    throw InvalidInputError("cannot write " + path + ": unsupported extension '" + ext +
                            "' (expected .off, .obj or .ply)");
  }
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "wb"));
  if (!file) throw IoError("cannot write " + path + ": " + std::strerror(errno));
  const bool written = std::fwrite(text.data(), 1, text.size(), file.get()) == text.size();
  const bool closed = std::fclose(file.release()) == 0;
  if (!written || !closed) throw IoError("cannot write " + path + ": " + std::strerror(errno));
}

}  // namespace symembed
