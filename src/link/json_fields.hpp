// Strict readers for one field of a parsed JSON object: the type checks (and ranges, from
// driver/operator_commands.hpp) that every operator command shares, each failing with a
// FieldError that names the field and says what is allowed. Internal to the codec
// (command_json.cpp) and the console's parser (operator_message.cpp).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "driver/operator_commands.hpp"

namespace marsokhod::link {

// An std::invalid_argument, as the recordings' and scenario files' readers expect.
class FieldError : public std::invalid_argument {
 public:
  FieldError(std::string field, const std::string& message)
      : std::invalid_argument(message), field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// A key as a field name: itself when it is a plain identifier, else quoted and escaped, so that
// a hostile key cannot put control characters into an error message.
std::string field_name(const std::string& key);

// The value's JSON text for an error message: ASCII only and cut to a readable length.
std::string shown_value(const nlohmann::json& value);

// A number (JSON has no NaN or infinity); with a range, inside it.
double read_number(const nlohmann::json& value, const std::string& field);
double read_number(const nlohmann::json& value, const std::string& field,
                   const driver::NumberRange& range);
bool read_bool(const nlohmann::json& value, const std::string& field);
const std::string& read_string(const nlohmann::json& value, const std::string& field);

// Throws for the first key of `object` not in `known`; `what` names the message in the error
// ("a gamepad message") and `prefix` is prepended to the key ("behaviours.").
void reject_unknown_keys(const nlohmann::json& object, std::string_view prefix,
                         const std::vector<std::string_view>& known, std::string_view what);

// Throws `error` as a FieldError, its field and message behind `prefix` ("targets.").
[[noreturn]] void throw_field_error(const driver::CommandError& error, std::string_view prefix);

// Parses `text` into a JSON value; throws FieldError("json", …) for malformed JSON (including a
// number too large for a double, which would otherwise become infinity) and
// FieldError(key, …) for a key that appears twice in one object (JSON leaves that undefined and
// the parser would silently keep the last one).
nlohmann::json parse_json_strictly(std::string_view text);

}  // namespace marsokhod::link
