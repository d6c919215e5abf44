#include "bus/socketcand_protocol.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace marsokhod::bus::socketcand {
namespace {

constexpr std::uint32_t kMaxStandardId = 0x7FF;
constexpr std::uint32_t kMaxExtendedId = 0x1FFFFFFF;
constexpr std::size_t kExtendedIdDigits = 8;  // socketcand: an 8-digit ID is an extended one
constexpr std::size_t kMaxDataBytes = 8;

bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> tokens_of(std::string_view s) {
  std::vector<std::string_view> tokens;
  while (true) {
    s = trim(s);
    if (s.empty()) return tokens;
    const auto end = std::find_if(s.begin(), s.end(), is_space);
    const auto length = static_cast<std::size_t>(end - s.begin());
    tokens.push_back(s.substr(0, length));
    s.remove_prefix(length);
  }
}

// Parses 1..max_digits hex digits; nullopt for anything else (sign, "0x", empty, too long).
std::optional<std::uint32_t> parse_hex(std::string_view text, std::size_t max_digits) {
  if (text.empty() || text.size() > max_digits) return std::nullopt;
  if (!std::all_of(text.begin(), text.end(),
                   [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); })) {
    return std::nullopt;
  }
  std::uint32_t value = 0;
  std::from_chars(text.data(), text.data() + text.size(), value, 16);
  return value;
}

// The identifier of a send or frame message; writes `extended` and returns an error or nullopt.
std::optional<ParseError> parse_id(std::string_view verb, std::string_view text,
                                   protocol::CanFrame& frame, bool& extended) {
  const auto value = parse_hex(text, kExtendedIdDigits);
  if (!value) {
    return ParseError{std::string(verb) + ": identifier '" + std::string(text) +
                      "' is not 1-8 hex digits"};
  }
  extended = text.size() == kExtendedIdDigits;
  if (extended ? *value > kMaxExtendedId : *value > kMaxStandardId) {
    return ParseError{std::string(verb) + ": identifier " + std::string(text) +
                      (extended ? " exceeds 1FFFFFFF"
                                : " exceeds 7FF (an extended identifier has 8 hex digits)")};
  }
  frame.id = *value;
  return std::nullopt;
}

// `< send ID DLC B0 … >`: DLC in decimal (socketcand reads it with %hhu), one token per byte.
std::variant<Message, ParseError> parse_send(const std::vector<std::string_view>& tokens) {
  if (tokens.size() < 3)
    return ParseError{"send: expected an identifier, a DLC and DLC data bytes"};
  Send send;
  if (auto error = parse_id("send", tokens[1], send.frame, send.extended)) return *error;
  const std::string_view dlc = tokens[2];
  unsigned value = 0;
  const auto [ptr, ec] = std::from_chars(dlc.data(), dlc.data() + dlc.size(), value);
  if (ec != std::errc() || ptr != dlc.data() + dlc.size()) {
    return ParseError{"send: DLC '" + std::string(dlc) + "' is not a number 0..8"};
  }
  if (value > kMaxDataBytes) {
    return ParseError{"send: DLC " + std::to_string(value) + " exceeds 8 (classic CAN)"};
  }
  if (tokens.size() - 3 != value) {
    return ParseError{"send: DLC " + std::to_string(value) + " but " +
                      std::to_string(tokens.size() - 3) + " data bytes"};
  }
  for (std::size_t i = 0; i < value; ++i) {
    const auto byte = parse_hex(tokens[3 + i], 2);
    if (!byte) {
      return ParseError{"send: data byte '" + std::string(tokens[3 + i]) +
                        "' is not 1-2 hex digits"};
    }
    send.frame.data[i] = static_cast<std::uint8_t>(*byte);
  }
  send.frame.dlc = static_cast<std::uint8_t>(value);
  return Message{send};
}

// `< frame ID SECONDS.USECONDS DATA >`: the data is one run of hex pairs in socketcand, separate
// pairs in socketcand's protocol.md; both are accepted by joining the tokens.
std::variant<Message, ParseError> parse_frame(const std::vector<std::string_view>& tokens) {
  if (tokens.size() < 3)
    return ParseError{"frame: expected an identifier, SECONDS.USECONDS and the data"};
  Frame frame;
  if (auto error = parse_id("frame", tokens[1], frame.frame, frame.extended)) return *error;
  const std::string_view time = tokens[2];
  const auto [ptr, ec] = std::from_chars(time.data(), time.data() + time.size(), frame.time_s);
  if (ec != std::errc() || ptr != time.data() + time.size() || !std::isfinite(frame.time_s) ||
      frame.time_s < 0.0) {
    return ParseError{"frame: timestamp '" + std::string(time) + "' is not SECONDS.USECONDS"};
  }
  std::string hex;
  for (std::size_t i = 3; i < tokens.size(); ++i) hex += tokens[i];
  if (hex.size() % 2 != 0)
    return ParseError{"frame: data '" + hex + "' has an odd number of hex digits"};
  if (hex.size() > 2 * kMaxDataBytes) {
    return ParseError{"frame: " + std::to_string(hex.size() / 2) +
                      " data bytes exceed 8 (classic CAN)"};
  }
  for (std::size_t i = 0; i < hex.size(); i += 2) {
    const auto byte = parse_hex(std::string_view(hex).substr(i, 2), 2);
    if (!byte) return ParseError{"frame: data '" + hex + "' is not hexadecimal"};
    frame.frame.data[i / 2] = static_cast<std::uint8_t>(*byte);
  }
  frame.frame.dlc = static_cast<std::uint8_t>(hex.size() / 2);
  return Message{frame};
}

