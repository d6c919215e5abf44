// Remark 5.7's joystick on the W3C standard gamepad (https://w3c.github.io/gamepad/#remapping).
// docs/gamepad.md has the same map as a table for operators.
//
//   left stick  up/down (−axis 1)   v1ᵈ drive straight, up = forward         ±max_drive_speed_radps
//   left stick  x (axis 0)          v2ᵈ spin, right = clockwise seen from above (v2 < 0: m2 then
//                                   drives the left side forward, the right side backward)
//   right stick up/down (−axis 3)   gait speed s ∈ [−1, 1], up = forward through the gait's cycle
//   right stick x (axis 2)          v4ᵈ trench, right = front-right wheel forward (m4)
//   X (button 2, left) / A (0)      v3ᵈ sideways drift (m3, chapter 5.2) = +/− drift speed:
//                                   X turns the left-rear and right-front wheels forward, the
//                                   left-front and right-rear backward; A the reverse
//   d-pad up / right / down / left  rolking / front-wheel walking / worm-like / rear-wheel walking
//   Y (button 3, top)               rolking with extended base
//   B (button 1, right)             no gait (wheel walking off); wins over a d-pad press
//   LB (4) / LT (6)                 contract / extend the front joint: v6ᵈ = +/− joint speed
//   RB (5) / RT (7)                 contract / extend the rear joint:  v7ᵈ = −/+ joint speed
//   back/select (8)                 toggles calibration mode (Procedure 4.3) on each press
// (p6 = −γf: extending the front joint decreases p6; p7 = +γr: extending the rear increases p7.)
// A selected gait stays selected until another gait button or B; two gait buttons at once change
// nothing. In calibration mode every velocity is 0, the gait is none, and only the four front
// buttons count: calibration_duties() turns them into d6, d7 = ±calibration_duty (Procedure
// 4.3's d6 = d7 = −0.08 is LT + RB). Both buttons of one joint at once cancel, as X and A do.
// Dead zone: |axis| < dead_zone reads 0; above it (|axis| − dead_zone)/(1 − dead_zone) keeps the
// sign, so the output is continuous and reaches ±1 at full deflection.
#pragma once

#include <array>
#include <cstddef>
#include <optional>

#include "core/mobility/gait_table.hpp"
#include "core/params.hpp"

namespace marsokhod::mobility {

inline constexpr std::size_t kGamepadAxisCount = 4;
inline constexpr std::size_t kGamepadButtonCount = 17;

// W3C standard mapping indices.
enum GamepadAxis : std::size_t {
  kLeftStickX = 0,  // right = +1
  kLeftStickY = 1,  // down = +1
  kRightStickX = 2,
  kRightStickY = 3,
};
enum GamepadButton : std::size_t {
  kButtonBottom = 0,  // A
  kButtonRight = 1,   // B
  kButtonLeft = 2,    // X
  kButtonTop = 3,     // Y
  kLeftBumper = 4,    // LB
  kRightBumper = 5,   // RB
  kLeftTrigger = 6,   // LT
  kRightTrigger = 7,  // RT
  kSelect = 8,        // back/select
  kStart = 9,
  kLeftStickPress = 10,
  kRightStickPress = 11,
  kDpadUp = 12,
  kDpadDown = 13,
  kDpadLeft = 14,
  kDpadRight = 15,
  kHome = 16,
};

// One reading of the gamepad: axes in [−1, 1], buttons pressed or not (the browser's `pressed`).
struct GamepadState {
  std::array<double, kGamepadAxisCount> axes{};
  std::array<bool, kGamepadButtonCount> buttons{};
  bool operator==(const GamepadState&) const = default;
};

struct JointButtons {
  bool contract_front = false;  // LB
  bool extend_front = false;    // LT
  bool contract_rear = false;   // RB
  bool extend_rear = false;     // RT
  bool operator==(const JointButtons&) const = default;
};

// What the mapping carries from one reading to the next (button edges and latched choices).
struct GamepadMemory {
  bool calibration_mode = false;
  Gait gait = Gait::kNone;
  bool select_was_pressed = false;
  bool operator==(const GamepadMemory&) const = default;
};

struct OperatorTargets {
  double v1_radps = 0.0;  // drive straight (m1), > 0 forward
  double v2_radps = 0.0;  // spin (m2), > 0 counter-clockwise seen from above
  double v3_radps = 0.0;  // sideways drift (m3), > 0 left-rear and right-front wheels forward
  double v4_radps = 0.0;  // trench (m4), > 0 front-right wheel forward
  double v6_radps = 0.0;  // front joint (m6), > 0 contracts
  double v7_radps = 0.0;  // rear joint (m7), > 0 extends
  Gait gait = Gait::kNone;
  double gait_speed = 0.0;  // s ∈ [−1, 1]
  bool calibration_mode = false;
  JointButtons joint_buttons;
  GamepadMemory memory;  // pass to the next call of map_gamepad
  // Joint positions to reach with (4.15) (Procedure 4.17), used instead of v6/v7 while no gait
  // runs. Never set by the gamepad: consoles, scenarios and calibration send them.
  std::optional<double> front_joint_target_rad{};  // p6ᵈ
  std::optional<double> rear_joint_target_rad{};   // p7ᵈ
  bool operator==(const OperatorTargets&) const = default;
};

// The dead zone above for one axis value. Throws std::invalid_argument naming `axis_name` if the
// value is NaN or |value| > 1.
double apply_dead_zone(double value, double dead_zone, const char* axis_name);

// Throws std::invalid_argument naming the field unless dead_zone ∈ [0, 1) and every speed and the
// calibration duty are finite and ≥ 0 (the duty at most 1).
void validate(const OperatorParams& params);

// The map above. `before` is the previous call's OperatorTargets::memory ({} at start-up).
// Throws std::invalid_argument naming the axis ("axis 1 (left stick y)") for a NaN or |axis| > 1.
OperatorTargets map_gamepad(const GamepadState& gamepad, const OperatorParams& params,
                            const GamepadMemory& before = {});

// Calibration-mode duty cycles of the joints from the front buttons: {d6, d7}.
std::array<double, 2> calibration_duties(const JointButtons& buttons, const OperatorParams& params);

}  // namespace marsokhod::mobility
