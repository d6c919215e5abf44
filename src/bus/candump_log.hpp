// The candump log format of can-utils (`candump -L`), one frame a line:
//   (1436509052.249713) can0 180#03012C
// Classic CAN only: a 3-hex-digit standard or 8-hex-digit extended identifier, '#', 0–8 data
// bytes as hex pairs; `R` after '#' marks a remote frame. CAN FD ("##") is not ours and rejected.
// A trailing direction flag, " R" or " T" (python-can's CanutilsLogWriter writes one), is accepted
// and not kept.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "core/protocol/can_frame.hpp"

namespace marsokhod::bus {

struct LoggedFrame {
  std::string timestamp;  // as written, e.g. "1436509052.249713" (kept exact for replay)
  double time_s = 0.0;
  std::string interface;  // e.g. "can0"
  protocol::CanFrame frame;
  bool extended = false;  // 29-bit identifier (never ours)
  bool remote = false;    // remote transmission request (never ours)
};

struct LogParseError {
  std::string reason;
};

// Parses one line; blank lines and lines starting with '#' are not frames (std::monostate).
std::variant<std::monostate, LoggedFrame, LogParseError> parse_candump_line(std::string_view line);

// Formats a frame as one candump log line (the inverse of parse_candump_line).
std::string format_candump_line(const LoggedFrame& logged);

}  // namespace marsokhod::bus
