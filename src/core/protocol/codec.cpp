// Encoding side of the codec and the message helpers (chapter 3.2–3.3 tables).
#include "core/protocol/codec.hpp"

#include <stdexcept>
#include <string>

#include "core/protocol/wire.hpp"

namespace marsokhod::protocol {
namespace {

using wire::write_u16;

// "encode control response: vel = 40000 is out of range, allowed 0..32767 (15 bits)"
[[noreturn]] void throw_out_of_range(const char* message, const std::string& field, long value,
                                     long min, long max, const char* why) {
  std::string text = std::string("encode ") + message + ": " + field + " = " +
                     std::to_string(value) + " is out of range, allowed " + std::to_string(min) +
                     ".." + std::to_string(max);
  if (why != nullptr) {
    text += std::string(" (") + why + ")";
  }
  throw std::invalid_argument(text);
}

// Inline and string-free on the success path: encode runs 18 times per control cycle.
inline void check_range(const char* message, const char* field, long value, long min, long max,
                        const char* why = nullptr) {
  if (value < min || value > max) {
    throw_out_of_range(message, field, value, min, max, why);
  }
}

void check_motor_node(const char* message, std::uint8_t node) {
  check_range(message, "node", node, 0, kMotorControllerCount - 1, "µ0–µ7 drive the motors");
}

CanFrame frame_for(std::uint8_t node, std::uint8_t type) {
  CanFrame frame;
  frame.id = can_id(node, type);
  frame.dlc = wire::kDlc[wire::message_index(node, type)];
  return frame;
}

void check_adc(const char* field, std::uint16_t reading) {
  check_range("measurement response", field, reading, 0, kMaxAdc, "10-bit ADC");
}

}  // namespace

std::uint8_t node_of(const Message& message) {
  return std::visit(
      [](const auto& m) -> std::uint8_t {
        if constexpr (requires { m.node; }) {
          return m.node;
        } else {
          return kSensorController;
        }
      },
      message);
}

std::uint8_t type_of(const Message& message) {
  return static_cast<std::uint8_t>(message.index() % 4);
}

const char* message_name(const Message& message) { return wire::kNames[message.index()]; }

// 0xi0: byte 0 bit0 drv, bit1 eim; bytes 1–2 pwm.
CanFrame encode(const ControlRequest& message) {
  const char* name = "control request";
  check_motor_node(name, message.node);
  check_range(name, "pwm", message.pwm, 0, kMaxIcr, "pwm ≤ icr ≤ 2047");
  CanFrame frame = frame_for(message.node, kControlRequestType);
  frame.data[MK_CONTROL_REQUEST_FLAGS] = static_cast<std::uint8_t>((message.drv ? wire::kDrvBit : 0U) |
                                            (message.eim ? wire::kEimBit : 0U));
  write_u16(frame.data, MK_CONTROL_REQUEST_PWM, message.pwm);
  return frame;
}

// 0xi1: tim, enc, stp; byte 6 = dir | vel_h (7 bits); byte 7 = vel_l.
CanFrame encode(const ControlResponse& message) {
  const char* name = "control response";
  check_motor_node(name, message.node);
  check_range(name, "vel", message.vel, 0, kMaxVel, "15 bits");
  CanFrame frame = frame_for(message.node, kControlResponseType);
  write_u16(frame.data, MK_CONTROL_RESPONSE_TIM, message.tim);
  write_u16(frame.data, MK_CONTROL_RESPONSE_ENC, message.enc);
  write_u16(frame.data, MK_CONTROL_RESPONSE_STP, message.stp);
  frame.data[MK_CONTROL_RESPONSE_DIR_VEL] = static_cast<std::uint8_t>((message.dir ? wire::kDirBit : 0U) |
                                            ((message.vel >> 8) & wire::kVelHighBits));
  frame.data[MK_CONTROL_RESPONSE_VEL_LOW] = static_cast<std::uint8_t>(message.vel & 0xFF);
  return frame;
}

// 0xi2: icr, pwm, con.
CanFrame encode(const ConfigurationRequest& message) {
  const char* name = "configuration request";
  check_motor_node(name, message.node);
  check_range(name, "icr", message.icr, kMinIcr, kMaxIcr);
  check_range(name, "pwm", message.pwm, 0, message.icr, "pwm ≤ icr of the same request");
  CanFrame frame = frame_for(message.node, kConfigurationRequestType);
  write_u16(frame.data, MK_CONFIGURATION_REQUEST_ICR, message.icr);
  write_u16(frame.data, MK_CONFIGURATION_REQUEST_PWM, message.pwm);
  frame.data[MK_CONFIGURATION_REQUEST_CON] = message.con;
  return frame;
}

// 0xi3: tim.
CanFrame encode(const ConfigurationResponse& message) {
  check_motor_node("configuration response", message.node);
  CanFrame frame = frame_for(message.node, kConfigurationResponseType);
  write_u16(frame.data, MK_CONFIGURATION_RESPONSE_TIM, message.tim);
  return frame;
}

// 0x80: bytes 0–1 led | 7-bit ASCII, bytes 2–7 ASCII.
CanFrame encode(const MeasurementRequest& message) {
  CanFrame frame = frame_for(kSensorController, kMeasurementRequestType);
  for (std::size_t i = 0; i < message.lcd.size(); ++i) {
    const auto character = static_cast<unsigned char>(message.lcd[i]);
    if (character < kMinLcdChar || character > kMaxLcdChar) {
      throw_out_of_range("measurement request", "lcd[" + std::to_string(i) + "]", character,
                         kMinLcdChar, kMaxLcdChar, "ASCII");
    }
    frame.data[i] = character;
  }
  frame.data[0] = static_cast<std::uint8_t>(frame.data[0] | (message.led0 ? wire::kLedBit : 0U));
  frame.data[1] = static_cast<std::uint8_t>(frame.data[1] | (message.led1 ? wire::kLedBit : 0U));
  return frame;
}

// 0x81: high 8 bits in bytes 0–5; b6 = yaw, acc¹, acc², acc³ low bits from bit 7 down;
// b7 = tlt low bits 7–6, vcc low bits 5–4, j in bit 0.
CanFrame encode(const MeasurementResponse& message) {
  check_adc("yaw", message.yaw);
  check_adc("acc[0]", message.acc[0]);
  check_adc("acc[1]", message.acc[1]);
  check_adc("acc[2]", message.acc[2]);
  check_adc("tlt", message.tlt);
  check_adc("vcc", message.vcc);
  const auto channel = static_cast<std::uint8_t>(message.tilt_channel);
  check_range("measurement response", "tilt_channel", channel, 0, 1, "0 front, 1 rear");

  const std::array<std::uint16_t, 6> readings{message.yaw,    message.acc[0], message.acc[1],
                                              message.acc[2], message.tlt,    message.vcc};
  CanFrame frame = frame_for(kSensorController, kMeasurementResponseType);
  for (std::size_t i = 0; i < readings.size(); ++i) {
    frame.data[i] = static_cast<std::uint8_t>(readings[i] >> 2);
  }
  frame.data[MK_MEASUREMENT_LOW_BITS_1] = static_cast<std::uint8_t>(((readings[0] & 3U) << 6) | ((readings[1] & 3U) << 4) |
                                            ((readings[2] & 3U) << 2) | (readings[3] & 3U));
  frame.data[MK_MEASUREMENT_LOW_BITS_2] = static_cast<std::uint8_t>(((readings[4] & 3U) << 6) | ((readings[5] & 3U) << 4) |
                                            channel);
  return frame;
}

// 0x82: dog.
CanFrame encode(const DeadManRequest& message) {
  CanFrame frame = frame_for(kSensorController, kDeadManRequestType);
  frame.data[MK_DEAD_MAN_REQUEST_DOG] = message.dog;
  return frame;
}

// 0x83: no data.
CanFrame encode(const DeadManResponse& /*message*/) {
  return frame_for(kSensorController, kDeadManResponseType);
}

CanFrame encode(const Message& message) {
  return std::visit([](const auto& m) { return encode(m); }, message);
}

}  // namespace marsokhod::protocol
