#include "driver/joint_memory.hpp"

#include <cmath>
#include <cstdio>

#include "core/adaptation/backlash.hpp"
#include "core/checks/checks.hpp"
#include "core/protocol/messages.hpp"
#include "core/tracking/counter.hpp"

namespace marsokhod::driver {
namespace {

constexpr double kDeadManPeriod_s = protocol::kDeadManTickUs * 1e-6;  // µ8's unit of dog
constexpr double kSupplyHeadroom = 1.25;       // no-load speed scales with U/Ū; U ≤ 1.25·Ū
constexpr std::uint32_t kHalfCounterRange = 32768;

std::string refusal(std::size_t motor, const char* format, double a, double b, double c) {
  char text[200];
  std::snprintf(text, sizeof text, format, a, b, c);
  return "µ" + std::to_string(motor) + text;
}

}  // namespace

ShiftBounds kept_joint_shift_bounds(const Params& params, double duty) {
  const double rad_per_count = tracking::encoder_rad_per_count(params.motors.encoder_pulses_per_rev);
  const double wrap_rad = rad_per_count * kHalfCounterRange;
  if (params.safety.dead_man_dog <= 0) return {wrap_rad, wrap_rad};
  const double w = kSupplyHeadroom * params.motors.max_no_load_speed_radps;
  const double h = params.cycle.period_s;
  const double dead_man_s = kDeadManPeriod_s * params.safety.dead_man_dog;
  const double d = std::min(1.0, std::abs(duty));
  const double before = std::min(1.0, d + params.safety.max_duty_step);
  ShiftBounds bounds;
  bounds.along_rad = std::min(wrap_rad, w * (d * (dead_man_s + h) + before * 2.0 * h) + kReboundRad);
  bounds.against_rad = w * params.safety.direction_change_duty * 2.0 * h + kReboundRad;
  if (d == 0.0) bounds.against_rad = bounds.along_rad;
  return bounds;
}

std::optional<RestoredJoint> restore_joint(const KeptJoint& kept,
                                           const tracking::EncoderReading& now,
                                           double backlash_rad, const Params& params,
                                           std::size_t motor, std::string& why) {
  checks::require_finite(kept.shaft_rad, "restore_joint", "kept.shaft_rad");
  checks::require_finite(kept.joint_rad, "restore_joint", "kept.joint_rad");
  checks::require_finite(kept.duty, "restore_joint", "kept.duty");
  const double rad_per_count = tracking::encoder_rad_per_count(params.motors.encoder_pulses_per_rev);
  const std::int32_t kept_sign = kept.reading.dir ? -1 : 1;
  const std::int32_t sign = now.dir ? -1 : 1;
  const auto total = static_cast<std::int32_t>(tracking::counter_difference(now.enc, kept.reading.enc));
  std::int32_t before_reversal = total;  // pulses in the kept direction
  if (now.stp != kept.reading.stp || now.dir != kept.reading.dir) {
    before_reversal =
        static_cast<std::int32_t>(tracking::counter_difference(now.stp, kept.reading.enc));
    if (before_reversal > total) {
      why = refusal(motor, " reversed at stp %.0f, off the arc from the kept enc %.0f to enc %.0f",
                    now.stp, kept.reading.enc, now.enc);
      return std::nullopt;
    }
  }
  // The direction of the pulses before the last reversal (joint_memory.hpp).
  std::int32_t before_sign = kept_sign;
  if (now.dir == kept.reading.dir && now.stp != kept.reading.stp) {
    before_sign = kept.duty > 0.0 ? 1 : kept.duty < 0.0 ? -1 : -sign;
  }
  const std::int32_t counts = before_sign * before_reversal + sign * (total - before_reversal);
  RestoredJoint out;
  out.shift_rad = rad_per_count * static_cast<double>(counts);
  const ShiftBounds bounds = kept_joint_shift_bounds(params, kept.duty);
  const double along = kept.duty < 0.0 ? -out.shift_rad : out.shift_rad;
  if (along > bounds.along_rad || -along > bounds.against_rad) {
    why = refusal(motor,
                  "'s shaft moved %+.4f rad while the driver was down, more than it can at the "
                  "duty %.3f it was left with (%.4f rad)",
                  out.shift_rad, kept.duty, along > 0.0 ? bounds.along_rad : bounds.against_rad);
    return std::nullopt;
  }
  out.shaft_rad = kept.shaft_rad + out.shift_rad;
  const double reversal_rad = kept.shaft_rad + rad_per_count * before_sign * before_reversal;
  const double joint_rad = adaptation::backlash_position(reversal_rad, kept.joint_rad, backlash_rad);
  out.joint_rad = adaptation::backlash_position(out.shaft_rad, joint_rad, backlash_rad);
  return out;
}

}  // namespace marsokhod::driver
