// Differential test of µ0–µ7: the same request sequences against the C++ emulation
// (sim/firmware/motor_controller.hpp) and the real firmware (firmware/motor.c) in simavr give
// the same responses bit for bit, and the same duty.
//
// Timing of the test's trajectories: at con = 0 tim ticks every 0.5 µs and vel's slices end every
// 4096 ticks = 2.048 ms. The shaft crosses its pulse boundaries on a grid 20 µs + k·64 µs, and
// requests arrive at 52 µs + k·64 µs, so no pulse falls within 20 µs of a slice end or a request:
// the firmware's own latencies (the LS7184's 4 µs from direction to pulse, the interrupt's
// entry) never decide a count, and both must agree exactly.
#include "sim/avr/motor_firmware.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "core/protocol/codec.hpp"
#include "sim/firmware/motor_controller.hpp"

namespace marsokhod::sim {
namespace {

using protocol::CanFrame;

constexpr int kPulsesPerRev = 115000;
constexpr double kRadPerPulse = 2.0 * std::numbers::pi / kPulsesPerRev;
constexpr SimTimeNs kUs = 1000;
constexpr SimTimeNs kMs = 1'000'000;
constexpr SimTimeNs kGridNs = 64 * kUs;
constexpr SimTimeNs kPulsePhaseNs = 20 * kUs;
constexpr SimTimeNs kAnswerWindowNs = 100 * kUs;  // the firmware answers within tens of µs
constexpr std::uint8_t kNode = 3;

std::string image(std::uint8_t node) {
  return std::string(MARSOKHOD_FIRMWARE_DIR) + "/mu" + std::to_string(node) + ".elf";
}

// A request time on the grid: 52 µs + k·64 µs, the first at or after time_ns.
SimTimeNs request_time(SimTimeNs time_ns) {
  const SimTimeNs offset = kPulsePhaseNs + kGridNs / 2;
  return offset + (time_ns - offset + kGridNs - 1) / kGridNs * kGridNs;
}

// A piecewise linear shaft: the angle through knots (time, pulses), where whole pulse numbers
// fall on the 20 µs + k·64 µs grid when the shaft turns at one pulse per 64 µs.
class Shaft {
 public:
  explicit Shaft(double pulses_at_zero) { knots_.push_back({0, pulses_at_zero}); }
  // Moves at `pulses_per_grid` (±1 or 0) per 64 µs until time_ns.
  void move_until(SimTimeNs time_ns, int pulses_per_grid) {
    const Knot last = knots_.back();
    knots_.push_back({time_ns, last.pulses + pulses_per_grid * static_cast<double>(time_ns - last.time_ns) /
                                                 static_cast<double>(kGridNs)});
  }
  double angle_rad(SimTimeNs time_ns) const {
    for (std::size_t i = 1; i < knots_.size(); ++i) {
      if (time_ns <= knots_[i].time_ns) {
        const Knot& a = knots_[i - 1];
        const Knot& b = knots_[i];
        const double f = static_cast<double>(time_ns - a.time_ns) / static_cast<double>(b.time_ns - a.time_ns);
        return (a.pulses + f * (b.pulses - a.pulses)) * kRadPerPulse;
      }
    }
    return knots_.back().pulses * kRadPerPulse;
  }
  std::vector<SimTimeNs> knot_times() const {
    std::vector<SimTimeNs> times;
    for (const Knot& knot : knots_) times.push_back(knot.time_ns);
    return times;
  }

 private:
  struct Knot {
    SimTimeNs time_ns;
    double pulses;
  };
  std::vector<Knot> knots_;
};

struct Answers {
  std::optional<CanFrame> emulation;
  std::optional<CanFrame> firmware;
};

class MotorPair {
 public:
  explicit MotorPair(const Shaft& shaft)
      : shaft_(shaft),
        emulation_(kNode, shaft.angle_rad(0), kPulsesPerRev, 1),
        firmware_(image(kNode), shaft.angle_rad(0), kPulsesPerRev) {}

  // Both controllers to time_ns, through every knot of the shaft on the way.
  void advance(SimTimeNs time_ns) {
    for (const SimTimeNs knot : shaft_.knot_times()) {
      if (knot > now_ns_ && knot < time_ns) step(knot);
    }
    step(time_ns);
  }

