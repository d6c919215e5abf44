#include "runner/mcap_writer.hpp"

#include <array>
#include <limits>
#include <stdexcept>
#include <tuple>

namespace marsokhod::runner {
namespace {

constexpr std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1U) != 0 ? 0xEDB88320U ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}
constexpr auto kCrcTable = make_crc_table();

template <typename T>
void put(std::string& out, T value) {
  for (std::size_t i = 0; i < sizeof(T); ++i) {
    out.push_back(static_cast<char>(static_cast<std::uint64_t>(value) >> (8 * i) & 0xFFU));
  }
}

void put_string(std::string& out, std::string_view text) {
  if (text.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::length_error("mcap: a string longer than 4 GiB");
  }
  put(out, static_cast<std::uint32_t>(text.size()));
  out += text;
}

void put_string_map(std::string& out, const std::map<std::string, std::string>& map) {
  std::string entries;
  for (const auto& [key, value] : map) {
    put_string(entries, key);
    put_string(entries, value);
  }
  put_string(out, entries);  // a map is its byte length, then its entries
}

std::string record(std::uint8_t opcode, const std::string& content) {
  std::string out;
  put(out, opcode);
  put(out, static_cast<std::uint64_t>(content.size()));
  return out + content;
}

}  // namespace

std::uint32_t crc32(std::string_view bytes, std::uint32_t crc) {
  crc = ~crc;
  for (const char byte : bytes) {
    crc = kCrcTable[(crc ^ static_cast<std::uint8_t>(byte)) & 0xFFU] ^ (crc >> 8);
  }
  return ~crc;
}

McapWriter::McapWriter(std::ostream& out, std::string profile, std::string library,
                       std::size_t chunk_size)
    : out_(&out), chunk_size_(chunk_size) {
  emit(std::string_view(mcap::kMagic, mcap::kMagicSize));
  std::string header;
  put_string(header, profile);
  put_string(header, library);
  emit_record(mcap::kHeader, header);
}

McapWriter::~McapWriter() {
  if (finished_) return;
  try {
    finish();
  } catch (const std::exception&) {
    // Reported by an explicit finish() only.
  }
}

void McapWriter::emit(std::string_view bytes) {
  out_->write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  data_crc_ = crc32(bytes, data_crc_);
  position_ += bytes.size();
}

void McapWriter::emit_record(std::uint8_t opcode, const std::string& content) {
  emit(record(opcode, content));
}

std::uint16_t McapWriter::add_schema(const std::string& name, const std::string& encoding,
                                     const std::string& data) {
  const auto id = static_cast<std::uint16_t>(schemas_.size() + 1);
  std::string content;
  put(content, id);
  put_string(content, name);
  put_string(content, encoding);
  put_string(content, data);
  schemas_.push_back(content);
  chunk_ += record(mcap::kSchema, content);
  return id;
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema_id, const std::string& topic,
                                      const std::string& message_encoding,
                                      const std::map<std::string, std::string>& metadata) {
  if (schema_id > schemas_.size()) throw std::invalid_argument("mcap: no schema " + std::to_string(schema_id));
  const auto id = static_cast<std::uint16_t>(channels_.size() + 1);
  std::string content;
  put(content, id);
  put(content, schema_id);
  put_string(content, topic);
  put_string(content, message_encoding);
  put_string_map(content, metadata);
  channels_.push_back(content);
  channel_message_counts_[id] = 0;
  chunk_ += record(mcap::kChannel, content);
  return id;
}

void McapWriter::write_message(std::uint16_t channel_id, std::uint64_t log_time_ns,
                               std::uint64_t publish_time_ns, std::string_view data) {
  if (channel_id == 0 || channel_id > channels_.size()) {
    throw std::invalid_argument("mcap: no channel " + std::to_string(channel_id));
  }
  std::string content;
  put(content, channel_id);
  put(content, sequence_[channel_id]++);
  put(content, log_time_ns);
  put(content, publish_time_ns);
  content += data;
  chunk_index_[channel_id].emplace_back(log_time_ns, chunk_.size());
  chunk_ += record(mcap::kMessage, content);
  if (!chunk_has_messages_ || log_time_ns < chunk_start_ns_) chunk_start_ns_ = log_time_ns;
  if (!chunk_has_messages_ || log_time_ns > chunk_end_ns_) chunk_end_ns_ = log_time_ns;
  chunk_has_messages_ = true;
  if (message_count_ == 0 || log_time_ns < start_ns_) start_ns_ = log_time_ns;
  if (message_count_ == 0 || log_time_ns > end_ns_) end_ns_ = log_time_ns;
  ++message_count_;
  ++channel_message_counts_[channel_id];
  if (chunk_.size() >= chunk_size_) flush_chunk();
}

void McapWriter::flush_chunk() {
  if (chunk_.empty()) return;
  ChunkIndex index{};
  index.start_ns = chunk_has_messages_ ? chunk_start_ns_ : 0;
  index.end_ns = chunk_has_messages_ ? chunk_end_ns_ : 0;
  index.offset = position_;
  index.uncompressed_size = chunk_.size();
  std::string content;
  put(content, index.start_ns);
  put(content, index.end_ns);
  put(content, static_cast<std::uint64_t>(chunk_.size()));
  put(content, crc32(chunk_));
  put_string(content, "");  // compression: none
  put(content, static_cast<std::uint64_t>(chunk_.size()));
  content += chunk_;
  emit_record(mcap::kChunk, content);
  index.length = position_ - index.offset;
  const std::uint64_t indexes_start = position_;
  for (const auto& [channel, entries] : chunk_index_) {
    std::string message_index;
    put(message_index, channel);
    put(message_index, static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [time, offset] : entries) {
      put(message_index, time);
      put(message_index, offset);
    }
    index.message_index_offsets[channel] = position_;
    emit_record(mcap::kMessageIndex, message_index);
  }
  index.message_index_length = position_ - indexes_start;
  chunk_indexes_.push_back(index);
  chunk_.clear();
  chunk_index_.clear();
  chunk_has_messages_ = false;
}

