// A minimal JSON value with a deterministic writer and a strict reader, for the small files the
// evaluator writes and reads back (summary.json, baselines, per-pair records).
//
// Numbers are doubles written with 17 significant digits, so Parse(Write(x)) == x exactly.
// NaN and infinities, which JSON cannot represent, are written as null; NumberOr() reads null
// back as NaN. Objects keep insertion order so that output is stable and readable.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace symembed {

class JsonValue {
 public:
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject };

  JsonValue() = default;  // null
  static JsonValue Bool(bool b);
  static JsonValue Number(double x);
  static JsonValue String(std::string s);
  static JsonValue Array();
  static JsonValue Object();

  Type type() const { return type_; }
  bool IsNull() const { return type_ == Type::kNull; }
  bool IsNumber() const { return type_ == Type::kNumber; }
  bool IsString() const { return type_ == Type::kString; }
  bool IsArray() const { return type_ == Type::kArray; }
  bool IsObject() const { return type_ == Type::kObject; }

  bool AsBool() const;                 // throws InvalidInputError on a type mismatch
  double AsNumber() const;             // throws InvalidInputError on a type mismatch
  double NumberOr(double fallback) const;  // number, or fallback (e.g. NaN) for null/others
  const std::string& AsString() const;

  // Arrays.
  void Push(JsonValue v);
  const std::vector<JsonValue>& items() const { return items_; }

  // Objects: Set replaces an existing key in place or appends it.
  void Set(const std::string& key, JsonValue v);
  bool Has(const std::string& key) const;
  // The member, or a null value when absent.
  const JsonValue& Get(const std::string& key) const;
  const std::vector<std::pair<std::string, JsonValue>>& members() const { return members_; }

 private:
  Type type_ = Type::kNull;
  bool bool_ = false;
  double number_ = 0.0;
  std::string string_;
  std::vector<JsonValue> items_;
  std::vector<std::pair<std::string, JsonValue>> members_;
};

// Writes v. indent > 0: pretty-printed with that many spaces per level, except that arrays of
// numbers stay on one line; indent == 0: one line. Ends without a newline.
std::string WriteJson(const JsonValue& v, int indent = 2);

// Parses a whole JSON text (trailing whitespace allowed). Throws InvalidInputError naming
// `where` and the line:column of the problem.
JsonValue ParseJson(const std::string& text, const std::string& where = "json");

// Formats a double with the shortest of %.15g/%.16g/%.17g that reads back exactly.
std::string FormatExactDouble(double x);

}  // namespace symembed
