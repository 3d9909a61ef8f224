// PLY reader: ascii, binary_little_endian and binary_big_endian (Turk 1994, "The PLY polygon
// file format").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "core/mesh_io_internal.h"

namespace symembed::mesh_io {
namespace {

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };
enum class Encoding { kAscii, kLittleEndian, kBigEndian };

bool ParsePlyType(std::string_view s, PlyType* type) {
  static const std::pair<const char*, PlyType> kNames[] = {
      {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUint8},
      {"uint8", PlyType::kUint8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
      {"ushort", PlyType::kUint16},  {"uint16", PlyType::kUint16},   {"int", PlyType::kInt32},
      {"int32", PlyType::kInt32},    {"uint", PlyType::kUint32},     {"uint32", PlyType::kUint32},
      {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
      {"float64", PlyType::kFloat64}};
  for (const auto& [n, t] : kNames) {
    if (s == n) {
      *type = t;
      return true;
    }
  }
  return false;
}

int SizeOf(PlyType t) {
  switch (t) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 8;
}

bool IsFloat(PlyType t) { return t == PlyType::kFloat32 || t == PlyType::kFloat64; }

struct PlyProperty {
  std::string name;
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;
  PlyType type = PlyType::kFloat32;
};

struct PlyElement {
  std::string name;
  int64_t count = 0;
  std::vector<PlyProperty> properties;
};

bool HostIsLittleEndian() {
  const uint16_t probe = 1;
  unsigned char first;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}

// Reads the scalar values of the body, record by record, in either encoding.
class PlyBody {
 public:
  PlyBody(std::string_view body, int first_line, Encoding encoding, const std::string& name)
      : encoding_(encoding),
        text_(body, name, 0, first_line),
        bytes_(body),
        name_(name),
        swap_(encoding != Encoding::kAscii &&
              (encoding == Encoding::kLittleEndian) != HostIsLittleEndian()) {}

  void BeginRecord(const PlyElement& e, int64_t i) {
    context_ = "'" + e.name + "' " + std::to_string(i);
    if (encoding_ == Encoding::kAscii && !text_.SkipToContent()) {
      text_.Fail("truncated: the data ends at " + context_ + " of " + std::to_string(e.count));
    }
  }
  void EndRecord() {
    if (encoding_ != Encoding::kAscii) return;
    if (!text_.AtLineEnd()) {
      text_.Fail("unexpected value " + Quote(text_.Token()) + " at the end of " + context_ +
                 " (do the header's properties match the data?)");
    }
    text_.NextLine();
  }
  double Read(PlyType t) {
    if (encoding_ == Encoding::kAscii) {
      const std::string_view token = text_.Token();
      if (token.empty()) text_.Fail("missing value in " + context_);
      double v = 0.0;
      int64_t k = 0;
      if (IsFloat(t) ? !ParseDouble(token, &v) : !ParseInt(token, &k)) {
        text_.Fail(std::string("expected ") + (IsFloat(t) ? "a number" : "an integer") + " in " +
                   context_ + ", found " + Quote(token));
      }
      return IsFloat(t) ? v : static_cast<double>(k);
    }
    const int size = SizeOf(t);
    Require(size);
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + pos_, size);
    pos_ += size;
    if (swap_) std::reverse(b, b + size);
    switch (t) {
      case PlyType::kInt8:
        return Cast<int8_t>(b);
      case PlyType::kUint8:
        return Cast<uint8_t>(b);
      case PlyType::kInt16:
        return Cast<int16_t>(b);
      case PlyType::kUint16:
        return Cast<uint16_t>(b);
      case PlyType::kInt32:
        return Cast<int32_t>(b);
      case PlyType::kUint32:
        return Cast<uint32_t>(b);
      case PlyType::kFloat32:
        return Cast<float>(b);
      case PlyType::kFloat64:
        return Cast<double>(b);
    }
    return 0.0;
  }
  // Binary: fails unless `bytes` more bytes are available.
  void Require(int64_t bytes) const {
    if (encoding_ != Encoding::kAscii && bytes > static_cast<int64_t>(bytes_.size() - pos_)) {
      Fail(name_, 0, "truncated binary data at " + context_);
    }
  }
  size_t Remaining() const { return bytes_.size() - pos_; }
  void Finish() {
    if (encoding_ == Encoding::kAscii) {
      if (text_.SkipToContent()) {
        text_.Fail("unexpected data " + Quote(text_.Token()) + " after the last element");
      }
      return;
    }
    for (size_t i = pos_; i < bytes_.size(); ++i) {
      if (bytes_[i] != '\n' && bytes_[i] != '\r') {
        Fail(name_, 0,
             std::to_string(bytes_.size() - pos_) +
                 " bytes of unexpected data after the last element");
      }
    }
  }
  std::string context() const { return context_; }

 private:
  template <typename T>
  static double Cast(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof(T));
    return static_cast<double>(v);
  }
  Encoding encoding_;
  TextCursor text_;
  std::string_view bytes_;
  size_t pos_ = 0;
  std::string name_, context_;
  bool swap_;
};

int FindProperty(const PlyElement& e, std::initializer_list<const char*> names) {
  for (size_t i = 0; i < e.properties.size(); ++i) {
    for (const char* n : names) {
      if (e.properties[i].name == n) return static_cast<int>(i);
    }
  }
  return -1;
}

}  // namespace