void McapWriter::write_attachment(const std::string& name, const std::string& media_type,
                                  std::uint64_t log_time_ns, std::string_view data) {
  flush_chunk();
  std::string content;
  put(content, log_time_ns);
  put(content, log_time_ns);  // create_time: the log time, never the wall clock
  put_string(content, name);
  put_string(content, media_type);
  put(content, static_cast<std::uint64_t>(data.size()));
  content += data;
  put(content, crc32(content));
  const std::uint64_t offset = position_;
  emit_record(mcap::kAttachment, content);
  std::string index;
  put(index, offset);
  put(index, position_ - offset);
  put(index, log_time_ns);
  put(index, log_time_ns);
  put(index, static_cast<std::uint64_t>(data.size()));
  put_string(index, name);
  put_string(index, media_type);
  attachment_indexes_.push_back({offset, position_ - offset, index});
}

void McapWriter::write_metadata(const std::string& name,
                                const std::map<std::string, std::string>& entries) {
  flush_chunk();
  std::string content;
  put_string(content, name);
  put_string_map(content, entries);
  const std::uint64_t offset = position_;
  emit_record(mcap::kMetadata, content);
  std::string index;
  put(index, offset);
  put(index, position_ - offset);
  put_string(index, name);
  metadata_indexes_.push_back({offset, position_ - offset, index});
}

void McapWriter::finish() {
  if (finished_) return;
  finished_ = true;
  flush_chunk();
  std::string data_end;
  put(data_end, data_crc_);
  emit_record(mcap::kDataEnd, data_end);

  // The summary: groups of records of one opcode each, with their offsets.
  const std::uint64_t summary_start = position_;
  std::uint32_t summary_crc = 0;
  std::vector<std::tuple<std::uint8_t, std::uint64_t, std::uint64_t>> groups;
  auto write_summary = [&](const std::string& bytes) {
    out_->write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    summary_crc = crc32(bytes, summary_crc);
    position_ += bytes.size();
  };
  auto group = [&](std::uint8_t opcode, const std::vector<std::string>& contents) {
    if (contents.empty()) return;
    const std::uint64_t start = position_;
    for (const std::string& c : contents) write_summary(record(opcode, c));
    groups.emplace_back(opcode, start, position_ - start);
  };
  group(mcap::kSchema, schemas_);
  group(mcap::kChannel, channels_);
  std::string statistics;
  put(statistics, message_count_);
  put(statistics, static_cast<std::uint16_t>(schemas_.size()));
  put(statistics, static_cast<std::uint32_t>(channels_.size()));
  put(statistics, static_cast<std::uint32_t>(attachment_indexes_.size()));
  put(statistics, static_cast<std::uint32_t>(metadata_indexes_.size()));
  put(statistics, static_cast<std::uint32_t>(chunk_indexes_.size()));
  put(statistics, start_ns_);
  put(statistics, end_ns_);
  std::string counts;
  for (const auto& [channel, count] : channel_message_counts_) {
    put(counts, channel);
    put(counts, count);
  }
  put_string(statistics, counts);
  group(mcap::kStatistics, {statistics});
  std::vector<std::string> chunk_records;
  for (const ChunkIndex& c : chunk_indexes_) {
    std::string content;
    put(content, c.start_ns);
    put(content, c.end_ns);
    put(content, c.offset);
    put(content, c.length);
    std::string offsets;
    for (const auto& [channel, offset] : c.message_index_offsets) {
      put(offsets, channel);
      put(offsets, offset);
    }
    put_string(content, offsets);
    put(content, c.message_index_length);
    put_string(content, "");
    put(content, c.uncompressed_size);  // compressed_size: the same, uncompressed
    put(content, c.uncompressed_size);
    chunk_records.push_back(content);
  }
  group(mcap::kChunkIndex, chunk_records);
  std::vector<std::string> attachment_records, metadata_records;
  for (const Index& i : attachment_indexes_) attachment_records.push_back(i.record);
  for (const Index& i : metadata_indexes_) metadata_records.push_back(i.record);
  group(mcap::kAttachmentIndex, attachment_records);
  group(mcap::kMetadataIndex, metadata_records);

  const std::uint64_t summary_offset_start = position_;
  for (const auto& [opcode, start, length] : groups) {
    std::string content;
    put(content, opcode);
    put(content, start);
    put(content, length);
    write_summary(record(mcap::kSummaryOffset, content));
  }
  std::string footer;
  put(footer, mcap::kFooter);
  put(footer, std::uint64_t{20});
  put(footer, summary_start);
  put(footer, summary_offset_start);
  summary_crc = crc32(footer, summary_crc);
  put(footer, summary_crc);
  out_->write(footer.data(), static_cast<std::streamsize>(footer.size()));
  out_->write(mcap::kMagic, static_cast<std::streamsize>(mcap::kMagicSize));
  position_ += footer.size() + mcap::kMagicSize;
  out_->flush();
  if (!*out_) throw std::runtime_error("mcap: the recording could not be written");
}

}  // namespace marsokhod::runner
