// A decoded CAN frame described for people and for JSON: every field by its thesis name with its
// raw register value, and the physical quantities the thesis' conversions give (chapter 3.2–3.3).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/params.hpp"
#include "core/protocol/codec.hpp"

namespace marsokhod::protocol {

struct RawField {
  std::string name;  // thesis name: "pwm", "enc", "acc1", "lcd"
  std::int64_t value = 0;
  std::string text;  // set instead of value for the LCD text
};

struct PhysicalField {
  std::string name;  // "d", "w", "U": the thesis' symbol for the quantity
  double value = 0.0;
  std::string unit;  // "" for dimensionless
  int decimals = 3;
  bool show_sign = false;
};

struct FrameDescription {
  std::uint8_t node = 0;
  std::string type;  // "control_request", …
  std::vector<RawField> raw;
  std::vector<PhysicalField> physical;
};

// What a trace tells about the controllers beyond one frame: the icr and con each µ0–µ7 was last
// configured with (0xi2), starting from the configuration file's values.
class BusContext {
 public:
  explicit BusContext(const Params& params);
  // Remembers a configuration request's icr and con; other messages change nothing.
  void observe(const Message& message);
  DecodeContext decode_context() const;
  int icr(std::uint8_t node) const { return icr_.at(node); }
  int con(std::uint8_t node) const { return con_.at(node); }
  const Params& params() const { return *params_; }

 private:
  const Params* params_;
  std::array<int, kMotorCount> icr_{};
  std::array<int, kMotorCount> con_{};
};

FrameDescription describe(const Message& message, const BusContext& context);

// "drv=1 eim=1 pwm=300 d=-0.587": raw fields, then physical ones with their units.
std::string format_text(const FrameDescription& description);

}  // namespace marsokhod::protocol
