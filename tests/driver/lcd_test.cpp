// The eight LCD characters of lcd.hpp: layout, codes and their order, rounding and edges.
#include "driver/lcd.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace marsokhod::driver {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180.0;

DriverStatus driving(double slope_deg) {
  DriverStatus s;
  s.mode = DriverMode::kDriving;
  s.operator_timeout = false;
  s.slope_rad = slope_deg * kRadPerDeg;
  return s;
}

TEST(Lcd, FigureEightOnesSlopeWhileDriving) {
  // Figure 8.1's status line reads −2,5°.
  EXPECT_EQ(lcd_characters(driving(-2.5)), "   -2.5d");
  EXPECT_EQ(lcd_characters(driving(12.46)), "  +12.5d");
  EXPECT_EQ(lcd_characters(driving(90.0)), "  +90.0d");
}

TEST(Lcd, LevelReadsPlusZeroNotMinusZero) {
  EXPECT_EQ(lcd_characters(driving(0.0)), "   +0.0d");
  EXPECT_EQ(lcd_characters(driving(-0.04)), "   +0.0d");
  EXPECT_EQ(lcd_characters(driving(-0.06)), "   -0.1d");
}

TEST(Lcd, ClampsAndMarksANonFiniteSlope) {
  DriverStatus s = driving(0.0);
  s.slope_rad = 3.0;  // 171.9°: not a slope the rover stands on, but must fit
  EXPECT_EQ(lcd_characters(s), "  +99.9d");
  s.slope_rad = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(lcd_characters(s), "   --.-d");
}

TEST(Lcd, CodesInTheirOrder) {
  DriverStatus s = driving(-2.5);
  s.operator_timeout = true;
  EXPECT_EQ(lcd_characters(s), "TO -2.5d");
  s.stop_latched = true;  // the operator's stop outranks the timeout
  EXPECT_EQ(lcd_characters(s), "ST -2.5d");
  s.mode = DriverMode::kCalibration;
  EXPECT_EQ(lcd_characters(s), "CA -2.5d");
  s.mode = DriverMode::kStartup;  // σ is not estimated before the first driving cycle
  EXPECT_EQ(lcd_characters(s), "SU --.-d");
  s.mode = DriverMode::kFault;
  EXPECT_EQ(lcd_characters(s), "FT -2.5d");
}

TEST(Lcd, AlwaysEightPrintableAsciiCharacters) {
  for (double deg = -120.0; deg <= 120.0; deg += 0.37) {
    for (DriverMode mode : {DriverMode::kStartup, DriverMode::kDriving, DriverMode::kCalibration,
                            DriverMode::kFault}) {
      DriverStatus s = driving(deg);
      s.mode = mode;
      const std::string text = lcd_characters(s);
      ASSERT_EQ(text.size(), 8u) << deg;
      for (char c : text) {
        ASSERT_GE(static_cast<int>(c), 32);
        ASSERT_LE(static_cast<int>(c), 127);
      }
    }
  }
}

// lcd.cpp writes the slope by hand; printf's "%+5.1f" is the layout's definition (lcd.hpp). Every
// slope the display can show, in 0.1° steps and between them, against printf.
TEST(Lcd, TheSlopeReadsAsPrintfWritesIt) {
  for (int k = -1200; k <= 1200; ++k) {
    for (double offset : {0.0, 0.0499, -0.0499, 0.05}) {
      const double deg = k / 10.0 + offset;
      const double shown = driving(deg).slope_rad * 180.0 / std::numbers::pi;  // as lcd.cpp
      const double tenths = std::round(std::clamp(shown, -99.9, 99.9) * 10.0) / 10.0;
      char expected[16];
      std::snprintf(expected, sizeof expected, "  %+5.1fd", tenths == 0.0 ? 0.0 : tenths);
      ASSERT_EQ(lcd_characters(driving(deg)), expected) << deg << "°";
    }
  }
}

}  // namespace
}  // namespace marsokhod::driver
