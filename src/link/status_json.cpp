#include "link/status_json.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/mobility/gait_table.hpp"
#include "link/command_json.hpp"

namespace marsokhod::link {
namespace {

using Json = nlohmann::json;

Json motor_json(const driver::MotorStatus& motor) {
  return {{"shaft_position_rad", motor.shaft_position_rad},
          {"position_rad", motor.position_rad},
          {"position_uncertainty_rad", motor.position_uncertainty_rad},
          {"velocity_radps", motor.velocity_radps},
          {"no_load_velocity_radps", motor.no_load_velocity_radps},
          {"load_radps", motor.load_radps},
          {"torque_nm", motor.torque_nm},
          {"commanded_radps", motor.commanded_radps},
          {"slope_hold_radps", motor.slope_hold_radps},
          {"duty", motor.duty},
          {"silent_cycles", motor.silent_cycles}};
}

Json velocities_json(const driver::TargetStatus& t) {
  return {{"v1_radps", t.v1_radps},
          {"v2_radps", t.v2_radps},
          {"v3_radps", t.v3_radps},
          {"v4_radps", t.v4_radps},
          {"v6_radps", t.v6_radps},
          {"v7_radps", t.v7_radps}};
}

Json bus_json(const driver::BusCounters& bus) {
  return {{"frames", bus.frames},         {"malformed", bus.malformed},
          {"duplicates", bus.duplicates}, {"foreign", bus.foreign},
          {"missed", bus.missed},         {"last_error", bus.last_error}};
}

Json gait_json(const driver::DriverStatus& s) {
  return {{"id", mobility::gait_id(s.gait)},
          {"name", mobility::gait_name(s.gait)},
          {"state", s.gait_state},
          {"speed", s.gait_speed}};
}

Json joint_bounds_json(const driver::JointBoundsStatus& b) {
  return {{"front_min_rad", b.front_min_rad},
          {"front_max_rad", b.front_max_rad},
          {"rear_min_rad", b.rear_min_rad},
          {"rear_max_rad", b.rear_max_rad}};
}


Json optional_number(const std::optional<double>& v) { return v ? Json(*v) : Json(); }

Json mission_json(const navigation::MissionStatus& m) {
  Json waypoints = Json::array();
  for (const navigation::Waypoint& w : m.waypoints) waypoints.push_back({w.x_m, w.y_m});
  return {{"id", m.id},
          {"kind", navigation::mission_kind_id(m.kind)},
          {"state", navigation::mission_state_id(m.state)},
          {"reason", m.reason},
          {"progress", m.progress},
          {"leg", m.leg},
          {"waypoints", waypoints},
          {"target_heading_rad", optional_number(m.target_heading_rad)},
          {"remaining_m", optional_number(m.remaining_m)},
          {"remaining_rad", optional_number(m.remaining_rad)},
          {"corrections", m.corrections},
          {"settle_s", m.settle_s}};
}

}  // namespace

Json pose_json(const estimation::Pose& p) {
  return {{"x_m", p.x_m},
          {"y_m", p.y_m},
          {"heading_rad", p.heading_rad},
          {"speed_mps", p.speed_mps},
          {"yaw_rate_radps", p.yaw_rate_radps},
          {"distance_m", p.distance_m},
          {"position_sigma_m", p.position_sigma_m()},
          {"heading_sigma_rad", p.heading_sigma_rad()}};
}

Json status_json(const driver::DriverStatus& s, const Json& truth) {
  if (!truth.is_null() && !truth.is_object()) {
    throw std::invalid_argument("status_json: truth must be a JSON object or null, got " +
                                std::string(truth.type_name()));
  }
  Json motors = Json::object();
  for (std::size_t i = 0; i < kMotorCount; ++i) motors[kMotorNames[i]] = motor_json(s.motors[i]);
  Json out = {
      {"mission_time_s", s.mission_time_s},
      {"cycle_time_s", s.cycle_time_s},
      {"cycle", s.cycle},
      {"mode", driver::mode_name(s.mode)},
      {"startup_phase", driver::phase_name(s.startup_phase)},
      {"supply_v", s.supply_v},
      {"reference_supply_v", s.reference_supply_v},
      {"yaw_rate_radps", s.yaw_rate_radps},
      {"accel_mps2", s.accel_mps2},
      {"front_tilt_rad", s.front_tilt_rad},
      {"rear_tilt_rad", s.rear_tilt_rad},
      {"slope_rad", s.slope_rad},
      {"motors", motors},
      {"sensor_silent_cycles", s.sensor_silent_cycles},
      {"max_duty", s.max_duty},
      {"supply_current_bound_a", s.supply_current_bound_a},
      {"current_duty_bound", s.current_duty_bound},
      {"driving_scale", s.driving_scale},
      {"walking_scale", s.walking_scale},
      {"targets", velocities_json(s.targets)},
      {"commands", velocities_json(s.commands)},
      {"gait", gait_json(s)},
      {"front_axle_factor", s.front_axle_factor},
      {"rear_axle_factor", s.rear_axle_factor},
      {"joint_bounds", joint_bounds_json(s.joint_bounds)},
      {"joints_known", s.joints_known},
      {"joint_origin", s.joint_origin},
      {"operator_timeout", s.operator_timeout},
      {"operator_rejection", s.operator_rejection},
      {"stop_latched", s.stop_latched},
      {"stop_reason", s.stop_reason},
      {"faults", s.faults},
      {"warnings", s.warnings},
      {"bus", bus_json(s.bus)},
      {"lcd", s.lcd},
      {"pose", pose_json(s.pose)},
      {"attitude", Json{{"roll_rad", s.attitude.roll_rad}, {"pitch_rad", s.attitude.pitch_rad}}},
      {"stalled_s", s.stalled_s},
      {"joint_stalled_s", Json::array({s.joint_stalled_s[0], s.joint_stalled_s[1]})},
      {"mission", mission_json(s.mission)},
      {"settings", runtime_settings_json(s.settings)},
  };
  if (!truth.is_null()) out["truth"] = truth;
  return out;
}

Json soil_patch_json(const sim::soil::SoilGrid& grid, double x_m, double y_m) {
  constexpr int kStride = 2;  // every second cell
  const sim::soil::GridSpec& spec = grid.spec();
  const double step_m = kStride * spec.cell_m;
  // The patch's cells: span/step of every kStride-th cell from the grid's first, starting at the
  // first whose centre lies within half the span before the point; clipped to the grid.
  const auto range = [&](double centre, double origin, int cells, double span) {
    const int count = static_cast<int>(std::lround(span / step_m));
    const double first = (centre - 0.5 * span - origin - 0.5 * spec.cell_m) / step_m;
    const int last_sample = (cells - 1) / kStride;
    if (!std::isfinite(first) || first > last_sample || first + count < 0) {
      return std::pair<int, int>{0, -1};  // off the grid (or no position): an empty patch
    }
    const int lo = static_cast<int>(std::ceil(first));
    return std::pair<int, int>{std::max(0, lo), std::min(last_sample, lo + count - 1)};
  };
  const auto [x_lo, x_hi] = range(x_m, spec.origin_x_m, spec.cells_x, kSoilPatchSpanM[0]);
  const auto [y_lo, y_hi] = range(y_m, spec.origin_y_m, spec.cells_y, kSoilPatchSpanM[1]);
  const int columns = std::max(0, x_hi - x_lo + 1);
  const int rows = std::max(0, y_hi - y_lo + 1);
  std::vector<long> heights;
  heights.reserve(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows));
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      heights.push_back(std::lround(
          1000.0 * grid.cell_surface_m((x_lo + c) * kStride, (y_lo + r) * kStride)));
    }
  }
  return {{"origin_m",
           {spec.origin_x_m + (x_lo * kStride + 0.5) * spec.cell_m,
            spec.origin_y_m + (y_lo * kStride + 0.5) * spec.cell_m}},
          {"cell_m", step_m},
          {"columns", columns},
          {"rows", rows},
          {"height_mm", std::move(heights)}};
}

