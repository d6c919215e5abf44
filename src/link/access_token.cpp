#include "link/access_token.hpp"

#include <array>
#include <random>
#include <stdexcept>

namespace marsokhod::link {
namespace {

constexpr std::size_t kMinTokenChars = 16;

bool url_safe(char c) {
  return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '.' ||
         c == '_' || c == '~' || c == '-';
}

}  // namespace

std::string generate_token() {
  static constexpr std::array<char, 16> kHex = {'0', '1', '2', '3', '4', '5', '6', '7',
                                                '8', '9', 'a', 'b', 'c', 'd', 'e', 'f'};
  std::random_device source;
  std::string token;
  for (int word = 0; word < 4; ++word) {
    // random_device yields unsigned int; take exactly 32 bits of each of four draws.
    const std::uint32_t bits = static_cast<std::uint32_t>(source());
    for (int shift = 28; shift >= 0; shift -= 4) token += kHex[(bits >> shift) & 0xFU];
  }
  return token;
}

void validate_token(std::string_view token) {
  bool safe = true;
  for (const char c : token) safe = safe && url_safe(c);
  if (token.size() < kMinTokenChars || !safe) {
    throw std::invalid_argument(
        "token: needs at least 16 characters from 0-9 A-Z a-z . _ ~ -; leave it empty to have "
        "the server generate one");
  }
}

bool tokens_equal(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;  // the length is not the secret
  unsigned difference = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    difference |= static_cast<unsigned char>(a[i]) ^ static_cast<unsigned char>(b[i]);
  }
  return difference == 0;
}

std::string_view target_path(std::string_view target) {
  return target.substr(0, target.find_first_of("?#"));
}

std::optional<std::string_view> query_parameter(std::string_view target, std::string_view name) {
  const auto question = target.find('?');
  if (question == std::string_view::npos) return std::nullopt;
  std::string_view query = target.substr(question + 1);
  query = query.substr(0, query.find('#'));
  while (!query.empty()) {
    const auto amp = query.find('&');
    const std::string_view pair = query.substr(0, amp);
    const auto equals = pair.find('=');
    if (pair.substr(0, equals) == name) {
      return equals == std::string_view::npos ? std::string_view{} : pair.substr(equals + 1);
    }
    query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
  }
  return std::nullopt;
}

}  // namespace marsokhod::link
