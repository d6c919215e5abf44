// libFuzzer target: any text must parse to a message or to an error without crashing or
// throwing; an error must name a field and say something; and every text the parser accepts
// must come back unchanged through operator_message_json → dump → parse (the console's writer
// and the server's reader agree on every value the parser lets through).
//
// Input: the bytes are the WebSocket text as it arrives (any bytes, not only UTF-8).
// operator_message.dict gives libFuzzer the protocol's keys and values.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "link/operator_message.hpp"

namespace {

[[noreturn]] void fail(const char* what, std::string_view input) {
  std::fprintf(stderr, "link_operator_message_fuzzer: %s for input of %zu bytes: %.*s\n", what,
               input.size(), static_cast<int>(input.size() > 300 ? 300 : input.size()),
               input.data());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace link = marsokhod::link;
  static const marsokhod::Params params{};
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const link::ParseResult result = link::parse_operator_message(input, params);
  const std::optional<link::OperatorMessage> message = link::message_of(result);
  if (!message) {
    const auto& error = std::get<link::MessageError>(result);
    if (error.field.empty() || error.message.empty()) fail("an error without field or text", input);
    return 0;
  }
  const std::string again = link::operator_message_json(*message).dump();
  const std::optional<link::OperatorMessage> back =
      link::message_of(link::parse_operator_message(again, params));
  if (!back) fail("operator_message_json wrote a message the parser rejects", input);
  if (!(*back == *message)) fail("the round trip changed the message", input);
  return 0;
}
