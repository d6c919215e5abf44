// Decoding side of the codec: validates a frame against the chapter 3.2–3.3 tables and docs/design.md's
// bit layouts, and says in words what was wrong. The success path allocates nothing.
#include <optional>
#include <string>
#include <utility>

#include "core/protocol/codec.hpp"
#include "core/protocol/wire.hpp"

namespace marsokhod::protocol {
namespace {

using wire::read_u16;

std::string hex(std::uint32_t value, int min_digits) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  int digits = min_digits;
  while (digits < 8 && (value >> (4 * digits)) != 0) {
    ++digits;
  }
  std::string text = "0x";
  for (int i = digits - 1; i >= 0; --i) {
    text += kDigits[(value >> (4 * i)) & 0xFU];
  }
  return text;
}

std::string number(unsigned value) { return std::to_string(value); }

// "0x188 (idt 0x31)"; the idt only where the identifier has one.
std::string frame_label(const CanFrame& frame) {
  std::string label = hex(frame.id, 3);
  if (frame.id <= kMaxCanId && (frame.id & 7U) == 0) {
    label += " (idt " + hex(frame.id >> 3, 2) + ")";
  }
  return label;
}

// "control response (0xi1)"
std::string kind(std::uint8_t node, std::uint8_t type) {
  const std::size_t index = wire::message_index(node, type);
  return std::string(wire::kNames[index]) + " (" + wire::kIdtPatterns[index] + ")";
}

DecodeResult reject(DecodeErrorCode code, const CanFrame& frame, const std::string& what) {
  return DecodeError{code, frame_label(frame) + ": " + what};
}

DecodeResult decode_control_request(const CanFrame& frame, std::uint8_t node,
                                    const DecodeContext& context) {
  const std::uint8_t flags = frame.data[MK_CONTROL_REQUEST_FLAGS];
  if ((flags & wire::kControlReservedBits) != 0) {
    return reject(DecodeErrorCode::kReservedBitsSet, frame,
                  "reserved bits 7..2 of byte 0 are " + hex(flags & wire::kControlReservedBits, 2) +
                      ", expected 0 in a " + kind(node, kControlRequestType) +
                      ", whose byte 0 holds only drv (bit 0) and eim (bit 1)");
  }
  const std::uint16_t pwm = read_u16(frame.data, MK_CONTROL_REQUEST_PWM);
  const std::uint16_t icr = context.icr[node];
  if (pwm > icr) {
    return reject(DecodeErrorCode::kPwmAboveIcr, frame,
                  "pwm " + number(pwm) + " exceeds icr " + number(icr) + " of µ" + number(node) +
                      ", expected pwm ≤ icr (|d| ≤ 1) in a " + kind(node, kControlRequestType));
  }
  return Message{ControlRequest{.node = node,
                                .drv = (flags & wire::kDrvBit) != 0,
                                .eim = (flags & wire::kEimBit) != 0,
                                .pwm = pwm}};
}

DecodeResult decode_control_response(const CanFrame& frame, std::uint8_t node) {
  const auto vel = static_cast<std::uint16_t>(((frame.data[MK_CONTROL_RESPONSE_DIR_VEL] & wire::kVelHighBits) << 8) |
                                              frame.data[MK_CONTROL_RESPONSE_VEL_LOW]);
  return Message{ControlResponse{.node = node,
                                 .tim = read_u16(frame.data, MK_CONTROL_RESPONSE_TIM),
                                 .enc = read_u16(frame.data, MK_CONTROL_RESPONSE_ENC),
                                 .stp = read_u16(frame.data, MK_CONTROL_RESPONSE_STP),
                                 .dir = (frame.data[MK_CONTROL_RESPONSE_DIR_VEL] & wire::kDirBit) != 0,
                                 .vel = vel}};
}

DecodeResult decode_configuration_request(const CanFrame& frame, std::uint8_t node) {
  const std::uint16_t icr = read_u16(frame.data, MK_CONFIGURATION_REQUEST_ICR);
  const std::uint16_t pwm = read_u16(frame.data, MK_CONFIGURATION_REQUEST_PWM);
  if (icr < kMinIcr || icr > kMaxIcr) {
    return reject(DecodeErrorCode::kIcrOutOfRange, frame,
                  "icr " + number(icr) + " is outside " + number(kMinIcr) + ".." +
                      number(kMaxIcr) + " in a " + kind(node, kConfigurationRequestType));
  }
  if (pwm > icr) {
    return reject(DecodeErrorCode::kPwmAboveIcr, frame,
                  "pwm " + number(pwm) + " exceeds icr " + number(icr) +
                      " of the same request, expected pwm ≤ icr (|d| ≤ 1) in a " +
                      kind(node, kConfigurationRequestType));
  }
  return Message{ConfigurationRequest{.node = node, .icr = icr, .pwm = pwm, .con = frame.data[MK_CONFIGURATION_REQUEST_CON]}};
}

DecodeResult decode_measurement_request(const CanFrame& frame) {
  MeasurementRequest message;
  message.led0 = (frame.data[0] & wire::kLedBit) != 0;
  message.led1 = (frame.data[1] & wire::kLedBit) != 0;
  for (std::size_t i = 0; i < message.lcd.size(); ++i) {
    const bool has_led = i < 2;
    const unsigned character = has_led ? (frame.data[i] & wire::kAsciiBits) : frame.data[i];
    if (character < kMinLcdChar || character > kMaxLcdChar) {
      return reject(DecodeErrorCode::kNonAsciiLcd, frame,
                    "LCD character " + number(static_cast<unsigned>(i)) +
                        (has_led ? " (low 7 bits of byte " : " (byte ") +
                        number(static_cast<unsigned>(i)) + ") is " + hex(character, 2) +
                        ", expected ASCII 32..127 in a " +
                        kind(kSensorController, kMeasurementRequestType));
    }
    message.lcd[i] = static_cast<char>(character);
  }
  return Message{message};
}

std::uint16_t reading(const CanFrame& frame, std::size_t high_byte, std::uint8_t low_bits) {
  return static_cast<std::uint16_t>((frame.data[high_byte] << 2) | (low_bits & 3U));
}

DecodeResult decode_measurement_response(const CanFrame& frame) {
  const std::uint8_t b6 = frame.data[MK_MEASUREMENT_LOW_BITS_1];
  const std::uint8_t b7 = frame.data[MK_MEASUREMENT_LOW_BITS_2];
  if ((b7 & wire::kStatusReservedBits) != 0) {
    return reject(DecodeErrorCode::kReservedBitsSet, frame,
                  "reserved bits 3..1 of b7 are " + hex(b7 & wire::kStatusReservedBits, 2) +
                      ", expected 0 in a " + kind(kSensorController, kMeasurementResponseType) +
                      ", whose b7 holds tlt (bits 7–6), vcc (bits 5–4) and j (bit 0)");
  }
  MeasurementResponse message;
  message.yaw = reading(frame, 0, static_cast<std::uint8_t>(b6 >> 6));
  message.acc[0] = reading(frame, 1, static_cast<std::uint8_t>(b6 >> 4));
  message.acc[1] = reading(frame, 2, static_cast<std::uint8_t>(b6 >> 2));
  message.acc[2] = reading(frame, 3, b6);
  message.tlt = reading(frame, 4, static_cast<std::uint8_t>(b7 >> 6));
  message.vcc = reading(frame, 5, static_cast<std::uint8_t>(b7 >> 4));
  message.tilt_channel =
      (b7 & wire::kTiltChannelBit) != 0 ? TiltChannel::kRear : TiltChannel::kFront;
  return Message{message};
}

// Identifier, node, type and DLC: everything the message layout does not decide.
std::optional<DecodeError> check_header(const CanFrame& frame) {
  const std::uint32_t idt = frame.id >> 3;
  const auto node = static_cast<std::uint8_t>((idt >> 4) & 0xFU);
  const auto type = static_cast<std::uint8_t>(idt & 0xFU);
  const auto error = [&frame](DecodeErrorCode code, const std::string& what) {
    return DecodeError{code, frame_label(frame) + ": " + what};
  };
  if (frame.id > kMaxCanId) {
    return error(DecodeErrorCode::kIdOutOfRange,
                 "identifier exceeds " + hex(kMaxCanId, 3) +
                     ", the largest 11-bit standard identifier");
  }
  if ((frame.id & 7U) != 0) {
    return error(DecodeErrorCode::kIdLowBitsSet,
                 "lowest 3 identifier bits are " + number(frame.id & 7U) +
                     ", expected 0 (idt fills the 8 highest bits, CAN ID = idt << 3)");
  }
  if (node > kSensorController) {
    return error(DecodeErrorCode::kNodeOutOfRange,
                 "node " + number(node) + " does not exist, expected 0..8 (µ0–µ8)");
  }
  if (type > 3) {
    return error(DecodeErrorCode::kUnknownType,
                 "type " + number(type) + " is unknown for µ" + number(node) + ", expected idt " +
                     hex(node << 4U, 2) + ".." + hex((node << 4U) | 3U, 2));
  }
  const std::uint8_t expected = wire::kDlc[wire::message_index(node, type)];
  if (frame.dlc != expected) {
    return error(DecodeErrorCode::kWrongDlc, "DLC " + number(frame.dlc) + ", expected " +
                                                 number(expected) + " for a " + kind(node, type));
  }
  return std::nullopt;
}

}  // namespace

