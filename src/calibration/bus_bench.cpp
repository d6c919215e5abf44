#include <chrono>
#include <istream>
#include <ostream>
#include <string>

#include "bus/transport.hpp"
#include "calibration/bench.hpp"

namespace marsokhod::calibration {

BusBench::BusBench(const Params& params, std::unique_ptr<bus::CanTransport> transport,
                   std::istream& in, std::ostream& out)
    : Bench(params), transport_(std::move(transport)), in_(&in), out_(&out) {
  if (!transport_) throw std::invalid_argument("bus bench: no transport");
}

BusBench::~BusBench() {
  // Leave the motors stopped, whatever happened; µ8's dead man's switch is the backstop.
  try {
    stop();
  } catch (const std::exception&) {
  }
}

std::vector<protocol::CanFrame> BusBench::exchange(
    const std::vector<protocol::CanFrame>& requests, double period_s) {
  using clock = std::chrono::steady_clock;
  const auto deadline =
      clock::now() + std::chrono::microseconds(static_cast<std::int64_t>(period_s * 1e6));
  try {
    for (const protocol::CanFrame& frame : requests) transport_->send(frame);
    std::vector<protocol::CanFrame> frames;
    for (auto now = clock::now(); now < deadline; now = clock::now()) {
      const auto wait = std::chrono::duration_cast<std::chrono::microseconds>(deadline - now);
      for (const protocol::CanFrame& f : transport_->receive(wait)) frames.push_back(f);
    }
    return frames;
  } catch (const std::exception& e) {
    throw BenchError(std::string("bench: ") + e.what());
  }
}

void BusBench::arrange(const BenchSetup& setup) {
  stop();
  std::ostream& out = *out_;
  out << "\n== " << setup.instruction << "\n";
  if (setup.placement == BenchSetup::Placement::kStand) {
    out << "   The rover rests on a stand, all six wheels free of the ground.\n";
  } else {
    out << "   The rover stands on the ground.\n";
  }
  if (setup.supply_v) {
    out << "   Set the laboratory supply to " << *setup.supply_v << " V.\n";
  }
  if (setup.weight_wheel) {
    out << "   Strap the weight to wheel " << kMotorNames.at(*setup.weight_wheel)
        << " (peak torque " << setup.weight_peak_torque_nm << " N·m).\n";
  }
  out << "   Press Enter when done (q and Enter to give up): " << std::flush;
  std::string line;
  if (!std::getline(*in_, line) || line == "q") {
    throw BenchError("calibration given up by the operator at: " + setup.instruction);
  }
  // The controllers have kept their configuration; µ8 may have stopped the motors meanwhile,
  // which they are anyway. A few cycles bring the trackers up to date.
  const MotorVector zero{};
  if (started()) hold(zero, 0.5);
}

double BusBench::measure_supply_v() {
  for (;;) {
    *out_ << "   Type the multimeter's reading at the power distribution board [V] (q gives up): "
          << std::flush;
    std::string line;
    if (!std::getline(*in_, line) || line == "q") {
      throw BenchError("calibration given up by the operator at the multimeter reading");
    }
    try {
      std::size_t used = 0;
      const double volts = std::stod(line, &used);
      if (used == line.size() && volts > 0.0 && volts < 40.0) return volts;
    } catch (const std::exception&) {
    }
    *out_ << "   '" << line << "' is not a voltage between 0 and 40 V.\n";
  }
}

std::string BusBench::source() const { return transport_->name(); }

}  // namespace marsokhod::calibration
