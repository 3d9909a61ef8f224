// The compact encoding of the HTML report's side files (harness/html/html_report.h): numeric arrays
// as little-endian typed arrays, zlib-compressed (RFC 1950) and base64-encoded, inside a script
// that registers them with the page:
//
//   symembedData("shape", "cat0", {"vertices": 5000, "positions": {...}, ...});
//
// A page opened from file:// may not read local files with fetch() or XMLHttpRequest (Chromium
// blocks it), but it may load <script src>; the page (harness/html/assets/sidefiles.js) defines
// symembedData and decodes the arrays with the browser's DecompressionStream("deflate").
//
// An encoded array is a JSON object:
//   {"type": "u8" | "u16" | "u32", "count": n, "shift": s, "zlib": "<base64 of zlib stream>"}
// whose decoded value i is element i of the typed array minus s (s = 1 lets -1 mean "none").
// Quantized arrays add "lo"/"hi" (positions) or "max" (unit values); see each encoder.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "eval/json.h"

namespace symembed {

// RFC 4648 base64 with padding.
std::string Base64Encode(const std::string& bytes);
// Throws InvalidInputError for characters outside the alphabet or a bad length.
std::string Base64Decode(const std::string& text);

// zlib stream of bytes (best compression); ZlibInflate reverses it (expected_size: the exact
// decompressed size). Both throw InternalError when zlib fails, ZlibInflate InvalidInputError
// for a corrupt stream or a size other than expected_size.
std::string ZlibDeflate(const std::string& bytes);
std::string ZlibInflate(const std::string& compressed, size_t expected_size);

// Ids >= -1 (vertex ids, -1: none) in the narrowest unsigned type that holds max + 1, shift 1.
// Throws InvalidInputError for an id < -1.
JsonValue EncodeIds(const std::vector<int>& ids);

// #V x 3 positions quantized to 16 bits per coordinate on their bounding box: "lo" and "hi"
// (3 numbers each) give the box; coordinate k of vertex i is lo[k] + q * (hi[k] - lo[k]) /
// 65535 with q = element 3 i + k (vertex-major). The error is at most 1/131070 of the box size
// per axis. Throws InvalidInputError for a non-finite coordinate.
JsonValue EncodePositions(const Eigen::MatrixX3d& V);

// Values in [0, max_value] quantized to 8 bits: element = round(254 * min(x, max_value) /
// max_value) for x >= 0, 255 for NaN or a negative x (unknown); "max" holds max_value > 0.
JsonValue EncodeUnitValues(const std::vector<double>& x, double max_value);

// A vertex map between two meshes (map[v]: the target vertex of source vertex v), coded by
// the meshes' edges, since neighbours on the source usually map to nearby target vertices.
// Both meshes' adjacency lists are built alike (VertexAdjacency); the source vertices are
// visited breadth first (components from their lowest vertex, neighbours in list order). A
// vertex with a parent p in that search is coded by the rank r of map[v] in the breadth-first
// enumeration of the target from map[p] (r in [0, 254]); otherwise, or when r would be > 254,
// by 255 and its id, next in "ids". JSON: {"coding": "ranks", "ranks": u8 array (#source
// vertices, in visiting order), "ids": EncodeIds}. transfer.js decodes it the same way.
// faces: #F x 3 vertex ids, row-major. Throws InvalidInputError for an id out of range.
JsonValue EncodeVertexMap(const std::vector<int>& map, int source_vertices,
                          const std::vector<int>& source_faces, int target_vertices,
                          const std::vector<int>& target_faces);
std::vector<int> DecodeVertexMap(const JsonValue& encoded, int source_vertices,
                                 const std::vector<int>& source_faces, int target_vertices,
                                 const std::vector<int>& target_faces);

// Neighbour lists (compressed rows: the neighbours of v are index[start[v] .. start[v + 1]))
// with, for every face (a, b, c) in order, b and c appended to a's list, c and a to b's, a and
// b to c's (repeats kept): the one order both coders use.
struct VertexAdjacency {
  std::vector<int> start, index;
};
VertexAdjacency BuildVertexAdjacency(int vertices, const std::vector<int>& faces);

// The decoded integers of any encoded array above (the quantized ones undecoded), as sidefiles.js
// reads them; for tests and tools. Throws InvalidInputError for a malformed array.
std::vector<int64_t> DecodeArray(const JsonValue& encoded);

// The text of a side file: symembedData(kind, key, payload); with a newline.
std::string SideFileScript(const std::string& kind, const std::string& key,
                           const JsonValue& payload);

}  // namespace symembed
