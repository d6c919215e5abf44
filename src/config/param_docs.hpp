// docs/parameters.md, generated from the parameter schema (param_schema.hpp): every key of
// config/marsokhod.toml with its value, unit, range, thesis source and meaning. The program
// marsokhod-param-docs prints it (`make params-doc`); a test fails when the page in docs/ differs.
#pragma once

#include <string>

#include "config/param_schema.hpp"

namespace marsokhod::config {

// The Markdown page.
std::string parameters_markdown();

// A value as TOML writes it: 0.145, 511, true, "off", [0.0, 0.052].
std::string format_value(const ParamSpec& spec, const ParamValue& value);

}  // namespace marsokhod::config
