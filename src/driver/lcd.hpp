// µ8's display (chapter 3.3): the eight characters lcd⁰…lcd⁷ the driver sends in every 0x80.
// µ8's firmware shows them followed by its own reading of the supply voltage, so the driver does
// not repeat the voltage; it shows what the thesis' troubleshooting table (Conclusion) asks the
// operator to read: "adjust inclination of accelerometer sensor with the robot on flat terrain
// until the LCD reads ≈ 0 deg" — the slope σ of chapter 6.2.1, the number the slant response
// (6.4) acts on — and a code for a latched fault or a mode in which the rover does not drive.
//
//   character  0 1   2 3 4 5 6   7
//              code  σ [deg]     'd'
//
//   code: "FT" a latched fault, "SU" start-up, "CA" the operator's calibration mode, "ST" the
//         operator's stop latched, "TO" no operator input for operator_timeout_s; the first that
//         applies in this order; two blanks while the rover drives under operator control.
//   σ:    printf "%+5.1f" of σ in degrees, rounded to 0.1° (−0.0 shows as +0.0), clamped to
//         ±99.9; " --.-" when σ is not finite, and during start-up, before the first estimate.
//         'd' stands for the degree sign, which is not in ASCII 32..127 (chapter 3.3's lcdⁱ
//         range).
//
// Examples: σ = −2.5° while driving "   -2.5d" (the −2,5° of Figure 8.1), σ = 12.46° on a
// latched fault "FT+12.5d". With µ8's voltage the 16-character display reads "   -2.5d  24.10V".
// σ is estimated in the driving mode's cycles (stopped or not); in calibration mode and on a
// fault the display keeps the last estimate; start-up comes before the first ("SU --.-d").
#pragma once

#include <string>

#include "driver/status.hpp"

namespace marsokhod::driver {

// The code of the layout above ("FT", "SU", "CA", "ST", "TO" or "  ").
const char* lcd_code(const DriverStatus& status);

// The eight characters, every one in ASCII 32..127.
std::string lcd_characters(const DriverStatus& status);

}  // namespace marsokhod::driver