const char* error_code_name(DecodeErrorCode code) {
  switch (code) {
    case DecodeErrorCode::kIdOutOfRange: return "id_out_of_range";
    case DecodeErrorCode::kIdLowBitsSet: return "id_low_bits_set";
    case DecodeErrorCode::kNodeOutOfRange: return "node_out_of_range";
    case DecodeErrorCode::kUnknownType: return "unknown_type";
    case DecodeErrorCode::kWrongDlc: return "wrong_dlc";
    case DecodeErrorCode::kPwmAboveIcr: return "pwm_above_icr";
    case DecodeErrorCode::kIcrOutOfRange: return "icr_out_of_range";
    case DecodeErrorCode::kNonAsciiLcd: return "non_ascii_lcd";
    case DecodeErrorCode::kReservedBitsSet: return "reserved_bits_set";
  }
  return "unknown";
}

DecodeResult decode(const CanFrame& frame, const DecodeContext& context) {
  if (auto error = check_header(frame)) {
    return std::move(*error);
  }
  const auto node = static_cast<std::uint8_t>(frame.id >> 7);
  const auto type = static_cast<std::uint8_t>((frame.id >> 3) & 0xFU);
  switch (wire::message_index(node, type)) {
    case 0: return decode_control_request(frame, node, context);
    case 1: return decode_control_response(frame, node);
    case 2: return decode_configuration_request(frame, node);
    case 3: return Message{ConfigurationResponse{.node = node, .tim = read_u16(frame.data, MK_CONFIGURATION_RESPONSE_TIM)}};
    case 4: return decode_measurement_request(frame);
    case 5: return decode_measurement_response(frame);
    case 6: return Message{DeadManRequest{.dog = frame.data[MK_DEAD_MAN_REQUEST_DOG]}};
    default: return Message{DeadManResponse{}};
  }
}

}  // namespace marsokhod::protocol
