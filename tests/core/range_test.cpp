// Range: membership at closed and open ends, infinite ends, and the text of errors.
#include "core/range.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace symembed {
namespace {

TEST(Range, ContainsAndText) {
  constexpr Range relaxation = Range::ClosedOpen(1.0, 2.0);
  static_assert(relaxation.Contains(1.0) && relaxation.Contains(1.9995));
  static_assert(!relaxation.Contains(2.0) && !relaxation.Contains(0.999));
  EXPECT_EQ(relaxation.Text(), "[1, 2)");
  EXPECT_EQ(relaxation.Violation(2.5), "must be in [1, 2), got 2.5");
  EXPECT_EQ(Range::OpenClosed(0.0, 1.0).Text(), "(0, 1]");
  EXPECT_EQ(Range::Closed(1e-6, 1e6).Text(), "[1e-06, 1000000]");
  // An infinite end is open, so a Range holds finite numbers only.
  EXPECT_EQ(Range::AtLeast(0).Text(), "[0, inf)");
  EXPECT_EQ(Range::Above(0).Text(), "(0, inf)");
  EXPECT_FALSE(Range::AtLeast(0).Contains(std::numeric_limits<double>::infinity()));
  EXPECT_FALSE(Range::Any().Contains(std::nan("")));
  EXPECT_TRUE(Range::Any().Contains(-1e300));
}

TEST(FirstViolation, NamesTheFirstFieldOutsideItsRangeInTheOrderGiven) {
  const Range count = Range::AtLeast(1), fraction = Range::Closed(0.0, 1.0);
  const int samples = 0;
  EXPECT_EQ(FirstViolation({{"samples", count, 10}, {"fraction", fraction, 0.5}}), "");
  EXPECT_EQ(FirstViolation({{"samples", count, samples}, {"fraction", fraction, 1.5}}),
            "samples must be in [1, inf), got 0");
  EXPECT_EQ(FirstViolation({{"samples", count, 3}, {"fraction", fraction, 1.5}}),
            "fraction must be in [0, 1], got 1.5");
  EXPECT_EQ(FirstViolation({}), "");
}

TEST(FormatNumber, ShortestTextThatReadsBackExactly) {
  EXPECT_EQ(FormatNumber(0.1), "0.1");
  EXPECT_EQ(FormatNumber(1.0 / 3.0), "0.3333333333333333");
  EXPECT_EQ(FormatNumber(1e-6), "1e-06");
}

}  // namespace
}  // namespace symembed
