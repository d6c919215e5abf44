// A small MCAP writer (https://mcap.dev/spec, major version 0: magic 0x89 "MCAP0\r\n"), for the
// recordings' recording.mcap. Debian 12 packages no MCAP library, so this is written from the
// specification: little-endian records <opcode u8><length u64><content>.
//
// Layout written:
//   Magic Header
//   data section:   Chunks (uncompressed, up to chunk_size bytes of records each: the Schemas
//                   and Channels as they are added, the Messages) each followed by its Message
//                   Index records; Attachments and Metadata between chunks; Data End (CRC-32 of
//                   every byte before it, the leading magic included)
//   summary:        Schemas, Channels, Statistics, Chunk Indexes, Attachment Indexes,
//                   Metadata Indexes
//   summary offsets: one Summary Offset per group of the summary
//   Footer (summary CRC: the summary and summary offset sections and the footer up to its CRC)
//   Magic
// Nothing in it depends on the wall clock: the same calls give the same bytes.
#pragma once

#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace marsokhod::runner {

// CRC-32 (IEEE 802.3, reflected polynomial 0xEDB88320), as zlib's crc32(); `crc` continues one.
std::uint32_t crc32(std::string_view bytes, std::uint32_t crc = 0);

namespace mcap {

inline constexpr char kMagic[] = "\x89MCAP0\r\n";
inline constexpr std::size_t kMagicSize = 8;

enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

}  // namespace mcap

class McapWriter {
 public:
  // Writes the magic and the Header to `out` (binary). The stream must outlive the writer.
  McapWriter(std::ostream& out, std::string profile, std::string library,
             std::size_t chunk_size = 1 << 20);
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;
  ~McapWriter();  // finish()es if not yet done (errors then go unreported)

  // Ids from 1 in the order added.
  std::uint16_t add_schema(const std::string& name, const std::string& encoding,
                           const std::string& data);
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic,
                            const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata = {});
  // Times in nanoseconds; each channel's sequence numbers count from 0.
  void write_message(std::uint16_t channel_id, std::uint64_t log_time_ns,
                     std::uint64_t publish_time_ns, std::string_view data);
  void write_attachment(const std::string& name, const std::string& media_type,
                        std::uint64_t log_time_ns, std::string_view data);
  void write_metadata(const std::string& name, const std::map<std::string, std::string>& entries);
  // Closes the last chunk, writes the summary, footer and magic and flushes. Throws
  // std::runtime_error when the stream failed; nothing may be written after it.
  void finish();

  std::uint64_t message_count() const { return message_count_; }

 private:
  struct ChunkIndex {
    std::uint64_t start_ns, end_ns, offset, length;
    std::map<std::uint16_t, std::uint64_t> message_index_offsets;
    std::uint64_t message_index_length, uncompressed_size;
  };
  struct Index {
    std::uint64_t offset, length;
    std::string record;  // the index record's content, written in the summary
  };

  void emit(std::string_view bytes);              // to the file, counted in the data CRC
  void emit_record(std::uint8_t opcode, const std::string& content);
  void flush_chunk();

  std::ostream* out_;
  std::size_t chunk_size_;
  std::uint64_t position_ = 0;
  std::uint32_t data_crc_ = 0;
  bool finished_ = false;

  std::vector<std::string> schemas_;   // record contents, for the summary
  std::vector<std::string> channels_;
  std::map<std::uint16_t, std::uint32_t> sequence_;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts_;
  std::uint64_t message_count_ = 0;
  std::uint64_t start_ns_ = 0, end_ns_ = 0;

  // The open chunk: its records and, per channel, (log time, offset in the records).
  std::string chunk_;
  std::uint64_t chunk_start_ns_ = 0, chunk_end_ns_ = 0;
  bool chunk_has_messages_ = false;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;

  std::vector<ChunkIndex> chunk_indexes_;
  std::vector<Index> attachment_indexes_;
  std::vector<Index> metadata_indexes_;
};

}  // namespace marsokhod::runner
