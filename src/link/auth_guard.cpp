#include "link/auth_guard.hpp"

#include <algorithm>
#include <cmath>

#include "link/access_token.hpp"

namespace marsokhod::link {

std::string SessionStore::create() {
  std::string id = random_hex(16);
  if (ids_.size() >= capacity_) ids_.pop_front();
  ids_.push_back(id);
  return id;
}

bool SessionStore::valid(std::string_view id) const {
  bool found = false;
  for (const std::string& stored : ids_) found = tokens_equal(stored, id) || found;
  return found;
}

double AuthThrottle::wait_s(const std::string& address, double now_s) const {
  const auto it = entries_.find(address);
  if (it == entries_.end()) return 0.0;
  return std::max(0.0, it->second.blocked_until_s - now_s);
}

AuthThrottle::Failure AuthThrottle::failed(const std::string& address, double now_s) {
  if (entries_.find(address) == entries_.end()) make_room(now_s);
  Entry& entry = entries_[address];
  ++entry.failures;
  const double delay_s =
      std::min(max_delay_s_, first_delay_s_ * std::pow(2.0, std::min(entry.failures - 1, 30)));
  entry.blocked_until_s = now_s + delay_s;
  return {entry.failures, delay_s};
}

void AuthThrottle::make_room(double now_s) {
  if (entries_.size() < max_addresses_) return;
  // Forget addresses whose back-off ran out; if none has, the one freed soonest.
  for (auto it = entries_.begin(); it != entries_.end();) {
    it = it->second.blocked_until_s <= now_s ? entries_.erase(it) : std::next(it);
  }
  if (entries_.size() < max_addresses_) return;
  const auto soonest = std::min_element(entries_.begin(), entries_.end(), [](const auto& a, const auto& b) {
    return a.second.blocked_until_s < b.second.blocked_until_s;
  });
  entries_.erase(soonest);
}

}  // namespace marsokhod::link