namespace {

// The PLY header: the magic line, the format and the elements with their properties. Leaves the
// cursor at the start of the body.
struct PlyHeader {
  Encoding encoding = Encoding::kAscii;
  std::vector<PlyElement> elements;
};

PlyHeader ReadPlyHeader(TextCursor& c) {
  const std::string_view magic = c.Token();
  if (magic != "ply" || !c.AtLineEnd()) {
    c.Fail("not a PLY file: expected 'ply' on the first line, found " + Quote(magic));
  }
  c.NextLine();
  PlyHeader out;
  bool has_format = false;
  std::vector<PlyElement>& elements = out.elements;
  while (true) {
    if (!c.SkipToContent()) c.Fail("truncated header: no 'end_header' line");
    const std::string_view kw = c.Token();
    if (kw == "end_header") {
      if (!c.AtLineEnd()) c.Fail("unexpected token after 'end_header'");
      break;
    } else if (kw == "comment" || kw == "obj_info") {
    } else if (kw == "format") {
      const std::string_view f = c.Token();
      if (f == "ascii") {
        out.encoding = Encoding::kAscii;
      } else if (f == "binary_little_endian") {
        out.encoding = Encoding::kLittleEndian;
      } else if (f == "binary_big_endian") {
        out.encoding = Encoding::kBigEndian;
      } else {
        c.Fail("unknown PLY format " + Quote(f));
      }
      const std::string_view version = c.Token();
      double number;
      if (!ParseDouble(version, &number)) c.Fail("invalid PLY format version " + Quote(version));
      has_format = true;
    } else if (kw == "element") {
      PlyElement e;
      e.name = std::string(c.Token());
      e.count = c.Int("element count");
      if (e.name.empty() || e.count < 0 || e.count > 1000000000) {
        c.Fail("invalid element line (expected 'element NAME COUNT')");
      }
      for (const auto& other : elements) {
        if (other.name == e.name) c.Fail("element '" + e.name + "' declared twice");
      }
      elements.push_back(std::move(e));
    } else if (kw == "property") {
      if (elements.empty()) c.Fail("property before any element");
      PlyProperty p;
      std::string_view type = c.Token();
      if (type == "list") {
        p.is_list = true;
        if (!ParsePlyType(c.Token(), &p.count_type) || IsFloat(p.count_type)) {
          c.Fail("invalid list count type (expected an integer type)");
        }
        type = c.Token();
      }
      if (!ParsePlyType(type, &p.type)) c.Fail("unknown property type " + Quote(type));
      p.name = std::string(c.Token());
      if (p.name.empty()) c.Fail("property without a name");
      elements.back().properties.push_back(std::move(p));
    } else {
      c.Fail("unknown header keyword " + Quote(kw));
    }
    if (kw != "comment" && kw != "obj_info" && !c.AtLineEnd()) {
      c.Fail("unexpected token " + Quote(c.Token()) + " in header line");
    }
    c.NextLine();
  }
  if (!has_format) c.Fail("header has no 'format' line");
  c.NextLine();
  return out;
}

// Where a PLY file's mesh is: its vertex and face elements, the properties of the coordinates,
// the colours (-1 when absent) and the face's vertex ids.
struct PlyLayout {
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  int coord[3] = {-1, -1, -1};
  int color[3] = {-1, -1, -1};
  bool has_color = false;
  int ids_prop = -1;
};

// Fails (Fail) naming the file when an element or property the mesh needs is missing.
PlyLayout FindPlyLayout(const std::vector<PlyElement>& elements, const std::string& name) {
  PlyLayout layout;
  const auto vertex_it = std::find_if(elements.begin(), elements.end(),
                                      [](const PlyElement& e) { return e.name == "vertex"; });
  if (vertex_it == elements.end()) Fail(name, 0, "PLY header has no 'vertex' element");
  const auto face_it = std::find_if(elements.begin(), elements.end(),
                                    [](const PlyElement& e) { return e.name == "face"; });
  if (face_it == elements.end()) Fail(name, 0, "PLY header has no 'face' element");
  layout.vertex = &*vertex_it;
  layout.face = &*face_it;
  const char* axes[3] = {"x", "y", "z"};
  const char* channels[3] = {"red", "green", "blue"};
  for (int k = 0; k < 3; ++k) {
    layout.coord[k] = FindProperty(*vertex_it, {axes[k]});
    if (layout.coord[k] < 0 || vertex_it->properties[layout.coord[k]].is_list) {
      Fail(name, 0, std::string("'vertex' element has no scalar property '") + axes[k] + "'");
    }
    layout.color[k] = FindProperty(*vertex_it, {channels[k], k == 0 ? "r" : k == 1 ? "g" : "b"});
  }
  layout.has_color = layout.color[0] >= 0 && layout.color[1] >= 0 && layout.color[2] >= 0;
  layout.ids_prop = FindProperty(*face_it, {"vertex_indices", "vertex_index"});
  if (layout.ids_prop < 0 || !face_it->properties[layout.ids_prop].is_list) {
    Fail(name, 0, "'face' element has no list property 'vertex_indices'");
  }
  return layout;
}

}  // namespace

