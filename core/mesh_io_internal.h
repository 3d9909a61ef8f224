// Building blocks shared by the mesh file readers (core/mesh_io*.cpp); not a public interface.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace symembed::mesh_io {

// A mesh as read from a file, before conversion to Surface.
struct RawMesh {
  std::vector<double> positions;  // 3 per vertex
  std::vector<int> triangles;     // 3 per triangle, 0-based, checked against the vertex count
  std::vector<double> colors;     // 3 per vertex in [0, 1], or empty when not every vertex has one
  int NumVertices() const { return static_cast<int>(positions.size() / 3); }
};

// Throws InvalidInputError "name:line: what" (or "name: what" when line <= 0).
[[noreturn]] void Fail(const std::string& name, int line, const std::string& what);

// A token for an error message: quoted, at most 24 characters, non-printable bytes as \xNN.
std::string Quote(std::string_view token);

// Clamps a colour component into [0, 1]; NaN becomes 0.
inline double Clamp01(double v) { return v > 0.0 ? (v < 1.0 ? v : 1.0) : 0.0; }

// Appends the fan triangulation (p0, pi, pi+1) of a polygon.
void AppendFan(const int* ids, int n, std::vector<int>* triangles);

// Line-oriented tokenizer over a text buffer. Tokens are separated by spaces, tabs and '\r';
// '\n' ends a line; when comment_char is non-zero it starts a comment that runs to the end of
// the line. Numbers are parsed locale-independently with std::from_chars, and a token must be a
// number as a whole ("1.5x" is rejected).
class TextCursor {
 public:
  TextCursor(std::string_view data, std::string name, char comment_char, int first_line = 1);

  // Skips blanks on the current line; true when the line has no further token.
  bool AtLineEnd();
  // Moves to the start of the next line (no-op at end of data).
  void NextLine();
  // Moves to the next line holding a token (staying on the current one if it has one); false at
  // end of data.
  bool SkipToContent();
  bool AtEnd() const { return pos_ >= data_.size(); }

  // Next token on the current line; empty when the line has none.
  std::string_view Token();
  // Parse the next token on the current line; `what` names the value in error messages. Fails
  // (throws) at line end or when the token is not a number of that type.
  double Double(const std::string& what);
  int64_t Int(const std::string& what);
  // As above without failing: false when the line has no further token; throws on a bad token.
  bool TryDouble(const std::string& what, double* value);

  int line() const { return line_; }
  size_t pos() const { return pos_; }
  const std::string& name() const { return name_; }
  [[noreturn]] void Fail(const std::string& what) const { mesh_io::Fail(name_, line_, what); }

 private:
  std::string_view data_;
  std::string name_;
  char comment_char_;
  size_t pos_ = 0;
  int line_ = 1;
};

// Parses a number token as a whole; false on failure or overflow.
bool ParseDouble(std::string_view token, double* value);
bool ParseInt(std::string_view token, int64_t* value);

// Readers per format: fill *mesh or throw InvalidInputError naming `name`.
void ReadOff(std::string_view data, const std::string& name, RawMesh* mesh);
void ReadObj(std::string_view data, const std::string& name, RawMesh* mesh);
void ReadPly(std::string_view data, const std::string& name, RawMesh* mesh);
void ReadStl(std::string_view data, const std::string& name, RawMesh* mesh);

}  // namespace symembed::mesh_io
