#include "link/json_fields.hpp"

#include <cmath>
#include <set>
#include <vector>

namespace marsokhod::link {
namespace {

constexpr std::size_t kShownValueChars = 40;
constexpr std::size_t kParseReasonChars = 200;

std::string type_name(const nlohmann::json& value) {
  if (value.is_number()) return "a number";
  if (value.is_boolean()) return "a boolean";
  if (value.is_string()) return "a string";
  if (value.is_array()) return "an array";
  if (value.is_object()) return "an object";
  return "null";
}

[[noreturn]] void wrong_type(const nlohmann::json& value, const std::string& field,
                             const char* expected) {
  const std::string got = value.is_null() ? "null" : type_name(value) + " " + shown_value(value);
  throw FieldError(field, field + ": expected " + expected + ", got " + got);
}

}  // namespace

std::string field_name(const std::string& key) {
  bool plain = !key.empty() && key.size() <= kShownValueChars;
  for (const char c : key) {
    const bool letter = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    plain = plain && (letter || c == '_' || c == '-');
  }
  return plain ? key : shown_value(key);
}

std::string shown_value(const nlohmann::json& value) {
  // ensure_ascii: the cut below can then never split a UTF-8 sequence.
  std::string text = value.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
  if (text.size() > kShownValueChars) text = text.substr(0, kShownValueChars) + "...";
  return text;
}

double read_number(const nlohmann::json& value, const std::string& field) {
  if (!value.is_number()) wrong_type(value, field, "a number");
  const double number = value.get<double>();
  // JSON has no NaN or Infinity, and the strict parser refuses a literal like 1e999.
  if (!std::isfinite(number)) throw FieldError(field, field + " is not a finite number");
  return number;
}

double read_number(const nlohmann::json& value, const std::string& field,
                   const driver::NumberRange& range) {
  const double number = read_number(value, field);
  if (auto error = driver::check_number(field, number, range)) throw_field_error(*error, "");
  return number;
}

void throw_field_error(const driver::CommandError& error, std::string_view prefix) {
  throw FieldError(std::string(prefix) + error.field, std::string(prefix) + error.message);
}

bool read_bool(const nlohmann::json& value, const std::string& field) {
  if (!value.is_boolean()) wrong_type(value, field, "true or false");
  return value.get<bool>();
}

const std::string& read_string(const nlohmann::json& value, const std::string& field) {
  if (!value.is_string()) wrong_type(value, field, "a string");
  return value.get_ref<const std::string&>();
}

void reject_unknown_keys(const nlohmann::json& object, std::string_view prefix,
                         const std::vector<std::string_view>& known, std::string_view what) {
  for (const auto& item : object.items()) {
    bool found = false;
    for (std::string_view k : known) found = found || item.key() == k;
    if (found) continue;
    std::string allowed;
    for (std::string_view k : known) allowed += (allowed.empty() ? "" : ", ") + std::string(k);
    const std::string field = std::string(prefix) + field_name(item.key());
    throw FieldError(field, field + ": unknown field; " + std::string(what) + " has " + allowed);
  }
}

nlohmann::json parse_json_strictly(std::string_view text) {
  using Event = nlohmann::json::parse_event_t;
  std::vector<std::set<std::string>> keys_per_object;
  std::string duplicate;
  bool found_duplicate = false;
  const auto check_keys = [&](int /*depth*/, Event event, nlohmann::json& parsed) {
    if (event == Event::object_start) keys_per_object.emplace_back();
    if (event == Event::object_end && !keys_per_object.empty()) keys_per_object.pop_back();
    if (event == Event::key && !keys_per_object.empty() &&
        !keys_per_object.back().insert(parsed.get<std::string>()).second && !found_duplicate) {
      found_duplicate = true;
      duplicate = parsed.get<std::string>();
    }
    return true;
  };
  nlohmann::json value;
  try {
    value = nlohmann::json::parse(text.begin(), text.end(), check_keys);
  } catch (const nlohmann::json::exception& error) {
    // A syntax error, or a number beyond double's range (1e999: out_of_range, not parse_error).
    // what() starts with "[json.exception.parse_error.101] ", noise to an operator.
    std::string reason = error.what();
    if (const auto end = reason.find("] "); end != std::string::npos) reason.erase(0, end + 2);
    if (reason.size() > kParseReasonChars) reason = reason.substr(0, kParseReasonChars) + "...";
    throw FieldError("json", "malformed JSON: " + reason);
  }
  if (found_duplicate) {
    const std::string field = field_name(duplicate);
    throw FieldError(field, field + ": the key appears twice; send each key once");
  }
  return value;
}

}  // namespace marsokhod::link
