#include "bus/socketcand_protocol.hpp"

#include <gtest/gtest.h>

#include <random>

namespace marsokhod::bus::socketcand {
namespace {

Message message_of(std::string_view text) {
  auto parsed = parse_message(text);
  if (auto* e = std::get_if<ParseError>(&parsed)) ADD_FAILURE() << text << ": " << e->reason;
  if (auto* m = std::get_if<Message>(&parsed)) return *m;
  return Unsupported{};
}

std::string error_of(std::string_view text) {
  auto parsed = parse_message(text);
  if (auto* e = std::get_if<ParseError>(&parsed)) return e->reason;
  ADD_FAILURE() << text << " was accepted";
  return "";
}

protocol::CanFrame frame(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
  protocol::CanFrame f;
  f.id = id;
  f.dlc = static_cast<std::uint8_t>(bytes.size());
  std::copy(bytes.begin(), bytes.end(), f.data.begin());
  return f;
}

TEST(SocketcandProtocol, ParsesTheHandshake) {
  EXPECT_EQ(message_of("< hi >"), Message{Hi{}});
  EXPECT_EQ(message_of("< open can0 >"), Message{Open{"can0"}});
  EXPECT_EQ(message_of("< ok >"), Message{Ok{}});
  EXPECT_EQ(message_of("< rawmode >"), Message{RawMode{}});
  EXPECT_EQ(message_of("< echo >"), Message{Echo{}});
  EXPECT_EQ(message_of("<hi>"), Message{Hi{}});  // lenient on spacing, strict when writing
}

TEST(SocketcandProtocol, ParsesSendAsPythonCanWritesIt) {
  // python-can 4: f"< send {id:X} {dlc:X} {' '.join('{:x}'.format(b))} >", bytes unpadded.
  EXPECT_EQ(message_of("< send 180 3 3 1 2c >"),
            Message(Send{frame(0x180, {0x03, 0x01, 0x2C}), false}));
  EXPECT_EQ(message_of("< send 418 0  >"), Message(Send{frame(0x418, {}), false}));
  // socketcand's protocol.md example with an extended identifier.
  EXPECT_EQ(message_of("< send 1AAAAAAA 2 1 F1 >"),
            Message(Send{frame(0x1AAAAAAA, {0x01, 0xF1}), true}));
}

TEST(SocketcandProtocol, ParsesFramesAsSocketcandWritesThem) {
  const auto parsed = message_of("< frame 188 1436509052.249713 0001000200038005 >");
  const auto& f = std::get<Frame>(parsed);
  EXPECT_EQ(f.frame, frame(0x188, {0x00, 0x01, 0x00, 0x02, 0x00, 0x03, 0x80, 0x05}));
  EXPECT_DOUBLE_EQ(f.time_s, 1436509052.249713);
  EXPECT_FALSE(f.extended);
  // socketcand's protocol.md writes the bytes separately; an empty frame leaves two spaces.
  EXPECT_EQ(std::get<Frame>(message_of("< frame 123 23.424242 11 22 33 44 >")).frame,
            frame(0x123, {0x11, 0x22, 0x33, 0x44}));
  EXPECT_EQ(std::get<Frame>(message_of("< frame 418 1.000000  >")).frame, frame(0x418, {}));
}

TEST(SocketcandProtocol, ErrorsAndUnknownCommands) {
  EXPECT_EQ(message_of("< error could not open bus >"), Message{Error{"could not open bus"}});
  EXPECT_EQ(message_of("< bcmmode >"), Message{Unsupported{"bcmmode"}});
  EXPECT_EQ(message_of("< fdframe 123 00 1.0 11 >"), Message{Unsupported{"fdframe"}});
}

TEST(SocketcandProtocol, RejectsMalformedMessages) {
  EXPECT_EQ(error_of("hi"), "expected a message in angle brackets, e.g. '< hi >'");
  EXPECT_EQ(error_of("< >"), "empty message");
  EXPECT_EQ(error_of("< hi there >"), "hi: takes no arguments");
  EXPECT_EQ(error_of("< open >"), "open: expected one bus name of 1-16 characters");
  EXPECT_EQ(error_of("< open averyveryverylongbus >"),
            "open: expected one bus name of 1-16 characters");
  EXPECT_EQ(error_of("< send 180 >"), "send: expected an identifier, a DLC and DLC data bytes");
  EXPECT_EQ(error_of("< send 18G 0 >"), "send: identifier '18G' is not 1-8 hex digits");
  EXPECT_EQ(error_of("< send 800 0 >"),
            "send: identifier 800 exceeds 7FF (an extended identifier has 8 hex digits)");
  EXPECT_EQ(error_of("< send 180 9 1 2 3 4 5 6 7 8 9 >"), "send: DLC 9 exceeds 8 (classic CAN)");
  EXPECT_EQ(error_of("< send 180 x >"), "send: DLC 'x' is not a number 0..8");
  EXPECT_EQ(error_of("< send 180 3 01 02 >"), "send: DLC 3 but 2 data bytes");
  EXPECT_EQ(error_of("< send 180 2 zz 01 >"), "send: data byte 'zz' is not 1-2 hex digits");
  EXPECT_EQ(error_of("< send 180 1 123 >"), "send: data byte '123' is not 1-2 hex digits");
  EXPECT_EQ(error_of("< frame 188 abc 00 >"), "frame: timestamp 'abc' is not SECONDS.USECONDS");
  EXPECT_EQ(error_of("< frame 188 -1.0 00 >"), "frame: timestamp '-1.0' is not SECONDS.USECONDS");
  EXPECT_EQ(error_of("< frame 188 1.0 0 >"), "frame: data '0' has an odd number of hex digits");
  EXPECT_EQ(error_of("< frame 188 1.0 0G >"), "frame: data '0G' is not hexadecimal");
  EXPECT_EQ(error_of("< frame 188 1.0 000102030405060708 >"),
            "frame: 9 data bytes exceed 8 (classic CAN)");
}

TEST(SocketcandProtocol, FormatsExactlyLikeSocketcand) {
  EXPECT_EQ(format_message(Hi{}), "< hi >");
  EXPECT_EQ(format_message(Ok{}), "< ok >");
  EXPECT_EQ(format_message(Open{"can0"}), "< open can0 >");
  EXPECT_EQ(format_message(RawMode{}), "< rawmode >");
  EXPECT_EQ(format_message(Frame{frame(0x180, {0x03, 0x01, 0x2C}), 1436509052.249713, false}),
            "< frame 180 1436509052.249713 03012C >");
  EXPECT_EQ(format_message(Frame{frame(0x418, {}), 2.5, false}), "< frame 418 2.500000  >");
  EXPECT_EQ(format_message(Frame{frame(0x1AAAAAAA, {0xF1}), 0.0, true}),
            "< frame 1AAAAAAA 0.000000 F1 >");
  EXPECT_EQ(format_message(Send{frame(0x180, {0x03, 0x01, 0x2C}), false}),
            "< send 180 3 03 01 2C >");
  EXPECT_EQ(format_message(Send{frame(0x418, {}), false}), "< send 418 0 >");
  EXPECT_EQ(format_message(Error{"bad <frame>\n µ"}), "< error bad ?frame?? ?? >");  // ASCII only
}

TEST(SocketcandProtocol, RoundsTimeToTheMicrosecond) {
  EXPECT_EQ(format_message(Frame{frame(0x1, {}), 0.0000004, false}), "< frame 001 0.000000  >");
  EXPECT_EQ(format_message(Frame{frame(0x1, {}), 0.9999996, false}), "< frame 001 1.000000  >");
  EXPECT_EQ(format_message(Frame{frame(0x1, {}), 12.0000016, false}), "< frame 001 12.000002  >");
}

TEST(SocketcandProtocol, FormatRejectsWhatTheWireCannotCarry) {
  EXPECT_THROW(format_message(Frame{frame(0x800, {}), 0.0, false}), std::invalid_argument);
  EXPECT_THROW(format_message(Frame{frame(0x180, {}), -1.0, false}), std::invalid_argument);
  EXPECT_THROW(format_message(Frame{frame(0x180, {}), std::nan(""), false}), std::invalid_argument);
  protocol::CanFrame too_long = frame(0x180, {});
  too_long.dlc = 9;
  EXPECT_THROW(format_message(Send{too_long, false}), std::invalid_argument);
  EXPECT_THROW(format_message(Open{"can 0"}), std::invalid_argument);
}

TEST(SocketcandProtocol, SendAndFrameRoundTripForRandomFrames) {
  std::mt19937 random(7);
  for (int i = 0; i < 1000; ++i) {
    protocol::CanFrame f;
    f.id = random() % 0x800;
    f.dlc = static_cast<std::uint8_t>(random() % 9);
    for (std::size_t b = 0; b < f.dlc; ++b) f.data[b] = static_cast<std::uint8_t>(random());
    const double time_s =
        static_cast<double>(random() % 2000000000) + static_cast<double>(random() % 1000000) * 1e-6;
    EXPECT_EQ(message_of(format_message(Send{f, false})), Message(Send{f, false}));
    const auto back = std::get<Frame>(message_of(format_message(Frame{f, time_s, false})));
    EXPECT_EQ(back.frame, f);
    EXPECT_NEAR(back.time_s, time_s, 1e-6);
  }
}

std::vector<std::string> split_all(MessageSplitter& splitter) {
  std::vector<std::string> items;
  while (auto item = splitter.next()) {
    if (auto* text = std::get_if<std::string>(&*item)) {
      items.push_back(*text);
    } else {
      items.push_back("!" + std::get<ParseError>(*item).reason);
    }
  }
  return items;
}

TEST(SocketcandSplitter, SplitsAStreamWithoutSeparators) {
  MessageSplitter splitter;
  splitter.append("< hi >< ok >\n< frame 180 1.0 01 ");
  EXPECT_EQ(split_all(splitter), (std::vector<std::string>{"< hi >", "< ok >"}));
  EXPECT_GT(splitter.pending(), 0u);
  splitter.append(">");
  EXPECT_EQ(split_all(splitter), (std::vector<std::string>{"< frame 180 1.0 01 >"}));
  EXPECT_EQ(splitter.pending(), 0u);
}

TEST(SocketcandSplitter, ResynchronisesAfterGarbage) {
  MessageSplitter splitter;
  splitter.append("GET / HTTP/1.1\r\n< hi >< open can0 < ok >");
  EXPECT_EQ(split_all(splitter),
            (std::vector<std::string>{
                "!unexpected text 'GET / HTTP/1.1' between messages", "< hi >",
                "!message 'open can0' was not closed before the next one began", "< ok >"}));
}

TEST(SocketcandSplitter, DropsOverlongMessagesAndRecovers) {
  MessageSplitter splitter;
  splitter.append("< " + std::string(kMaxMessageLength, 'x'));
  EXPECT_EQ(split_all(splitter),
            (std::vector<std::string>{"!message longer than 256 characters dropped"}));
  splitter.append(std::string(1000, 'y') + " >< hi >");
  EXPECT_EQ(split_all(splitter), (std::vector<std::string>{"< hi >"}));
  EXPECT_LT(splitter.pending(), kMaxMessageLength);
}

TEST(SocketcandSplitter, ByteByByteGivesTheSameMessages) {
  const std::string stream = "< hi >< frame 188 1.000000 0001000200038005 >  < error x >";
  MessageSplitter splitter;
  std::vector<std::string> items;
  for (char c : stream) {
    splitter.append(std::string_view(&c, 1));
    for (auto& item : split_all(splitter)) items.push_back(item);
  }
  EXPECT_EQ(items, (std::vector<std::string>{"< hi >", "< frame 188 1.000000 0001000200038005 >",
                                             "< error x >"}));
}

}  // namespace
}  // namespace marsokhod::bus::socketcand