Json truth_json(const sim::SimulatedRover& rover,
                const std::optional<estimation::PlanarPose>& odometry, bool with_soil) {
  const sim::GroundTruth t = rover.truth();
  Json wheels = Json::array();
  for (const auto& w : t.wheel_position_m) wheels.push_back(w);
  Json out = {{"position_m", t.position_m},
          {"roll_pitch_yaw_rad", t.roll_pitch_yaw_rad},
          {"velocity_mps", t.velocity_mps},
          {"joint_angle_rad", t.joint_angle_rad},
          {"wheel_angle_rad",
           std::vector<double>(t.joint_angle_rad.begin(), t.joint_angle_rad.begin() + 6)},
          {"wheel_position_m", wheels},
          {"wheel_slip_mps", t.wheel_slip_mps},
          {"supply_v", rover.electrics().supply_v},
          {"computer_on", rover.computer_on()}};
  if (odometry) {
    out["odometry"] = {{"x_m", odometry->x_m},
                       {"y_m", odometry->y_m},
                       {"heading_rad", odometry->heading_rad}};
  }
  if (with_soil && rover.soft_soil() != nullptr) {
    out["soil"] = soil_patch_json(rover.soft_soil()->grid(), t.position_m[0], t.position_m[1]);
  }
  return out;
}

}  // namespace marsokhod::link
