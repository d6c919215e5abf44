// Reading config/marsokhod.toml into the const Configuration (the rover's Params and the
// console's settings), validated once by the parameter schema (param_schema.hpp). A missing key, a
// wrong type, an out-of-range value, an unknown key or an inconsistent pair of values is a
// ConfigError that lists every problem, each naming the key, the value and what is allowed, with
// FILE:LINE where the file gives one.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "config/configuration.hpp"
#include "core/params.hpp"

namespace marsokhod::config {

class ConfigError : public std::runtime_error {
 public:
  ConfigError(const std::string& source, std::vector<std::string> problems);
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  std::vector<std::string> problems_;
};

// Parses TOML text; `source` names it in messages (a file name, or "<string>").
Configuration parse_configuration(std::string_view toml_text,
                                  const std::string& source = "<string>");
Params parse_params(std::string_view toml_text, const std::string& source = "<string>");

// Reads and parses a file; a missing or unreadable file is a ConfigError too.
Configuration load_configuration(const std::filesystem::path& file);
Params load_params(const std::filesystem::path& file);

// Checks relations between values that single ranges cannot (h < T(con), ordered joint bounds,
// monotone W tables, a δ table for the configured (h, con)). Empty when all is well.
std::vector<std::string> consistency_problems(const Params& params);

}  // namespace marsokhod::config
