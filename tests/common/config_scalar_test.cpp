// Strict scalar parsing shared by config files and --set values.
#include "common/config_scalar.h"

#include <gtest/gtest.h>

#include <cmath>

namespace bsg {
namespace {

TEST(ParseConfigBool, AcceptsYamlSpellingsAndRejectsOthers) {
  EXPECT_EQ(parse_config_bool("true"), true);
  EXPECT_EQ(parse_config_bool("False"), false);
  EXPECT_EQ(parse_config_bool("off"), false);
  EXPECT_EQ(parse_config_bool("YES"), true);
  EXPECT_FALSE(parse_config_bool("1").has_value());
  EXPECT_FALSE(parse_config_bool("tru").has_value());
  EXPECT_FALSE(parse_config_bool("").has_value());
}

TEST(ParseConfigInteger, AcceptsOnlyWholeDecimalNumbers) {
  EXPECT_EQ(parse_config_integer("32000"), 32000);
  EXPECT_EQ(parse_config_integer("-3"), -3);
  EXPECT_EQ(parse_config_integer("+4"), 4);
  EXPECT_FALSE(parse_config_integer("2.5").has_value());
  EXPECT_FALSE(parse_config_integer("1e3").has_value());
  EXPECT_FALSE(parse_config_integer("12abc").has_value());
  EXPECT_FALSE(parse_config_integer("").has_value());
  EXPECT_FALSE(parse_config_integer("99999999999999999999").has_value());
}

TEST(ParseConfigReal, AcceptsFiniteDecimalsAndRejectsTheRest) {
  EXPECT_EQ(parse_config_real("0.01"), 0.01);
  EXPECT_EQ(parse_config_real("1e-4"), 1e-4);
  EXPECT_EQ(parse_config_real("25"), 25.0);
  EXPECT_FALSE(parse_config_real("nan").has_value());
  EXPECT_FALSE(parse_config_real("inf").has_value());
  EXPECT_FALSE(parse_config_real(".inf").has_value());
  EXPECT_FALSE(parse_config_real("0x1p3").has_value());
  EXPECT_FALSE(parse_config_real("0.1.2").has_value());
  EXPECT_FALSE(parse_config_real("1e999").has_value());
}

TEST(FormatConfigReal, ReadsBackExactlyAndLooksLikeAReal) {
  for (double value : {0.1, 1e-4, 0.000123456789, 25.0, 1.0 / 3.0, 64000.0, 5e-324}) {
    const std::string text = format_config_real(value);
    ASSERT_EQ(parse_config_real(text), value) << text;
  }
  EXPECT_EQ(format_config_real(25.0), "25.0");
  EXPECT_EQ(format_config_real(0.01), "0.01");
}

}  // namespace
}  // namespace bsg