std::variant<Message, ParseError> parse_bare(std::string_view verb, std::size_t token_count,
                                             Message message) {
  if (token_count != 1) return ParseError{std::string(verb) + ": takes no arguments"};
  return message;
}

}  // namespace

bool valid_channel_name(std::string_view name) {
  return !name.empty() && name.size() <= kMaxChannelLength &&
         std::none_of(name.begin(), name.end(), [](char c) {
           return is_space(c) || c == '<' || c == '>' || c == '/' || c == ':' ||
                  std::iscntrl(static_cast<unsigned char>(c));
         });
}

std::variant<Message, ParseError> parse_message(std::string_view text) {
  if (text.size() < 2 || text.front() != '<' || text.back() != '>') {
    return ParseError{"expected a message in angle brackets, e.g. '< hi >'"};
  }
  const std::string_view inner = text.substr(1, text.size() - 2);
  const std::vector<std::string_view> tokens = tokens_of(inner);
  if (tokens.empty()) return ParseError{"empty message"};
  const std::string_view verb = tokens[0];
  if (verb == "hi") return parse_bare(verb, tokens.size(), Hi{});
  if (verb == "ok") return parse_bare(verb, tokens.size(), Ok{});
  if (verb == "echo") return parse_bare(verb, tokens.size(), Echo{});
  if (verb == "rawmode") return parse_bare(verb, tokens.size(), RawMode{});
  if (verb == "send") return parse_send(tokens);
  if (verb == "frame") return parse_frame(tokens);
  if (verb == "error") {
    const std::string_view rest = trim(inner);
    return Message{Error{std::string(trim(rest.substr(verb.size())))}};
  }
  if (verb == "open") {
    if (tokens.size() != 2 || !valid_channel_name(tokens[1])) {
      return ParseError{"open: expected one bus name of 1-16 characters"};
    }
    return Message{Open{std::string(tokens[1])}};
  }
  return Message{Unsupported{std::string(verb)}};
}

namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

// Error texts and quoted fragments end up inside `< … >` or a log line: nothing may close the
// message early, and python-can decodes what it receives as ASCII (anything else raises).
// "GET /path HTTP/1.1", "POST / HTTP/1.0", …: a method word in capitals, then a space.
bool looks_like_http_request(std::string_view text) {
  static constexpr std::string_view kMethods[] = {"GET ",    "POST ",    "PUT ",   "HEAD ",
                                                  "DELETE ", "OPTIONS ", "PATCH ", "CONNECT ",
                                                  "TRACE "};
  for (const std::string_view method : kMethods) {
    if (text.substr(0, method.size()) == method) return true;
  }
  return text.find(" HTTP/1.") != std::string_view::npos;
}

std::string printable(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '<' || c == '>' || byte > 0x7E || byte < 0x20) c = '?';
  }
  return out;
}

std::string format_id(const protocol::CanFrame& frame, bool extended) {
  if (frame.dlc > kMaxDataBytes) {
    throw std::invalid_argument("socketcand: DLC " + std::to_string(frame.dlc) + " exceeds 8");
  }
  if (frame.id > (extended ? kMaxExtendedId : kMaxStandardId)) {
    throw std::invalid_argument("socketcand: identifier " + std::to_string(frame.id) +
                                (extended ? " exceeds 0x1FFFFFFF" : " exceeds 0x7FF"));
  }
  char id[16];
  std::snprintf(id, sizeof id, extended ? "%08X" : "%03X", static_cast<unsigned>(frame.id));
  return id;
}

std::string format_time(double time_s) {
  if (!std::isfinite(time_s) || time_s < 0.0) {
    throw std::invalid_argument("socketcand: frame time " + std::to_string(time_s) +
                                " s is not a non-negative finite number");
  }
  auto seconds = static_cast<long long>(std::floor(time_s));
  auto microseconds = std::llround((time_s - std::floor(time_s)) * 1e6);
  if (microseconds >= 1000000) {
    ++seconds;
    microseconds -= 1000000;
  }
  char text[48];
  std::snprintf(text, sizeof text, "%lld.%06lld", seconds, static_cast<long long>(microseconds));
  return text;
}