void ReadPly(std::string_view data, const std::string& name, RawMesh* mesh) {
  TextCursor c(data, name, 0);
  const PlyHeader header = ReadPlyHeader(c);
  const Encoding encoding = header.encoding;
  const std::vector<PlyElement>& elements = header.elements;
  const PlyLayout layout = FindPlyLayout(elements, name);
  const PlyElement* vertex = layout.vertex;
  const int64_t nv = vertex->count;
  const int* coord = layout.coord;
  const int* color = layout.color;
  const bool has_color = layout.has_color;
  const int ids_prop = layout.ids_prop;

  PlyBody body(data.substr(c.pos()), c.line(), encoding, name);
  std::vector<double> values;
  std::vector<int> ids;
  for (const PlyElement& e : elements) {
    const bool is_vertex = &e == vertex, is_face = &e == layout.face;
    if (e.count > 0 && e.properties.empty()) Fail(name, 0, "element '" + e.name + "' is empty");
    int64_t record_bytes = 0;
    for (const auto& p : e.properties) record_bytes += SizeOf(p.is_list ? p.count_type : p.type);
    if (encoding != Encoding::kAscii && record_bytes > 0 &&
        e.count > static_cast<int64_t>(body.Remaining()) / record_bytes) {
      Fail(name, 0,
           "truncated binary data: element '" + e.name + "' declares " + std::to_string(e.count) +
               " records, more than the file holds");
    }
    if (is_vertex) mesh->positions.reserve(3 * e.count);
    if (is_vertex && has_color) mesh->colors.reserve(3 * e.count);
    for (int64_t i = 0; i < e.count; ++i) {
      body.BeginRecord(e, i);
      values.assign(e.properties.size(), 0.0);
      for (size_t j = 0; j < e.properties.size(); ++j) {
        const PlyProperty& p = e.properties[j];
        if (!p.is_list) {
          values[j] = body.Read(p.type);
          continue;
        }
        const double n = body.Read(p.count_type);
        if (n < 0) Fail(name, 0, "negative list length in " + body.context());
        body.Require(static_cast<int64_t>(n) * SizeOf(p.type));
        const bool face_ids = is_face && static_cast<int>(j) == ids_prop;
        if (face_ids && n < 3) {
          Fail(name, 0,
               "face " + std::to_string(i) + " has " + std::to_string(int64_t(n)) +
                   " vertices; a face needs at least 3");
        }
        if (face_ids) ids.clear();
        for (int64_t k = 0; k < static_cast<int64_t>(n); ++k) {
          const double id = body.Read(p.type);
          if (!face_ids) continue;
          if (!(id >= 0 && id < static_cast<double>(nv)) || id != std::floor(id)) {
            char id_text[32];
            std::snprintf(id_text, sizeof(id_text), "%.17g", id);
            Fail(name, 0,
                 "face " + std::to_string(i) + ": vertex id " + id_text + " out of range [0, " +
                     std::to_string(nv) + ")");
          }
          ids.push_back(static_cast<int>(id));
        }
        if (face_ids) AppendFan(ids.data(), static_cast<int>(ids.size()), &mesh->triangles);
      }
      body.EndRecord();
      if (is_vertex) {
        for (int k = 0; k < 3; ++k) mesh->positions.push_back(values[coord[k]]);
        for (int k = 0; has_color && k < 3; ++k) {
          const PlyProperty& p = e.properties[color[k]];
          const double v = IsFloat(p.type) ? values[color[k]] : values[color[k]] / 255.0;
          mesh->colors.push_back(Clamp01(v));
        }
      }
    }
  }
  body.Finish();
}

}  // namespace symembed::mesh_io
