// libFuzzer target: any frame must decode without crashing, and every frame decode accepts must
// re-encode to the same bytes (encode ∘ decode = identity on legal frames).
//
// Input layout: bytes 0–1 the identifier (big-endian, up to 0xFFFF so that ids above 0x7FF are
// exercised), byte 2 the DLC (low nibble, 0..15 so that DLC 9..15 is exercised), then the data.
// Missing bytes read as zero; data bytes beyond min(DLC, 8) stay zero, as on a SocketCAN frame.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "core/protocol/codec.hpp"

namespace {

using marsokhod::protocol::CanFrame;

std::uint8_t byte_at(const std::uint8_t* data, std::size_t size, std::size_t at) {
  return at < size ? data[at] : 0;
}

CanFrame frame_from(const std::uint8_t* data, std::size_t size) {
  CanFrame frame;
  frame.id = static_cast<std::uint32_t>((byte_at(data, size, 0) << 8) | byte_at(data, size, 1));
  frame.dlc = static_cast<std::uint8_t>(byte_at(data, size, 2) & 0x0F);
  for (std::size_t i = 0; i < frame.data.size() && i < frame.dlc; ++i) {
    frame.data[i] = byte_at(data, size, 3 + i);
  }
  return frame;
}

[[noreturn]] void fail(const char* what, const CanFrame& frame) {
  std::fprintf(stderr, "protocol_decode_fuzzer: %s for id 0x%X dlc %u\n", what,
               static_cast<unsigned>(frame.id), static_cast<unsigned>(frame.dlc));
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace protocol = marsokhod::protocol;
  const CanFrame frame = frame_from(data, size);
  const protocol::DecodeResult result = protocol::decode(frame);
  if (!result.ok()) {
    if (result.error().reason.empty()) {
      fail("rejected without a reason", frame);
    }
    return 0;
  }
  const protocol::Message& message = result.message();
  if (protocol::message_name(message) == nullptr || protocol::node_of(message) > 8) {
    fail("decoded message has no name or an impossible node", frame);
  }
  try {
    if (!(protocol::encode(message) == frame)) {
      fail("encode(decode(frame)) differs from frame", frame);
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "protocol_decode_fuzzer: encode threw: %s\n", error.what());
    fail("encode refused a message decode accepted", frame);
  }
  return 0;
}
