// Byte-exact CAN codec of the controllers µ0–µ8 (chapter 3.2–3.3; bit layouts fixed in docs/design.md).
//
// idt = 0xiT: node i in the high nibble, type T in the low one, placed in the 8 highest bits of
// the 11-bit identifier (chapter 3, "the lowest 3 bits are always zero"). Multi-byte fields are
// big-endian because the thesis' tables list the _h byte before the _l byte.
//
//   type  µ0–µ7 (0xi0..0xi3)            DLC   µ8 (0x80..0x83)            DLC
//   0     ControlRequest                3     MeasurementRequest         8
//   1     ControlResponse               8     MeasurementResponse        8
//   2     ConfigurationRequest          5     DeadManRequest             1
//   3     ConfigurationResponse         2     DeadManResponse            0
//
// encode() throws std::invalid_argument for a field the wire cannot carry or the controller must
// not receive; decode() never throws and says in DecodeError::reason what was wrong.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

#include "core/protocol/can_frame.hpp"
#include "core/protocol/messages.hpp"
#include "core/protocol/wire_layout.h"

namespace marsokhod::protocol {

inline constexpr std::uint8_t kMotorControllerCount = MK_MOTOR_CONTROLLER_COUNT;// µ0–µ7
inline constexpr std::uint8_t kSensorController = MK_SENSOR_NODE;// µ8
inline constexpr std::uint32_t kMaxCanId = MK_MAX_CAN_ID;// 11-bit standard identifier
inline constexpr std::uint16_t kMinIcr = MK_ICR_MIN;// chapter 3.2 input table
inline constexpr std::uint16_t kMaxIcr = MK_ICR_MAX;
inline constexpr std::uint16_t kMaxVel = MK_VEL_MAX;// 15 bit
inline constexpr std::uint16_t kMaxAdc = MK_ADC_MAX;// 10-bit ADC of µ8
inline constexpr int kMinLcdChar = MK_LCD_CHAR_MIN;// chapter 3.3: lcdⁱ in 32..127
inline constexpr int kMaxLcdChar = MK_LCD_CHAR_MAX;

// The type nibble T of idt. µ8's types share the numbers 0..3 with the motor controllers'.
inline constexpr std::uint8_t kControlRequestType = MK_TYPE_CONTROL_REQUEST;
inline constexpr std::uint8_t kControlResponseType = MK_TYPE_CONTROL_RESPONSE;
inline constexpr std::uint8_t kConfigurationRequestType = MK_TYPE_CONFIGURATION_REQUEST;
inline constexpr std::uint8_t kConfigurationResponseType = MK_TYPE_CONFIGURATION_RESPONSE;
inline constexpr std::uint8_t kMeasurementRequestType = MK_TYPE_MEASUREMENT_REQUEST;
inline constexpr std::uint8_t kMeasurementResponseType = MK_TYPE_MEASUREMENT_RESPONSE;
inline constexpr std::uint8_t kDeadManRequestType = MK_TYPE_DEAD_MAN_REQUEST;
inline constexpr std::uint8_t kDeadManResponseType = MK_TYPE_DEAD_MAN_RESPONSE;

// CAN ID = idt << 3 with idt = (node << 4) | type: µ3's control request → 0x180, µ8's
// measurement request (idt 0x80) → 0x400. Both arguments must fit a nibble.
constexpr std::uint32_t can_id(std::uint8_t node, std::uint8_t type) {
  if (node > 0xF || type > 0xF) {
    throw std::invalid_argument("can_id: node and type must each fit 4 bits (0..15)");
  }
  return ((static_cast<std::uint32_t>(node) << 4) | type) << 3;
}

// The controller a message is addressed to or comes from: µ8's messages → 8.
std::uint8_t node_of(const Message& message);
// The type nibble T of the message's idt.
std::uint8_t type_of(const Message& message);
// "control request", "measurement response", …: for logs and the decode command.
const char* message_name(const Message& message);

// Throws std::invalid_argument naming the field, its value and the allowed range when a field
// is out of range: node > 7, vel > 0x7FFF, ADC reading > 1023, LCD character outside 32..127,
// icr outside 255..2047, pwm > icr (configuration request) or pwm > 2047 (control request: the
// largest legal icr; the codec does not know the controller's configured icr).
CanFrame encode(const ControlRequest& message);
CanFrame encode(const ControlResponse& message);
CanFrame encode(const ConfigurationRequest& message);
CanFrame encode(const ConfigurationResponse& message);
CanFrame encode(const MeasurementRequest& message);
CanFrame encode(const MeasurementResponse& message);
CanFrame encode(const DeadManRequest& message);
CanFrame encode(const DeadManResponse& message);
CanFrame encode(const Message& message);

// What the decoder knows about the bus beyond a single frame: the icr each motor controller was
// configured with, so that a control request with pwm > icr (|d| > 1) is rejected. The default is
// the largest legal icr, which accepts every pwm a controller could be configured to take.
struct DecodeContext {
  std::array<std::uint16_t, kMotorControllerCount> icr{kMaxIcr, kMaxIcr, kMaxIcr, kMaxIcr,
                                                       kMaxIcr, kMaxIcr, kMaxIcr, kMaxIcr};
};

enum class DecodeErrorCode : std::uint8_t {
  kIdOutOfRange,     // id > 0x7FF
  kIdLowBitsSet,     // the 3 lowest identifier bits are not zero
  kNodeOutOfRange,   // node 9..15
  kUnknownType,      // type 4..15
  kWrongDlc,         // DLC differs from the message's fixed length
  kPwmAboveIcr,      // |d| = pwm/icr > 1
  kIcrOutOfRange,    // icr outside 255..2047
  kNonAsciiLcd,      // LCD character outside 32..127
  kReservedBitsSet,  // a bit the layout leaves unused is set
};

// "id_out_of_range", "wrong_dlc", …: stable names for logs and JSON.
const char* error_code_name(DecodeErrorCode code);

struct DecodeError {
  DecodeErrorCode code = DecodeErrorCode::kIdOutOfRange;
  std::string reason;  // e.g. "0x188 (idt 0x31): DLC 7, expected 8 for a control response (0xi1)"
  friend bool operator==(const DecodeError&, const DecodeError&) = default;
};

// Either the decoded message or why the frame was rejected.
class DecodeResult {
 public:
  DecodeResult(Message message) : value_(std::move(message)) {}  // NOLINT: implicit by design
  DecodeResult(DecodeError error) : value_(std::move(error)) {}   // NOLINT: implicit by design

  bool ok() const { return value_.index() == 0; }
  explicit operator bool() const { return ok(); }
  // Precondition ok() (resp. !ok()); otherwise std::bad_variant_access.
  const Message& message() const { return std::get<Message>(value_); }
  const DecodeError& error() const { return std::get<DecodeError>(value_); }

 private:
  std::variant<Message, DecodeError> value_;
};

// Never throws (beyond std::bad_alloc for the reason string). Bytes beyond the DLC are ignored.
DecodeResult decode(const CanFrame& frame, const DecodeContext& context = {});

}  // namespace marsokhod::protocol