std::string hex_byte(std::uint8_t byte) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  return {kHex[byte >> 4], kHex[byte & 0xF]};
}

}  // namespace

std::string format_message(const Message& message) {
  return std::visit(
      Overloaded{
          [](const Hi&) -> std::string { return "< hi >"; },
          [](const Ok&) -> std::string { return "< ok >"; },
          [](const Echo&) -> std::string { return "< echo >"; },
          [](const RawMode&) -> std::string { return "< rawmode >"; },
          [](const Open& open) -> std::string {
            if (!valid_channel_name(open.channel)) {
              throw std::invalid_argument("socketcand: '" + printable(open.channel) +
                                          "' is not a bus name (1-16 characters, no spaces)");
            }
            return "< open " + open.channel + " >";
          },
          [](const Error& error) -> std::string {
            return "< error " + printable(error.text) + " >";
          },
          [](const Send& send) {
            std::string text = "< send " + format_id(send.frame, send.extended) + " " +
                               std::to_string(send.frame.dlc) + " ";
            for (std::size_t i = 0; i < send.frame.dlc; ++i)
              text += hex_byte(send.frame.data[i]) + " ";
            return text + ">";
          },
          // socketcand's own layout, which python-can's parser splits on single spaces: the data
          // is one run of hex pairs and an empty frame leaves two spaces before '>'.
          [](const Frame& frame) {
            std::string text = "< frame " + format_id(frame.frame, frame.extended) + " " +
                               format_time(frame.time_s) + " ";
            for (std::size_t i = 0; i < frame.frame.dlc; ++i) text += hex_byte(frame.frame.data[i]);
            return text + " >";
          },
          [](const Unsupported& unsupported) -> std::string {
            return "< " + printable(unsupported.verb) + " >";
          },
      },
      message);
}

void MessageSplitter::append(std::string_view bytes) {
  if (begin_ > 0 && begin_ >= buffer_.size() / 2) {
    buffer_.erase(0, begin_);
    begin_ = 0;
  }
  buffer_.append(bytes);
}

std::optional<MessageSplitter::Item> MessageSplitter::next() {
  if (discarding_) {
    const auto stop = buffer_.find_first_of("<>", begin_);
    if (stop == std::string::npos) {
      begin_ = buffer_.size();
      return std::nullopt;
    }
    begin_ = buffer_[stop] == '>' ? stop + 1 : stop;
    discarding_ = false;
  }
  while (begin_ < buffer_.size() && is_space(buffer_[begin_])) ++begin_;
  if (begin_ == buffer_.size()) return std::nullopt;
  if (buffer_[begin_] != '<') return skip_stray_text();
  const auto close = buffer_.find('>', begin_ + 1);
  const auto reopen = buffer_.find('<', begin_ + 1);
  if (reopen < close) {
    const std::string fragment = printable(trim(std::string_view(buffer_).substr(
        begin_ + 1, std::min<std::size_t>(reopen - begin_ - 1, 40))));
    begin_ = reopen;
    return Item{ParseError{"message '" + fragment + "' was not closed before the next one began"}};
  }
  const std::size_t length = close == std::string::npos ? pending() : close + 1 - begin_;
  if (length > kMaxMessageLength) {
    discarding_ = close == std::string::npos;
    begin_ = close == std::string::npos ? buffer_.size() : close + 1;
    return Item{ParseError{"message longer than " + std::to_string(kMaxMessageLength) +
                           " characters dropped"}};
  }
  if (close == std::string::npos) return std::nullopt;
  std::string message = buffer_.substr(begin_, length);
  begin_ = close + 1;
  return Item{std::move(message)};
}

std::optional<MessageSplitter::Item> MessageSplitter::skip_stray_text() {
  const auto open = buffer_.find('<', begin_);
  const std::size_t end = open == std::string::npos ? buffer_.size() : open;
  const std::string_view raw = std::string_view(buffer_).substr(begin_, end - begin_);
  const std::string stray = printable(trim(raw.substr(0, std::min<std::size_t>(raw.size(), 40))));
  const bool http = looks_like_http_request(raw);
  begin_ = end;
  return Item{ParseError{"unexpected text '" + stray + "' between messages", true, http}};
}

std::string escaped(std::string_view text) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte <= 0x7E && c != '\\') {
      out += c;
    } else {
      out += "\\x";
      out += kHex[byte >> 4U];
      out += kHex[byte & 0xFU];
    }
  }
  return out;
}

}  // namespace marsokhod::bus::socketcand
