#include "bus/candump_log.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

namespace marsokhod::bus {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::optional<std::string> parse_timestamp(std::string_view field, LoggedFrame& out) {
  if (field.size() < 3 || field.front() != '(' || field.back() != ')') {
    return "expected a timestamp in parentheses, e.g. (1436509052.249713), got '" +
           std::string(field) + "'";
  }
  out.timestamp = std::string(field.substr(1, field.size() - 2));
  const char* begin = out.timestamp.data();
  const char* end = begin + out.timestamp.size();
  const auto [ptr, ec] = std::from_chars(begin, end, out.time_s);
  if (ec != std::errc() || ptr != end || !std::isfinite(out.time_s) || out.time_s < 0.0) {
    return "timestamp '" + out.timestamp + "' is not a finite, non-negative number of seconds";
  }
  return std::nullopt;
}

std::optional<std::string> parse_identifier(std::string_view id, LoggedFrame& out) {
  if (id.size() != 3 && id.size() != 8) {
    return "identifier '" + std::string(id) +
           "' must have 3 hex digits (standard) or 8 (extended)";
  }
  std::uint32_t value = 0;
  for (char c : id) {
    const int d = hex_digit(c);
    if (d < 0) return "identifier '" + std::string(id) + "' is not hexadecimal";
    value = value * 16 + static_cast<std::uint32_t>(d);
  }
  out.extended = id.size() == 8;
  if (!out.extended && value > 0x7FF) {
    return "standard identifier 0x" + std::string(id) + " exceeds 0x7FF";
  }
  if (out.extended && value > 0x1FFFFFFF) {
    return "extended identifier 0x" + std::string(id) + " exceeds 0x1FFFFFFF";
  }
  out.frame.id = value;
  return std::nullopt;
}

std::optional<std::string> parse_data(std::string_view data, LoggedFrame& out) {
  if (!data.empty() && data.front() == '#') return "CAN FD frames (##) are not supported";
  if (!data.empty() && (data.front() == 'R' || data.front() == 'r')) {
    out.remote = true;
    out.frame.dlc = 0;
    if (data.size() > 1) {
      const int d = hex_digit(data[1]);
      if (data.size() != 2 || d < 0 || d > 8) return "remote frame length '" + std::string(data) + "' is invalid";
      out.frame.dlc = static_cast<std::uint8_t>(d);
    }
    return std::nullopt;
  }
  if (data.size() % 2 != 0) return "data '" + std::string(data) + "' has an odd number of hex digits";
  if (data.size() > 16) {
    return "data has " + std::to_string(data.size() / 2) + " bytes; classic CAN carries at most 8";
  }
  for (std::size_t i = 0; i < data.size(); i += 2) {
    const int hi = hex_digit(data[i]);
    const int lo = hex_digit(data[i + 1]);
    if (hi < 0 || lo < 0) return "data '" + std::string(data) + "' is not hexadecimal";
    out.frame.data[i / 2] = static_cast<std::uint8_t>(hi * 16 + lo);
  }
  out.frame.dlc = static_cast<std::uint8_t>(data.size() / 2);
  return std::nullopt;
}

}  // namespace

std::variant<std::monostate, LoggedFrame, LogParseError> parse_candump_line(std::string_view line) {
  line = trim(line);
  if (line.empty() || line.front() == '#') return std::monostate{};
  const auto space1 = line.find(' ');
  if (space1 == std::string_view::npos) return LogParseError{"expected '(time) interface ID#DATA'"};
  const std::string_view rest = trim(line.substr(space1 + 1));
  const auto space2 = rest.find(' ');
  if (space2 == std::string_view::npos) return LogParseError{"expected '(time) interface ID#DATA'"};
  LoggedFrame out;
  if (auto e = parse_timestamp(line.substr(0, space1), out)) return LogParseError{*e};
  out.interface = std::string(rest.substr(0, space2));
  std::string_view frame = trim(rest.substr(space2 + 1));
  // python-can's CanutilsLogWriter appends the direction, " R" (received) or " T" (sent).
  if (const auto space3 = frame.find(' '); space3 != std::string_view::npos) {
    const std::string_view direction = trim(frame.substr(space3 + 1));
    if (direction != "R" && direction != "T" && direction != "r" && direction != "t") {
      return LogParseError{"unexpected '" + std::string(direction) +
                           "' after the frame; only a direction R or T may follow it"};
    }
    frame = frame.substr(0, space3);
  }
  const auto hash = frame.find('#');
  if (hash == std::string_view::npos) {
    return LogParseError{"frame '" + std::string(frame) + "' has no '#' between identifier and data"};
  }
  if (auto e = parse_identifier(frame.substr(0, hash), out)) return LogParseError{*e};
  if (auto e = parse_data(frame.substr(hash + 1), out)) return LogParseError{*e};
  return out;
}

std::string format_candump_line(const LoggedFrame& logged) {
  char id[16];
  if (logged.extended) {
    std::snprintf(id, sizeof id, "%08X", static_cast<unsigned>(logged.frame.id));
  } else {
    std::snprintf(id, sizeof id, "%03X", static_cast<unsigned>(logged.frame.id));
  }
  std::string line = "(" + logged.timestamp + ") " + logged.interface + " " + id + "#";
  // can-utils writes a remote frame's length after the R ("123#R6") when it is not 0; the parser
  // reads it, so dropping it would change the frame (the candump fuzzer found this).
  if (logged.remote) {
    return line + "R" + (logged.frame.dlc > 0 ? std::to_string(logged.frame.dlc) : "");
  }
  static constexpr char kHex[] = "0123456789ABCDEF";
  for (std::size_t i = 0; i < logged.frame.dlc && i < 8; ++i) {
    line += kHex[logged.frame.data[i] >> 4];
    line += kHex[logged.frame.data[i] & 0xF];
  }
  return line;
}

}  // namespace marsokhod::bus
