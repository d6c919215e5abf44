// Checks on the headers of every HTTP request, pure:
//  - Host (DNS rebinding): a page on evil.example whose name is re-pointed at 127.0.0.1 reaches
//    the server with "Host: evil.example"; only the listen address, loopback names and the
//    configured names are served. When listening on every interface (0.0.0.0, ::) any IP
//    literal is also allowed: a rebinding needs a name, and the rover's address is not known
//    in advance.
//  - Origin (cross-site WebSocket hijacking): a browser sends the page's origin with every
//    WebSocket upgrade; only the server's own origins (an allowed host on this port) and the
//    configured extra ones may open one. Clients that are not browsers send no Origin; they
//    still need the token.
//  - the session cookie and the Authorization: Bearer token.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace marsokhod::link {

struct OriginPolicy {
  std::vector<std::string> hosts;    // lower case, no port; IPv6 without brackets
  std::vector<std::string> origins;  // exact extra origins, "https://rover.example"
  bool any_ip_literal = false;       // listening on every interface
  std::uint16_t port = 0;            // the server's port: its own origins use it
};

// The policy for a server listening on `address`:`port` with extra names and origins (as
// configured: checked by validate_host_name / validate_origin).
OriginPolicy origin_policy(const std::string& address, std::uint16_t port,
                           const std::vector<std::string>& extra_hosts,
                           const std::vector<std::string>& extra_origins);

// Throws std::invalid_argument naming the value unless it is a host name or IP literal (no
// scheme, port or path) / an origin "http[s]://HOST[:PORT]".
void validate_host_name(const std::string& host);
void validate_origin(const std::string& origin);

// The Host header's host part is allowed. A missing or empty Host is not.
bool host_allowed(std::string_view host_header, const OriginPolicy& policy);
// An Origin header's value is one of the server's origins or a configured one.
bool origin_allowed(std::string_view origin, const OriginPolicy& policy);

// The value of cookie `name` in a Cookie header ("a=1; name=value"), if present.
std::optional<std::string_view> cookie_value(std::string_view header, std::string_view name);
// The token of "Bearer TOKEN", if the header has that form.
std::optional<std::string_view> bearer_token(std::string_view authorization);

}  // namespace marsokhod::link
