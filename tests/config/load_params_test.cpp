#include "config/load_params.hpp"
#include "core/tracking/clock.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace marsokhod::config {
namespace {

const std::string kShippedFile = std::string(MARSOKHOD_SOURCE_DIR) + "/config/marsokhod.toml";

std::string shipped_text() {
  std::ifstream in(kShippedFile);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The shipped file with one line replaced (the line must exist exactly once).
std::string with_line(const std::string& old_line, const std::string& new_line) {
  std::string text = shipped_text();
  const auto at = text.find(old_line);
  EXPECT_NE(at, std::string::npos) << old_line;
  EXPECT_EQ(text.find(old_line, at + 1), std::string::npos) << old_line;
  if (at != std::string::npos) text.replace(at, old_line.size(), new_line);
  return text;
}

// The shipped file with `key` in the section whose header line is `section` ("[cycle]",
// "[[motor_curve]]") set to `value`, keeping the line's comment.
std::string with_value(const std::string& section, const std::string& key,
                       const std::string& value) {
  std::string text = shipped_text();
  const auto header = text.find("\n" + section);
  EXPECT_NE(header, std::string::npos) << section;
  const auto line = text.find("\n" + key + " =", header);
  EXPECT_NE(line, std::string::npos) << key;
  if (header == std::string::npos || line == std::string::npos) return text;
  const auto start = text.find('=', line) + 1;
  auto end = text.find_first_of("#\n", start);
  text.replace(start, end - start, " " + value + "   ");
  return text;
}

// The single problem a broken text yields.
std::string problem_of(const std::string& text) {
  try {
    parse_params(text, "test.toml");
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.problems().size(), 1u) << e.what();
    return e.problems().empty() ? "" : e.problems().front();
  }
  ADD_FAILURE() << "no ConfigError";
  return "";
}

TEST(LoadParams, ShippedFileMatchesTheThesisDefaults) {
  const Params p = load_params(kShippedFile);
  const Params d;  // params.hpp's defaults are the thesis' values
  EXPECT_EQ(p.geometry.joint_to_exterior_axle_m, d.geometry.joint_to_exterior_axle_m);
  EXPECT_EQ(p.geometry.center_axle_to_joint_m, d.geometry.center_axle_to_joint_m);
  EXPECT_EQ(p.geometry.wheel_radius_m, d.geometry.wheel_radius_m);
  EXPECT_EQ(p.geometry.track_width_m, d.geometry.track_width_m);
  EXPECT_EQ(p.cycle.period_s, d.cycle.period_s);
  EXPECT_EQ(p.cycle.con, d.cycle.con);
  EXPECT_EQ(p.cycle.icr, d.cycle.icr);
  EXPECT_EQ(p.motors.scale, d.motors.scale);
  EXPECT_EQ(p.motors.backlash_rad, d.motors.backlash_rad);
  EXPECT_EQ(p.motors.initial_position_rad, d.motors.initial_position_rad);
  ASSERT_EQ(p.motor_curves.size(), 1u);
  EXPECT_EQ(p.motor_curves[0].duty, d.motor_curves[0].duty);
  EXPECT_EQ(p.motor_curves[0].no_load_speed_radps, d.motor_curves[0].no_load_speed_radps);
  ASSERT_EQ(p.responses.size(), 2u);
  EXPECT_EQ(p.responses[0].delta, d.responses[0].delta);
  EXPECT_EQ(p.responses[1].delta, d.responses[1].delta);
  EXPECT_EQ(p.power.duty_drop_v, 0.6);
  EXPECT_EQ(p.power.load_drop_v_s2_per_rad2, 0.4);
  EXPECT_EQ(p.power.max_drop_v, 1.5);
  EXPECT_EQ(p.load.gain_same_sign_radps_per_nm, 0.030);
  EXPECT_EQ(p.load.gain_opposite_sign_radps_per_nm, 0.015);
  ASSERT_EQ(p.load_gains.size(), d.load_gains.size());
  for (std::size_t i = 0; i < p.load_gains.size(); ++i) {
    EXPECT_EQ(p.load_gains[i].icr, d.load_gains[i].icr);
    EXPECT_EQ(p.load_gains[i].duty, d.load_gains[i].duty);
    EXPECT_EQ(p.load_gains[i].same_sign_radps_per_nm, d.load_gains[i].same_sign_radps_per_nm);
    EXPECT_EQ(p.load_gains[i].opposite_sign_radps_per_nm,
              d.load_gains[i].opposite_sign_radps_per_nm);
  }
  EXPECT_EQ(p.joints.front_min_rad, -2.55);
  EXPECT_EQ(p.joints.rear_max_rad, 2.55);
  EXPECT_EQ(p.spin.slope_per_m, 5.3);
  EXPECT_EQ(p.spin.offset, 0.04);
  EXPECT_EQ(p.load_distribution.mode, LoadDistributionMode::kOff);
  EXPECT_EQ(p.load_distribution.max_correction_radps, 0.3);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(p.sensors.accelerometer[i].minus_g_counts, d.sensors.accelerometer[i].minus_g_counts);
    EXPECT_EQ(p.sensors.accelerometer[i].plus_g_counts, d.sensors.accelerometer[i].plus_g_counts);
  }
  EXPECT_EQ(p.sensors.tilt_rear.offset, 2.74);  // docs/design.md: the table's +2.74, not −2.74
  EXPECT_EQ(p.sensors.supply.gain, 0.06768);
  EXPECT_EQ(p.safety.operator_timeout_s, 0.5);
  EXPECT_EQ(p.safety.dead_man_dog, d.safety.dead_man_dog);
  EXPECT_EQ(p.safety.max_duty_step, d.safety.max_duty_step);
  EXPECT_EQ(p.safety.direction_change_duty, d.safety.direction_change_duty);
  EXPECT_EQ(p.safety.missed_responses_limit, d.safety.missed_responses_limit);
  EXPECT_EQ(p.operator_input.dead_zone, d.operator_input.dead_zone);
  EXPECT_EQ(p.operator_input.max_drive_speed_radps, d.operator_input.max_drive_speed_radps);
  EXPECT_EQ(p.operator_input.max_spin_speed_radps, d.operator_input.max_spin_speed_radps);
  EXPECT_EQ(p.operator_input.calibration_duty, 0.08);  // Procedure 4.3
  EXPECT_EQ(p.gaits.extended_rad, 2.55);
  EXPECT_EQ(p.gaits.max_joint_speed_fraction, d.gaits.max_joint_speed_fraction);
  EXPECT_EQ(p.behaviours.power_management, d.behaviours.power_management);
  EXPECT_EQ(p.behaviours.axle_placement_load_radps, d.behaviours.axle_placement_load_radps);
}

