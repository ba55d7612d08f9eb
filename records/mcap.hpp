#pragma once
// run.mcap: the fleet's DDS samples as an MCAP file (format version 0, the published MCAP
// specification). Layout written here:
//   magic, Header, Schema and Channel records, Chunks (each followed by one MessageIndex per
//   channel it holds), DataEnd, summary section (Schemas, Channels, ChunkIndexes, Statistics),
//   summary-offset section (one SummaryOffset per group), Footer, magic.
// Chunks are compressed as the writer is told ("" none, "zstd" or "lz4": records/compression);
// every chunk carries the CRC-32 of its uncompressed records,
// DataEnd the CRC-32 of the file up to it and the Footer that of the summary sections. Times are
// nanoseconds since the Unix epoch. The reader is the writer's counterpart for tests and tools:
// it checks every CRC and the indexes against the chunks it reads.
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "records/csv.hpp"

namespace maptr::records::mcap {

/// The file's leading and trailing magic bytes (format version 0).
inline const std::string kMagic("\x89MCAP0\r\n", 8);

/// Record opcodes of the specification (those written or read here).
namespace op {
inline constexpr uint8_t kHeader = 0x01, kFooter = 0x02, kSchema = 0x03, kChannel = 0x04, kMessage = 0x05,
                         kChunk = 0x06, kMessageIndex = 0x07, kChunkIndex = 0x08, kStatistics = 0x0B,
                         kSummaryOffset = 0x0E, kDataEnd = 0x0F;
}  // namespace op

/// A message's type: `encoding` "omgidl" with the IDL text as `data`, `name` the type's fully
/// qualified name (e.g. "maptr::msg::PlantTick").
struct Schema {
  uint16_t id = 0;
  std::string name, encoding, data;
};

/// A topic: its schema and how its messages are encoded ("cdr").
struct Channel {
  uint16_t id = 0;
  uint16_t schema_id = 0;
  std::string topic, message_encoding;
  std::map<std::string, std::string> metadata;
};

/// One message; `data` holds its bytes (for "cdr": the encapsulation header and the CDR body).
struct Message {
  uint16_t channel_id = 0;
  uint32_t sequence = 0;
  uint64_t log_time_ns = 0, publish_time_ns = 0;
  std::string data;
};

/// The Statistics record of the summary section.
struct Statistics {
  uint64_t message_count = 0;
  uint16_t schema_count = 0;
  uint32_t channel_count = 0, chunk_count = 0;
  uint64_t message_start_ns = 0, message_end_ns = 0;
  std::map<uint16_t, uint64_t> channel_message_counts;
};

/// Writes an MCAP file: schemas and channels first, then messages (buffered into chunks of
/// about `chunk_bytes`), then close() writes the summary. Throws RecordError when the file
/// cannot be written or a message names an unknown channel.
class Writer {
 public:
  static constexpr std::size_t kDefaultChunkBytes = 1u << 20;

  /// `compression`: the chunks' MCAP compression ("", "zstd" or "lz4").
  Writer(const std::string& path, const std::string& profile, const std::string& library,
         std::size_t chunk_bytes = kDefaultChunkBytes, const std::string& compression = "");
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  /// Returns the new schema's id (1, 2, ...).
  uint16_t add_schema(const std::string& name, const std::string& encoding, const std::string& data);
  /// Returns the new channel's id (0, 1, ...). A channel may be added after messages of others
  /// (its record then precedes the chunk that holds its first message).
  uint16_t add_channel(uint16_t schema_id, const std::string& topic, const std::string& message_encoding,
                       const std::map<std::string, std::string>& metadata = {});
  void write(const Message& m);
  /// Ends the data section and writes the summary, footer and magic (once; also on destruction).
  void close();
  uint64_t message_count() const { return stats_.message_count; }

 private:
  struct ChunkIndex {
    uint64_t start_ns, end_ns, offset, length, index_length, size, compressed_size;
    std::map<uint16_t, uint64_t> index_offsets;
  };
  void put(const std::string& bytes);
  void flush_chunk();
  std::string summary_group(uint8_t opcode) const;

  std::FILE* f_ = nullptr;
  std::string path_;
  std::size_t chunk_bytes_;
  std::string compression_;
  uint64_t offset_ = 0;
  uint32_t data_crc_ = 0;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::string chunk_;  // records of the open chunk
  uint64_t chunk_start_ns_ = 0, chunk_end_ns_ = 0;
  std::map<uint16_t, std::vector<std::pair<uint64_t, uint64_t>>> chunk_index_;  // (log time, offset)
  std::vector<ChunkIndex> chunks_;
  Statistics stats_;
  bool closed_ = false;
};

/// What a file holds, read back through its summary and chunk indexes.
struct File {
  std::string profile, library;
  std::map<uint16_t, Schema> schemas;
  std::map<uint16_t, Channel> channels;
  std::vector<Message> messages;  ///< every message, chunk by chunk, in file order
  Statistics statistics;
};

/// Reads a file written by Writer (or any indexed MCAP file whose chunks are uncompressed or
/// compressed with zstd or lz4). Throws RecordError
/// naming the file and what is wrong: bad magic, a CRC that does not match, a chunk index or
/// message index that does not point at its records, statistics that disagree with the messages.
File read_file(const std::string& path);

/// CRC-32 (ISO-HDLC, as zlib and the MCAP specification use) of `bytes`, continuing `crc`.
uint32_t crc32(const std::string& bytes, uint32_t crc = 0);

}  // namespace maptr::records::mcap