  Answers request(SimTimeNs time_ns, const CanFrame& frame) {
    advance(time_ns);
    Answers answers;
    answers.emulation = emulation_.receive(frame);
    firmware_.deliver(frame);
    advance(time_ns + kAnswerWindowNs);
    const std::vector<avr::TimedCanFrame> sent = firmware_.take_transmitted();
    EXPECT_LE(sent.size(), 1U) << "one request, at most one answer";
    if (!sent.empty()) answers.firmware = sent.front().frame;
    return answers;
  }

  double emulation_duty() const { return emulation_.duty(); }
  double firmware_duty() const { return firmware_.duty(); }
  avr::MotorFirmware& firmware() { return firmware_; }

 private:
  void step(SimTimeNs time_ns) {
    emulation_.advance(time_ns, shaft_.angle_rad(time_ns));
    firmware_.advance(time_ns, shaft_.angle_rad(time_ns));
    now_ns_ = time_ns;
  }

  const Shaft& shaft_;
  MotorController emulation_;
  avr::MotorFirmware firmware_;
  SimTimeNs now_ns_ = 0;
};

std::string describe(const std::optional<CanFrame>& frame) {
  if (!frame) return "no answer";
  const protocol::DecodeResult decoded = protocol::decode(*frame);
  std::string text = "id " + std::to_string(frame->id) + " dlc " + std::to_string(frame->dlc) + ":";
  for (int i = 0; i < frame->dlc; ++i) text += " " + std::to_string(frame->data[static_cast<std::size_t>(i)]);
  if (decoded.ok() && std::holds_alternative<protocol::ControlResponse>(decoded.message())) {
    const auto& r = std::get<protocol::ControlResponse>(decoded.message());
    text += " (tim " + std::to_string(r.tim) + " enc " + std::to_string(r.enc) + " stp " +
            std::to_string(r.stp) + " dir " + std::to_string(r.dir) + " vel " + std::to_string(r.vel) + ")";
  }
  return text;
}

void expect_same(const Answers& answers, const std::string& what) {
  EXPECT_EQ(answers.emulation, answers.firmware)
      << what << "\n  emulation: " << describe(answers.emulation)
      << "\n  firmware:  " << describe(answers.firmware);
}

CanFrame control(bool drv, bool eim, std::uint16_t pwm) {
  return protocol::encode(protocol::ControlRequest{kNode, drv, eim, pwm});
}

TEST(MotorFirmware, ConfigurationAndControlWithEveryFlagAtRest) {
  const Shaft shaft(1000.5);
  MotorPair pair(shaft);
  SimTimeNs t = request_time(1 * kMs);
  expect_same(pair.request(t, protocol::encode(protocol::ConfigurationRequest{kNode, 511, 0, 0})),
              "configuration at reset");
  for (const bool drv : {false, true}) {
    for (const bool eim : {false, true}) {
      for (const std::uint16_t pwm : {0, 1, 255, 511}) {
        t = request_time(t + 1 * kMs + 37 * kUs);
        const Answers answers = pair.request(t, control(drv, eim, pwm));
        ASSERT_TRUE(answers.emulation.has_value());
        expect_same(answers, "control drv " + std::to_string(drv) + " eim " + std::to_string(eim) +
                                 " pwm " + std::to_string(pwm));
        EXPECT_DOUBLE_EQ(pair.firmware_duty(), pair.emulation_duty());
        EXPECT_DOUBLE_EQ(pair.firmware_duty(), (drv ? -1.0 : 1.0) * pwm / 511.0);
      }
    }
  }
  t = request_time(t + 1 * kMs);
  expect_same(pair.request(t, protocol::encode(protocol::ConfigurationRequest{kNode, 1023, 300, 0})),
              "configuration icr 1023, pwm 300");
  EXPECT_DOUBLE_EQ(pair.firmware_duty(), -300.0 / 1023.0);  // drv stays 1 from the last control
}

TEST(MotorFirmware, EncoderDirectionAndVelocityWhileTurning) {
  // Stands while the firmware boots, then crosses pulse boundaries 32 µs after each request slot.
  Shaft shaft(1000.5);
  shaft.move_until(request_time(2 * kMs), 0);
  shaft.move_until(request_time(30 * kMs), +1);   // forward, 15625 pulses/s
  shaft.move_until(request_time(50 * kMs), -1);   // reversal with eim = 1
  shaft.move_until(request_time(60 * kMs), +1);   // reversal with eim = 0 (masked)
  shaft.move_until(request_time(80 * kMs), -1);   // reversal with eim = 1 again
  shaft.move_until(request_time(90 * kMs), 0);    // stands
  MotorPair pair(shaft);
  SimTimeNs t = request_time(1 * kMs);
  expect_same(pair.request(t, control(false, true, 100)), "eim on");
  std::uint16_t last_dir_changes = 0;
  for (t = request_time(t + 3 * kMs); t < 100 * kMs; t = request_time(t + 2 * kMs + 300 * kUs)) {
    const bool eim = !(t > 52 * kMs && t < 70 * kMs);
    const Answers answers = pair.request(t, control(false, eim, 100));
    ASSERT_TRUE(answers.emulation.has_value());
    expect_same(answers, "measurement at " + std::to_string(t / kUs) + " µs");
    last_dir_changes += answers.emulation->data[6] >> 7;
  }
  EXPECT_GT(last_dir_changes, 0) << "the trajectory must reverse the measured direction";
  EXPECT_GT(pair.firmware().pulses(), 1000U);
}

// con changes. The emulation restarts tim's prescaler the instant a 0xi2 with a new con arrives;
// the firmware can write CANTCON only after its interrupt has read and checked the frame (about
// 15 µs later), while the CAN timer still counts at the old rate, and then takes what the timer
// gained meanwhile off tim (change_con in firmware/motor.c). It measures that gain on the old
// clock, so tim agrees within one tick of the old clock (in ticks of the new one: (old+1)/(new+1))
// and one tick of rounding, at each change; for the driver's change at start-up, con 0 → 1,
// within one tick.
int tim_lead(const Answers& answers) {
  const auto tim = [](const CanFrame& frame) {
    return static_cast<std::uint16_t>((frame.data[0] << 8) | frame.data[1]);
  };
  return static_cast<std::int16_t>(tim(*answers.firmware) - tim(*answers.emulation));
}

void expect_same_but_tim(const Answers& answers, const std::string& what) {
  ASSERT_TRUE(answers.emulation.has_value() && answers.firmware.has_value()) << what;
  CanFrame firmware = *answers.firmware;
  firmware.data[0] = answers.emulation->data[0];
  firmware.data[1] = answers.emulation->data[1];
  EXPECT_EQ(firmware, *answers.emulation) << what;
}

TEST(MotorFirmware, ClockDividerChangesKeepTimWithinATickOfTheOldClock) {
  const Shaft shaft(1000.5);
  MotorPair pair(shaft);
  SimTimeNs t = request_time(1 * kMs);
  int old_con = 0;
  int bound = 0;  // ticks, carried over to the next change's configuration response
  for (const std::uint8_t con : {1, 0, 3, 7, 1, 255, 0}) {
    const Answers configured =
        pair.request(t, protocol::encode(protocol::ConfigurationRequest{kNode, 511, 0, con}));
    expect_same_but_tim(configured, "configuration con " + std::to_string(con));
    EXPECT_LE(std::abs(tim_lead(configured)), bound) << "con " << old_con << " → " << int{con};
    bound += (old_con + 1 + con) / (con + 1) + 1;  // ⌈(old+1)/(new+1)⌉ + 1 more at each change
    for (int i = 0; i < 3; ++i) {
      t = request_time(t + 5 * kMs + 111 * kUs * i);
      const Answers answers = pair.request(t, control(false, true, 0));
      const std::string what = "control " + std::to_string(i) + " after con " + std::to_string(con);
      expect_same_but_tim(answers, what);
      EXPECT_LE(std::abs(tim_lead(answers)), bound) << what << " (from con " << old_con << ")";
      if (old_con == 0 && con == 1) {
        EXPECT_LE(std::abs(tim_lead(answers)), 1) << what << ": the driver's change";
      }
    }
    old_con = con;
    t = request_time(t + 3 * kMs);
  }
}

// Past 2^24 ticks of the 2 MHz Timer 2 (8.39 s): the first firmware kept Timer 2's count in 24
// bits, and its vel froze there.
TEST(MotorFirmware, VelocityKeepsItsWindowPastEightSeconds) {
  Shaft shaft(1000.5);
  shaft.move_until(request_time(2 * kMs), 0);
  shaft.move_until(request_time(9000 * kMs), 1);   // 15625 pulses/s until 9 s
  shaft.move_until(request_time(9100 * kMs), 0);   // stands
  MotorPair pair(shaft);
  expect_same(pair.request(request_time(1 * kMs), control(false, true, 100)), "eim on");
  for (const SimTimeNs t : {8300 * kMs, 8500 * kMs, 8990 * kMs, 9200 * kMs}) {
    const Answers answers = pair.request(request_time(t), control(false, true, 100));
    ASSERT_TRUE(answers.emulation.has_value());
    expect_same(answers, "at " + std::to_string(t / kMs) + " ms");
  }
}

TEST(MotorFirmware, MalformedFramesGetNoAnswerFromEither) {
  const Shaft shaft(1000.5);
  MotorPair pair(shaft);
  SimTimeNs t = request_time(1 * kMs);
  expect_same(pair.request(t, control(false, true, 200)), "valid control");
  std::vector<std::pair<std::string, CanFrame>> malformed;
  CanFrame frame = control(false, false, 100);
  frame.dlc = 2;
  malformed.emplace_back("control DLC 2", frame);
  frame.dlc = 4;
  malformed.emplace_back("control DLC 4", frame);
  frame = control(true, true, 100);
  frame.data[0] |= 0x04;
  malformed.emplace_back("control reserved bit 2", frame);
  frame = control(false, true, 600);
  malformed.emplace_back("control pwm 600 > icr 511", frame);
  frame = protocol::encode(protocol::ConfigurationRequest{kNode, 511, 0, 0});
  frame.data[0] = 0;
  frame.data[1] = 254;
  malformed.emplace_back("configuration icr 254", frame);
  frame.data[0] = 0x08;
  frame.data[1] = 0x00;
  malformed.emplace_back("configuration icr 2048", frame);
  frame = protocol::encode(protocol::ConfigurationRequest{kNode, 511, 0, 0});
  frame.data[3] = 0xFF;
  frame.data[2] = 0x01;  // pwm 511 is fine; 0x1FF → make it 512 below
  frame.data[3] = 0x00;
  frame.data[2] = 0x02;
  malformed.emplace_back("configuration pwm 512 > icr 511", frame);
  frame = protocol::encode(protocol::ConfigurationRequest{kNode, 511, 0, 0});
  frame.dlc = 4;
  malformed.emplace_back("configuration DLC 4", frame);
  frame = control(false, true, 100);
  frame.id = protocol::can_id(2, 0);
  malformed.emplace_back("another node's control request", frame);
  frame = control(false, true, 100);
  frame.id |= 1;
  malformed.emplace_back("identifier's low bits set", frame);
  frame = protocol::encode(protocol::ControlResponse{kNode, 1, 2, 3, false, 4});
  malformed.emplace_back("a control response", frame);
  frame = control(false, true, 100);
  frame.id = protocol::can_id(kNode, 7);
  malformed.emplace_back("type 7", frame);
  for (const auto& [what, bad] : malformed) {
    t = request_time(t + 700 * kUs);
    const Answers answers = pair.request(t, bad);
    EXPECT_FALSE(answers.emulation.has_value()) << what;
    expect_same(answers, what);
  }
  EXPECT_DOUBLE_EQ(pair.firmware_duty(), 200.0 / 511.0) << "nothing malformed changed the duty";
  t = request_time(t + 1 * kMs);
  expect_same(pair.request(t, control(false, true, 50)), "valid control after the malformed ones");
}

TEST(MotorFirmware, MissingImageIsAClearError) {
  try {
    avr::MotorFirmware firmware("/nonexistent/mu3.elf", 0.0, kPulsesPerRev);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/mu3.elf"), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("make firmware"), std::string::npos);
  }
}

}  // namespace
}  // namespace marsokhod::sim
