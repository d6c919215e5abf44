// Emulation of the firmware of µ8 (chapter 3.3): sensors, LCD and LEDs, dead man's switch.
//
// 0x80 → 0x81: stores led⁰, led¹ and the eight LCD characters, feeds the dead man's switch, and
// answers with the ADC readings sampled at the request's arrival (sensor_adc.hpp: yaw, acc¹⁻³,
// one tilt channel, vcc; Gaussian noise, then rounding to 0..1023). The tilt channel alternates
// with every 0x81: front (j = 0) first, then rear (j = 1), and so on.
// 0x82 → 0x83: sets dog (0 disables). Arming a disabled switch restarts its timer, so that a
// driver configuring dog before its first 0x80 is not stopped at once.
// Dead man's switch: Timer 1 at 16 MHz/64 overflows every 65536·64/16 MHz = 0.262144 s; dog
// overflows after the last 0x80 (or the arming) µ8 sends pwm = 0 to µ0–µ7 itself: eight control
// requests 0xi0 with drv = 0, eim = 1, pwm = 0, ready at exactly last + dog·0.262144 s, and again
// every 0.262144 s (each overflow) while the silence lasts, so that a stop frame the bus lost
// reaches its motor one overflow later. The next 0x80 ends the silence.
// Frames µ8 cannot use (other nodes, responses, codec rejections) are ignored without answer.
// The LCD shows the 8 characters and the supply voltage; with no 0x80 for a second (the bus
// inactive) it shows the firmware's idle text, as the photograph of Figure 3.7 describes.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "core/protocol/can_frame.hpp"
#include "core/protocol/messages.hpp"
#include "sim/electrics/seeded_random.hpp"
#include "sim/electrics/sim_truth.hpp"
#include "sim/firmware/sensor_adc.hpp"
#include "sim/firmware/sim_time.hpp"

namespace marsokhod::sim {

inline constexpr SimTimeNs kDeadManPeriodNs = protocol::kDeadManTickUs * 1000;
inline constexpr SimTimeNs kLcdIdleAfterNs = kNanosecondsPerSecond;
inline constexpr const char* kLcdIdleText = "Pleasure in the job puts perfection in the work.";

// What µ8's sensors are exposed to at one instant; the physics' ImuTruth plus the supply voltage.
struct SensorTruthSample {
  std::array<double, 3> accel_mps2{0.0, 0.0, -9.81};  // what (3.5) returns: gravity − accel.
  double yaw_rate_radps = 0.0;
  double front_tilt_rad = 0.0;  // θf
  double rear_tilt_rad = 0.0;   // θr
  double supply_v = 24.0;       // U
};

class SensorController {
 public:
  SensorController(const SensorTruth& truth, std::uint64_t seed,
                   const SensorTruthSample& initial = {});

  // The sensors' state at time_ns (the potentiometers move through their backlash here).
  void advance(SimTimeNs time_ns, const SensorTruthSample& sample);
  // A frame delivered at the time of the last advance(): the response, if µ8 answers.
  std::optional<protocol::CanFrame> receive(const protocol::CanFrame& frame);

  // When the dead man's next stop frames are due, if the switch is armed.
  std::optional<SimTimeNs> dead_man_deadline_ns() const;
  // The eight stop frames (µ0 … µ7); the next are due one overflow later.
  std::array<protocol::CanFrame, 8> fire_dead_man();

  // The readings µ8 would send now (advances the noise and the tilt channel like a response).
  protocol::MeasurementResponse measure();

  std::uint8_t dog() const { return dog_; }
  bool green_led() const { return led0_; }
  bool white_led() const { return led1_; }
  const std::array<char, 8>& lcd_characters() const { return lcd_; }
  // The 16 characters on the display: the text and the supply voltage, or the idle text.
  std::string lcd_display() const;
  // Silences the switch ended with stop frames, and the times it sent them (repeats included).
  std::uint64_t dead_man_stops() const { return dead_man_stops_; }
  std::uint64_t dead_man_firings() const { return dead_man_firings_; }
  const std::optional<protocol::MeasurementResponse>& last_measurement() const {
    return last_measurement_;
  }

 private:
  SensorTruth truth_;
  SeededRandom random_;
  SensorTruthSample sample_;
  PotentiometerBacklash front_pot_;
  PotentiometerBacklash rear_pot_;
  SimTimeNs time_ns_ = 0;
  protocol::TiltChannel next_channel_ = protocol::TiltChannel::kFront;
  std::optional<protocol::MeasurementResponse> last_measurement_;
  bool led0_ = false;
  bool led1_ = false;
  std::array<char, 8> lcd_{' ', ' ', ' ', ' ', ' ', ' ', ' ', ' '};
  std::optional<SimTimeNs> last_request_ns_;
  std::uint8_t dog_ = 0;
  SimTimeNs dead_man_start_ns_ = 0;
  std::uint32_t dead_man_overflows_ = 0;  // stop frames sent since dead_man_start_ns_
  std::uint64_t dead_man_stops_ = 0;
  std::uint64_t dead_man_firings_ = 0;
};

}  // namespace marsokhod::sim
