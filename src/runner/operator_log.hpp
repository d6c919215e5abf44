// The operator's inputs and run-time settings as JSON, for operator.jsonl and scenario files.
// Numbers are written with nlohmann's shortest round-trip form, so replay gets the same doubles.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "driver/motion_controller.hpp"
#include "driver/operator_channel.hpp"

namespace marsokhod::runner {

nlohmann::json to_json(const driver::OperatorInput& input);
nlohmann::json to_json(const driver::RuntimeSettings& settings);

// Throw std::invalid_argument naming the field (e.g. "targets.gait: \"hop\" is not a gait").
driver::OperatorInput operator_input_from_json(const nlohmann::json& json);
driver::RuntimeSettings runtime_settings_from_json(const nlohmann::json& json,
                                                   driver::RuntimeSettings base);

// "rolking" ⇄ Gait::kRolking, with the names of docs/operator-protocol.md.
mobility::Gait gait_from_key(const std::string& key);  // throws std::invalid_argument

}  // namespace marsokhod::runner
