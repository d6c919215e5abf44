#include "driver/lcd.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
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

// printf's "%+5.1f" of a value with one decimal in [−99.9, 99.9], written by hand: snprintf's
// floating-point formatting was a twentieth of the whole control cycle (issue #19). The value is
// k/10 rounded to a double, so k = round(10·value) exactly and k's digits are the printed ones.
void write_tenths(double tenths, char* out5) {
  const long k = std::lround(tenths * 10.0);
  const long magnitude = std::labs(k);
  char* end = out5 + 5;
  *--end = static_cast<char>('0' + magnitude % 10);
  *--end = '.';
  *--end = static_cast<char>('0' + magnitude / 10 % 10);
  if (magnitude >= 100) *--end = static_cast<char>('0' + magnitude / 100);
  *--end = k < 0 ? '-' : '+';
  while (end > out5) *--end = ' ';
}

std::string lcd_characters(const DriverStatus& status) {
  std::string out(lcd_code(status));
  out.resize(8, ' ');
  const double degrees = status.slope_rad * 180.0 / std::numbers::pi;
  if (std::isfinite(degrees) && status.mode != DriverMode::kStartup) {
    // Rounded first, so that −0.04° shows as +0.0 and not −0.0.
    double tenths = std::round(std::clamp(degrees, -99.9, 99.9) * 10.0) / 10.0;
    if (tenths == 0.0) tenths = 0.0;
    write_tenths(tenths, out.data() + 2);
  } else {
    out.replace(2, 5, " --.-");
  }
  out[7] = 'd';
  return out;
}

}  // namespace marsokhod::driver
