#include "runner/live_pacing.hpp"

#include <atomic>
#include <csignal>
#include <thread>

namespace marsokhod::runner {
namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }

}  // namespace

Pacer::Pacer(std::chrono::microseconds period) : period_(period) {
  g_stop = false;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  start_ = Clock::now();
}

void Pacer::sleep_until(std::uint64_t k) const { std::this_thread::sleep_until(deadline(k)); }

bool Pacer::stop_requested() { return g_stop; }

}  // namespace marsokhod::runner
