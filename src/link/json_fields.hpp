// Strict readers for one field of a parsed JSON message: the type, finiteness and range checks
// that every operator message shares, each failing with a FieldError that names the field and
// says what is allowed. Internal to the parser (operator_message.cpp).
#pragma once

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace marsokhod::link {

class FieldError : public std::runtime_error {
 public:
  FieldError(std::string field, const std::string& message)
      : std::runtime_error(message), field_(std::move(field)) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

// A closed interval [min, max], or (min, max] when min_open; `unit` follows it in messages.
struct NumberRange {
  double min = 0.0;
  double max = 0.0;
  bool min_open = false;
  std::string_view unit;
};
NumberRange symmetric_range(double limit, std::string_view unit);

// A key as a field name: itself when it is a plain identifier, else quoted and escaped, so that
// a hostile key cannot put control characters into an error message.
std::string field_name(const std::string& key);

// The value's JSON text for an error message: ASCII only and cut to a readable length.
std::string shown_value(const nlohmann::json& value);

double read_number(const nlohmann::json& value, const std::string& field, const NumberRange& range);
bool read_bool(const nlohmann::json& value, const std::string& field);
const std::string& read_string(const nlohmann::json& value, const std::string& field);

// Throws for the first key of `object` not in `known`; `what` names the message in the error
// ("a gamepad message") and `prefix` is prepended to the key ("behaviours.").
void reject_unknown_keys(const nlohmann::json& object, std::string_view prefix,
                         std::initializer_list<std::string_view> known, std::string_view what);

// Parses `text` into a JSON value; throws FieldError("json", …) for malformed JSON (including a
// number too large for a double, which would otherwise become infinity) and
// FieldError(key, …) for a key that appears twice in one object (JSON leaves that undefined and
// the parser would silently keep the last one).
nlohmann::json parse_json_strictly(std::string_view text);

}  // namespace marsokhod::link
