// The ASCII protocol of socketcand (linux-can/socketcand, doc/protocol.md) in its raw mode, as
// spoken by socketcand itself and by python-can's `socketcand` interface:
//
//   server → client   < hi >                       greeting on connect
//   client → server   < open can0 >                → < ok >, or < error … > for an unknown bus
//   client → server   < rawmode >                  → < ok >; from now on every bus frame is sent as
//   server → client   < frame 180 1436509052.249713 03012C >
//                       ID hex (3 digits, 8 for extended), SECONDS.USECONDS, data as one run of
//                       hex pairs; no data → "< frame 183 1.000000  >" (two spaces)
//   client → server   < send 180 3 03 01 2C >      ID hex, DLC, each byte a separate hex token
//                                                  (python-can writes "< send 180 3 3 1 2c >")
//   either            < echo >, < error TEXT >
//
// Messages carry no separator between them; bytes outside `< … >` are reported (and skipped, as
// socketcand does); the server closes the connection for them before a successful open. Pure: no I/O, never throws on input (ParseError says what was wrong).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>

#include "core/protocol/can_frame.hpp"

namespace marsokhod::bus::socketcand {

// socketcand's own command buffer is far larger; every message of ours fits in 64 characters,
// so anything near this bound is a peer speaking something else.
inline constexpr std::size_t kMaxMessageLength = 256;
// socketcand's doc/protocol.md: "canbus may be at maximum 16 characters long".
inline constexpr std::size_t kMaxChannelLength = 16;

// 1–16 characters, none of them whitespace, '<', '>', '/' or ':'.
bool valid_channel_name(std::string_view name);

struct Hi {
  friend bool operator==(const Hi&, const Hi&) = default;
};
struct Ok {
  friend bool operator==(const Ok&, const Ok&) = default;
};
struct Echo {
  friend bool operator==(const Echo&, const Echo&) = default;
};
struct RawMode {
  friend bool operator==(const RawMode&, const RawMode&) = default;
};
struct Open {
  std::string channel;  // see valid_channel_name
  friend bool operator==(const Open&, const Open&) = default;
};
struct Error {
  std::string text;
  friend bool operator==(const Error&, const Error&) = default;
};
// A frame the client wants on the bus. `extended` frames parse (a valid message) but are not
// ours: frame.id then holds the 29-bit identifier.
struct Send {
  protocol::CanFrame frame;
  bool extended = false;
  friend bool operator==(const Send&, const Send&) = default;
};
// A frame seen on the bus, time_s in seconds (socketcand sends the kernel's receive timestamp).
struct Frame {
  protocol::CanFrame frame;
  double time_s = 0.0;
  bool extended = false;
  friend bool operator==(const Frame&, const Frame&) = default;
};
// Well-formed, but a command or report this implementation does not handle ("bcmmode",
// "fdframe", "rtr", "subscribe", …).
struct Unsupported {
  std::string verb;
  friend bool operator==(const Unsupported&, const Unsupported&) = default;
};

using Message = std::variant<Hi, Ok, Echo, RawMode, Open, Error, Send, Frame, Unsupported>;

struct ParseError {
  std::string reason;  // e.g. "send: DLC 9 exceeds 8 (classic CAN)"
  // Set by MessageSplitter for bytes outside `< … >`, and when those start like an HTTP request
  // line ("POST / HTTP/1.1"): a web page posting to the server (see SocketcandServer).
  bool outside_message = false;
  bool http_request = false;
};

// The text with every byte outside printable ASCII (and the backslash) as \xHH: safe to quote a
// peer's words in an error message or on a terminal.
std::string escaped(std::string_view text);

// Parses one complete message including its brackets, e.g. "< send 180 3 03 01 2C >".
std::variant<Message, ParseError> parse_message(std::string_view text);

// Formats exactly as socketcand does (see the table above). Throws std::invalid_argument for a
// frame the protocol cannot carry (id > 0x7FF, or > 0x1FFFFFFF when extended; DLC > 8), a
// negative or non-finite time, or an Open channel that is not a bus name. Error text is made
// printable ASCII: '<', '>', control characters and non-ASCII bytes become '?'.
std::string format_message(const Message& message);

// Splits the TCP byte stream into messages.
class MessageSplitter {
 public:
  using Item = std::variant<std::string, ParseError>;

  void append(std::string_view bytes);
  // The next complete message ("< … >"), a framing error (stray text, an unclosed or overlong
  // message; the splitter resynchronises at the next '<'), or nullopt when more bytes are needed.
  std::optional<Item> next();
  // Bytes held back waiting for the rest of a message.
  std::size_t pending() const { return buffer_.size() - begin_; }

 private:
  std::optional<Item> skip_stray_text();

  std::string buffer_;
  std::size_t begin_ = 0;
  bool discarding_ = false;  // inside an overlong message: drop through its '>'
};

}  // namespace marsokhod::bus::socketcand
