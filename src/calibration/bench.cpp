#include "calibration/bench.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "calibration/procedure.hpp"
#include "core/protocol/codec.hpp"
#include "driver/duty_rules.hpp"

namespace marsokhod::calibration {
namespace {

// How long a controller may take to acknowledge its configuration before it counts as absent.
constexpr int kConfigureCycles = 16;
// stop(): the shafts count as still below this speed …
constexpr double kStillRadps = 0.02;
// … and stop() waits at most this long for them.
constexpr double kStopTimeoutS = 3.0;

}  // namespace

Bench::Bench(const Params& params)
    : params_(params),
      intake_(params.cycle.icr),
      icr_(params.cycle.icr),
      con_(params.cycle.con),
      motors_(params.motors),
      sensors_(params.sensors, params.filters) {}

Bench::~Bench() = default;

void Bench::start(int icr, int con) {
  if (icr < 255 || icr > 2047) {
    throw std::invalid_argument("bench: icr must lie in 255..2047, got " + std::to_string(icr));
  }
  if (con < 0 || con > 255) {
    throw std::invalid_argument("bench: con must lie in 0..255, got " + std::to_string(con));
  }
  if (started_) stop();
  icr_ = icr;
  con_ = con;
  intake_ = driver::FrameIntake(icr);
  configure();
  started_ = true;
}

void Bench::configure() {
  std::vector<protocol::CanFrame> requests;
  for (std::uint8_t node = 0; node < kMotorCount; ++node) {
    requests.push_back(protocol::encode(protocol::ConfigurationRequest{
        node, static_cast<std::uint16_t>(icr_), 0, static_cast<std::uint8_t>(con_)}));
  }
  requests.push_back(protocol::encode(
      protocol::DeadManRequest{static_cast<std::uint8_t>(params_.safety.dead_man_dog)}));
  std::array<bool, kMotorCount + 1> acknowledged{};
  for (int attempt = 0; attempt < kConfigureCycles; ++attempt) {
    std::vector<protocol::CanFrame> pending;
    for (std::size_t i = 0; i <= kMotorCount; ++i) {
      if (!acknowledged[i]) pending.push_back(requests[i]);
    }
    if (pending.empty()) break;
    const std::vector<protocol::CanFrame> frames = exchange(pending, period_s());
    const driver::CycleResponses responses = intake_.take(frames, {});
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      if (responses.configuration[i]) acknowledged[i] = true;
    }
    if (responses.dead_man_acknowledged) acknowledged[kMotorCount] = true;
    ++cycles_;
    sample_.time_s = static_cast<double>(cycles_) * period_s();
  }
  std::string missing;
  for (std::size_t i = 0; i <= kMotorCount; ++i) {
    if (!acknowledged[i]) missing += (missing.empty() ? "µ" : ", µ") + std::to_string(i);
  }
  if (!missing.empty()) {
    throw BenchError("bench: no acknowledgement from " + missing + " within " +
                     std::to_string(kConfigureCycles) +
                     " cycles: check the bus, the power and the controllers' wiring");
  }
}

const BenchSample& Bench::cycle(const MotorVector& wanted_duty) {
  if (!started_) throw BenchError("bench: start() before cycling");
  std::vector<protocol::CanFrame> requests;
  requests.reserve(kMotorCount + 1);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    const double wanted = std::isfinite(wanted_duty[i]) ? std::clamp(wanted_duty[i], -1.0, 1.0)
                                                        : 0.0;
    sent_duty_[i] = driver::next_duty(sent_duty_[i], wanted, params_.safety);
    requests.push_back(protocol::encode(
        driver::control_request(static_cast<std::uint8_t>(i), sent_duty_[i], icr_)));
  }
  protocol::MeasurementRequest measurement;
  const std::string lcd = "CALIB   ";
  std::copy_n(lcd.begin(), measurement.lcd.size(), measurement.lcd.begin());
  requests.push_back(protocol::encode(measurement));
  expected_.fill(true);
  take(exchange(requests, period_s()));
  return sample_;
}

void Bench::take(const std::vector<protocol::CanFrame>& frames) {
  const driver::CycleResponses responses = intake_.take(frames, expected_);
  ++cycles_;
  sample_.time_s = static_cast<double>(cycles_) * period_s();
  sample_.duty = sent_duty_;
  sample_.fresh.fill(false);
  for (std::size_t i = 0; i < kMotorCount; ++i) {
    if (!responses.control[i]) {
      ++missed_;
      continue;
    }
    const tracking::MotorSample& m = motors_.update_motor(*responses.control[i], con_);
    sample_.position_rad[i] = m.position_rad;
    sample_.velocity_radps[i] = m.velocity_radps;
    sample_.fresh[i] = true;
  }
  sample_.raw = responses.measurement;
  if (responses.measurement) {
    bool still = true;
    bool zero = true;
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      still = still && std::abs(sample_.velocity_radps[i]) < kStillRadps;
      zero = zero && sent_duty_[i] == 0.0;
    }
    sample_.sensors = sensors_.update(*responses.measurement, still, zero);
  } else {
    ++missed_;
  }
}

std::vector<BenchSample> Bench::hold(const MotorVector& wanted_duty, double seconds) {
  const auto cycles = std::max<long>(1, std::lround(seconds / period_s()));
  std::vector<BenchSample> out;
  out.reserve(static_cast<std::size_t>(cycles));
  for (long k = 0; k < cycles; ++k) out.push_back(cycle(wanted_duty));
  return out;
}

void Bench::stop() {
  if (!started_) return;
  const MotorVector zero{};
  const auto limit = std::lround(kStopTimeoutS / period_s());
  long still_cycles = 0;
  for (long k = 0; k < limit; ++k) {
    cycle(zero);
    bool all_zero = true;
    bool still = true;
    for (std::size_t i = 0; i < kMotorCount; ++i) {
      all_zero = all_zero && sent_duty_[i] == 0.0;
      still = still && std::abs(sample_.velocity_radps[i]) < kStillRadps;
    }
    still_cycles = all_zero && still ? still_cycles + 1 : 0;
    if (still_cycles >= 4) return;
  }
}

BenchSetup stand_at_nominal_supply(const Params& params, std::string_view then) {
  BenchSetup setup;
  setup.placement = BenchSetup::Placement::kStand;
  setup.supply_v = params.motors.nominal_supply_v;
  setup.instruction =
      "Put the rover on the stand so that all six wheels turn freely, and power it from the "
      "laboratory supply set to " + fixed(params.motors.nominal_supply_v, 1) + " V" +
      std::string(then);
  return setup;
}

}  // namespace marsokhod::calibration
