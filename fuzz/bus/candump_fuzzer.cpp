// libFuzzer target for the candump log parser (src/bus/candump_log.hpp), which reads traces from
// anywhere (`marsokhod decode`, recordings): any line parses to a frame, a non-frame or an error
// without crashing or throwing; an error says something; a frame has a finite, non-negative time
// and a DLC ≤ 8; and format_candump_line of it parses back to the same frame.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <variant>

#include "bus/candump_log.hpp"

namespace {

[[noreturn]] void fail(const char* what, std::size_t size) {
  std::fprintf(stderr, "bus_candump_fuzzer: %s for input of %zu bytes\n", what, size);
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace bus = marsokhod::bus;
  const std::string_view line(reinterpret_cast<const char*>(data), size);
  const auto parsed = bus::parse_candump_line(line);
  if (const auto* error = std::get_if<bus::LogParseError>(&parsed)) {
    if (error->reason.empty()) fail("an error without a reason", size);
    return 0;
  }
  const auto* logged = std::get_if<bus::LoggedFrame>(&parsed);
  if (logged == nullptr) return 0;
  if (!std::isfinite(logged->time_s) || logged->time_s < 0.0) fail("a bad time passed", size);
  if (logged->frame.dlc > 8) fail("a DLC above 8 passed", size);
  const auto again = bus::parse_candump_line(bus::format_candump_line(*logged));
  const auto* back = std::get_if<bus::LoggedFrame>(&again);
  if (back == nullptr || back->frame != logged->frame || back->extended != logged->extended ||
      back->remote != logged->remote || back->timestamp != logged->timestamp) {
    fail("the line did not survive format and parse", size);
  }
  return 0;
}
