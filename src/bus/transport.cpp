#include "bus/transport.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <string_view>

#include "bus/socketcan_transport.hpp"
#include "bus/socketcand_client.hpp"
#include "bus/socketcand_protocol.hpp"

namespace marsokhod::bus {
namespace {

constexpr std::string_view kSocketCanScheme = "socketcan:";
constexpr std::string_view kSocketcandScheme = "socketcand://";
constexpr const char* kExpectedForms =
    "expected 'socketcan:IFACE' (e.g. socketcan:can0) or 'socketcand://HOST[:PORT][/CHANNEL]' "
    "(e.g. socketcand://127.0.0.1:29536/can0)";

[[noreturn]] void fail(const std::string& url, const std::string& what) {
  throw TransportError("bad transport URL '" + url + "': " + what + "; " + kExpectedForms);
}

// The kernel's rule for interface names (net/core/dev.c dev_valid_name): 1-15 characters, none of
// them '/', ':' or whitespace.
bool valid_interface_name(std::string_view name) {
  if (name.empty() || name.size() > 15 || name == "." || name == "..") return false;
  return std::none_of(name.begin(), name.end(), [](char c) {
    return c == '/' || c == ':' || std::isspace(static_cast<unsigned char>(c));
  });
}

std::uint16_t parse_port(const std::string& url, std::string_view text) {
  unsigned value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || ptr != text.data() + text.size() || value == 0 ||
      value > 65535) {
    fail(url, "port '" + std::string(text) + "' is not a number in 1..65535");
  }
  return static_cast<std::uint16_t>(value);
}

// Splits "HOST[:PORT]" with an optional bracketed IPv6 host ("[::1]:29536").
void parse_authority(const std::string& url, std::string_view authority, TransportUrl& out) {
  std::string_view port_text;
  if (!authority.empty() && authority.front() == '[') {
    const auto close = authority.find(']');
    if (close == std::string_view::npos) fail(url, "IPv6 host has no closing ']'");
    out.host = std::string(authority.substr(1, close - 1));
    const std::string_view rest = authority.substr(close + 1);
    if (!rest.empty() && rest.front() != ':') fail(url, "unexpected text after ']'");
    if (!rest.empty()) port_text = rest.substr(1);
    if (rest.size() == 1) fail(url, "empty port after ':'");
  } else {
    const auto colon = authority.find(':');
    out.host = std::string(authority.substr(0, colon));
    if (colon != std::string_view::npos) {
      port_text = authority.substr(colon + 1);
      if (port_text.empty()) fail(url, "empty port after ':'");
    }
  }
  if (out.host.empty()) fail(url, "no host");
  out.port = port_text.empty() ? kSocketcandDefaultPort : parse_port(url, port_text);
}

TransportUrl parse_socketcand(const std::string& url) {
  TransportUrl out;
  out.kind = TransportUrl::Kind::kSocketcand;
  const std::string_view rest = std::string_view(url).substr(kSocketcandScheme.size());
  const auto slash = rest.find('/');
  parse_authority(url, rest.substr(0, slash), out);
  out.channel = kSocketcandDefaultChannel;
  if (slash != std::string_view::npos) {
    const std::string_view channel = rest.substr(slash + 1);
    if (!socketcand::valid_channel_name(channel)) {
      fail(url, "channel '" + std::string(channel) +
                    "' is not a bus name (1-16 characters, no '/', ':', '<', '>' or spaces)");
    }
    out.channel = std::string(channel);
  }
  return out;
}

}  // namespace

TransportUrl parse_transport_url(const std::string& url) {
  const std::string_view view(url);
  if (view.substr(0, kSocketcandScheme.size()) == kSocketcandScheme) return parse_socketcand(url);
  if (view.substr(0, kSocketCanScheme.size()) == kSocketCanScheme) {
    TransportUrl out;
    out.interface = std::string(view.substr(kSocketCanScheme.size()));
    if (!valid_interface_name(out.interface)) {
      fail(url, "interface '" + out.interface +
                    "' is not an interface name (1-15 characters, no '/', ':' or spaces)");
    }
    return out;
  }
  fail(url, "unknown transport");
}

std::string describe_frame(const protocol::CanFrame& frame) {
  char text[48];
  std::snprintf(text, sizeof text, "id 0x%X, DLC %u", static_cast<unsigned>(frame.id),
                static_cast<unsigned>(frame.dlc));
  return text;
}

std::unique_ptr<CanTransport> open_transport(const std::string& url) {
  const TransportUrl parsed = parse_transport_url(url);
  if (parsed.kind == TransportUrl::Kind::kSocketCan) {
    return std::make_unique<SocketCanTransport>(parsed.interface);
  }
  SocketcandClient::Config config;
  config.host = parsed.host;
  config.port = parsed.port;
  config.channel = parsed.channel;
  return std::make_unique<SocketcandClient>(config);
}

}  // namespace marsokhod::bus
