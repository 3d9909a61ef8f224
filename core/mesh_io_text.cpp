// Tokenizer and the text readers (OFF, OBJ).
#include <algorithm>
#include <charconv>
#include <cstring>

#include "core/errors.h"
#include "core/mesh_io_internal.h"

namespace symembed::mesh_io {

void Fail(const std::string& name, int line, const std::string& what) {
  if (line > 0) throw InvalidInputError(name + ":" + std::to_string(line) + ": " + what);
  throw InvalidInputError(name + ": " + what);
}

std::string Quote(std::string_view token) {
  static const char kHex[] = "0123456789abcdef";
  std::string out = "'";
  const size_t n = std::min<size_t>(token.size(), 24);
  for (size_t i = 0; i < n; ++i) {
    const unsigned char ch = static_cast<unsigned char>(token[i]);
    if (ch >= 0x20 && ch < 0x7f) {
      out += static_cast<char>(ch);
    } else {
      out += "\\x";
      out += kHex[ch >> 4];
      out += kHex[ch & 15];
    }
  }
  if (token.size() > n) out += "...";
  return out + "'";
}

void AppendFan(const int* ids, int n, std::vector<int>* triangles) {
  for (int i = 1; i + 1 < n; ++i) {
    triangles->push_back(ids[0]);
    triangles->push_back(ids[i]);
    triangles->push_back(ids[i + 1]);
  }
}

bool ParseDouble(std::string_view token, double* value) {
  // from_chars rejects a leading '+', which some writers emit.
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
  return ec == std::errc() && ptr == end && !token.empty();
}

bool ParseInt(std::string_view token, int64_t* value) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
  return ec == std::errc() && ptr == end && !token.empty();
}

TextCursor::TextCursor(std::string_view data, std::string name, char comment_char, int first_line)
    : data_(data), name_(std::move(name)), comment_char_(comment_char), line_(first_line) {}

static bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

bool TextCursor::AtLineEnd() {
  while (pos_ < data_.size() && IsBlank(data_[pos_])) ++pos_;
  return pos_ >= data_.size() || data_[pos_] == '\n' ||
         (comment_char_ != 0 && data_[pos_] == comment_char_);
}

void TextCursor::NextLine() {
  if (pos_ >= data_.size()) return;
  const void* nl = std::memchr(data_.data() + pos_, '\n', data_.size() - pos_);
  if (nl == nullptr) {
    pos_ = data_.size();
    return;
  }
  pos_ = static_cast<const char*>(nl) - data_.data() + 1;
  ++line_;
}

bool TextCursor::SkipToContent() {
  while (AtLineEnd()) {
    if (AtEnd()) return false;
    NextLine();
  }
  return true;
}

std::string_view TextCursor::Token() {
  if (AtLineEnd()) return {};
  const size_t start = pos_;
  while (pos_ < data_.size() && !IsBlank(data_[pos_]) && data_[pos_] != '\n' &&
         !(comment_char_ != 0 && data_[pos_] == comment_char_)) {
    ++pos_;
  }
  return data_.substr(start, pos_ - start);
}

double TextCursor::Double(const std::string& what) {
  double value = 0.0;
  if (!TryDouble(what, &value)) Fail("expected a number (" + what + "), found end of line");
  return value;
}

bool TextCursor::TryDouble(const std::string& what, double* value) {
  const std::string_view token = Token();
  if (token.empty()) return false;
  if (!ParseDouble(token, value)) {
    Fail("expected a number (" + what + "), found " + Quote(token));
  }
  return true;
}

int64_t TextCursor::Int(const std::string& what) {
  const std::string_view token = Token();
  if (token.empty()) Fail("expected an integer (" + what + "), found end of line");
  int64_t value = 0;
  if (!ParseInt(token, &value)) Fail("expected an integer (" + what + "), found " + Quote(token));
  return value;
}

namespace {

// Reads a colour component given as a 0-255 integer or a 0-1 real; clamps into [0, 1].
double ColorComponent(std::string_view token, double value) {
  const bool is_integer = token.find_first_of(".eEnN") == std::string_view::npos;
  if (is_integer) value /= 255.0;
  return Clamp01(value);
}

}  // namespace

