// Who may drive, past the token: the console's session cookies, and the back-off for wrong
// tokens. Pure (time is a value); the server keeps one of each on its thread.
//
// The console exchanges the token once (POST /session, Authorization: Bearer TOKEN) for a
// session cookie — HttpOnly (no script reads it), SameSite=Strict (no other site's page sends
// it) — so the token leaves the address bar, the browser's history and Referer headers.
#pragma once

#include <cstddef>
#include <deque>
#include <map>
#include <string>
#include <string_view>

namespace marsokhod::link {

class SessionStore {
 public:
  explicit SessionStore(std::size_t capacity) : capacity_(capacity) {}
  // A new session id (128 bits from getrandom, hex); the oldest session ends when full.
  std::string create();
  bool valid(std::string_view id) const;  // compares in constant time per stored id
  std::size_t size() const { return ids_.size(); }

 private:
  std::size_t capacity_;
  std::deque<std::string> ids_;
};

// Per client address: after a wrong token the address is refused (without looking at what it
// sends) for first_delay_s, doubling with every further wrong one up to max_delay_s; a right
// token resets it. Guessing a 128-bit token is hopeless anyway; this keeps a script from
// hammering the server and makes the attempts visible in the log.
class AuthThrottle {
 public:
  AuthThrottle(double first_delay_s, double max_delay_s, std::size_t max_addresses)
      : first_delay_s_(first_delay_s), max_delay_s_(max_delay_s), max_addresses_(max_addresses) {}

  // Seconds `address` must still wait before its token is looked at; 0: it may try now.
  double wait_s(const std::string& address, double now_s) const;
  struct Failure {
    int in_a_row = 0;
    double delay_s = 0.0;
  };
  Failure failed(const std::string& address, double now_s);
  void succeeded(const std::string& address) { entries_.erase(address); }

 private:
  struct Entry {
    int failures = 0;
    double blocked_until_s = 0.0;
  };
  void make_room(double now_s);

  double first_delay_s_;
  double max_delay_s_;
  std::size_t max_addresses_;
  std::map<std::string, Entry, std::less<>> entries_;
};

}  // namespace marsokhod::link
