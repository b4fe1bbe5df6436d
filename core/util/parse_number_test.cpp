// The one number reader: the whole text, one finite number, nothing else.
#include "core/util/parse_number.h"

#include <gtest/gtest.h>

namespace fb {
namespace {

TEST(ParseNumber, ReadsTheWholeTextAsOneFiniteNumber) {
  EXPECT_EQ(parse_number("1.5"), 1.5);
  EXPECT_EQ(parse_number("-2e-3"), -2e-3);
  EXPECT_EQ(parse_number("0"), 0.0);
  EXPECT_EQ(parse_number("1e308"), 1e308);
}

TEST(ParseNumber, RefusesAnythingElse) {
  for (const char* text :
       {"", " 1", "1 ", "1.5x", "+1", "0x10", "inf", "-inf", "nan", "1e400", "1,5", "--1"})
    EXPECT_EQ(parse_number(text), std::nullopt) << '"' << text << '"';
}

}  // namespace
}  // namespace fb
