#include "driver/duty_rules.hpp"

#include <algorithm>
#include <cmath>

#include "core/tracking/encoder_interrupt.hpp"

namespace marsokhod::driver {

namespace {
bool reversed(double duty) { return duty < 0.0; }  // drv of control_request()
}  // namespace

double next_duty(double previous, double wanted, const SafetyParams& safety) {
  if (!std::isfinite(wanted)) return previous;
  wanted = std::clamp(wanted, -1.0, 1.0);
  const double step = safety.max_duty_step;
  double next = previous + std::clamp(wanted - previous, -step, step);
  // The request that toggles drv carries a pwm ≈ 0: at most the band.
  const double band = safety.direction_change_duty;
  if (reversed(next) != reversed(previous) && std::abs(next) > band) {
    next = std::copysign(band, next);
  }
  return next;
}

protocol::ControlRequest control_request(std::uint8_t node, double duty, int icr) {
  const double d = std::isfinite(duty) ? std::clamp(duty, -1.0, 1.0) : 0.0;
  protocol::ControlRequest r;
  r.node = node;
  r.pwm = static_cast<std::uint16_t>(std::lround(std::abs(d) * icr));
  r.drv = d < 0.0 && r.pwm > 0;
  r.eim = tracking::direction_change_update_enabled(r.pwm, icr);
  return r;
}

double duty_of(const protocol::ControlRequest& request, int icr) {
  return (request.drv ? -1.0 : 1.0) * request.pwm / icr;
}

double sent_duty(double duty, int icr) { return duty_of(control_request(0, duty, icr), icr); }

}  // namespace marsokhod::driver
