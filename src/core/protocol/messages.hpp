// Typed messages of the nine controllers (chapter 3.2–3.3; bit layouts fixed in docs/design.md).
// Raw register values live here and in the emulated firmware only; physical units are made in
// core/tracking. idt = 0xiT (i = node 0–8, T = type 0–3); CAN ID = idt << 3.
#pragma once

#include <array>
#include <cstdint>
#include <variant>

#include "core/protocol/wire_layout.h"

namespace marsokhod::protocol {

// 0xi0, 3 bytes, ReadyBoard → µi (i = 0..7). Also sent by µ8's dead man's switch with pwm = 0.
// byte 0: bit0 drv, bit1 eim; bytes 1–2: pwm (big-endian). d = (−1)^drv · pwm/icr.
struct ControlRequest {
  std::uint8_t node = 0;
  bool drv = false;  // desired direction: 0 forward-positive, 1 reversed
  bool eim = false;  // update stp on measured direction change
  std::uint16_t pwm = 0;
  friend bool operator==(const ControlRequest&, const ControlRequest&) = default;
};

// 0xi1, 8 bytes, µi → ReadyBoard. tim, enc, stp big-endian 16 bit; byte 6: bit7 dir, bits 6..0
// high 7 bits of the 15-bit vel; byte 7: low 8 bits of vel.
struct ControlResponse {
  std::uint8_t node = 0;
  std::uint16_t tim = 0;
  std::uint16_t enc = 0;
  std::uint16_t stp = 0;
  bool dir = false;
  std::uint16_t vel = 0;  // 15 bit: encoder pulses in the last period T(con)
  friend bool operator==(const ControlResponse&, const ControlResponse&) = default;
};

// 0xi2, 5 bytes: icr (16 bit), pwm (16 bit), con (8 bit). pwm ≤ icr.
struct ConfigurationRequest {
  std::uint8_t node = 0;
  std::uint16_t icr = 511;
  std::uint16_t pwm = 0;
  std::uint8_t con = 0;
  friend bool operator==(const ConfigurationRequest&, const ConfigurationRequest&) = default;
};

// 0xi3, 2 bytes: tim.
struct ConfigurationResponse {
  std::uint8_t node = 0;
  std::uint16_t tim = 0;
  friend bool operator==(const ConfigurationResponse&, const ConfigurationResponse&) = default;
};

// 0x80, 8 bytes, ReadyBoard → µ8. Bytes 0–1: bit7 led⁰/led¹, bits 6..0 ASCII; bytes 2–7 ASCII.
struct MeasurementRequest {
  bool led0 = false;  // green
  bool led1 = false;  // white
  std::array<char, 8> lcd{' ', ' ', ' ', ' ', ' ', ' ', ' ', ' '};  // ASCII 32..127
  friend bool operator==(const MeasurementRequest&, const MeasurementRequest&) = default;
};

enum class TiltChannel : std::uint8_t { kFront = 0, kRear = 1 };  // bit j of b7

// 0x81, 8 bytes, µ8 → ReadyBoard: 10-bit ADC readings split into high 8 bits (bytes 0–5) and low
// 2 bits (b6: yaw 7–6, acc1 5–4, acc2 3–2, acc3 1–0; b7: tlt 7–6, vcc 5–4, bit 0 = j).
struct MeasurementResponse {
  std::uint16_t yaw = 0;
  std::array<std::uint16_t, 3> acc{};  // acc¹, acc², acc³
  std::uint16_t tlt = 0;               // tltᶠ or tltʳ, see tilt_channel
  std::uint16_t vcc = 0;
  TiltChannel tilt_channel = TiltChannel::kFront;
  friend bool operator==(const MeasurementResponse&, const MeasurementResponse&) = default;
};

// 0x82, 1 byte: dog (0 disables; otherwise stop after 0.2621·dog s without a 0x80).
// µ8's unit of dog: Timer 1 at 16 MHz/64 overflows every 65536·64/16 MHz = 0.262144 s.
inline constexpr std::int64_t kDeadManTickUs = MK_DEAD_MAN_TICK_US;
struct DeadManRequest {
  std::uint8_t dog = 0;
  friend bool operator==(const DeadManRequest&, const DeadManRequest&) = default;
};

// 0x83, no data.
struct DeadManResponse {
  friend bool operator==(const DeadManResponse&, const DeadManResponse&) = default;
};

using Message = std::variant<ControlRequest, ControlResponse, ConfigurationRequest,
                             ConfigurationResponse, MeasurementRequest, MeasurementResponse,
                             DeadManRequest, DeadManResponse>;

}  // namespace marsokhod::protocol