TEST(LoadParams, ConsoleSection) {
  const Configuration p = load_configuration(kShippedFile);
  EXPECT_EQ(p.console.listen, "127.0.0.1:8080");
  EXPECT_EQ(p.console.token, "");
  EXPECT_EQ(p.console.status_rate_hz, 20.0);
  EXPECT_TRUE(p.console.allowed_hosts.empty());
  EXPECT_TRUE(p.console.allowed_origins.empty());
  const std::string e = problem_of(with_value("[console]", "token", "42"));
  EXPECT_NE(e.find("console.token: 42 is not a string"), std::string::npos) << e;
  const Configuration named = parse_configuration(
      with_value("[console]", "allowed_hosts", R"(["rover.local", "10.0.0.7"])"), "test.toml");
  EXPECT_EQ(named.console.allowed_hosts, (std::vector<std::string>{"rover.local", "10.0.0.7"}));
  const std::string not_text = problem_of(with_value("[console]", "allowed_origins", "[1]"));
  EXPECT_NE(not_text.find("console.allowed_origins[0]: 1 is not a string"), std::string::npos)
      << not_text;
}

TEST(LoadParams, BooleanMustBeABoolean) {
  const std::string e = problem_of(with_value("[behaviours]", "slant_response", "1"));
  EXPECT_NE(e.find("behaviours.slant_response: 1 is not a boolean; expected true or false"),
            std::string::npos)
      << e;
}

