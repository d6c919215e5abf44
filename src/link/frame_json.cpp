#include "link/frame_json.hpp"

namespace marsokhod::link {
namespace {

std::string unit_suffix(const std::string& unit) {
  if (unit == "rad/s") return "_radps";
  if (unit == "m/s^2") return "_mps2";
  if (unit == "kHz") return "_khz";
  if (unit == "V") return "_v";
  if (unit.empty()) return "";
  return "_" + unit;
}

}  // namespace

nlohmann::ordered_json frame_json(const bus::LoggedFrame& logged,
                                  const protocol::FrameDescription& d) {
  nlohmann::ordered_json j;
  j["time"] = logged.time_s;
  j["timestamp"] = logged.timestamp;
  j["interface"] = logged.interface;
  j["id"] = logged.frame.id;
  j["node"] = d.node;
  j["type"] = d.type;
  for (const protocol::RawField& f : d.raw) {
    if (f.name == "lcd") {
      j[f.name] = f.text;
    } else {
      j[f.name] = f.value;
    }
  }
  for (const protocol::PhysicalField& f : d.physical) j[f.name + unit_suffix(f.unit)] = f.value;
  return j;
}

}  // namespace marsokhod::link
