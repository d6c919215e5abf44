#include "core/tracking/encoder_interrupt.hpp"

#include <sstream>
#include <stdexcept>

namespace marsokhod::tracking {

static_assert(kEncoderInterruptDutyLimit == 3.0 / 5.0, "the integer comparison below uses 3/5");

bool direction_change_update_enabled(std::uint16_t pwm, int icr) {
  if (icr <= 0) {
    std::ostringstream message;
    message << "invalid icr = " << icr
            << ": the PWM period register must be positive (255..2047); configure cycle.icr";
    throw std::invalid_argument(message.str());
  }
  // pwm/icr < 3/5 ⇔ 5·pwm < 3·icr for icr > 0; both sides fit comfortably in 64 bits.
  return 5 * static_cast<std::int64_t>(pwm) < 3 * static_cast<std::int64_t>(icr);
}

}  // namespace marsokhod::tracking
