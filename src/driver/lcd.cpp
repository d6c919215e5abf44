#include "driver/lcd.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace marsokhod::driver {

const char* lcd_code(const DriverStatus& status) {
  switch (status.mode) {
    case DriverMode::kFault: return "FT";
    case DriverMode::kStartup: return "SU";
    case DriverMode::kCalibration: return "CA";
    case DriverMode::kDriving: break;
  }
  if (status.stop_latched) return "ST";
  if (status.operator_timeout) return "TO";
  return "  ";
}

std::string lcd_characters(const DriverStatus& status) {
  char text[16];
  const double degrees = status.slope_rad * 180.0 / std::numbers::pi;
  if (std::isfinite(degrees) && status.mode != DriverMode::kStartup) {
    // Rounded first, so that −0.04° shows as +0.0 and not −0.0.
    double tenths = std::round(std::clamp(degrees, -99.9, 99.9) * 10.0) / 10.0;
    if (tenths == 0.0) tenths = 0.0;
    std::snprintf(text, sizeof text, "%s%+5.1fd", lcd_code(status), tenths);
  } else {
    std::snprintf(text, sizeof text, "%s --.-d", lcd_code(status));
  }
  std::string out(text);
  out.resize(8, ' ');
  return out;
}

}  // namespace marsokhod::driver