TEST(LoadParams, JointBoundsMatchTheGeometry) {
  // (5.3): p6_max = −acos(a/b), p7_min = +acos(a/b) = 1.2121 (Remark 3.1).
  const Params p = load_params(kShippedFile);
  const double vertical = std::acos(p.geometry.joint_to_exterior_axle_m /
                                    p.geometry.center_axle_to_joint_m);
  EXPECT_NEAR(vertical, 1.2121, 5e-5);
  EXPECT_NEAR(p.joints.front_max_rad, -vertical, 5e-5);
  EXPECT_NEAR(p.joints.rear_min_rad, vertical, 5e-5);
  EXPECT_NEAR(p.motors.initial_position_rad[kFrontJoint], -vertical, 5e-5);
  EXPECT_NEAR(p.motors.initial_position_rad[kRearJoint], vertical, 5e-5);
}

TEST(LoadParams, MissingKeyIsNamedWithWhatIsExpected) {
  const std::string e = problem_of(with_line("wheel_radius_m = 0.125", ""));
  EXPECT_EQ(e, "geometry.wheel_radius_m: missing; expected a number in [0.05, 0.5]");
}

TEST(LoadParams, WrongTypeIsNamedWithTheValue) {
  const std::string e = problem_of(with_value("[cycle]", "con", "\"zero\""));
  EXPECT_NE(e.find("cycle.con: \"zero\" is not an integer; expected an integer in [0, 255]"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("(test.toml:"), std::string::npos) << e;
}

TEST(LoadParams, OutOfRangeValueIsNamedWithTheRange) {
  const std::string e = problem_of(with_value("[[motor_curve]]", "icr", "4000"));
  EXPECT_NE(e.find("motor_curve[0].icr: 4000 is out of range; allowed [255, 2047]"),
            std::string::npos)
      << e;
}

TEST(LoadParams, LoadGainTablesMustPairUpIncreaseAndCoverTheConfiguredIcr) {
  // (4.6)'s B± tables: the first shipped one is icr 255's.
  EXPECT_NE(problem_of(with_value("[[load_gain]]", "icr", "511"))
                .find("load_gain[1].icr: 511 is given twice"),
            std::string::npos);
  EXPECT_NE(problem_of(with_value("[[load_gain]]", "duty", "[0.0, 0.3]"))
                .find("load_gain[0]: duty has 2 entries, same_sign_radps_per_nm 3 and "
                      "opposite_sign_radps_per_nm 3; they must pair up"),
            std::string::npos);
  EXPECT_NE(problem_of(with_value("[[load_gain]]", "duty", "[0.0, 0.3, 0.3]"))
                .find("load_gain[0].duty[2]: 0.3 does not increase"),
            std::string::npos);
  EXPECT_NE(problem_of(with_line("icr = 511\nduty = [0.0, 0.3, 1.0]",
                                 "icr = 600\nduty = [0.0, 0.3, 1.0]"))
                .find("cycle.icr: 511 has no [[load_gain]] with that icr; add one"),
            std::string::npos);
}

TEST(LoadParams, OperatorTimeoutIsCappedAtOneSecond) {
  // A longer timeout lets a rover whose link dropped drive on for longer than anyone can react.
  const std::string e = problem_of(with_value("[safety]", "operator_timeout_s", "1.5"));
  EXPECT_NE(e.find("safety.operator_timeout_s: 1.5 is out of range; allowed [0.05, 1]"),
            std::string::npos)
      << e;
  EXPECT_EQ(parse_params(with_value("[safety]", "operator_timeout_s", "1.0"), "test.toml")
                .safety.operator_timeout_s,
            1.0);
}

TEST(LoadParams, OutOfRangeVectorElementIsNamedByIndex) {
  const std::string e = problem_of(with_line(
      "backlash_rad = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.052, 0.250]",
      "backlash_rad = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.052, -0.250]"));
  EXPECT_NE(e.find("motors.backlash_rad[7]: -0.25 is out of range; allowed [0, 1]"),
            std::string::npos)
      << e;
}

TEST(LoadParams, WrongVectorLengthIsRejected) {
  const std::string e = problem_of(
      with_line("scale = [0.9896, 0.9808, 0.9707, 0.941, 0.9713, 0.9707, 0.9808, 0.9713]",
                "scale = [0.9896, 0.9808]"));
  EXPECT_NE(e.find("motors.scale: an array of 2 given; expected an array of 8 numbers"),
            std::string::npos)
      << e;
}

TEST(LoadParams, UnknownKeyIsRejected) {
  const std::string e = problem_of(with_line("track_width_m = 0.70", "track_width_m = 0.70\ntrack_wdth_m = 0.7"));
  EXPECT_NE(e.find("geometry.track_wdth_m: unknown key"), std::string::npos) << e;
}

TEST(LoadParams, UnknownChoiceIsRejected) {
  const std::string e = problem_of(with_line("mode = \"off\"", "mode = \"auto\""));
  EXPECT_NE(e.find("load_distribution.mode: \"auto\" is not allowed; expected one of \"off\", "
                   "\"v\", \"s\""),
            std::string::npos)
      << e;
}

TEST(LoadParams, NaNIsOutOfRange) {
  const std::string e = problem_of(with_line("max_drop_v = 1.5", "max_drop_v = nan"));
  EXPECT_NE(e.find("power.max_drop_v: nan is out of range"), std::string::npos) << e;
}

TEST(LoadParams, SyntaxErrorGivesTheLine) {
  const std::string e = problem_of(with_line("offset = 0.04", "offset = = 0.04"));
  EXPECT_NE(e.find("TOML syntax error"), std::string::npos) << e;
  EXPECT_NE(e.find("line "), std::string::npos) << e;
}

TEST(LoadParams, EveryProblemIsListedAtOnce) {
  std::string text = with_line("wheel_radius_m = 0.125", "wheel_radius_m = 2.0");
  const auto at = text.find("operator_timeout_s = 0.5");
  text.replace(at, std::string("operator_timeout_s = 0.5").size(), "operator_timeout_s = -1");
  try {
    parse_params(text, "test.toml");
    FAIL() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_EQ(e.problems().size(), 2u) << e.what();
    EXPECT_NE(std::string(e.what()).find("test.toml: 2 configuration problems"), std::string::npos);
  }
}

TEST(LoadParams, CyclePeriodMustStayBelowClockOverflow) {
  // T(0) = 65536/2e6 = 0.032768 s; h = 0.04 s would lose tim overflows (3.2).
  EXPECT_DOUBLE_EQ(tracking::clock_overflow_period_s(0), 0.032768);
  EXPECT_DOUBLE_EQ(tracking::clock_overflow_period_s(1), 0.065536);
  try {
    parse_params(with_value("[cycle]", "period_s", "0.04"), "test.toml");
    FAIL() << "no ConfigError";
  } catch (const ConfigError& error) {
    // Two problems: the overflow, and no δ table for h = 0.04.
    ASSERT_EQ(error.problems().size(), 2u) << error.what();
    const std::string& e = error.problems().front();
  EXPECT_NE(e.find("cycle.period_s: 0.04 s is not below T(con = 0) = 0.032768 s"),
              std::string::npos)
        << e;
  }
}

TEST(LoadParams, MotorCurveMustBeStrictlyIncreasing) {
  const std::string e = problem_of(
      with_line("no_load_speed_radps = [0.0, 0.19, 0.52, 0.847, 1.18,",
                "no_load_speed_radps = [0.0, 0.19, 0.52, 0.50, 1.18,"));
  EXPECT_NE(e.find("motor_curve[0].no_load_speed_radps[3]: 0.5 does not increase"),
            std::string::npos)
      << e;
}

TEST(LoadParams, ConfiguredCycleNeedsAResponseTable) {
  // con = 1 with h = 0.0156: the δ table only has (0.0313, 1).
  const std::string e = problem_of(with_value("[cycle]", "con", "1"));
  EXPECT_NE(e.find("cycle: no [[response]] for period_s 0.0156"), std::string::npos) << e;
}

TEST(LoadParams, JointBoundsMustBeOrdered) {
  const std::string e = problem_of(with_line("front_min_rad = -2.55", "front_min_rad = -1.0"));
  EXPECT_NE(e.find("joints.front_min_rad: -1 must be below joints.front_max_rad"),
            std::string::npos)
      << e;
}

TEST(LoadParams, MissingFileSaysSo) {
  try {
    load_params("/nonexistent/marsokhod.toml");
    FAIL() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/marsokhod.toml: 1 configuration problem"),
              std::string::npos);
    EXPECT_NE(std::string(e.what()).find("cannot open the file"), std::string::npos);
  }
}

}  // namespace
}  // namespace marsokhod::config
