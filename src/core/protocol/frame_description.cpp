#include "core/protocol/frame_description.hpp"

#include <cstdio>
#include <numbers>
#include <type_traits>

#include "core/tracking/clock.hpp"
#include "core/tracking/motor_position.hpp"
#include "core/tracking/motor_velocity.hpp"
#include "core/tracking/sensor_conversion.hpp"

namespace marsokhod::protocol {
namespace {

double duty(bool drv, int pwm, int icr) { return (drv ? -1.0 : 1.0) * pwm / icr; }

void describe_control(const ControlRequest& m, const BusContext& c, FrameDescription& d) {
  d.raw = {{"drv", m.drv, {}}, {"eim", m.eim, {}}, {"pwm", m.pwm, {}}};
  d.physical = {{"d", duty(m.drv, m.pwm, c.icr(m.node)), "", 3, true}};
}

void describe_control(const ControlResponse& m, const BusContext& c, FrameDescription& d) {
  const int con = c.con(m.node);
  const int pulses = c.params().motors.encoder_pulses_per_rev;
  const double rad_per_count = tracking::encoder_rad_per_count(pulses);
  d.raw = {{"tim", m.tim, {}}, {"enc", m.enc, {}}, {"stp", m.stp, {}},
           {"dir", m.dir, {}}, {"vel", m.vel, {}}};
  d.physical = {{"t", m.tim * tracking::clock_tick_s(con), "s", 6, false},
                {"enc_angle", m.enc * rad_per_count, "rad", 4, false},
                {"stp_angle", m.stp * rad_per_count, "rad", 4, false},
                {"w", tracking::motor_velocity_radps(m.vel, m.dir, con, pulses), "rad/s", 3, true}};
}

void describe_configuration(const ConfigurationRequest& m, FrameDescription& d) {
  d.raw = {{"icr", m.icr, {}}, {"pwm", m.pwm, {}}, {"con", m.con, {}}};
  d.physical = {{"f_pwm", 8.0e6 / (m.icr + 1) / 1000.0, "kHz", 3, false},
                {"d", duty(false, m.pwm, m.icr), "", 3, true},
                {"T", tracking::clock_overflow_period_s(m.con), "s", 6, false}};
}

void describe_measurement(const MeasurementRequest& m, FrameDescription& d) {
  d.raw = {{"led0", m.led0, {}}, {"led1", m.led1, {}},
           {"lcd", 0, std::string(m.lcd.begin(), m.lcd.end())}};
}

void describe_measurement(const MeasurementResponse& m, const BusContext& c, FrameDescription& d) {
  const SensorParams& s = c.params().sensors;
  const bool rear = m.tilt_channel == TiltChannel::kRear;
  d.raw = {{"yaw", m.yaw, {}},   {"acc1", m.acc[0], {}}, {"acc2", m.acc[1], {}},
           {"acc3", m.acc[2], {}}, {rear ? "tltr" : "tltf", m.tlt, {}},
           {"j", rear ? 1 : 0, {}}, {"vcc", m.vcc, {}}};
  // The null rate y is a running estimate on the rover; a trace alone shows the TYP base line.
  d.physical = {
      {"omega3", tracking::yaw_rate_radps(m.yaw, s.gyro_null_typ_counts, s.gyro_radps_per_count),
       "rad/s", 3, true},
      {"a1", tracking::accelerometer_mps2(m.acc[0], s.accelerometer[0], s.gravity_mps2), "m/s^2", 2, true},
      {"a2", tracking::accelerometer_mps2(m.acc[1], s.accelerometer[1], s.gravity_mps2), "m/s^2", 2, true},
      {"a3", tracking::accelerometer_mps2(m.acc[2], s.accelerometer[2], s.gravity_mps2), "m/s^2", 2, true},
      {rear ? "theta_r" : "theta_f", rear ? s.tilt_rear(m.tlt) : s.tilt_front(m.tlt), "rad", 3, true},
      {"U", s.supply(m.vcc), "V", 2, false}};
}

void describe_dead_man(const DeadManRequest& m, FrameDescription& d) {
  d.raw = {{"dog", m.dog, {}}};
  // µ8 stops the motors 0.2621·dog s after the last 0x80 (chapter 3.3); dog = 0 disables it.
  d.physical = {{"timeout", static_cast<double>(kDeadManTickUs) * 1e-6 * m.dog, "s", 3, false}};
}

}  // namespace

BusContext::BusContext(const Params& params) : params_(&params) {
  icr_.fill(params.cycle.icr);
  con_.fill(params.cycle.con);
}

void BusContext::observe(const Message& message) {
  if (const auto* m = std::get_if<ConfigurationRequest>(&message)) {
    icr_.at(m->node) = m->icr;
    con_.at(m->node) = m->con;
  }
}

DecodeContext BusContext::decode_context() const {
  DecodeContext context;
  for (std::size_t i = 0; i < kMotorCount; ++i) context.icr[i] = static_cast<std::uint16_t>(icr_[i]);
  return context;
}

FrameDescription describe(const Message& message, const BusContext& context) {
  FrameDescription d;
  d.node = node_of(message);
  d.type = message_name(message);
  for (char& ch : d.type) ch = ch == ' ' ? '_' : ch;
  std::visit(
      [&](const auto& m) {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, ControlRequest> || std::is_same_v<T, ControlResponse>) {
          describe_control(m, context, d);
        } else if constexpr (std::is_same_v<T, ConfigurationRequest>) {
          describe_configuration(m, d);
        } else if constexpr (std::is_same_v<T, ConfigurationResponse>) {
          d.raw = {{"tim", m.tim, {}}};
        } else if constexpr (std::is_same_v<T, MeasurementRequest>) {
          describe_measurement(m, d);
        } else if constexpr (std::is_same_v<T, MeasurementResponse>) {
          describe_measurement(m, context, d);
        } else if constexpr (std::is_same_v<T, DeadManRequest>) {
          describe_dead_man(m, d);
        }
      },
      message);
  return d;
}

std::string format_text(const FrameDescription& description) {
  std::string out;
  for (const RawField& f : description.raw) {
    if (!out.empty()) out += ' ';
    out += f.name + "=" + (f.name == "lcd" ? "\"" + f.text + "\"" : std::to_string(f.value));
  }
  for (const PhysicalField& f : description.physical) {
    char number[64];
    std::snprintf(number, sizeof number, f.show_sign ? "%+.*f" : "%.*f", f.decimals, f.value);
    if (!out.empty()) out += ' ';
    out += f.name + "=" + number + (f.unit.empty() ? "" : " " + f.unit);
  }
  return out;
}

}  // namespace marsokhod::protocol
