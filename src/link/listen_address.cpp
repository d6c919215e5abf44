#include "link/listen_address.hpp"

#include <charconv>
#include <stdexcept>

#include <boost/asio/ip/address.hpp>

namespace marsokhod::link {
namespace {

[[noreturn]] void bad(std::string_view text, const std::string& what) {
  throw std::invalid_argument("--listen \"" + std::string(text) + "\": " + what +
                              "; expected ADDR:PORT, e.g. 127.0.0.1:8080, 0.0.0.0:8080 or "
                              "[::1]:8080");
}

std::uint16_t parse_port(std::string_view text, std::string_view port) {
  if (port.empty()) bad(text, "the port is missing");
  unsigned value = 0;
  const auto [end, error] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (error != std::errc() || end != port.data() + port.size() || value > 65535) {
    bad(text, "the port \"" + std::string(port) + "\" is not a number in 0..65535");
  }
  return static_cast<std::uint16_t>(value);
}

}  // namespace

ListenAddress parse_listen_address(std::string_view text) {
  const auto colon = text.rfind(':');
  if (colon == std::string_view::npos) bad(text, "no ':' before the port");
  std::string_view address = text.substr(0, colon);
  const std::string_view port = text.substr(colon + 1);
  const bool bracketed = address.size() >= 2 && address.front() == '[' && address.back() == ']';
  if (bracketed) address = address.substr(1, address.size() - 2);
  if (address.empty()) bad(text, "the address is missing");
  boost::system::error_code error;
  const auto ip = boost::asio::ip::make_address(std::string(address), error);
  if (error) bad(text, "\"" + std::string(address) + "\" is not an IP address");
  if (ip.is_v6() && !bracketed) bad(text, "write an IPv6 address in brackets");
  return {std::string(address), parse_port(text, port)};
}

std::string to_string(const ListenAddress& listen) {
  const bool v6 = listen.address.find(':') != std::string::npos;
  const std::string address = v6 ? "[" + listen.address + "]" : listen.address;
  return address + ":" + std::to_string(listen.port);
}

}  // namespace marsokhod::link
