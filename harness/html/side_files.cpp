#include "harness/html/side_files.h"

#include <zlib.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "core/errors.h"

namespace symembed {

namespace {

constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

int Base64Value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

// Little-endian bytes of values in elements of `width` bytes.
template <typename T>
std::string PackLittleEndian(const std::vector<T>& values, int width) {
  std::string bytes(values.size() * width, '\0');
  for (size_t i = 0; i < values.size(); ++i) {
    const uint64_t v = static_cast<uint64_t>(values[i]);
    for (int b = 0; b < width; ++b) bytes[i * width + b] = static_cast<char>((v >> (8 * b)) & 0xff);
  }
  return bytes;
}

JsonValue EncodedArray(const std::string& type, size_t count, int shift, const std::string& bytes) {
  JsonValue a = JsonValue::Object();
  a.Set("type", JsonValue::String(type));
  a.Set("count", JsonValue::Number(static_cast<double>(count)));
  a.Set("shift", JsonValue::Number(shift));
  a.Set("zlib", JsonValue::String(Base64Encode(ZlibDeflate(bytes))));
  return a;
}

int WidthOf(const std::string& type) {
  if (type == "u8") return 1;
  if (type == "u16") return 2;
  if (type == "u32") return 4;
  throw InvalidInputError("encoded array: unknown type '" + type + "'");
}

}  // namespace

std::string Base64Encode(const std::string& bytes) {
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = (static_cast<uint8_t>(bytes[i]) << 16) |
                       (static_cast<uint8_t>(bytes[i + 1]) << 8) |
                       static_cast<uint8_t>(bytes[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  const size_t rest = bytes.size() - i;
  if (rest > 0) {
    uint32_t v = static_cast<uint8_t>(bytes[i]) << 16;
    if (rest == 2) v |= static_cast<uint8_t>(bytes[i + 1]) << 8;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += rest == 2 ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string Base64Decode(const std::string& text) {
  if (text.size() % 4 != 0) throw InvalidInputError("base64: length is not a multiple of 4");
  std::string out;
  out.reserve(text.size() / 4 * 3);
  for (size_t i = 0; i < text.size(); i += 4) {
    int v[4];
    int padding = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = text[i + k];
      const bool last_group = i + 4 == text.size();
      if (c == '=' && last_group && k >= 2 && (k == 3 || text[i + 3] == '=')) {
        v[k] = 0;
        ++padding;
        continue;
      }
      v[k] = Base64Value(c);
      if (v[k] < 0 || padding > 0) {
        throw InvalidInputError("base64: invalid character at offset " + std::to_string(i + k));
      }
    }
    const uint32_t bits = (v[0] << 18) | (v[1] << 12) | (v[2] << 6) | v[3];
    out += static_cast<char>((bits >> 16) & 0xff);
    if (padding < 2) out += static_cast<char>((bits >> 8) & 0xff);
    if (padding < 1) out += static_cast<char>(bits & 0xff);
  }
  return out;
}

std::string ZlibDeflate(const std::string& bytes) {
  uLongf size = compressBound(static_cast<uLong>(bytes.size()));
  std::string out(size, '\0');
  const int status = compress2(reinterpret_cast<Bytef*>(&out[0]), &size,
                               reinterpret_cast<const Bytef*>(bytes.data()),
                               static_cast<uLong>(bytes.size()), Z_BEST_COMPRESSION);
  SYMEMBED_CHECK(status == Z_OK, "zlib compress2 failed with status " << status);
  out.resize(size);
  return out;
}

std::string ZlibInflate(const std::string& compressed, size_t expected_size) {
  // One spare byte: a stream longer than expected_size then shows as Z_OK with a full buffer.
  std::string out(expected_size + 1, '\0');
  uLongf size = static_cast<uLongf>(out.size());
  const int status = uncompress(reinterpret_cast<Bytef*>(&out[0]), &size,
                                reinterpret_cast<const Bytef*>(compressed.data()),
                                static_cast<uLong>(compressed.size()));
  if (status == Z_DATA_ERROR || status == Z_BUF_ERROR) {
    throw InvalidInputError("zlib: corrupt or oversized stream");
  }
  SYMEMBED_CHECK(status == Z_OK, "zlib uncompress failed with status " << status);
  if (size != expected_size) {
    throw InvalidInputError("zlib: " + std::to_string(size) + " bytes, expected " +
                            std::to_string(expected_size));
  }
  out.resize(size);
  return out;
}

JsonValue EncodeIds(const std::vector<int>& ids) {
  int64_t max_value = 0;
  for (int id : ids) {
    if (id < -1) throw InvalidInputError("EncodeIds: id " + std::to_string(id) + " < -1");
    max_value = std::max<int64_t>(max_value, static_cast<int64_t>(id) + 1);
  }
  std::vector<uint32_t> shifted(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) shifted[i] = static_cast<uint32_t>(ids[i] + 1);
  const std::string type = max_value <= 0xff ? "u8" : max_value <= 0xffff ? "u16" : "u32";
  return EncodedArray(type, ids.size(), 1, PackLittleEndian(shifted, WidthOf(type)));
}

JsonValue EncodePositions(const Eigen::MatrixX3d& V) {
  if (!V.allFinite()) throw InvalidInputError("EncodePositions: non-finite coordinate");
  Eigen::RowVector3d lo = Eigen::RowVector3d::Zero(), hi = Eigen::RowVector3d::Zero();
  if (V.rows() > 0) {
    lo = V.colwise().minCoeff();
    hi = V.colwise().maxCoeff();
  }
  std::vector<uint16_t> q(V.rows() * 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double extent = hi(k) - lo(k);
      const double t = extent > 0 ? (V(i, k) - lo(k)) / extent : 0.0;
      q[3 * i + k] = static_cast<uint16_t>(std::lround(std::clamp(t, 0.0, 1.0) * 65535.0));
    }
  }
  JsonValue a = EncodedArray("u16", q.size(), 0, PackLittleEndian(q, 2));
  JsonValue jlo = JsonValue::Array(), jhi = JsonValue::Array();
  for (int k = 0; k < 3; ++k) {
    jlo.Push(JsonValue::Number(lo(k)));
    jhi.Push(JsonValue::Number(hi(k)));
  }
  a.Set("lo", jlo);
  a.Set("hi", jhi);
  return a;
}

JsonValue EncodeUnitValues(const std::vector<double>& x, double max_value) {
  SYMEMBED_CHECK(max_value > 0, "EncodeUnitValues: max_value " << max_value << " <= 0");
  std::vector<uint8_t> q(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    if (std::isnan(x[i]) || x[i] < 0) {
      q[i] = 255;
    } else {
      q[i] = static_cast<uint8_t>(std::lround(254.0 * std::min(x[i], max_value) / max_value));
    }
  }
  JsonValue a = EncodedArray("u8", q.size(), 0, PackLittleEndian(q, 1));
  a.Set("max", JsonValue::Number(max_value));
  return a;
}

VertexAdjacency BuildVertexAdjacency(int vertices, const std::vector<int>& faces) {
  for (int id : faces) {
    if (id < 0 || id >= vertices) {
      throw InvalidInputError("face vertex " + std::to_string(id) + " out of range [0, " +
                              std::to_string(vertices) + ")");
    }
  }
  VertexAdjacency a;
  a.start.assign(vertices + 1, 0);
  for (int id : faces) a.start[id + 1] += 2;
  for (int v = 0; v < vertices; ++v) a.start[v + 1] += a.start[v];
  a.index.resize(a.start[vertices]);
  std::vector<int> fill(a.start.begin(), a.start.end() - 1);
  for (size_t f = 0; f + 2 < faces.size(); f += 3) {
    for (int k = 0; k < 3; ++k) {
      const int v = faces[f + k];
      a.index[fill[v]++] = faces[f + (k + 1) % 3];
      a.index[fill[v]++] = faces[f + (k + 2) % 3];
    }
  }
  return a;
}

namespace {

constexpr int kRankEscape = 255;

// The breadth-first enumeration of a mesh from one vertex, one vertex at a time, without
// clearing its marks between starts (a stamp per start).
class Enumeration {
 public:
  explicit Enumeration(const VertexAdjacency& graph)
      : graph_(graph), stamp_(graph.start.size() - 1, 0) {}

  // Enumerates from `from` and returns the rank of `wanted` (<= max_rank), or -1.
  int RankOf(int from, int wanted, int max_rank) {
    Start(from);
    for (int rank = 0; rank <= max_rank; ++rank) {
      const int v = Next();
      if (v < 0) return -1;
      if (v == wanted) return rank;
    }
    return -1;
  }

  // The vertex of the given rank from `from`; -1 when the component is smaller.
  int AtRank(int from, int rank) {
    Start(from);
    int v = -1;
    for (int r = 0; r <= rank; ++r) {
      v = Next();
      if (v < 0) return -1;
    }
    return v;
  }

 private:
  void Start(int from) {
    ++current_;
    list_.clear();
    list_.push_back(from);
    stamp_[from] = current_;
    head_ = 0;
    emitted_ = 0;
    edge_ = graph_.start[from];
  }

  // Vertices in order: `from`, then the neighbours of each listed vertex in list order.
  int Next() {
    if (emitted_ < static_cast<int>(list_.size())) return list_[emitted_++];
    while (head_ < static_cast<int>(list_.size())) {
      const int v = list_[head_];
      while (edge_ < graph_.start[v + 1]) {
        const int u = graph_.index[edge_++];
        if (stamp_[u] == current_) continue;
        stamp_[u] = current_;
        list_.push_back(u);
        return list_[emitted_++];
      }
      ++head_;
      if (head_ < static_cast<int>(list_.size())) edge_ = graph_.start[list_[head_]];
    }
    return -1;
  }

  const VertexAdjacency& graph_;
  std::vector<uint32_t> stamp_;
  uint32_t current_ = 0;
  std::vector<int> list_;
  int head_ = 0, emitted_ = 0, edge_ = 0;
};

// The breadth-first visiting order of a mesh's vertices and each one's parent (-1: the first
// of its component).
void VisitingOrder(const VertexAdjacency& graph, std::vector<int>* order,
                   std::vector<int>* parent) {
  const int n = static_cast<int>(graph.start.size()) - 1;
  order->clear();
  order->reserve(n);
  parent->assign(n, -1);
  std::vector<char> seen(n, 0);
  for (int s = 0; s < n; ++s) {
    if (seen[s]) continue;
    seen[s] = 1;
    size_t head = order->size();
    order->push_back(s);
    for (; head < order->size(); ++head) {
      const int v = (*order)[head];
      for (int e = graph.start[v]; e < graph.start[v + 1]; ++e) {
        const int u = graph.index[e];
        if (seen[u]) continue;
        seen[u] = 1;
        (*parent)[u] = v;
        order->push_back(u);
      }
    }
  }
}

}  // namespace

JsonValue EncodeVertexMap(const std::vector<int>& map, int source_vertices,
                          const std::vector<int>& source_faces, int target_vertices,
                          const std::vector<int>& target_faces) {
  if (static_cast<int>(map.size()) != source_vertices) {
    throw InvalidInputError("EncodeVertexMap: " + std::to_string(map.size()) + " entries for " +
                            std::to_string(source_vertices) + " vertices");
  }
  for (int t : map) {
    if (t < 0 || t >= target_vertices) {
      throw InvalidInputError("EncodeVertexMap: target vertex " + std::to_string(t) +
                              " out of range");
    }
  }
  const VertexAdjacency source = BuildVertexAdjacency(source_vertices, source_faces);
  const VertexAdjacency target = BuildVertexAdjacency(target_vertices, target_faces);
  std::vector<int> order, parent;
  VisitingOrder(source, &order, &parent);
  Enumeration enumeration(target);
  std::vector<uint8_t> ranks;
  std::vector<int> ids;
  ranks.reserve(order.size());
  for (int v : order) {
    const int rank =
        parent[v] < 0 ? -1 : enumeration.RankOf(map[parent[v]], map[v], kRankEscape - 1);
    if (rank < 0) {
      ranks.push_back(kRankEscape);
      ids.push_back(map[v]);
    } else {
      ranks.push_back(static_cast<uint8_t>(rank));
    }
  }
  JsonValue encoded = JsonValue::Object();
  encoded.Set("coding", JsonValue::String("ranks"));
  encoded.Set("ranks", EncodedArray("u8", ranks.size(), 0, PackLittleEndian(ranks, 1)));
  encoded.Set("ids", EncodeIds(ids));
  return encoded;
}

std::vector<int> DecodeVertexMap(const JsonValue& encoded, int source_vertices,
                                 const std::vector<int>& source_faces, int target_vertices,
                                 const std::vector<int>& target_faces) {
  if (!encoded.IsObject() || !encoded.Get("coding").IsString() ||
      encoded.Get("coding").AsString() != "ranks") {
    throw InvalidInputError("vertex map: expected {\"coding\": \"ranks\", ...}");
  }
  const std::vector<int64_t> ranks = DecodeArray(encoded.Get("ranks"));
  const std::vector<int64_t> ids = DecodeArray(encoded.Get("ids"));
  if (static_cast<int>(ranks.size()) != source_vertices) {
    throw InvalidInputError("vertex map: " + std::to_string(ranks.size()) + " ranks for " +
                            std::to_string(source_vertices) + " vertices");
  }
  const VertexAdjacency source = BuildVertexAdjacency(source_vertices, source_faces);
  const VertexAdjacency target = BuildVertexAdjacency(target_vertices, target_faces);
  std::vector<int> order, parent;
  VisitingOrder(source, &order, &parent);
  Enumeration enumeration(target);
  std::vector<int> map(source_vertices, -1);
  size_t next_id = 0;
  for (size_t i = 0; i < order.size(); ++i) {
    const int v = order[i];
    if (ranks[i] == kRankEscape) {
      if (next_id >= ids.size()) throw InvalidInputError("vertex map: too few ids");
      map[v] = static_cast<int>(ids[next_id++]);
    } else if (parent[v] < 0 ||
               (map[v] = enumeration.AtRank(map[parent[v]], static_cast<int>(ranks[i]))) < 0) {
      throw InvalidInputError("vertex map: rank " + std::to_string(ranks[i]) + " of vertex " +
                              std::to_string(v) + " does not exist");
    }
    if (map[v] < 0 || map[v] >= target_vertices) {
      throw InvalidInputError("vertex map: target vertex " + std::to_string(map[v]) +
                              " out of range");
    }
  }
  return map;
}

std::vector<int64_t> DecodeArray(const JsonValue& encoded) {
  if (!encoded.IsObject() || !encoded.Get("type").IsString() || !encoded.Get("count").IsNumber() ||
      !encoded.Get("zlib").IsString()) {
    throw InvalidInputError("encoded array: expected an object with type, count and zlib");
  }
  const int width = WidthOf(encoded.Get("type").AsString());
  const size_t count = static_cast<size_t>(encoded.Get("count").AsNumber());
  const int64_t shift = static_cast<int64_t>(encoded.Get("shift").NumberOr(0.0));
  const std::string bytes =
      ZlibInflate(Base64Decode(encoded.Get("zlib").AsString()), count * width);
  std::vector<int64_t> values(count);
  for (size_t i = 0; i < count; ++i) {
    uint64_t v = 0;
    for (int b = 0; b < width; ++b)
      v |= static_cast<uint64_t>(static_cast<uint8_t>(bytes[i * width + b])) << (8 * b);
    values[i] = static_cast<int64_t>(v) - shift;
  }
  return values;
}

std::string SideFileScript(const std::string& kind, const std::string& key,
                           const JsonValue& payload) {
  return "symembedData(" + WriteJson(JsonValue::String(kind), 0) + ", " +
         WriteJson(JsonValue::String(key), 0) + ", " + WriteJson(payload, 0) + ");\n";
}

}  // namespace symembed
