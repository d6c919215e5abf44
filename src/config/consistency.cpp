// Relations between configuration values that single ranges cannot express.
#include <cmath>
#include <string>
#include <vector>

#include "config/config_reader.hpp"
#include "config/load_params.hpp"
#include "core/tracking/clock.hpp"

namespace marsokhod::config {
namespace {

void check_curve(const MotorCurveParams& c, std::size_t index, std::vector<std::string>& out) {
  const std::string name = "motor_curve[" + std::to_string(index) + "]";
  if (c.duty.size() != c.no_load_speed_radps.size()) {
    out.push_back(name + ": duty has " + std::to_string(c.duty.size()) +
                  " entries but no_load_speed_radps has " +
                  std::to_string(c.no_load_speed_radps.size()) + "; they must pair up");
    return;
  }
  if (c.duty.front() != 0.0 || c.duty.back() != 1.0) {
    out.push_back(name + ".duty: must run from 0 to 1 (W is defined on [0, 1], odd below 0)");
  }
  if (c.no_load_speed_radps.front() != 0.0) {
    out.push_back(name + ".no_load_speed_radps[0]: " + show_number(c.no_load_speed_radps.front()) +
                  "; W(0) must be 0");
  }
  for (std::size_t i = 1; i < c.duty.size(); ++i) {
    if (!(c.duty[i] > c.duty[i - 1])) {
      out.push_back(name + ".duty[" + std::to_string(i) + "]: " + show_number(c.duty[i]) +
                    " does not increase; duty must be strictly increasing");
    }
    if (!(c.no_load_speed_radps[i] > c.no_load_speed_radps[i - 1])) {
      out.push_back(name + ".no_load_speed_radps[" + std::to_string(i) +
                    "]: " + show_number(c.no_load_speed_radps[i]) +
                    " does not increase; W must be strictly increasing to be invertible");
    }
  }
}

// (4.6): a [[load_gain]] table's columns pair up and its duty cycles increase.
void check_load_gain(const LoadGainParams& g, std::size_t index, std::vector<std::string>& out) {
  const std::string name = "load_gain[" + std::to_string(index) + "]";
  if (g.same_sign_radps_per_nm.size() != g.duty.size() ||
      g.opposite_sign_radps_per_nm.size() != g.duty.size()) {
    out.push_back(name + ": duty has " + std::to_string(g.duty.size()) +
                  " entries, same_sign_radps_per_nm " +
                  std::to_string(g.same_sign_radps_per_nm.size()) +
                  " and opposite_sign_radps_per_nm " +
                  std::to_string(g.opposite_sign_radps_per_nm.size()) + "; they must pair up");
  }
  for (std::size_t i = 1; i < g.duty.size(); ++i) {
    if (!(g.duty[i] > g.duty[i - 1])) {
      out.push_back(name + ".duty[" + std::to_string(i) + "]: " + show_number(g.duty[i]) +
                    " does not increase; duty must be strictly increasing");
    }
  }
}

void check_load_gains(const Params& p, std::vector<std::string>& out) {
  bool configured = false;
  for (std::size_t i = 0; i < p.load_gains.size(); ++i) {
    check_load_gain(p.load_gains[i], i, out);
    configured = configured || p.load_gains[i].icr == p.cycle.icr;
    for (std::size_t k = 0; k < i; ++k) {
      if (p.load_gains[k].icr == p.load_gains[i].icr) {
        out.push_back("load_gain[" + std::to_string(i) +
                      "].icr: " + std::to_string(p.load_gains[i].icr) + " is given twice");
      }
    }
  }
  if (!configured) {
    out.push_back("cycle.icr: " + std::to_string(p.cycle.icr) +
                  " has no [[load_gain]] with that icr; add one (calibrate load)");
  }
}

bool has_curve(const Params& p) {
  for (const auto& c : p.motor_curves) {
    if (c.icr == p.cycle.icr) return true;
  }
  return false;
}

bool has_response(const Params& p) {
  for (const auto& r : p.responses) {
    if (r.con == p.cycle.con && std::abs(r.period_s - p.cycle.period_s) <= 0.001) return true;
  }
  return false;
}

}  // namespace

std::vector<std::string> consistency_problems(const Params& p) {
  std::vector<std::string> out;
  const auto& g = p.geometry;
  if (!(g.joint_to_exterior_axle_m < g.center_axle_to_joint_m)) {
    out.push_back("geometry.joint_to_exterior_axle_m: " + show_number(g.joint_to_exterior_axle_m) +
                  " must be below center_axle_to_joint_m (" +
                  show_number(g.center_axle_to_joint_m) +
                  ") for the joints to stand vertical at acos(a/b)");
  }
  const double overflow_s = tracking::clock_overflow_period_s(p.cycle.con);
  if (!(p.cycle.period_s < overflow_s)) {
    out.push_back("cycle.period_s: " + show_number(p.cycle.period_s) + " s is not below T(con = " +
                  std::to_string(p.cycle.con) + ") = " + show_number(overflow_s) +
                  " s, so (3.2) cannot track tim overflows; raise cycle.con");
  }
  const auto& j = p.joints;
  if (!(j.front_min_rad < j.front_max_rad)) {
    out.push_back("joints.front_min_rad: " + show_number(j.front_min_rad) +
                  " must be below joints.front_max_rad (" + show_number(j.front_max_rad) + ")");
  }
  if (!(j.rear_min_rad < j.rear_max_rad)) {
    out.push_back("joints.rear_min_rad: " + show_number(j.rear_min_rad) +
                  " must be below joints.rear_max_rad (" + show_number(j.rear_max_rad) + ")");
  }
  for (std::size_t i = 0; i < p.motor_curves.size(); ++i) {
    check_curve(p.motor_curves[i], i, out);
    for (std::size_t k = 0; k < i; ++k) {
      if (p.motor_curves[k].icr == p.motor_curves[i].icr) {
        out.push_back("motor_curve[" + std::to_string(i) +
                      "].icr: " + std::to_string(p.motor_curves[i].icr) + " is given twice");
      }
    }
  }
  check_load_gains(p, out);
  const auto& n = p.navigation;
  if (!(n.min_speed_mps <= n.cruise_speed_mps)) {
    out.push_back("navigation.min_speed_mps: " + show_number(n.min_speed_mps) +
                  " must not exceed cruise_speed_mps (" + show_number(n.cruise_speed_mps) + ")");
  }
  if (!(n.min_spin_radps <= n.max_spin_radps)) {
    out.push_back("navigation.min_spin_radps: " + show_number(n.min_spin_radps) +
                  " must not exceed max_spin_radps (" + show_number(n.max_spin_radps) + ")");
  }
  if (!has_curve(p)) {
    out.push_back("cycle.icr: " + std::to_string(p.cycle.icr) +
                  " has no [[motor_curve]] with that icr; add one (calibrate motor-curve)");
  }
  if (!has_response(p)) {
    out.push_back("cycle: no [[response]] for period_s " + show_number(p.cycle.period_s) +
                  " (±0.001) and con " + std::to_string(p.cycle.con) +
                  "; add one (calibrate response)");
  }
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& a = p.sensors.accelerometer[i];
    if (a.plus_g_counts == a.minus_g_counts) {
      out.push_back("sensors.accelerometer_plus_g_counts[" + std::to_string(i) +
                    "]: equals the −g reading; (3.5) divides by their difference");
    }
  }
  return out;
}

}  // namespace marsokhod::config
