// The shared secret every WebSocket connection must present (/ws?token=…). The server listens on
// loopback by default, but any local process — or any web page the operator's browser opens —
// can reach loopback ports; the token is what keeps those from driving the rover.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace marsokhod::link {

// 128 bits from the kernel's getrandom(2) as 32 lower-case hex digits.
std::string generate_token();

// `bytes` random bytes from getrandom(2) as lower-case hex. Throws std::runtime_error if the
// kernel has none to give (never silently a weaker source).
std::string random_hex(std::size_t bytes);

// The token in `file`: its first line, surrounding blanks removed, then validate_token. Throws
// std::invalid_argument naming the file when it cannot be read, when group or others may read
// or write it (it must be mode 0600 or stricter: `chmod 600 FILE`), or when the token is bad.
std::string read_token_file(const std::filesystem::path& file);

// Throws std::invalid_argument unless the token has at least 16 characters, all from
// [0-9A-Za-z._~-] (URL-safe without escaping, so it can be pasted into the console's address).
void validate_token(std::string_view token);

// Equality whose time does not depend on where the first difference is, so that a client cannot
// find the token one character at a time by timing refusals.
bool tokens_equal(std::string_view a, std::string_view b);

// The value of `name` in the query of a request target ("/ws?token=abc" → "abc"), as written
// (no percent-decoding: tokens never need escapes); nullopt if absent.
std::optional<std::string_view> query_parameter(std::string_view target, std::string_view name);

// The target without its query and fragment ("/ws?token=abc" → "/ws").
std::string_view target_path(std::string_view target);

}  // namespace marsokhod::link