namespace {

// What the OFF header says: the variant's optional per-vertex fields and the counts.
struct OffHeader {
  bool has_st = false, has_color = false, has_normal = false;
  int64_t vertices = 0, faces = 0;
};

// The OFF header: its variant letters and the counts line. Leaves the cursor at the first vertex
// line.
OffHeader ReadOffHeader(TextCursor& c) {
  if (!c.SkipToContent()) c.Fail("no OFF header (the file holds only blanks and comments)");
  const std::string_view header = c.Token();
  std::string_view h = header;
  OffHeader out;
  if (h.substr(0, 2) == "ST") {
    out.has_st = true;
    h.remove_prefix(2);
  }
  if (h.substr(0, 1) == "C") {
    out.has_color = true;
    h.remove_prefix(1);
  }
  if (h.substr(0, 1) == "N") {
    out.has_normal = true;
    h.remove_prefix(1);
  }
  if (h == "4OFF" || h == "nOFF" || h == "4nOFF") {
    c.Fail("unsupported OFF variant " + Quote(header) + " (only 3D OFF is read)");
  }
  if (h != "OFF") {
    c.Fail("expected an OFF header ('OFF', 'COFF', 'NOFF', ...), found " + Quote(header));
  }
  if (!c.AtLineEnd()) {
    // Counts may follow the header on the same line; "OFF BINARY" is the binary variant.
    const std::string_view next = c.Token();
    if (next == "BINARY") c.Fail("binary OFF is not supported");
    c.Fail("unexpected token " + Quote(next) +
           " after the OFF header (counts go on the next line)");
  }
  auto count = [&](const char* what) {
    if (!c.SkipToContent()) c.Fail(std::string("truncated header: missing the ") + what);
    const int64_t n = c.Int(what);
    if (n < 0 || n > 1000000000) c.Fail(std::string("invalid ") + what + " " + std::to_string(n));
    return n;
  };
  out.vertices = count("vertex count");
  out.faces = count("face count");
  count("edge count");
  if (!c.AtLineEnd()) c.Fail("unexpected token " + Quote(c.Token()) + " after the counts line");
  c.NextLine();
  return out;
}

// The header's vertices: positions, and colours when the variant has them.
void ReadOffVertices(TextCursor& c, const OffHeader& h, size_t data_size, RawMesh* mesh) {
  const int64_t nv = h.vertices;
  const bool has_st = h.has_st, has_color = h.has_color, has_normal = h.has_normal;
  // Reserve no more than the file could hold, so a garbage count cannot exhaust memory.
  mesh->positions.reserve(3 * std::min<int64_t>(nv, data_size / 6 + 1));
  if (has_color) mesh->colors.reserve(3 * std::min<int64_t>(nv, data_size / 6 + 1));
  const int base = 3 + (has_normal ? 3 : 0) + (has_st ? 2 : 0);
  const std::string hint = " (does the header's vertex count " + std::to_string(nv) + " match?)";
  for (int64_t i = 0; i < nv; ++i) {
    if (!c.SkipToContent()) {
      c.Fail("truncated: the file ends after " + std::to_string(i) + " of " + std::to_string(nv) +
             " vertices");
    }
    double values[16];
    std::string_view tokens[16];
    int k = 0;
    for (std::string_view t = c.Token(); !t.empty(); t = c.Token()) {
      if (k == 16) c.Fail("vertex " + std::to_string(i) + " has more than 16 values" + hint);
      if (!ParseDouble(t, &values[k])) {
        c.Fail("expected a number (vertex " + std::to_string(i) + "), found " + Quote(t));
      }
      tokens[k++] = t;
    }
    const bool ok = has_color ? (k == base + 3 || k == base + 4) : k == base;
    if (!ok) {
      c.Fail("vertex " + std::to_string(i) + " has " + std::to_string(k) + " values, expected " +
             (has_color ? std::to_string(base + 3) + " or " + std::to_string(base + 4)
                        : std::to_string(base)) +
             hint);
    }
    mesh->positions.insert(mesh->positions.end(), values, values + 3);
    if (has_color) {
      const int at = 3 + (has_normal ? 3 : 0);
      for (int j = at; j < at + 3; ++j)
        mesh->colors.push_back(ColorComponent(tokens[j], values[j]));
    }
    c.NextLine();
  }
}

// The header's faces, each fanned into triangles; per-face colours are skipped (but must be
// numeric).
void ReadOffFaces(TextCursor& c, const OffHeader& h, size_t data_size, RawMesh* mesh) {
  const int64_t nv = h.vertices, nf = h.faces;
  const std::string hint = " (does the header's vertex count " + std::to_string(nv) + " match?)";
  mesh->triangles.reserve(3 * std::min<int64_t>(nf, data_size / 8 + 1));
  std::vector<int> ids;
  for (int64_t f = 0; f < nf; ++f) {
    if (!c.SkipToContent()) {
      c.Fail("truncated: the file ends after " + std::to_string(f) + " of " + std::to_string(nf) +
             " faces");
    }
    const int64_t n = c.Int("vertex count of face " + std::to_string(f));
    if (n < 3) {
      c.Fail("face " + std::to_string(f) + " has " + std::to_string(n) +
             " vertices; a face needs at least 3" + hint);
    }
    ids.clear();
    for (int64_t j = 0; j < n; ++j) {
      const std::string_view t = c.Token();
      int64_t id = 0;
      if (t.empty()) {
        c.Fail("face " + std::to_string(f) + " declares " + std::to_string(n) +
               " vertices but lists " + std::to_string(j));
      }
      if (!ParseInt(t, &id)) {
        c.Fail("expected an integer vertex id (face " + std::to_string(f) + "), found " + Quote(t));
      }
      if (id < 0 || id >= nv) {
        c.Fail("face " + std::to_string(f) + ": vertex id " + std::to_string(id) +
               " out of range [0, " + std::to_string(nv) + ")");
      }
      ids.push_back(static_cast<int>(id));
    }
    // Anything after the ids is a per-face colour; it must still be numeric.
    for (std::string_view t = c.Token(); !t.empty(); t = c.Token()) {
      double ignored;
      if (!ParseDouble(t, &ignored)) {
        c.Fail("unexpected token " + Quote(t) + " after the vertex ids of face " +
               std::to_string(f));
      }
    }
    AppendFan(ids.data(), static_cast<int>(ids.size()), &mesh->triangles);
    c.NextLine();
  }
}

}  // namespace

