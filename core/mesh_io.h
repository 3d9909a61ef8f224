// Mesh files: strict readers for OFF, OBJ, PLY and STL and deterministic writers for OFF, OBJ
// and PLY.
//
// The readers keep vertex order and ids exactly as in the file (ground-truth files refer to
// them) and keep every face, including non-manifold, duplicate, flipped and degenerate ones, so
// that ValidateMesh (core/validation.h) can report them. Polygons with more than three vertices
// (OFF, OBJ, PLY) are split into triangle fans (v0, vi, vi+1) in file order.
//
// Supported input:
//   OFF   ASCII; header [ST][C][N]OFF; one vertex per line (x y z [normal] [colour] [st]);
//         colours as 0-255 integers or 0-1 reals; '#' comments.
//   OBJ   'v x y z [w]' or 'v x y z r g b'; 'f' with i, i/t, i//n, i/t/n and negative (relative)
//         ids; texture, normal, group and material statements are ignored; '#' comments.
//   PLY   ascii, binary_little_endian and binary_big_endian; vertex x, y, z of any scalar type,
//         optional red/green/blue (uchar 0-255 or float 0-1); face list 'vertex_indices' (or
//         'vertex_index') with any integer count and index types; other elements and properties
//         are skipped.
//   STL   ASCII and binary; vertices are welded by exact position, numbered in order of first
//         appearance.
// A file is rejected as a whole (nothing half-read is returned) with InvalidInputError whose
// message starts with the path, and the line for text formats ("path:12: ..."), followed by the
// problem: empty file, unknown extension, bad header, non-numeric token, wrong counts, truncated
// data, index out of range, polygon with fewer than 3 vertices, trailing data, no vertices or no
// faces. A file that cannot be opened or read raises IoError. Coordinates may be NaN or Inf
// (reported by ValidateMesh, not rejected here).
#pragma once

#include <Eigen/Core>
#include <string>

#include "core/mesh.h"

namespace symembed {

// Reads a mesh file; the format is chosen by the extension (.off, .obj, .ply, .stl, any case).
// V: #V x 3 positions in file order; F: #F x 3 0-based vertex ids.
Surface LoadSurface(const std::string& path);

// As above; *colors receives #V x 3 vertex colours in [0, 1] when the file has a colour for every
// vertex, else 0 x 3.
Surface LoadSurface(const std::string& path, Eigen::MatrixX3d* colors);

// LoadSurface converted to the OpenMesh type. Throws InvalidInputError naming the file when some
// faces cannot be represented in OpenMesh (non-manifold edges or vertices, faces with a
// repeated vertex): use LoadSurface and ValidateMesh to inspect such a mesh.
TriMesh LoadMesh(const std::string& path);

// Parses mesh data already in memory. `format` is "off", "obj", "ply" or "stl"; `name` is used in
// error messages in place of the path. Same behaviour and errors as LoadSurface.
Surface ParseMesh(const std::string& data, const std::string& format, const std::string& name,
                  Eigen::MatrixX3d* colors = nullptr);

// Writes OFF, OBJ or PLY (ASCII) by extension. colors: optional #V x 3 in [0, 1] (values outside
// are clamped), written as COFF (0-255 integers), OBJ 'v x y z r g b' and PLY uchar
// red/green/blue. Numbers are printed in the shortest form that reads back to the same double,
// so the output is byte-identical for identical input and positions round-trip exactly.
// Throws InvalidInputError for face ids out of range, colour rows != #V or non-finite colours,
// IoError when the file cannot be written.
void SaveMesh(const std::string& path, const Surface& surface,
              const Eigen::MatrixX3d* colors = nullptr);

}  // namespace symembed
