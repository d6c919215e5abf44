// Interoperability with python-can (Debian's python3-can), a socketcand client and candump-log
// reader that nobody here wrote. Always /usr/bin/python3: Debian's python-can lives there, not in
// whatever python3 comes first on PATH.
#include <gtest/gtest.h>

#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include "bus/candump_log.hpp"
#include "bus/socketcand_server.hpp"
#include "child_process.hpp"
#include "core/protocol/codec.hpp"

namespace marsokhod::bus {
namespace {

using std::chrono::milliseconds;

constexpr const char* kPython = "/usr/bin/python3";
// python-can retries its connect for 10 s and each exchange waits 5 s: the bound covers both.
constexpr milliseconds kScriptDeadline{60000};
constexpr int kPythonCanMissing = 77;

std::string script(const char* name) {
  return std::string(MARSOKHOD_SOURCE_DIR) + "/tests/bus/" + name;
}

// Why the interoperability tests cannot run here (and what to install), or nullopt.
std::optional<std::string> python_can_missing() {
  if (::access(kPython, X_OK) != 0)
    return std::string(kPython) + " not found: apt-get install python3";
  if (testing::run_program({kPython, "-c", "import can.interfaces.socketcand"}, kScriptDeadline) !=
      0) {
    return "python-can is not installed for " + std::string(kPython) +
           ": apt-get install python3-can";
  }
  return std::nullopt;
}

// "180#03012C": the notation of candump logs, which the scripts take.
std::string candump(const protocol::CanFrame& frame) {
  LoggedFrame logged;
  logged.timestamp = "0";
  logged.interface = "x";
  logged.frame = frame;
  const std::string line = format_candump_line(logged);
  return line.substr(line.rfind(' ') + 1);
}

TEST(PythonCanInterop, SocketcandClientTalksToOurServer) {
  if (const auto reason = python_can_missing()) GTEST_SKIP() << *reason;
  // The µ3 control exchange, and µ8's dead man's switch for an empty (DLC 0) response.
  const protocol::ControlRequest request{3, true, true, 300};
  const protocol::ControlResponse response{3, 0x1234, 0x0102, 0x0A0B, true, 0x1FF};
  const protocol::DeadManRequest dead_man{5};
  std::mutex mutex;
  std::vector<protocol::Message> received;
  SocketcandServer* server_pointer = nullptr;
  SocketcandServer::Config config;
  config.port = 0;
  SocketcandServer server(config, [&](const protocol::CanFrame& frame) {
    const auto decoded = protocol::decode(frame);
    if (!decoded) return;
    {
      const std::lock_guard lock(mutex);
      received.push_back(decoded.message());
    }
    if (decoded.message() == protocol::Message{request})
      server_pointer->broadcast(protocol::encode(response), 1.25);
    if (decoded.message() == protocol::Message{dead_man}) {
      server_pointer->broadcast(protocol::encode(protocol::DeadManResponse{}), 1.5);
    }
  });
  server_pointer = &server;
  server.start();
  const auto status = testing::run_program(
      {kPython, script("python_can_interop.py"), "--port", std::to_string(server.port()),
       "--exchange", candump(protocol::encode(request)), candump(protocol::encode(response)),
       "--exchange", candump(protocol::encode(dead_man)),
       candump(protocol::encode(protocol::DeadManResponse{}))},
      kScriptDeadline);
  server.stop();
  if (status == kPythonCanMissing) GTEST_SKIP() << "python-can is not installed for " << kPython;
  EXPECT_EQ(status, 0) << "python_can_interop.py failed (its output is above)";
  const std::lock_guard lock(mutex);
  EXPECT_EQ(received, (std::vector<protocol::Message>{request, dead_man}));
  EXPECT_EQ(server.counters().malformed_messages, 0u);
}

// The simulator broadcasts all the time: python-can must get through its handshake (which reads
// each reply with one recv() and compares it exactly) while frames are flowing, then receive them.
TEST(PythonCanInterop, SocketcandClientJoinsABusyBus) {
  if (const auto reason = python_can_missing()) GTEST_SKIP() << *reason;
  SocketcandServer::Config config;
  config.port = 0;
  SocketcandServer server(config, nullptr);
  server.start();
  protocol::MeasurementRequest measurement;
  measurement.lcd = {'M', 'A', 'R', 'S', 'O', 'K', 'H', 'D'};
  const protocol::CanFrame traffic = protocol::encode(measurement);
  std::mutex mutex;
  std::condition_variable stop_requested;
  bool stop = false;
  // Paces the bus; each wait ends early when the test is done. With a frame every 20 µs and no
  // Config::rawmode_grace, python-can's handshake failed in 2 of 6 runs ("< ok > message
  // expected!").
  constexpr std::chrono::microseconds kFramePeriod{50};
  const double period_s = std::chrono::duration<double>(kFramePeriod).count();
  std::thread bus([&] {
    std::unique_lock lock(mutex);
    for (double time_s = 0.0; !stop_requested.wait_for(lock, kFramePeriod, [&] { return stop; });
         time_s += period_s) {
      server.broadcast(traffic, time_s);
    }
  });
  const auto status = testing::run_program(
      {kPython, script("python_can_interop.py"), "--port", std::to_string(server.port()),
       "--traffic", candump(traffic), "200", "--exchange", "180#03012C", candump(traffic)},
      kScriptDeadline);
  {
    const std::lock_guard lock(mutex);
    stop = true;
  }
  stop_requested.notify_all();
  bus.join();
  server.stop();
  if (status == kPythonCanMissing) GTEST_SKIP() << "python-can is not installed for " << kPython;
  EXPECT_EQ(status, 0) << "python_can_interop.py failed (its output is above)";
  EXPECT_EQ(server.counters().frames_from_clients, 1u);  // its request got through the traffic
  EXPECT_EQ(server.counters().malformed_messages, 0u);
}

struct LogCase {
  LoggedFrame logged;
  std::string expected;  // as the script prints what python-can read
};

LogCase log_case(const char* timestamp, std::uint32_t id, std::initializer_list<std::uint8_t> bytes,
                 const char* expected, bool remote = false) {
  LogCase c;
  c.logged.timestamp = timestamp;
  c.logged.interface = "can0";
  c.logged.frame.id = id;
  c.logged.frame.dlc = static_cast<std::uint8_t>(bytes.size());
  std::copy(bytes.begin(), bytes.end(), c.logged.frame.data.begin());
  c.logged.remote = remote;
  c.expected = expected;
  return c;
}

std::vector<std::string> lines_of(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(PythonCanInterop, CandumpLogsReadBothWays) {
  if (const auto reason = python_can_missing()) GTEST_SKIP() << *reason;
  const LogCase cases[] = {
      log_case("1436509052.249713", 0x180, {0x03, 0x01, 0x2C},
               "1436509052.249713 180 3 03012C can0 0 0"),
      log_case("1436509052.250000", 0x188, {0x12, 0x34, 0x01, 0x02, 0x0A, 0x0B, 0x81, 0xFF},
               "1436509052.25 188 8 123401020A0B81FF can0 0 0"),
      log_case("1436509052.260001", 0x418, {}, "1436509052.260001 418 0 - can0 0 0"),
      log_case("1436509052.270000", 0x400, {}, "1436509052.27 400 0 - can0 0 1", true),
  };
  const auto dir =
      std::filesystem::temp_directory_path() / ("marsokhod_bus_log_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream log(dir / "ours.log");
    for (const auto& c : cases) log << format_candump_line(c.logged) << '\n';
  }
  const auto status = testing::run_program(
      {kPython, script("python_can_log_reader.py"), (dir / "ours.log").string(),
       (dir / "frames.txt").string(), (dir / "theirs.log").string()},
      kScriptDeadline);
  const auto read_by_python = lines_of(dir / "frames.txt");
  const auto written_by_python = lines_of(dir / "theirs.log");
  std::filesystem::remove_all(dir);
  if (status == kPythonCanMissing) GTEST_SKIP() << "python-can is not installed for " << kPython;
  ASSERT_EQ(status, 0) << "python_can_log_reader.py failed (its output is above)";
  ASSERT_EQ(read_by_python.size(), std::size(cases));
  ASSERT_EQ(written_by_python.size(), std::size(cases));
  for (std::size_t i = 0; i < std::size(cases); ++i) {
    EXPECT_EQ(read_by_python[i], cases[i].expected);
    // And python-can's writer (which appends " R") back through our parser.
    const auto parsed = parse_candump_line(written_by_python[i]);
    const auto* logged = std::get_if<LoggedFrame>(&parsed);
    ASSERT_NE(logged, nullptr) << written_by_python[i] << ": "
                               << std::get<LogParseError>(parsed).reason;
    EXPECT_EQ(logged->frame, cases[i].logged.frame) << written_by_python[i];
    EXPECT_EQ(logged->remote, cases[i].logged.remote) << written_by_python[i];
    EXPECT_EQ(logged->timestamp, cases[i].logged.timestamp) << written_by_python[i];
  }
}

}  // namespace
}  // namespace marsokhod::bus
