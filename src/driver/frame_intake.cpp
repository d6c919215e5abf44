#include "driver/frame_intake.hpp"

#include <type_traits>
#include <variant>

namespace marsokhod::driver {

FrameIntake::FrameIntake(int icr) {
  context_.icr.fill(static_cast<std::uint16_t>(icr));
}

void FrameIntake::sort(const protocol::Message& message, CycleResponses& out) {
  std::visit(
      [&](const auto& m) {
        using T = std::decay_t<decltype(m)>;
        auto keep = [&](auto& slot) {
          if (slot.has_value()) ++counters_.duplicates;
          slot = m;  // the latest one wins: it carries the newest register values
        };
        if constexpr (std::is_same_v<T, protocol::ControlResponse>) {
          keep(out.control[m.node]);
        } else if constexpr (std::is_same_v<T, protocol::ConfigurationResponse>) {
          keep(out.configuration[m.node]);
        } else if constexpr (std::is_same_v<T, protocol::MeasurementResponse>) {
          keep(out.measurement);
        } else if constexpr (std::is_same_v<T, protocol::DeadManResponse>) {
          out.dead_man_acknowledged = true;
        } else {
          ++counters_.foreign;
        }
      },
      message);
}

CycleResponses FrameIntake::take(std::span<const protocol::CanFrame> frames,
                                 const std::array<bool, kMotorCount + 1>& expected) {
  CycleResponses out;
  for (const protocol::CanFrame& frame : frames) {
    ++counters_.frames;
    const protocol::DecodeResult result = protocol::decode(frame, context_);
    if (!result.ok()) {
      ++counters_.malformed;
      counters_.last_error = result.error().reason;
      continue;
    }
    sort(result.message(), out);
  }
  for (std::size_t i = 0; i <= kMotorCount; ++i) {
    const bool answered = i < kMotorCount
                              ? out.control[i].has_value() || out.configuration[i].has_value()
                              : out.measurement.has_value() || out.dead_man_acknowledged;
    if (!expected[i] || answered) {
      silent_cycles_[i] = 0;
    } else {
      ++silent_cycles_[i];
      ++counters_.missed;
    }
  }
  return out;
}

}  // namespace marsokhod::driver
