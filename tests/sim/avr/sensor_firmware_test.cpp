// Differential test of µ8: the same requests against the C++ emulation
// (sim/firmware/sensor_controller.hpp, noise and gyro drift off so that both see the same counts)
// and the real firmware (firmware/sensor.c) in simavr: measurement responses bit for bit with the
// tilt channel alternating, the LEDs, the display, the dead man's switch and malformed frames.
#include "sim/avr/sensor_firmware.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "core/protocol/codec.hpp"
#include "sim/firmware/sensor_adc.hpp"
#include "sim/firmware/sensor_controller.hpp"

namespace marsokhod::sim {
namespace {

using protocol::CanFrame;

constexpr SimTimeNs kUs = 1000;
constexpr SimTimeNs kMs = 1'000'000;
constexpr SimTimeNs kAnswerWindowNs = 200 * kUs;
constexpr SimTimeNs kInputsAheadNs = 2 * kMs;  // the ADC ring converts all 7 channels in 0.73 ms
// µ8 starts Timer 1 (4 µs a count) at the time passed since the 0x80's CAN time stamp, and sends
// the stop frames one after the other from the overflow interrupt: the first after the
// emulation's exact deadline by under a count and the interrupts' reaction (30.4 µs measured
// here, 14.5 µs before the ADC interrupt counted for the watchdog: which interrupt the overflow
// waits behind decides), each next within 10 µs (8 µs measured); the emulation has all eight
// ready at the deadline. On the bus, where one frame takes over 50 µs, order and spacing hold.
constexpr SimTimeNs kReactionBoundNs = 40 * kUs;
constexpr SimTimeNs kNextFrameBoundNs = 10 * kUs;
// The display's power-on wait (40 ms) and initialisation: the firmware writes text from 50 ms on.
constexpr SimTimeNs kDisplayReadyNs = 50 * kMs;

std::string image() { return std::string(MARSOKHOD_FIRMWARE_DIR) + "/mu8.elf"; }

SensorTruth noiseless_truth() {
  SensorTruth truth;
  truth.gyro_drift_amplitude_counts = 0.0;
  truth.gyro_noise_counts = 0.0;
  truth.accelerometer_noise_counts = 0.0;
  truth.tilt_noise_counts = 0.0;
  truth.supply_noise_counts = 0.0;
  return truth;
}

class SensorPair {
 public:
  SensorPair() : emulation_(truth_, 1, sample_), firmware_(image(), true) { set(sample_, 0); }

  // New sensor values at time_ns, for both; the potentiometers move through their backlash.
  void set(const SensorTruthSample& sample, SimTimeNs time_ns) {
    advance(time_ns);
    sample_ = sample;
    emulation_.advance(time_ns, sample);
    front_.update(sample.front_tilt_rad);
    rear_.update(sample.rear_tilt_rad);
    avr::SensorCounts counts;
    counts.yaw = quantise_adc(gyro_counts(sample.yaw_rate_radps,
                                          gyro_null_counts(truth_, 0.0), truth_.gyro_radps_per_count));
    for (std::size_t i = 0; i < 3; ++i) {
      counts.acc[i] = quantise_adc(
          accelerometer_counts(sample.accel_mps2[i], truth_.accelerometer[i], truth_.gravity_mps2));
    }
    counts.tilt_front = quantise_adc(conversion_counts(front_.shaft_rad(), truth_.tilt_front));
    counts.tilt_rear = quantise_adc(conversion_counts(rear_.shaft_rad(), truth_.tilt_rear));
    counts.vcc = quantise_adc(conversion_counts(sample.supply_v, truth_.supply));
    firmware_.set_inputs(counts);
  }

  void advance(SimTimeNs time_ns) {
    if (time_ns > now_ns_) {
      emulation_.advance(time_ns, sample_);
      firmware_.advance(time_ns);
      now_ns_ = time_ns;
    }
  }

  // The answers of both to frame at time_ns; the firmware's frames of the answer window.
  std::pair<std::optional<CanFrame>, std::vector<avr::TimedCanFrame>> request(
      SimTimeNs time_ns, const CanFrame& frame) {
    advance(time_ns);
    std::optional<CanFrame> emulated = emulation_.receive(frame);
    firmware_.deliver(frame);
    advance(time_ns + kAnswerWindowNs);
    return {emulated, firmware_.take_transmitted()};
  }

