#include "eval/json.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "core/errors.h"

namespace symembed {

JsonValue JsonValue::Bool(bool b) {
  JsonValue v;
  v.type_ = Type::kBool;
  v.bool_ = b;
  return v;
}

JsonValue JsonValue::Number(double x) {
  JsonValue v;
  v.type_ = Type::kNumber;
  v.number_ = x;
  return v;
}

JsonValue JsonValue::String(std::string s) {
  JsonValue v;
  v.type_ = Type::kString;
  v.string_ = std::move(s);
  return v;
}

JsonValue JsonValue::Array() {
  JsonValue v;
  v.type_ = Type::kArray;
  return v;
}

JsonValue JsonValue::Object() {
  JsonValue v;
  v.type_ = Type::kObject;
  return v;
}

bool JsonValue::AsBool() const {
  if (type_ != Type::kBool) throw InvalidInputError("json: expected a boolean");
  return bool_;
}

double JsonValue::AsNumber() const {
  if (type_ != Type::kNumber) throw InvalidInputError("json: expected a number");
  return number_;
}

double JsonValue::NumberOr(double fallback) const {
  return type_ == Type::kNumber ? number_ : fallback;
}

const std::string& JsonValue::AsString() const {
  if (type_ != Type::kString) throw InvalidInputError("json: expected a string");
  return string_;
}

void JsonValue::Push(JsonValue v) {
  SYMEMBED_CHECK(type_ == Type::kArray, "Push on a non-array JSON value");
  items_.push_back(std::move(v));
}

void JsonValue::Set(const std::string& key, JsonValue v) {
  SYMEMBED_CHECK(type_ == Type::kObject, "Set on a non-object JSON value");
  for (auto& m : members_) {
    if (m.first == key) {
      m.second = std::move(v);
      return;
    }
  }
  members_.emplace_back(key, std::move(v));
}

bool JsonValue::Has(const std::string& key) const {
  for (const auto& m : members_) {
    if (m.first == key) return true;
  }
  return false;
}

const JsonValue& JsonValue::Get(const std::string& key) const {
  static const JsonValue kNull;
  for (const auto& m : members_) {
    if (m.first == key) return m.second;
  }
  return kNull;
}

std::string FormatExactDouble(double x) {
  if (!std::isfinite(x)) return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
  // to_chars with a precision writes what printf's %.*g writes, and from_chars reads what
  // strtod reads (both correctly rounded), several times faster.
  char buffer[40];
  char* end = buffer;
  for (int precision : {15, 16, 17}) {
    end =
        std::to_chars(buffer, buffer + sizeof buffer, x, std::chars_format::general, precision).ptr;
    double back = 0.0;
    const std::from_chars_result read = std::from_chars(buffer, end, back);
    if (read.ec == std::errc() && back == x) break;
  }
  return std::string(buffer, end);
}

namespace {

void WriteString(const std::string& s, std::ostringstream& out) {
  out << '"';
  for (unsigned char c : s) {
    switch (c) {
      case '"': out << "\\\""; break;
      case '\\': out << "\\\\"; break;
      case '\n': out << "\\n"; break;
      case '\r': out << "\\r"; break;
      case '\t': out << "\\t"; break;
      default:
        if (c < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
          out << buffer;
        } else {
          out << c;
        }
    }
  }
  out << '"';
}

bool AllScalars(const std::vector<JsonValue>& items) {
  for (const auto& v : items) {
    if (v.IsArray() || v.IsObject()) return false;
  }
  return true;
}

// A line break and the indentation of nesting level `level`; nothing on one line (indent 0).
std::string Pad(int indent, int level) {
  return indent > 0 ? "\n" + std::string(indent * level, ' ') : "";
}

void Write(const JsonValue& v, int indent, int depth, std::ostringstream& out) {
  switch (v.type()) {
    case JsonValue::Type::kNull: out << "null"; break;
    case JsonValue::Type::kBool: out << (v.AsBool() ? "true" : "false"); break;
    case JsonValue::Type::kNumber:
      out << (std::isfinite(v.AsNumber()) ? FormatExactDouble(v.AsNumber()) : "null");
      break;
    case JsonValue::Type::kString: WriteString(v.AsString(), out); break;
    case JsonValue::Type::kArray: {
      // Arrays of scalars (error vectors) stay on one line even when pretty-printing.
      const bool flat = indent == 0 || AllScalars(v.items());
      out << '[';
      for (size_t i = 0; i < v.items().size(); ++i) {
        if (i > 0) out << (flat ? ", " : ",");
        if (!flat) out << Pad(indent, depth + 1);
        Write(v.items()[i], indent, depth + 1, out);
      }
      if (!flat && !v.items().empty()) out << Pad(indent, depth);
      out << ']';
      break;
    }
    case JsonValue::Type::kObject: {
      out << '{';
      for (size_t i = 0; i < v.members().size(); ++i) {
        if (i > 0) out << (indent > 0 ? "," : ", ");
        out << Pad(indent, depth + 1);
        WriteString(v.members()[i].first, out);
        out << ": ";
        Write(v.members()[i].second, indent, depth + 1, out);
      }
      if (!v.members().empty()) out << Pad(indent, depth);
      out << '}';
      break;
    }
  }
}

class Parser {
 public:
  Parser(const std::string& text, const std::string& where) : s_(text), where_(where) {}

