// One CAN frame decoded as JSON: `marsokhod decode --json`'s line and the recordings' /can/decoded
// messages (recording.mcap) share it. Keys: time, timestamp, interface, id, node, type, every raw
// field by its thesis name, the physical values with their unit in the key (d, w_radps, U_v, …).
#pragma once

#include <nlohmann/json.hpp>

#include "bus/candump_log.hpp"
#include "core/protocol/frame_description.hpp"

namespace marsokhod::link {

nlohmann::ordered_json frame_json(const bus::LoggedFrame& logged,
                                  const protocol::FrameDescription& description);

}  // namespace marsokhod::link
