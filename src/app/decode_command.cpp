#include "app/decode_command.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <istream>
#include <ostream>

#include "bus/candump_log.hpp"
#include "core/protocol/codec.hpp"
#include "core/protocol/frame_description.hpp"
#include "link/frame_json.hpp"

namespace marsokhod::app {
namespace {

std::string text_line(const bus::LoggedFrame& logged, const protocol::FrameDescription& d) {
  char id[8];
  std::snprintf(id, sizeof id, "%03X", static_cast<unsigned>(logged.frame.id));
  std::string fields = protocol::format_text(d);
  return logged.timestamp + " " + logged.interface + " " + id + " µ" + std::to_string(d.node) +
         " " + d.type + (fields.empty() ? "" : " " + fields);
}

}  // namespace

int decode_trace(std::istream& in, const std::string& source, const Params& params,
                 const DecodeOptions& options, std::ostream& out, std::ostream& err) {
  protocol::BusContext context(params);
  std::string line;
  int line_number = 0;
  int invalid = 0;
  auto reject = [&](const std::string& reason) {
    err << source << ":" << line_number << ": " << reason << "\n";
    ++invalid;
  };
  while (std::getline(in, line)) {
    ++line_number;
    auto parsed = bus::parse_candump_line(line);
    if (const auto* e = std::get_if<bus::LogParseError>(&parsed)) {
      reject(e->reason);
      continue;
    }
    const auto* logged = std::get_if<bus::LoggedFrame>(&parsed);
    if (logged == nullptr) continue;  // blank or comment
    if (logged->extended || logged->remote) {
      reject(std::string(logged->extended ? "extended" : "remote") +
             " frame: the controllers µ0–µ8 use classic data frames with 11-bit identifiers");
      continue;
    }
    const protocol::DecodeResult result = protocol::decode(logged->frame, context.decode_context());
    if (!result.ok()) {
      reject(result.error().reason);
      continue;
    }
    context.observe(result.message());
    const protocol::FrameDescription d = protocol::describe(result.message(), context);
    if (options.json) {
      out << link::frame_json(*logged, d).dump() << "\n";
    } else {
      out << text_line(*logged, d) << "\n";
    }
  }
  return invalid == 0 ? 0 : 1;
}

}  // namespace marsokhod::app
