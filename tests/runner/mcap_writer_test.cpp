#include "runner/mcap_writer.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "mcap_test_reader.hpp"

namespace marsokhod::runner {
namespace {

using test::Cursor;
using test::Record;

TEST(Crc32, IsZlibsCrc) {
  EXPECT_EQ(crc32("123456789"), 0xCBF43926U);
  EXPECT_EQ(crc32(""), 0U);
  EXPECT_EQ(crc32("6789", crc32("12345")), 0xCBF43926U);  // continued
}

// Two channels, messages over several small chunks, an attachment and metadata in between.
std::string sample(std::size_t chunk_size) {
  std::ostringstream out;
  McapWriter w(out, "", "marsokhod test", chunk_size);
  const auto schema = w.add_schema("Value", "jsonschema", R"({"type":"object"})");
  const auto a = w.add_channel(schema, "/a", "json", {{"k", "v"}});
  const auto b = w.add_channel(schema, "/b", "json");
  for (std::uint64_t k = 0; k < 40; ++k) {
    w.write_message(a, 1000 * k, 1000 * k, "{\"v\":" + std::to_string(k) + "}");
    if (k % 4 == 0) w.write_message(b, 1000 * k + 1, 1000 * k + 1, "{}");
    if (k == 20) {
      w.write_attachment("config.toml", "application/toml", 20000, "a = 1\n");
      w.write_metadata("marsokhod", {{"seed", "1"}});
    }
  }
  w.finish();
  EXPECT_EQ(w.message_count(), 50u);
  return out.str();
}

TEST(McapWriter, RoundTripsMessagesSchemasAndChannels) {
  const std::string file = sample(256);
  const test::McapFile f = test::read_mcap(file);
  EXPECT_EQ(f.library, "marsokhod test");
  ASSERT_EQ(f.schemas.size(), 1u);
  EXPECT_EQ(f.schemas.at(1).at("encoding"), "jsonschema");
  EXPECT_EQ(f.schemas.at(1).at("data"), R"({"type":"object"})");
  ASSERT_EQ(f.channels.size(), 2u);
  EXPECT_EQ(f.channels.at(1).at("topic"), "/a");
  EXPECT_EQ(f.channels.at(2).at("encoding"), "json");
  EXPECT_EQ(f.channels.at(2).at("schema"), "1");
  ASSERT_EQ(f.messages.size(), 50u);
  std::uint32_t a = 0, b = 0;
  for (const test::Message& m : f.messages) {
    if (m.channel == 1) {
      EXPECT_EQ(m.sequence, a);
      EXPECT_EQ(m.log_time, 1000u * a);
      EXPECT_EQ(m.data, "{\"v\":" + std::to_string(a) + "}");
      ++a;
    } else {
      EXPECT_EQ(m.sequence, b++);
      EXPECT_EQ(m.data, "{}");
    }
  }
  EXPECT_EQ(a, 40u);
  EXPECT_EQ(b, 10u);
}

TEST(McapWriter, SummaryOffsetsAndIndexesPointAtTheirRecords) {
  const std::string file = sample(256);
  const test::McapFile f = test::read_mcap(file);
  std::map<std::uint64_t, const Record*> at;
  for (const Record& r : f.top) at[r.offset] = &r;
  Cursor footer(f.top.back().content);
  const auto summary_start = footer.get<std::uint64_t>();
  const auto summary_offset_start = footer.get<std::uint64_t>();
  ASSERT_TRUE(at.count(summary_start));
  EXPECT_EQ(at.at(summary_start)->opcode, mcap::kSchema);
  ASSERT_TRUE(at.count(summary_offset_start));
  std::map<std::uint8_t, int> group_records;
  std::size_t chunks = 0, chunk_indexes = 0;
  for (const Record& r : f.top) chunks += r.opcode == mcap::kChunk ? 1 : 0;
  EXPECT_GT(chunks, 3u);  // 256-byte chunks
  for (const Record& r : f.top) {
    if (r.opcode == mcap::kSummaryOffset) {
      Cursor c(r.content);
      const auto opcode = c.get<std::uint8_t>();
      const auto start = c.get<std::uint64_t>();
      const auto length = c.get<std::uint64_t>();
      // The group is exactly the records of that opcode from start to start + length.
      for (std::uint64_t o = start; o < start + length;) {
        ASSERT_TRUE(at.count(o)) << int(opcode);
        EXPECT_EQ(at.at(o)->opcode, opcode);
        ++group_records[opcode];
        o += 9 + at.at(o)->content.size();
      }
    }
    if (r.opcode == mcap::kStatistics) {
      Cursor c(r.content);
      EXPECT_EQ(c.get<std::uint64_t>(), 50u);   // messages
      EXPECT_EQ(c.get<std::uint16_t>(), 1u);    // schemas
      EXPECT_EQ(c.get<std::uint32_t>(), 2u);    // channels
      EXPECT_EQ(c.get<std::uint32_t>(), 1u);    // attachments
      EXPECT_EQ(c.get<std::uint32_t>(), 1u);    // metadata
      EXPECT_EQ(c.get<std::uint32_t>(), chunks);
      EXPECT_EQ(c.get<std::uint64_t>(), 0u);    // first log time
      EXPECT_EQ(c.get<std::uint64_t>(), 39000u);
      Cursor counts(c.string());
      EXPECT_EQ(counts.get<std::uint16_t>(), 1u);
      EXPECT_EQ(counts.get<std::uint64_t>(), 40u);
      EXPECT_EQ(counts.get<std::uint16_t>(), 2u);
      EXPECT_EQ(counts.get<std::uint64_t>(), 10u);
    }
    if (r.opcode == mcap::kChunkIndex) {
      ++chunk_indexes;
      Cursor c(r.content);
      const auto start = c.get<std::uint64_t>();
      const auto end = c.get<std::uint64_t>();
      const auto offset = c.get<std::uint64_t>();
      const auto length = c.get<std::uint64_t>();
      ASSERT_TRUE(at.count(offset));
      const Record& chunk = *at.at(offset);
      EXPECT_EQ(chunk.opcode, mcap::kChunk);
      EXPECT_EQ(length, 9 + chunk.content.size());
      Cursor chunk_fields(chunk.content);
      EXPECT_EQ(chunk_fields.get<std::uint64_t>(), start);
      EXPECT_EQ(chunk_fields.get<std::uint64_t>(), end);
      chunk_fields.get<std::uint64_t>();
      chunk_fields.get<std::uint32_t>();
      chunk_fields.string();
      const std::string records = chunk_fields.bytes(chunk_fields.get<std::uint64_t>());
      Cursor offsets(c.string());
      while (!offsets.done()) {
        const auto channel = offsets.get<std::uint16_t>();
        const auto index_at = offsets.get<std::uint64_t>();
        ASSERT_TRUE(at.count(index_at));
        const Record& index = *at.at(index_at);
        ASSERT_EQ(index.opcode, mcap::kMessageIndex);
        Cursor entries(index.content);
        EXPECT_EQ(entries.get<std::uint16_t>(), channel);
        Cursor pairs(entries.string());
        while (!pairs.done()) {
          const auto time = pairs.get<std::uint64_t>();
          const auto in_chunk = pairs.get<std::uint64_t>();
          // The offset inside the chunk's records: a Message of this channel at this time.
          Cursor m(std::string_view(records).substr(in_chunk));
          EXPECT_EQ(m.get<std::uint8_t>(), mcap::kMessage);
          m.get<std::uint64_t>();
          EXPECT_EQ(m.get<std::uint16_t>(), channel);
          m.get<std::uint32_t>();
          EXPECT_EQ(m.get<std::uint64_t>(), time);
        }
      }
    }
    if (r.opcode == mcap::kAttachmentIndex) {
      Cursor c(r.content);
      const auto offset = c.get<std::uint64_t>();
      const auto length = c.get<std::uint64_t>();
      ASSERT_TRUE(at.count(offset));
      const Record& attachment = *at.at(offset);
      ASSERT_EQ(attachment.opcode, mcap::kAttachment);
      EXPECT_EQ(length, 9 + attachment.content.size());
      Cursor a(attachment.content);
      EXPECT_EQ(a.get<std::uint64_t>(), 20000u);
      a.get<std::uint64_t>();
      EXPECT_EQ(a.string(), "config.toml");
      EXPECT_EQ(a.string(), "application/toml");
      EXPECT_EQ(a.bytes(a.get<std::uint64_t>()), "a = 1\n");
      const auto crc = a.get<std::uint32_t>();
      EXPECT_EQ(crc, crc32(std::string_view(attachment.content).substr(0, attachment.content.size() - 4)));
    }
    if (r.opcode == mcap::kMetadataIndex) {
      Cursor c(r.content);
      const Record& metadata = *at.at(c.get<std::uint64_t>());
      ASSERT_EQ(metadata.opcode, mcap::kMetadata);
      Cursor m(metadata.content);
      EXPECT_EQ(m.string(), "marsokhod");
      EXPECT_EQ(m.string_map().at("seed"), "1");
    }
  }
  EXPECT_EQ(chunk_indexes, chunks);
  EXPECT_EQ(group_records[mcap::kSchema], 1);
  EXPECT_EQ(group_records[mcap::kChannel], 2);
  EXPECT_EQ(group_records[mcap::kStatistics], 1);
  EXPECT_EQ(group_records[mcap::kChunkIndex], static_cast<int>(chunks));
  EXPECT_EQ(group_records[mcap::kAttachmentIndex], 1);
  EXPECT_EQ(group_records[mcap::kMetadataIndex], 1);
}

TEST(McapWriter, SameCallsGiveTheSameBytes) {
  EXPECT_EQ(sample(256), sample(256));
  EXPECT_EQ(test::read_mcap(sample(1 << 20)).messages.size(), 50u);  // one chunk
}

TEST(McapWriter, ACorruptedByteIsFound) {
  std::string file = sample(256);
  file[40] = static_cast<char>(file[40] ^ 0x01);
  EXPECT_THROW(test::read_mcap(file), std::runtime_error);
}

TEST(McapWriter, EmptyFileIsValid) {
  std::ostringstream out;
  {
    McapWriter w(out, "", "x");
  }  // finished by the destructor
  const test::McapFile f = test::read_mcap(out.str());
  EXPECT_TRUE(f.messages.empty());
}

TEST(McapWriter, UnknownChannelIsRefused) {
  std::ostringstream out;
  McapWriter w(out, "", "x");
  EXPECT_THROW(w.write_message(1, 0, 0, "{}"), std::invalid_argument);
  EXPECT_THROW(w.add_channel(3, "/x", "json"), std::invalid_argument);
}

}  // namespace
}  // namespace marsokhod::runner
