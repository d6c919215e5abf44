// End-to-end latency of `marsokhod run`'s path: a console's `targets` message over the WebSocket
// → the link server → the real-time cycle → the driver → the first CAN request whose duty cycle
// carries it. The cycle runs in real time at h = 15.6 ms as in `run`; messages are sent at varied
// phases of the cycle. Prints the median, the 90th percentile and the maximum over the trials.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <thread>
#include <vector>

#include "link/cycle_commands.hpp"
#include "link/link_server.hpp"
#include "runner/session.hpp"
#include "test_client.hpp"

using namespace marsokhod;
using Clock = std::chrono::steady_clock;

int main() {
  const Params params;
  runner::Session session(params, sim::SimOptions{});
  link::ServerOptions options;
  options.listen = {"127.0.0.1", 0};
  options.token = "latencybenchtoken0123456789";
  link::LinkServer server(params, options);
  server.start();
  std::atomic<bool> stop{false};
  std::atomic<bool> driving{false};
  std::mutex mutex;
  std::optional<Clock::time_point> first_frame;  // of the pending trial
  bool armed = false;
  std::thread loop([&] {
    const auto start = Clock::now();
    const auto period = std::chrono::microseconds(session.cycle_us());
    for (std::int64_t k = 0; !stop; ++k) {
      std::this_thread::sleep_until(start + period * k);
      const auto commands = link::merge_cycle_commands(server.take_inbound(), session.runtime());
      const auto& cycle = session.step(commands.input ? &*commands.input : nullptr);
      driving = session.status().mode == driver::DriverMode::kDriving;
      for (const auto& frame : cycle.sent) {
        const auto decoded = protocol::decode(frame);
        const auto* r = decoded.ok() ? std::get_if<protocol::ControlRequest>(&decoded.message()) : nullptr;
        if (r != nullptr && r->node == 0 && r->pwm > 0) {
          const std::lock_guard lock(mutex);
          if (armed && !first_frame) first_frame = Clock::now();
        }
      }
    }
  });
  while (!driving) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  link::testing::TestClient client(server.port(), "/ws",
                                  {{"Authorization", "Bearer " + options.token}});
  // Readings carry their place in the stream and their send time (docs/operator-protocol.md).
  std::uint64_t seq = 0;
  const auto targets = [&seq](double v1) {
    const double sent_ms =
        std::chrono::duration<double, std::milli>(Clock::now().time_since_epoch()).count();
    return nlohmann::json{{"type", "targets"}, {"seq", ++seq}, {"sent_ms", sent_ms}, {"v1", v1}};
  };
  client.send(nlohmann::json{{"type", "take_control"}});
  std::vector<double> latency_ms;
  for (int trial = 0; trial < 30; ++trial) {
    // Rest (the console keeps sending zero targets), then a phase offset that walks the cycle.
    const auto rest_until = Clock::now() + std::chrono::milliseconds(1200);
    while (Clock::now() < rest_until) {
      client.send(targets(0.0));
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    std::this_thread::sleep_for(std::chrono::microseconds(1000 + 1733 * trial % 15600));
    {
      const std::lock_guard lock(mutex);
      armed = true;
      first_frame.reset();
    }
    const auto sent = Clock::now();
    client.send(targets(1.0));
    for (int wait = 0; wait < 200; ++wait) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      const std::lock_guard lock(mutex);
      if (first_frame) {
        latency_ms.push_back(std::chrono::duration<double, std::milli>(*first_frame - sent).count());
        break;
      }
    }
    const std::lock_guard lock(mutex);
    armed = false;
  }
  stop = true;
  loop.join();
  server.stop();
  std::sort(latency_ms.begin(), latency_ms.end());
  if (latency_ms.empty()) {
    std::printf("no trial completed\n");
    return 1;
  }
  std::printf("operator message → first CAN request carrying it, %zu trials: median %.2f ms, "
              "p90 %.2f ms, max %.2f ms (cycle period 15.6 ms)\n",
              latency_ms.size(), latency_ms[latency_ms.size() / 2],
              latency_ms[latency_ms.size() * 9 / 10], latency_ms.back());
  return 0;
}