  void expect_same(SimTimeNs time_ns, const CanFrame& frame, const std::string& what) {
    const auto [emulated, sent] = request(time_ns, frame);
    if (emulated) {
      ASSERT_EQ(sent.size(), 1U) << what;
      EXPECT_EQ(sent.front().frame, *emulated) << what;
    } else {
      EXPECT_TRUE(sent.empty()) << what << ": the firmware answered, the emulation did not";
    }
  }

  SensorController& emulation() { return emulation_; }
  avr::SensorFirmware& firmware() { return firmware_; }

 private:
  SensorTruth truth_ = noiseless_truth();
  SensorTruthSample sample_;
  SensorController emulation_;
  avr::SensorFirmware firmware_;
  PotentiometerBacklash front_{truth_.tilt_backlash_rad, 0.0};
  PotentiometerBacklash rear_{truth_.tilt_backlash_rad, 0.0};
  SimTimeNs now_ns_ = 0;
};

CanFrame measurement(bool green, bool white, const char (&text)[9]) {
  protocol::MeasurementRequest request;
  request.led0 = green;
  request.led1 = white;
  for (std::size_t i = 0; i < 8; ++i) request.lcd[i] = text[i];
  return protocol::encode(request);
}

TEST(SensorFirmware, MeasurementsLedsAndDisplayMatchTheEmulation) {
  SensorPair pair;
  SimTimeNs t = kDisplayReadyNs + 10 * kMs;
  const char* texts[] = {"Joyride ", "24.0V ok", "tilt +4 ", "  spin  ", "#20 fw  ", "abc~XYZ}"};
  for (int i = 0; i < 6; ++i) {
    SensorTruthSample sample;
    sample.yaw_rate_radps = -0.5 + 0.2 * i;
    sample.accel_mps2 = {0.3 * i, -0.2 * i, -9.81 + 0.1 * i};
    sample.front_tilt_rad = 0.1 * i;   // beyond the 4° of half play: the shaft follows
    sample.rear_tilt_rad = -0.08 * i;
    sample.supply_v = 26.9 - 1.1 * i;
    pair.set(sample, t - kInputsAheadNs);
    char text[9];
    std::copy(texts[i], texts[i] + 9, text);
    const bool green = i % 2 == 0;
    const bool white = i % 3 == 0;
    pair.expect_same(t, measurement(green, white, text), "measurement " + std::to_string(i));
    EXPECT_EQ(pair.firmware().green_led(), pair.emulation().green_led()) << i;
    EXPECT_EQ(pair.firmware().white_led(), pair.emulation().white_led()) << i;
    EXPECT_EQ(pair.firmware().green_led(), green) << i;
    pair.advance(t + 5 * kMs);  // the display is written by the main loop, 0.9 ms a line
    EXPECT_EQ(pair.firmware().display(), pair.emulation().lcd_display()) << i;
    t += 20 * kMs;
  }
}

TEST(SensorFirmware, DisplayFallsBackToTheIdleTextAfterASecondWithoutRequests) {
  SensorPair pair;
  pair.expect_same(10 * kMs, measurement(false, false, "Marsokhd"), "measurement");
  pair.advance(1300 * kMs);
  EXPECT_EQ(pair.emulation().lcd_display(), kLcdIdleText);
  const std::string idle = std::string(kLcdIdleText) + "   " + kLcdIdleText;
  EXPECT_NE(idle.find(pair.firmware().display()), std::string::npos)
      << "'" << pair.firmware().display() << "' is no window of the idle text";
}

// The stop frames both send after a silence: identical frames, the firmware's within the
// reaction bound after the emulation's deadline.
void expect_stop(SensorPair& pair, SimTimeNs from_ns, const std::string& what) {
  const std::optional<SimTimeNs> deadline = pair.emulation().dead_man_deadline_ns();
  ASSERT_TRUE(deadline.has_value()) << what;
  pair.advance(*deadline - 1 * kMs);
  EXPECT_TRUE(pair.firmware().take_transmitted().empty()) << what << ": stopped early";
  pair.advance(*deadline + 1 * kMs);
  const std::array<CanFrame, 8> expected = pair.emulation().fire_dead_man();
  const std::vector<avr::TimedCanFrame> sent = pair.firmware().take_transmitted();
  ASSERT_EQ(sent.size(), expected.size()) << what;
  for (std::size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(sent[i].frame, expected[i]) << what << ", µ" << i;
    EXPECT_GE(sent[i].time_ns, *deadline) << what;
    EXPECT_LE(sent[i].time_ns - *deadline,
              kReactionBoundNs + static_cast<SimTimeNs>(i) * kNextFrameBoundNs) << what;
  }
  EXPECT_GT(*deadline, from_ns);
}

TEST(SensorFirmware, DeadMansSwitchStopsTheMotorsAfterDogTicksOfSilence) {
  SensorPair pair;
  pair.expect_same(5 * kMs, protocol::encode(protocol::DeadManRequest{2}), "dog 2");
  pair.expect_same(10 * kMs, measurement(false, false, "        "), "first 0x80");
  EXPECT_EQ(pair.emulation().dead_man_deadline_ns(), 10 * kMs + 2 * kDeadManPeriodNs);
  expect_stop(pair, 10 * kMs, "silence after 10 ms");
  // Again every overflow while the silence lasts (a stop frame the bus lost gets there later).
  EXPECT_EQ(pair.emulation().dead_man_deadline_ns(), 10 * kMs + 3 * kDeadManPeriodNs);
  expect_stop(pair, 10 * kMs, "the first repeat");
  expect_stop(pair, 10 * kMs, "the second repeat");
  pair.advance(1200 * kMs);
  EXPECT_TRUE(pair.firmware().take_transmitted().empty()) << "a repeat before its overflow";
  pair.expect_same(1210 * kMs, measurement(true, false, "again   "), "re-arm");
  pair.expect_same(1500 * kMs, measurement(true, false, "fed     "), "feed before the deadline");
  expect_stop(pair, 1500 * kMs, "silence after 1.5 s");
  // Disabled in the middle of the repeats: they end.
  pair.expect_same(2100 * kMs, protocol::encode(protocol::DeadManRequest{0}), "dog 0");
  pair.expect_same(2110 * kMs, measurement(false, true, "disabled"), "0x80, disabled");
  pair.advance(2800 * kMs);
  EXPECT_FALSE(pair.emulation().dead_man_deadline_ns().has_value());
  EXPECT_TRUE(pair.firmware().take_transmitted().empty()) << "disabled";
}

// Fed for longer than the watchdog's second: the first firmware fed its watchdog on Timer 1's
// overflows, which a 0x80 every 15.6 ms never lets happen; it was reset and forgot dog.
TEST(SensorFirmware, DeadMansSwitchHoldsThroughALongFedRun) {
  SensorPair pair;
  pair.expect_same(5 * kMs, protocol::encode(protocol::DeadManRequest{1}), "dog 1");
  SimTimeNs t = 10 * kMs;
  for (int k = 0; k < 192; ++k) {  // 3 s at 64 Hz
    t = 10 * kMs + static_cast<SimTimeNs>(k) * 15'625'000;
    pair.expect_same(t, measurement(false, false, "driving "), "0x80 " + std::to_string(k));
  }
  expect_stop(pair, t, "silence after 3 s of driving");
}

TEST(SensorFirmware, MalformedFramesGetNoAnswerAndDoNotFeedTheSwitch) {
  SensorPair pair;
  pair.expect_same(5 * kMs, protocol::encode(protocol::DeadManRequest{1}), "dog 1");
  pair.expect_same(10 * kMs, measurement(false, false, "ok      "), "0x80");
  std::vector<std::pair<std::string, CanFrame>> malformed;
  CanFrame frame = measurement(false, false, "bad     ");
  frame.data[3] = 0x1F;
  malformed.emplace_back("LCD character 0x1F", frame);
  frame = measurement(false, false, "bad     ");
  frame.dlc = 7;
  malformed.emplace_back("0x80 DLC 7", frame);
  frame = protocol::encode(protocol::DeadManRequest{5});
  frame.dlc = 2;
  malformed.emplace_back("0x82 DLC 2", frame);
  malformed.emplace_back("a 0x81", protocol::encode(protocol::MeasurementResponse{}));
  malformed.emplace_back("a 0x83", protocol::encode(protocol::DeadManResponse{}));
  frame = measurement(false, false, "type 5  ");
  frame.id = protocol::can_id(8, 5);
  malformed.emplace_back("type 5", frame);
  frame = measurement(false, false, "low bits");
  frame.id |= 2;
  malformed.emplace_back("identifier's low bits", frame);
  SimTimeNs t = 20 * kMs;
  for (const auto& [what, bad] : malformed) {
    pair.expect_same(t, bad, what);
    t += 10 * kMs;
  }
  expect_stop(pair, 10 * kMs, "the switch counts from the last valid 0x80");
}

}  // namespace
}  // namespace marsokhod::sim
