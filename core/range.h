// The allowed values of a numeric option, declared once next to the option.
//
// A Range is an interval whose ends are each closed or open; an end at infinity is always open,
// so every Range holds finite numbers only. An options struct declares the range of each bounded
// field (`static constexpr Range kRelaxation = Range::ClosedOpen(1.0, 2.0);`), and both its
// IsValid and the YAML reader (OptionReader::GetDouble / GetInt with a Range) check values
// against that one declaration, with the same text in their messages. Integer options use the
// same type: every int is exactly a double.
#pragma once

#include <initializer_list>
#include <limits>
#include <string>

namespace symembed {

// Shortest decimal text that reads back to exactly x ("0.1", not "0.10000000000000001").
std::string FormatNumber(double x);

class Range {
 public:
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();

  // [min, max]
  static constexpr Range Closed(double min, double max) { return Range(min, false, max, false); }
  // [min, max)
  static constexpr Range ClosedOpen(double min, double max) { return Range(min, false, max, true); }
  // (min, max]
  static constexpr Range OpenClosed(double min, double max) { return Range(min, true, max, false); }
  // [min, inf)
  static constexpr Range AtLeast(double min) { return Range(min, false, kInfinity, true); }
  // (min, inf)
  static constexpr Range Above(double min) { return Range(min, true, kInfinity, true); }
  // (-inf, inf): every finite number.
  static constexpr Range Any() { return Range(-kInfinity, true, kInfinity, true); }

  // Whether x lies in the range (never for NaN or an infinity).
  constexpr bool Contains(double x) const {
    return (min_open_ ? x > min_ : x >= min_) && (max_open_ ? x < max_ : x <= max_);
  }

  // The interval in the usual notation: "[1, 2)", "(0, 1]", "[0, inf)". Integral ends are
  // written as integers ("1000000", not "1e+06").
  std::string Text() const;
  // "must be in [1, 2), got 2.5": what an error message says of a value outside the range.
  std::string Violation(double x) const;

  constexpr double min() const { return min_; }
  constexpr double max() const { return max_; }
  constexpr bool min_open() const { return min_open_; }
  constexpr bool max_open() const { return max_open_; }

 private:
  constexpr Range(double min, bool min_open, double max, bool max_open)
      : min_(min),
        max_(max),
        min_open_(min_open || min == -kInfinity),
        max_open_(max_open || max == kInfinity) {}

  double min_;
  double max_;
  bool min_open_;
  bool max_open_;
};

// A numeric option as IsValid checks it: its name in messages, its declared range, its value
// (any arithmetic type, compared as a double, as Range::Contains does).
struct RangeField {
  template <typename T>
  RangeField(const char* name, const Range& range, T value)
      : name(name), range(range), value(static_cast<double>(value)) {}
  const char* name;
  Range range;
  double value;
};

// "NAME must be in [a, b), got x" for the first of `fields`, in the order given, whose value lies
// outside its range; "" when every value is allowed. For the bounded fields an options struct
// does not declare in its Fields (below).
std::string FirstViolation(std::initializer_list<RangeField> fields);

// An options struct declares its options once, in a static member template that visits each
// with its key (as in a YAML config and in messages), its member and its declared Range, in the
// order the YAML reader reads them:
//
//   template <typename Self, typename Visit>
//   static void Fields(Self& self, Visit&& visit) {
//     visit("graph_neighbors", self.graph_neighbors, kGraphNeighbors);
//     visit("symmetric", self.symmetric);  // a bool: no range
//     visit("confidence", self.confidence, kConfidence, kIfGiven);
//   }
//
// FieldViolation checks the declared fields (for IsValid), ReadFields (registry/options.h)
// reads them from YAML. kIfGiven marks an option read only when given
// (OptionReader::GetDoubleIfGiven).
struct IfGiven {};
inline constexpr IfGiven kIfGiven{};

// Stores why in *error (when error is given) and returns whether why is empty: how an IsValid
// ends.
inline bool NoViolation(const std::string& why, std::string* error) {
  if (error != nullptr) *error = why;
  return why.empty();
}

// FirstViolation over the fields Options::Fields declares, in their order; "" when each lies in
// its range.
template <typename Options>
std::string FieldViolation(const Options& options) {
  std::string found;
  struct Check {
    std::string* found;
    void operator()(const char* name, double value, const Range& range, IfGiven = {}) const {
      if (found->empty()) *found = FirstViolation({{name, range, value}});
    }
    void operator()(const char*, bool) const {}
  };
  Options::Fields(options, Check{&found});
  return found;
}

}  // namespace symembed
