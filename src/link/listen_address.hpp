// --listen ADDR:PORT: where the console server accepts connections. Only IP literals: a host
// name would make the bound interface depend on the resolver, and the point of the default
// 127.0.0.1 is that nothing outside the machine can reach the rover's controls.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace marsokhod::link {

struct ListenAddress {
  std::string address = "127.0.0.1";  // IPv4 or IPv6 literal; 0.0.0.0 or :: for every interface
  std::uint16_t port = 8080;          // 0: any free port (LinkServer::port() tells which)
};

// "127.0.0.1:8080", "0.0.0.0:80", "[::1]:8080". Throws std::invalid_argument saying what is
// wrong and giving an example.
ListenAddress parse_listen_address(std::string_view text);

// The form parse_listen_address reads ("[::1]:8080" for IPv6).
std::string to_string(const ListenAddress& listen);

}  // namespace marsokhod::link
