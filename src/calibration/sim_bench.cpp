#include <cmath>
#include <string>

#include "calibration/bench.hpp"
#include "sim/rover/simulated_rover.hpp"

namespace marsokhod::calibration {
namespace {

// After arrange(): the rover settles (the chassis stops swinging, the supply recovers) this long.
constexpr double kSettleS = 1.0;

}  // namespace

sim::SimOptions sim_bench_options(std::uint64_t seed) {
  sim::SimOptions options;
  options.seed = seed;
  options.supply = sim::SupplyKind::kTether;
  return options;
}

SimBench::SimBench(const Params& params, const sim::SimOptions& options)
    : SimBench(params, options, params) {}

SimBench::SimBench(const Params& params, const sim::SimOptions& options,
                   const Params& rover_params)
    : Bench(params),
      rover_params_(std::make_unique<Params>(rover_params)),
      rover_(std::make_unique<sim::SimulatedRover>(*rover_params_, options)),
      seed_(options.seed),
      supply_(options.supply),
      soft_soil_(options.terrain.ground.soil ? options.terrain.ground.soil->name : "") {}

SimBench::~SimBench() = default;

sim::SimulatedRover& SimBench::rover() { return *rover_; }

std::vector<protocol::CanFrame> SimBench::exchange(
    const std::vector<protocol::CanFrame>& requests, double period_s) {
  const double now = static_cast<double>(period_us_ * steps_) * 1e-6;
  if (period_us_ == 0 || std::abs(static_cast<double>(period_us_) * 1e-6 - period_s) > 1e-9) {
    // Time as whole microseconds (like runner::Session), so that cycles add up exactly.
    period_us_ = std::llround(period_s * 1e6);
  }
  for (const protocol::CanFrame& frame : requests) rover_->send(frame, now);
  ++steps_;
  std::vector<protocol::CanFrame> frames;
  for (const sim::TimedFrame& f :
       rover_->advance_to(static_cast<double>(period_us_ * steps_) * 1e-6)) {
    frames.push_back(f.frame);
  }
  return frames;
}

void SimBench::arrange(const BenchSetup& setup) {
  stop();
  if (setup.placement == BenchSetup::Placement::kStand) {
    rover_->place_on_stand(setup.stand_roll_rad, setup.stand_pitch_rad);
  } else {
    // Set down from the stand onto soft soil: on ground raked level, not into its last ruts.
    if (rover_->on_stand()) rover_->level_soil();
    rover_->place_on_ground();
  }
  sim::SimFaults faults = rover_->faults();
  // Procedure 4.1's straps: rigid wheels, so that the axles cannot move over the ground.
  faults.wheel_blocked.fill(setup.strapped_down &&
                            setup.placement == BenchSetup::Placement::kGround);
  rover_->set_faults(faults);
  if (setup.supply_v) rover_->set_tether_voltage(*setup.supply_v);
  for (std::size_t axle = 0; axle < setup.axle_tilt_rad.size(); ++axle) {
    rover_->hold_axle_tilt(axle, setup.axle_tilt_rad[axle]);
  }
  for (std::size_t wheel = 0; wheel < kWheelCount; ++wheel) {
    const bool strapped = setup.weight_wheel && *setup.weight_wheel == wheel;
    rover_->strap_weight(wheel, strapped ? setup.weight_peak_torque_nm : 0.0);
  }
  const MotorVector zero{};
  const auto cycles = std::lround(kSettleS / period_s());
  for (long k = 0; k < cycles; ++k) {
    if (started()) {
      cycle(zero);
    } else {
      exchange({}, period_s());
    }
  }
}

double SimBench::measure_supply_v() { return rover_->electrics().supply_v; }

std::string SimBench::source() const {
  return "simulator (seed " + std::to_string(seed_) + ", " +
         (supply_ == sim::SupplyKind::kTether ? "tether" : "battery") +
         (soft_soil_.empty() ? "" : ", soft soil: " + soft_soil_) + ")";
}

}  // namespace marsokhod::calibration
