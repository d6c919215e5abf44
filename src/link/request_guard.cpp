#include "link/request_guard.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <stdexcept>

#include <boost/asio/ip/address.hpp>

namespace marsokhod::link {
namespace {

// Names that always mean this machine (RFC 6761 and Debian's /etc/hosts).
constexpr std::string_view kLoopbackNames[] = {"localhost", "127.0.0.1", "::1", "ip6-localhost",
                                               "ip6-loopback"};

std::string lower(std::string_view text) {
  std::string out(text);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (!out.empty() && out.back() == '.') out.pop_back();  // "localhost." is "localhost"
  return out;
}

bool is_ip_literal(const std::string& host) {
  boost::system::error_code error;
  boost::asio::ip::make_address(host, error);
  return !error;
}

struct HostPort {
  std::string host;               // lower case, IPv6 without brackets
  std::optional<std::uint16_t> port;
};

// "name", "name:80", "[::1]", "[::1]:80"; nullopt when malformed.
std::optional<HostPort> split_host_port(std::string_view text) {
  HostPort out;
  std::string_view rest;
  if (!text.empty() && text.front() == '[') {
    const auto close = text.find(']');
    if (close == std::string_view::npos) return std::nullopt;
    out.host = lower(text.substr(1, close - 1));
    rest = text.substr(close + 1);
  } else {
    const auto colon = text.find(':');
    out.host = lower(text.substr(0, colon));
    rest = colon == std::string_view::npos ? std::string_view{} : text.substr(colon);
  }
  if (out.host.empty()) return std::nullopt;
  if (!rest.empty()) {
    if (rest.front() != ':' || rest.size() < 2) return std::nullopt;
    unsigned value = 0;
    const auto digits = rest.substr(1);
    const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error != std::errc() || end != digits.data() + digits.size() || value > 65535) {
      return std::nullopt;
    }
    out.port = static_cast<std::uint16_t>(value);
  }
  const bool clean = std::all_of(out.host.begin(), out.host.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '.' || c == '-' || c == ':';
  });
  if (!clean) return std::nullopt;
  return out;
}

bool listed(const std::string& host, const OriginPolicy& policy) {
  if (std::find(policy.hosts.begin(), policy.hosts.end(), host) != policy.hosts.end()) return true;
  return policy.any_ip_literal && is_ip_literal(host);
}

}  // namespace

void validate_host_name(const std::string& host) {
  const auto parsed = split_host_port(host);
  if (!parsed || parsed->port || host.find('/') != std::string::npos) {
    throw std::invalid_argument("allowed_hosts: \"" + host +
                                "\" is not a host name or IP address (no scheme, port or path)");
  }
}

void validate_origin(const std::string& origin) {
  const auto scheme_end = origin.find("://");
  const std::string scheme = scheme_end == std::string::npos ? "" : origin.substr(0, scheme_end);
  const auto parsed = scheme_end == std::string::npos
                          ? std::nullopt
                          : split_host_port(std::string_view(origin).substr(scheme_end + 3));
  if ((scheme != "http" && scheme != "https") || !parsed) {
    throw std::invalid_argument("allowed_origins: \"" + origin +
                                "\" is not an origin such as https://rover.example:8443");
  }
}

OriginPolicy origin_policy(const std::string& address, std::uint16_t port,
                           const std::vector<std::string>& extra_hosts,
                           const std::vector<std::string>& extra_origins) {
  OriginPolicy policy;
  policy.port = port;
  policy.any_ip_literal = address == "0.0.0.0" || address == "::";
  policy.hosts.emplace_back(lower(address));
  for (std::string_view name : kLoopbackNames) policy.hosts.emplace_back(name);
  for (const std::string& host : extra_hosts) policy.hosts.push_back(lower(host));
  for (const std::string& origin : extra_origins) policy.origins.push_back(lower(origin));
  return policy;
}

bool host_allowed(std::string_view host_header, const OriginPolicy& policy) {
  const auto parsed = split_host_port(host_header);
  return parsed && listed(parsed->host, policy);
}

bool origin_allowed(std::string_view origin, const OriginPolicy& policy) {
  const std::string text = lower(origin);
  if (std::find(policy.origins.begin(), policy.origins.end(), text) != policy.origins.end()) {
    return true;
  }
  constexpr std::string_view kHttp = "http://";  // the server itself speaks plain HTTP
  if (text.compare(0, kHttp.size(), kHttp) != 0) return false;
  const auto parsed = split_host_port(std::string_view(text).substr(kHttp.size()));
  return parsed && listed(parsed->host, policy) && parsed->port.value_or(80) == policy.port;
}

std::optional<std::string_view> cookie_value(std::string_view header, std::string_view name) {
  while (!header.empty()) {
    const auto semicolon = header.find(';');
    std::string_view pair = header.substr(0, semicolon);
    while (!pair.empty() && pair.front() == ' ') pair.remove_prefix(1);
    const auto equals = pair.find('=');
    if (equals != std::string_view::npos && pair.substr(0, equals) == name) {
      return pair.substr(equals + 1);
    }
    header = semicolon == std::string_view::npos ? std::string_view{} : header.substr(semicolon + 1);
  }
  return std::nullopt;
}

std::optional<std::string_view> bearer_token(std::string_view authorization) {
  constexpr std::string_view kBearer = "Bearer ";
  if (authorization.substr(0, kBearer.size()) != kBearer) return std::nullopt;
  return authorization.substr(kBearer.size());
}

}  // namespace marsokhod::link