void ReadOff(std::string_view data, const std::string& name, RawMesh* mesh) {
  TextCursor c(data, name, '#');
  const OffHeader header = ReadOffHeader(c);
  ReadOffVertices(c, header, data.size(), mesh);
  ReadOffFaces(c, header, data.size(), mesh);
  if (c.SkipToContent()) {
    c.Fail("unexpected data " + Quote(c.Token()) + " after the " + std::to_string(header.faces) +
           " faces declared in the header");
  }
}

namespace {

bool IsIgnoredObjStatement(std::string_view kw) {
  static const char* const kIgnored[] = {
      "vt",     "vn",     "vp",     "o",          "g",         "s",        "usemtl",
      "mtllib", "l",      "p",      "mg",         "cstype",    "deg",      "bmat",
      "step",   "curv",   "curv2",  "surf",       "parm",      "trim",     "hole",
      "scrv",   "sp",     "end",    "con",        "bevel",     "c_interp", "d_interp",
      "lod",    "usemap", "maplib", "shadow_obj", "trace_obj", "ctech",    "stech"};
  for (const char* s : kIgnored) {
    if (kw == s) return true;
  }
  return false;
}

}  // namespace

void ReadObj(std::string_view data, const std::string& name, RawMesh* mesh) {
  TextCursor c(data, name, '#');
  int64_t colored = 0;
  std::vector<int> ids;
  // Positive ids may refer to vertices defined later in the file; they are checked at the end.
  std::vector<std::pair<int, int64_t>> forward_refs;  // (line, 0-based id)
  while (c.SkipToContent()) {
    const std::string_view kw = c.Token();
    if (kw == "v") {
      double values[8];
      int k = 0;
      double value;
      while (c.TryDouble("vertex coordinate", &value)) {
        if (k == 7) c.Fail("vertex has more than 7 values (expected x y z [w] or x y z r g b)");
        values[k++] = value;
      }
      if (k != 3 && k != 4 && k != 6) {
        c.Fail("vertex has " + std::to_string(k) + " values (expected x y z [w] or x y z r g b)");
      }
      if (mesh->positions.size() >= 3u * 1000000000u) c.Fail("too many vertices");
      mesh->positions.insert(mesh->positions.end(), values, values + 3);
      if (k == 6) {
        // Colours are stored for every vertex; they are dropped below unless all have one.
        mesh->colors.resize(mesh->positions.size() - 3, 0.0);
        for (int j = 3; j < 6; ++j) mesh->colors.push_back(Clamp01(values[j]));
        ++colored;
      }
    } else if (kw == "f") {
      const int64_t nv = mesh->NumVertices();
      ids.clear();
      for (std::string_view t = c.Token(); !t.empty(); t = c.Token()) {
        const std::string_view head = t.substr(0, t.find('/'));
        int64_t id = 0;
        if (!ParseInt(head, &id)) c.Fail("expected a vertex id in face, found " + Quote(t));
        for (char ch : t.substr(head.size())) {
          if (ch != '/' && ch != '-' && (ch < '0' || ch > '9')) {
            c.Fail("malformed face vertex " + Quote(t));
          }
        }
        if (id == 0) c.Fail("vertex id 0 in face (OBJ ids start at 1)");
        id = id > 0 ? id - 1 : nv + id;
        if (id < 0) c.Fail("relative vertex id " + Quote(t) + " points before the first vertex");
        if (id >= nv) forward_refs.emplace_back(c.line(), id);
        if (id > 1000000000) c.Fail("vertex id " + Quote(t) + " out of range");
        ids.push_back(static_cast<int>(id));
      }
      if (ids.size() < 3) {
        c.Fail("face has " + std::to_string(ids.size()) + " vertices; a face needs at least 3");
      }
      AppendFan(ids.data(), static_cast<int>(ids.size()), &mesh->triangles);
    } else if (!IsIgnoredObjStatement(kw)) {
      c.Fail("unknown OBJ statement " + Quote(kw));
    }
    c.NextLine();
  }
  const int64_t nv = mesh->NumVertices();
  for (const auto& [line, id] : forward_refs) {
    if (id >= nv) {
      Fail(name, line,
           "vertex id " + std::to_string(id + 1) + " out of range [1, " + std::to_string(nv) + "]");
    }
  }
  if (colored != nv) mesh->colors.clear();
}

}  // namespace symembed::mesh_io
