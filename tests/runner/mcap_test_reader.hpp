// A reader of the MCAP files McapWriter writes, for the tests: records, their fields, and the
// checks of the specification that a reader may make (magic, CRCs, offsets).
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "runner/mcap_writer.hpp"

namespace marsokhod::runner::test {

class Cursor {
 public:
  // Keeps its own copy: a field read from another cursor may be a temporary.
  explicit Cursor(std::string_view bytes) : bytes_(bytes) {}
  template <typename T>
  T get() {
    need(sizeof(T));
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      v |= static_cast<std::uint64_t>(static_cast<std::uint8_t>(bytes_[at_ + i])) << (8 * i);
    }
    at_ += sizeof(T);
    return static_cast<T>(v);
  }
  std::string bytes(std::size_t n) {
    need(n);
    std::string out(bytes_.substr(at_, n));
    at_ += n;
    return out;
  }
  std::string string() { return bytes(get<std::uint32_t>()); }
  std::map<std::string, std::string> string_map() {
    Cursor entries(string());
    std::map<std::string, std::string> out;
    while (!entries.done()) {
      std::string key = entries.string();
      out[key] = entries.string();
    }
    return out;
  }
  std::string rest() { return bytes(bytes_.size() - at_); }
  bool done() const { return at_ == bytes_.size(); }
  std::size_t at() const { return at_; }

 private:
  void need(std::size_t n) const {
    if (at_ + n > bytes_.size()) throw std::runtime_error("mcap: record ends early");
  }
  std::string bytes_;
  std::size_t at_ = 0;
};

struct Record {
  std::uint8_t opcode = 0;
  std::uint64_t offset = 0;  // of its opcode in the file (or in its chunk)
  std::string content;
};

// The records of `bytes` one after the other.
inline std::vector<Record> records_of(std::string_view bytes, std::uint64_t base = 0) {
  std::vector<Record> out;
  Cursor c(bytes);
  while (!c.done()) {
    Record r;
    r.offset = base + c.at();
    r.opcode = c.get<std::uint8_t>();
    r.content = c.bytes(c.get<std::uint64_t>());
    out.push_back(std::move(r));
  }
  return out;
}

struct Message {
  std::uint16_t channel = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
  std::string data;
};

struct McapFile {
  std::string profile, library;
  std::vector<Record> top;  // the records between the magics
  std::map<std::uint16_t, std::map<std::string, std::string>> schemas;   // name, encoding, data
  std::map<std::uint16_t, std::map<std::string, std::string>> channels;  // topic, encoding, schema
  std::vector<Message> messages;  // in file order, from the chunks
};

// Parses and checks a whole file; throws std::runtime_error saying what is wrong.
inline McapFile read_mcap(const std::string& file) {
  auto fail = [](const std::string& what) { throw std::runtime_error("mcap: " + what); };
  const std::string magic(mcap::kMagic, mcap::kMagicSize);
  if (file.size() < 2 * magic.size() || file.compare(0, 8, magic) != 0 ||
      file.compare(file.size() - 8, 8, magic) != 0) {
    fail("no magic at both ends");
  }
  McapFile out;
  out.top = records_of(std::string_view(file).substr(8, file.size() - 16), 8);
  if (out.top.empty() || out.top.front().opcode != mcap::kHeader) fail("no header first");
  if (out.top.back().opcode != mcap::kFooter) fail("no footer last");
  Cursor header(out.top.front().content);
  out.profile = header.string();
  out.library = header.string();
  for (const Record& r : out.top) {
    if (r.opcode == mcap::kDataEnd) {
      Cursor c(r.content);
      if (c.get<std::uint32_t>() != crc32(std::string_view(file).substr(0, r.offset))) {
        fail("data section CRC");
      }
      break;
    }
    if (r.opcode != mcap::kChunk) continue;
    Cursor c(r.content);
    const auto start = c.get<std::uint64_t>();
    const auto end = c.get<std::uint64_t>();
    const auto size = c.get<std::uint64_t>();
    const auto crc = c.get<std::uint32_t>();
    if (!c.string().empty()) fail("compressed chunk");
    const std::string records = c.bytes(c.get<std::uint64_t>());
    if (records.size() != size || crc32(records) != crc) fail("chunk size or CRC");
    for (const Record& inner : records_of(records)) {
      Cursor m(inner.content);
      if (inner.opcode == mcap::kSchema) {
        const auto id = m.get<std::uint16_t>();
        out.schemas[id]["name"] = m.string();
        out.schemas[id]["encoding"] = m.string();
        out.schemas[id]["data"] = m.string();
      } else if (inner.opcode == mcap::kChannel) {
        const auto id = m.get<std::uint16_t>();
        out.channels[id]["schema"] = std::to_string(m.get<std::uint16_t>());
        out.channels[id]["topic"] = m.string();
        out.channels[id]["encoding"] = m.string();
      } else if (inner.opcode == mcap::kMessage) {
        Message msg;
        msg.channel = m.get<std::uint16_t>();
        msg.sequence = m.get<std::uint32_t>();
        msg.log_time = m.get<std::uint64_t>();
        msg.publish_time = m.get<std::uint64_t>();
        msg.data = m.rest();
        if (msg.log_time < start || msg.log_time > end) fail("message outside its chunk's times");
        out.messages.push_back(std::move(msg));
      }
    }
  }
  Cursor footer(out.top.back().content);
  const auto summary_start = footer.get<std::uint64_t>();
  footer.get<std::uint64_t>();
  const auto summary_crc = footer.get<std::uint32_t>();
  const std::uint64_t footer_at = out.top.back().offset;
  if (crc32(std::string_view(file).substr(summary_start, footer_at + 1 + 8 + 16 - summary_start)) !=
      summary_crc) {
    fail("summary CRC");
  }
  return out;
}

}  // namespace marsokhod::runner::test
