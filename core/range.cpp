#include "core/range.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace symembed {

std::string FormatNumber(double x) {
  char buffer[64];
  for (int precision = 6; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, x);
    if (std::strtod(buffer, nullptr) == x) break;
  }
  return buffer;
}

namespace {

// An end or a value: "inf" / "-inf", integers in full (a bound of 1000000 samples reads better
// than "1e+06"), other numbers as FormatNumber.
std::string NumberText(double x) {
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  if (std::isnan(x)) return "nan";
  if (x == std::floor(x) && std::fabs(x) < 1e15) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.0f", x == 0.0 ? 0.0 : x);  // no "-0"
    return buffer;
  }
  return FormatNumber(x);
}

}  // namespace

std::string Range::Text() const {
  return std::string(min_open_ ? "(" : "[") + NumberText(min_) + ", " + NumberText(max_) +
         (max_open_ ? ")" : "]");
}

std::string Range::Violation(double x) const {
  return "must be in " + Text() + ", got " + NumberText(x);
}

std::string FirstViolation(std::initializer_list<RangeField> fields) {
  for (const RangeField& f : fields) {
    if (!f.range.Contains(f.value)) return std::string(f.name) + " " + f.range.Violation(f.value);
  }
  return "";
}

}  // namespace symembed
