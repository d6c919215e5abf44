// One communication cycle of chapter 3.2–3.3 on the bus: 8 control requests and µ8's measurement
// request, and their 9 responses. The driver encodes the requests and decodes the responses; the
// emulated controllers do the reverse — so a cycle costs 18 encodes and 18 decodes in all.
#include <benchmark/benchmark.h>

#include <array>
#include <cstddef>
#include <cstdint>

#include "core/protocol/codec.hpp"

namespace {

namespace protocol = marsokhod::protocol;

constexpr std::size_t kCycleMessages = 18;

std::array<protocol::Message, kCycleMessages> cycle_messages() {
  std::array<protocol::Message, kCycleMessages> messages;
  for (std::uint8_t node = 0; node < protocol::kMotorControllerCount; ++node) {
    const auto step = static_cast<std::uint16_t>(node * 1000U);
    messages[node] = protocol::ControlRequest{node, node % 2 == 1, true,
                                              static_cast<std::uint16_t>(100 + 40 * node)};
    messages[9 + node] = protocol::ControlResponse{node, static_cast<std::uint16_t>(31000 + node),
                                                   step, static_cast<std::uint16_t>(step / 2),
                                                   node % 2 == 1, static_cast<std::uint16_t>(800 + node)};
  }
  protocol::MeasurementRequest lcd{true, false, {'2', '4', '.', '0', 'V', ' ', 'o', 'k'}};
  messages[8] = lcd;
  messages[17] = protocol::MeasurementResponse{505, {279, 251, 376}, 527, 970,
                                               protocol::TiltChannel::kFront};
  return messages;
}

std::array<protocol::CanFrame, kCycleMessages> cycle_frames() {
  std::array<protocol::CanFrame, kCycleMessages> frames;
  const auto messages = cycle_messages();
  for (std::size_t i = 0; i < kCycleMessages; ++i) {
    frames[i] = protocol::encode(messages[i]);
  }
  return frames;
}

void BM_EncodeCycle(benchmark::State& state) {
  const auto messages = cycle_messages();
  for (auto _ : state) {
    for (const protocol::Message& message : messages) {
      protocol::CanFrame frame = protocol::encode(message);
      benchmark::DoNotOptimize(frame);
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kCycleMessages));
}
BENCHMARK(BM_EncodeCycle);

void BM_DecodeCycle(benchmark::State& state) {
  const auto frames = cycle_frames();
  for (auto _ : state) {
    for (const protocol::CanFrame& frame : frames) {
      protocol::DecodeResult result = protocol::decode(frame);
      benchmark::DoNotOptimize(result);
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kCycleMessages));
}
BENCHMARK(BM_DecodeCycle);

// The figure that matters for the 64 Hz cycle: every frame of the cycle encoded and decoded.
void BM_EncodeDecodeCycle(benchmark::State& state) {
  const auto messages = cycle_messages();
  for (auto _ : state) {
    for (const protocol::Message& message : messages) {
      protocol::CanFrame frame = protocol::encode(message);
      benchmark::DoNotOptimize(frame);
      protocol::DecodeResult result = protocol::decode(frame);
      benchmark::DoNotOptimize(result);
    }
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kCycleMessages));
}
BENCHMARK(BM_EncodeDecodeCycle);

// A rejected frame builds its reason string: the cost of a noisy bus.
void BM_DecodeRejected(benchmark::State& state) {
  protocol::CanFrame frame = protocol::encode(protocol::ControlResponse{});
  frame.dlc = 7;
  for (auto _ : state) {
    protocol::DecodeResult result = protocol::decode(frame);
    benchmark::DoNotOptimize(result);
  }
}
BENCHMARK(BM_DecodeRejected);

}  // namespace
