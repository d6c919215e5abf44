// libFuzzer target for the socketcand protocol (src/bus/socketcand_protocol.hpp): any byte
// stream, split at any point, goes through MessageSplitter and parse_message without crashing or
// throwing; every error says something; a `send` the parser accepts formats to a message that
// parses back to the same frame; and escaped() leaves no control character in what it returns.
//
// Input: the first byte picks where the stream is cut in two (TCP delivers it in pieces); the
// rest is the stream, as a client (or a web page's POST) would send it.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>
#include <variant>

#include "bus/socketcand_protocol.hpp"

namespace {

namespace socketcand = marsokhod::bus::socketcand;

[[noreturn]] void fail(const char* what, std::string_view input) {
  std::fprintf(stderr, "bus_socketcand_fuzzer: %s for input of %zu bytes\n", what, input.size());
  std::abort();
}

void check_message(std::string_view text, std::string_view input) {
  const auto parsed = socketcand::parse_message(text);
  if (const auto* error = std::get_if<socketcand::ParseError>(&parsed)) {
    if (error->reason.empty()) fail("a parse error without a reason", input);
    return;
  }
  const auto& message = std::get<socketcand::Message>(parsed);
  const auto* send = std::get_if<socketcand::Send>(&message);
  if (send == nullptr) return;
  const auto again = socketcand::parse_message(socketcand::format_message(*send));
  const auto* back = std::get_if<socketcand::Message>(&again);
  if (back == nullptr || !(*back == message)) fail("a send did not survive format and parse", input);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string_view input(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::size_t cut = input.empty() ? 0 : data[0] % (input.size() + 1);
  socketcand::MessageSplitter splitter;
  for (const std::string_view piece : {input.substr(0, cut), input.substr(cut)}) {
    splitter.append(piece);
    while (const auto item = splitter.next()) {
      if (const auto* text = std::get_if<std::string>(&*item)) {
        if (text->size() > socketcand::kMaxMessageLength) fail("an overlong message passed", input);
        check_message(*text, input);
      } else if (std::get<socketcand::ParseError>(*item).reason.empty()) {
        fail("a framing error without a reason", input);
      }
    }
  }
  for (const char c : socketcand::escaped(input)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte > 0x7E) fail("escaped() let a control or non-ASCII byte through", input);
  }
  return 0;
}
