// Shared by the calibration tests: the configuration they start from and the checks on a
// procedure's problems.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "config/load_params.hpp"
#include "core/params.hpp"

namespace marsokhod::calibration::testing {

inline constexpr const char* kConfigFile = MARSOKHOD_SOURCE_DIR "/config/marsokhod.toml";

// config/marsokhod.toml as loaded, without a calibration file.
inline Params config() { return config::load_params(kConfigFile); }

// The first problem, for an assertion's message.
inline std::string first(const std::vector<std::string>& problems) {
  return problems.empty() ? "(no problem)" : problems.front();
}

// Whether a problem says `text`.
inline bool mentions(const std::vector<std::string>& problems, const std::string& text) {
  return std::any_of(problems.begin(), problems.end(),
                     [&](const std::string& p) { return p.find(text) != std::string::npos; });
}

}  // namespace marsokhod::calibration::testing
