// core/text_cells.h: the cells every line-based reader shares.
#include <gtest/gtest.h>

#include <cmath>

#include "interfere/core/text_cells.h"

using namespace interfere;

TEST(TextCells, TrimAndSplit) {
  EXPECT_EQ(trim_blanks(" \t a b \r\n"), "a b");
  EXPECT_EQ(trim_blanks(" \t\r\n"), "");
  const auto c = split_csv_cells(" a , b,,c ");
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0], "a");
  EXPECT_EQ(c[1], "b");
  EXPECT_EQ(c[2], "");
  EXPECT_EQ(c[3], "c");
  EXPECT_EQ(split_csv_cells("").size(), 1u);
}

TEST(TextCells, NumbersWholeCellOnly) {
  double v = 0;
  EXPECT_TRUE(parse_number_cell("+1.5e3", v));
  EXPECT_EQ(v, 1500.0);
  EXPECT_TRUE(parse_number_cell("-0.25", v));
  EXPECT_EQ(v, -0.25);
  for (const char* bad : {"", "+", "+-1", "++1", "1.5x", " 1", "1 ", "0x10", "1,2"})
    EXPECT_FALSE(parse_number_cell(bad, v)) << bad;
  EXPECT_TRUE(parse_number_cell("1e999", v));  // out of range: inf, the caller decides
  EXPECT_TRUE(std::isinf(v));
  EXPECT_FALSE(parse_finite_cell("1e999", v));
  EXPECT_FALSE(parse_finite_cell("nan", v));
  EXPECT_FALSE(parse_finite_cell("inf", v));
  EXPECT_TRUE(parse_finite_cell("1e-320", v));  // denormal: finite
  EXPECT_GT(v, 0);
}
