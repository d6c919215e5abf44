// A scripted stand-in for µ0–µ8 in driver tests: it answers every request the way the firmware
// would, with motors that turn exactly at the driver's own no-load model (4.3) — ŵ = ζ·W(d)·U/Ū
// with the nominal W₅₁₁ table, no load, no lag — and µ8 reporting the TYP readings of chapter 3.3
// (flat ground, vcc 970 → U = 24.5673 V). Frames are built with the protocol codec, so the
// driver sees byte-exact traffic. (The simulator, not this, tests the driver against physics.)
#pragma once

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "core/adaptation/motor_curve.hpp"
#include "core/adaptation/no_load_velocity.hpp"
#include "core/params.hpp"
#include "core/protocol/codec.hpp"
#include "driver/operator_commands.hpp"

namespace marsokhod::driver::testing {

class ScriptedRover {
 public:
  static constexpr double kSupplyV = 0.06768 * 970 - 41.0823;  // vcc 970, Procedure 3.5
  static constexpr double kPulsesPerRad = 115000.0 / (2.0 * std::numbers::pi);

  std::array<bool, 9> silent{};  // a silent controller never answers
  std::array<double, 8> duty{};  // the last duty each motor received
  std::array<double, 8> shaft_rad{};
  std::array<int, 8> configured_icr{};
  int dog = 0;
  int measurement_requests = 0;
  std::array<std::uint16_t, 3> acc{279, 251, 376};  // µ8's acc¹..³: TYP, level
  std::uint16_t yaw = 505;                           // µ8's gyro reading: TYP, at rest
  // vel reports the speed of the duty received this many requests earlier (0: of this very
  // request, as if the motor responded at once): a response chain δ = (0, …, 0, 1) of (4.4).
  int velocity_delay_cycles = 0;
  // A joint shaft (6, 7) that has travelled this far toward the negative end meets its joint
  // (0: never) and then drags it at dragging_speed_share of its speed; dragged_rad sums how far.
  std::array<double, 8> meets_joint_after_rad{};
  double dragging_speed_share = 1.0;
  std::array<double, 8> dragged_rad{};
  // Before its next response the shaft springs back this many pulses and forward again: two
  // direction changes inside one cycle, which leave dir as it was and move stp (motor_position.hpp)
  std::array<int, 8> spring_back_pulses{};
  // A motor the ground turns: this speed on top of its duty's [rad/s]; with `rocking` its sign
  // flips at every request (a wheel rocking where it stands in soft sand).
  std::array<double, 8> pushed_radps{};
  bool rocking = false;

  // Applies one cycle's requests, moves the motors for dt, and returns the responses.
  std::vector<protocol::CanFrame> respond(const std::vector<protocol::CanFrame>& requests,
                                          double dt_s) {
    std::vector<protocol::CanFrame> out;
    for (const auto& frame : requests) {
      const auto decoded = protocol::decode(frame);
      if (!decoded.ok()) continue;
      std::visit([&](const auto& m) { answer(m, dt_s, out); }, decoded.message());
    }
    return out;
  }

 private:
  struct Registers {
    double pulses = 0.0;       // all pulses counted so far, regardless of direction
    bool dir = false;
    std::uint16_t stp = 0;
    double tim_ticks = 0.0;
    std::vector<double> speeds;  // one per request
  };
  std::array<Registers, 8> reg_{};
  Params params_;
  adaptation::MotorCurve curve_{params_.motor_curves.front()};

  static std::uint16_t wrap(double counts) {
    return static_cast<std::uint16_t>(static_cast<long long>(std::floor(counts)) & 0xFFFF);
  }

  template <class M>
  void answer(const M& m, double dt_s, std::vector<protocol::CanFrame>& out) {
    using T = std::decay_t<M>;
    if constexpr (std::is_same_v<T, protocol::ControlRequest>) {
      if (silent[m.node]) return;
      const int icr = configured_icr[m.node] > 0 ? configured_icr[m.node] : 511;
      duty[m.node] = (m.drv ? -1.0 : 1.0) * m.pwm / icr;
      out.push_back(protocol::encode(move(m.node, dt_s)));
    } else if constexpr (std::is_same_v<T, protocol::ConfigurationRequest>) {
      if (silent[m.node]) return;
      configured_icr[m.node] = m.icr;
      out.push_back(protocol::encode(protocol::ConfigurationResponse{m.node, 0}));
    } else if constexpr (std::is_same_v<T, protocol::MeasurementRequest>) {
      ++measurement_requests;
      if (silent[8]) return;
      // TYP: yaw 505, acc 279/251/376, tlt 527/520, vcc 970.
      protocol::MeasurementResponse r{yaw, acc, 527, 970, protocol::TiltChannel::kFront};
      if (measurement_requests % 2 == 0) {
        r.tlt = 520;
        r.tilt_channel = protocol::TiltChannel::kRear;
      }
      out.push_back(protocol::encode(r));
    } else if constexpr (std::is_same_v<T, protocol::DeadManRequest>) {
      dog = m.dog;
      if (!silent[8]) out.push_back(protocol::encode(protocol::DeadManResponse{}));
    }
  }

  protocol::ControlResponse move(std::uint8_t node, double dt_s) {
    Registers& r = reg_[node];
    double speed = adaptation::no_load_velocity(curve_, duty[node], params_.motors.scale[node],
                                                kSupplyV, params_.motors.nominal_supply_v);
    if (meets_joint_after_rad[node] > 0.0 && -shaft_rad[node] >= meets_joint_after_rad[node]) {
      speed *= dragging_speed_share;
      dragged_rad[node] += std::abs(speed) * dt_s;
    }
    speed += pushed_radps[node];
    if (rocking) pushed_radps[node] = -pushed_radps[node];
    if (spring_back_pulses[node] > 0) {
      const double n = spring_back_pulses[node];
      r.stp = wrap(r.pulses + n);  // the second change, after n pulses back
      r.pulses += 2.0 * n;
      spring_back_pulses[node] = 0;
    }
    const bool dir = speed < 0.0;
    if (speed != 0.0 && dir != r.dir) {
      r.stp = wrap(r.pulses);
      r.dir = dir;
    }
    r.pulses += std::abs(speed) * dt_s * kPulsesPerRad;
    shaft_rad[node] += speed * dt_s;
    r.tim_ticks += dt_s * 2.0e6;
    // vel: pulses in the last T(0) = 32.768 ms at this speed (or at an earlier one).
    r.speeds.push_back(speed);
    const auto delay = static_cast<std::size_t>(velocity_delay_cycles);
    const double reported =
        r.speeds.size() > delay ? r.speeds[r.speeds.size() - 1 - delay] : 0.0;
    const double vel = std::abs(reported) * 0.032768 * kPulsesPerRad;
    return {node, wrap(r.tim_ticks), wrap(r.pulses), r.stp, r.dir,
            static_cast<std::uint16_t>(std::lround(vel))};
  }
};

// The operator's drive of driver_bench's BM_DriverStep and the allocation test: forward and
// turning with rolking running, so that every stage of the cycle is busy.
inline OperatorInput driving_with_rolking() {
  OperatorInput input;
  input.targets = mobility::OperatorTargets{};
  input.targets->v1_radps = 1.0;
  input.targets->v2_radps = 0.3;
  input.targets->gait = mobility::Gait::kRolking;
  input.targets->gait_speed = 0.5;
  return input;
}

}  // namespace marsokhod::driver::testing