  JsonValue ParseDocument() {
    JsonValue v = ParseValue(0);
    SkipSpace();
    if (pos_ != s_.size()) Fail("unexpected text after the JSON value");
    return v;
  }

 private:
  [[noreturn]] void Fail(const std::string& what) const {
    int line = 1, col = 1;
    for (size_t i = 0; i < pos_ && i < s_.size(); ++i) {
      if (s_[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    throw InvalidInputError(where_ + ":" + std::to_string(line) + ":" + std::to_string(col) +
                            ": " + what);
  }

  void SkipSpace() {
    while (pos_ < s_.size() &&
           (s_[pos_] == ' ' || s_[pos_] == '\n' || s_[pos_] == '\t' || s_[pos_] == '\r')) {
      ++pos_;
    }
  }

  bool Consume(const char* word) {
    const std::string w(word);
    if (s_.compare(pos_, w.size(), w) != 0) return false;
    pos_ += w.size();
    return true;
  }

  JsonValue ParseValue(int depth) {
    if (depth > 64) Fail("nesting too deep");
    SkipSpace();
    if (pos_ >= s_.size()) Fail("unexpected end of input");
    const char c = s_[pos_];
    if (c == '{') return ParseObject(depth);
    if (c == '[') return ParseArray(depth);
    if (c == '"') return JsonValue::String(ParseString());
    if (Consume("null")) return JsonValue();
    if (Consume("true")) return JsonValue::Bool(true);
    if (Consume("false")) return JsonValue::Bool(false);
    if (c == '-' || (c >= '0' && c <= '9')) return ParseNumber();
    Fail(std::string("unexpected character '") + c + "'");
  }

  JsonValue ParseNumber() {
    const size_t start = pos_;
    while (pos_ < s_.size() && IsNumberChar(s_[pos_])) ++pos_;
    const char* first = s_.data() + start;
    const char* last = s_.data() + pos_;
    // from_chars reads what strtod reads (correctly rounded, the token starting with '-' or a
    // digit); what it does not read as a whole (malformed, or out of range, where strtod gives
    // an underflow's 0 or subnormal) strtod decides.
    double x = 0.0;
    const std::from_chars_result read = std::from_chars(first, last, x);
    if (read.ec != std::errc() || read.ptr != last) {
      const std::string token(first, last);
      char* end = nullptr;
      x = std::strtod(token.c_str(), &end);
      if (end != token.c_str() + token.size()) {
        pos_ = start;
        Fail("malformed number '" + token + "'");
      }
      if (!std::isfinite(x)) {
        pos_ = start;
        Fail("number '" + token + "' is out of range");
      }
    }
    return JsonValue::Number(x);
  }

  static bool IsNumberChar(char c) {
    return (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.' || c == 'e' || c == 'E';
  }

  std::string ParseString() {
    ++pos_;  // opening quote
    std::string out;
    while (true) {
      if (pos_ >= s_.size()) Fail("unterminated string");
      const char c = s_[pos_++];
      if (c == '"') return out;
      if (c != '\\') {
        out += c;
        continue;
      }
      if (pos_ >= s_.size()) Fail("unterminated string");
      const char e = s_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': AppendCodePoint(ParseHex4(), out); break;
        default: Fail(std::string("unknown escape '\\") + e + "'");
      }
    }
  }

  unsigned ParseHex4() {
    if (pos_ + 4 > s_.size()) Fail("short \\u escape");
    unsigned code = 0;
    for (int i = 0; i < 4; ++i) {
      const char h = s_[pos_++];
      code <<= 4;
      if (h >= '0' && h <= '9') code |= h - '0';
      else if (h >= 'a' && h <= 'f') code |= h - 'a' + 10;
      else if (h >= 'A' && h <= 'F') code |= h - 'A' + 10;
      else Fail("bad hex digit in \\u escape");
    }
    return code;
  }

  // UTF-8 encoding of a code point (surrogate pairs are combined).
  void AppendCodePoint(unsigned code, std::string& out) {
    if (code >= 0xD800 && code < 0xDC00 && Consume("\\u")) {
      const unsigned low = ParseHex4();
      code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
    }
    if (code < 0x80) {
      out += static_cast<char>(code);
    } else if (code < 0x800) {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  JsonValue ParseArray(int depth) {
    ++pos_;
    JsonValue v = JsonValue::Array();
    SkipSpace();
    if (pos_ < s_.size() && s_[pos_] == ']') {
      ++pos_;
      return v;
    }
    while (true) {
      v.Push(ParseValue(depth + 1));
      SkipSpace();
      if (pos_ < s_.size() && s_[pos_] == ',') {
        ++pos_;
      } else if (pos_ < s_.size() && s_[pos_] == ']') {
        ++pos_;
        return v;
      } else {
        Fail("expected ',' or ']' in array");
      }
    }
  }

  JsonValue ParseObject(int depth) {
    ++pos_;
    JsonValue v = JsonValue::Object();
    SkipSpace();
    if (pos_ < s_.size() && s_[pos_] == '}') {
      ++pos_;
      return v;
    }
    while (true) {
      SkipSpace();
      if (pos_ >= s_.size() || s_[pos_] != '"') Fail("expected a string key in object");
      const size_t key_start = pos_;
      const std::string key = ParseString();
      if (v.Has(key)) {
        pos_ = key_start;
        Fail("duplicate key \"" + key + "\" in object");
      }
      SkipSpace();
      if (pos_ >= s_.size() || s_[pos_] != ':') Fail("expected ':' after object key");
      ++pos_;
      v.Set(key, ParseValue(depth + 1));
      SkipSpace();
      if (pos_ < s_.size() && s_[pos_] == ',') {
        ++pos_;
      } else if (pos_ < s_.size() && s_[pos_] == '}') {
        ++pos_;
        return v;
      } else {
        Fail("expected ',' or '}' in object");
      }
    }
  }

  const std::string& s_;
  std::string where_;
  size_t pos_ = 0;
};

}  // namespace

std::string WriteJson(const JsonValue& v, int indent) {
  std::ostringstream out;
  Write(v, indent, 0, out);
  return out.str();
}

JsonValue ParseJson(const std::string& text, const std::string& where) {
  return Parser(text, where).ParseDocument();
}

}  // namespace symembed
