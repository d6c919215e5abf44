// ServerCore's checks of who is asking (server_core.hpp): Host, Origin, the token, the session
// cookie and the back-off for wrong tokens. On the server thread only.
#include <chrono>
#include <cstdio>

#include "link/access_token.hpp"
#include "link/server_core.hpp"

namespace marsokhod::link {

double steady_now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

bool ServerCore::host_allowed(std::string_view host) {
  if (link::host_allowed(host, policy_)) return true;
  count(&ServerStats::forbidden);
  return false;
}

bool ServerCore::origin_allowed(std::optional<std::string_view> origin) {
  if (!origin || link::origin_allowed(*origin, policy_)) return true;
  count(&ServerStats::forbidden);
  return false;
}

AuthDecision ServerCore::check_token(std::string_view given, const std::string& address) {
  const double now_s = steady_now_s();
  if (const double wait_s = throttle_.wait_s(address, now_s); wait_s > 0.0) {
    count(&ServerStats::auth_throttled);
    return {AuthDecision::Result::kBackingOff, wait_s};
  }
  if (tokens_equal(given, token_)) {
    throttle_.succeeded(address);
    return {AuthDecision::Result::kAllowed, 0.0};
  }
  count(&ServerStats::unauthorized);
  const AuthThrottle::Failure failure = throttle_.failed(address, now_s);
  std::fprintf(stderr, "link: wrong token from %s (%d in a row); its next try waits %.1f s\n",
               address.c_str(), failure.in_a_row, failure.delay_s);
  return {AuthDecision::Result::kWrongToken, failure.delay_s};
}

AuthDecision ServerCore::authorize_upgrade(std::string_view cookie_header,
                                           std::string_view authorization,
                                           const std::string& address,
                                           std::optional<std::string_view> query_token) {
  if (const auto id = cookie_value(cookie_header, cookie_name()); id && sessions_.valid(*id)) {
    return {AuthDecision::Result::kAllowed, 0.0};
  }
  if (const auto bearer = bearer_token(authorization); bearer || !query_token) {
    return check_token(bearer.value_or(std::string_view{}), address);
  }
  return check_token(*query_token, address);
}

AuthDecision ServerCore::open_session(std::string_view authorization, const std::string& address,
                                      std::string& session_id) {
  const AuthDecision decision =
      check_token(bearer_token(authorization).value_or(std::string_view{}), address);
  if (decision.result == AuthDecision::Result::kAllowed) session_id = sessions_.create();
  return decision;
}

void ServerCore::on_handler_failure(const char* where, const std::exception& error) {
  count(&ServerStats::handler_failures);
  std::fprintf(stderr, "link: %s failed (%s); closing that connection\n", where, error.what());
}

}  // namespace marsokhod::link
