#include "records/mcap.hpp"

#include <zlib.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>

#include "records/compression.hpp"

namespace maptr::records::mcap {

using namespace op;

namespace {

/// Bytes of a record's opcode and length prefix.
constexpr std::size_t kRecordPrefix = 9;
/// Bytes of the Footer record's content (two offsets and a CRC).
constexpr std::size_t kFooterContent = 20;

/// Little-endian encoding of the specification's primitive types.
void put_le(std::string& out, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}
void u8(std::string& o, uint8_t v) { put_le(o, v, 1); }
void u16(std::string& o, uint16_t v) { put_le(o, v, 2); }
void u32(std::string& o, uint32_t v) { put_le(o, v, 4); }
void u64(std::string& o, uint64_t v) { put_le(o, v, 8); }
void str(std::string& o, const std::string& s) {
  u32(o, static_cast<uint32_t>(s.size()));
  o += s;
}

std::string record(uint8_t op, const std::string& content) {
  std::string r;
  u8(r, op);
  u64(r, content.size());
  return r + content;
}

std::string schema_record(const Schema& s) {
  std::string c;
  u16(c, s.id);
  str(c, s.name);
  str(c, s.encoding);
  str(c, s.data);
  return record(kSchema, c);
}

std::string channel_record(const Channel& ch) {
  std::string c, meta;
  u16(c, ch.id);
  u16(c, ch.schema_id);
  str(c, ch.topic);
  str(c, ch.message_encoding);
  for (const auto& [k, v] : ch.metadata) {
    str(meta, k);
    str(meta, v);
  }
  str(c, meta);
  return record(kChannel, c);
}

std::string message_record(const Message& m) {
  std::string c;
  u16(c, m.channel_id);
  u32(c, m.sequence);
  u64(c, m.log_time_ns);
  u64(c, m.publish_time_ns);
  return record(kMessage, c + m.data);
}

}  // namespace

uint32_t crc32(const std::string& bytes, uint32_t crc) {
  return static_cast<uint32_t>(
      ::crc32(crc, reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

Writer::Writer(const std::string& path, const std::string& profile, const std::string& library,
               std::size_t chunk_bytes, const std::string& compression)
    : path_(path), chunk_bytes_(chunk_bytes), compression_(compression) {
  compress(compression_, "");  // an unknown compression fails here, before the file is made
  f_ = std::fopen(path.c_str(), "wb");
  if (!f_) throw RecordError("cannot write " + path);
  put(kMagic);
  std::string c;
  str(c, profile);
  str(c, library);
  put(record(kHeader, c));
}

Writer::~Writer() {
  try {
    close();
  } catch (...) {
  }
}

void Writer::put(const std::string& bytes) {
  if (std::fwrite(bytes.data(), 1, bytes.size(), f_) != bytes.size())
    throw RecordError("cannot write " + path_);
  data_crc_ = crc32(bytes, data_crc_);
  offset_ += bytes.size();
}

uint16_t Writer::add_schema(const std::string& name, const std::string& encoding, const std::string& data) {
  Schema s{static_cast<uint16_t>(schemas_.size() + 1), name, encoding, data};
  schemas_.push_back(s);
  put(schema_record(s));
  return s.id;
}

uint16_t Writer::add_channel(uint16_t schema_id, const std::string& topic,
                             const std::string& message_encoding,
                             const std::map<std::string, std::string>& metadata) {
  if (channels_.size() > 0xffff) throw RecordError(path_ + ": more than 65536 channels");
  Channel ch{static_cast<uint16_t>(channels_.size()), schema_id, topic, message_encoding, metadata};
  channels_.push_back(ch);
  stats_.channel_message_counts[ch.id] = 0;
  put(channel_record(ch));
  return ch.id;
}

void Writer::write(const Message& m) {
  if (closed_) throw RecordError(path_ + ": message after close");
  if (m.channel_id >= channels_.size())
    throw RecordError(path_ + ": message on unknown channel " + std::to_string(m.channel_id));
  if (chunk_.empty()) chunk_start_ns_ = chunk_end_ns_ = m.log_time_ns;
  chunk_start_ns_ = std::min(chunk_start_ns_, m.log_time_ns);
  chunk_end_ns_ = std::max(chunk_end_ns_, m.log_time_ns);
  chunk_index_[m.channel_id].emplace_back(m.log_time_ns, chunk_.size());
  chunk_ += message_record(m);
  if (stats_.message_count == 0) stats_.message_start_ns = stats_.message_end_ns = m.log_time_ns;
  stats_.message_start_ns = std::min(stats_.message_start_ns, m.log_time_ns);
  stats_.message_end_ns = std::max(stats_.message_end_ns, m.log_time_ns);
  ++stats_.message_count;
  ++stats_.channel_message_counts[m.channel_id];
  if (chunk_.size() >= chunk_bytes_) flush_chunk();
}

void Writer::flush_chunk() {
  if (chunk_.empty()) return;
  std::string c;
  u64(c, chunk_start_ns_);
  u64(c, chunk_end_ns_);
  u64(c, chunk_.size());
  u32(c, crc32(chunk_));
  str(c, compression_);
  const std::string records = compress(compression_, chunk_);
  u64(c, records.size());
  ChunkIndex ci{chunk_start_ns_, chunk_end_ns_, offset_, 0, 0, chunk_.size(), records.size(), {}};
  put(record(kChunk, c + records));
  ci.length = offset_ - ci.offset;
  const uint64_t index_start = offset_;
  for (const auto& [channel, entries] : chunk_index_) {
    std::string mi, tuples;
    u16(mi, channel);
    for (const auto& [t, off] : entries) {
      u64(tuples, t);
      u64(tuples, off);
    }
    str(mi, tuples);
    ci.index_offsets[channel] = offset_;
    put(record(kMessageIndex, mi));
  }
  ci.index_length = offset_ - index_start;
  chunks_.push_back(ci);
  ++stats_.chunk_count;
  chunk_.clear();
  chunk_index_.clear();
}

std::string Writer::summary_group(uint8_t opcode) const {
  std::string g;
  if (opcode == kSchema)
    for (const auto& s : schemas_) g += schema_record(s);
  if (opcode == kChannel)
    for (const auto& ch : channels_) g += channel_record(ch);
  if (opcode == kChunkIndex)
    for (const auto& ci : chunks_) {
      std::string c, offsets;
      u64(c, ci.start_ns);
      u64(c, ci.end_ns);
      u64(c, ci.offset);
      u64(c, ci.length);
      for (const auto& [channel, off] : ci.index_offsets) {
        u16(offsets, channel);
        u64(offsets, off);
      }
      str(c, offsets);
      u64(c, ci.index_length);
      str(c, compression_);
      u64(c, ci.compressed_size);
      u64(c, ci.size);
      g += record(kChunkIndex, c);
    }
  if (opcode == kStatistics) {
    std::string c, counts;
    u64(c, stats_.message_count);
    u16(c, static_cast<uint16_t>(schemas_.size()));
    u32(c, static_cast<uint32_t>(channels_.size()));
    u32(c, 0);  // attachments
    u32(c, 0);  // metadata
    u32(c, stats_.chunk_count);
    u64(c, stats_.message_start_ns);
    u64(c, stats_.message_end_ns);
    for (const auto& [channel, n] : stats_.channel_message_counts) {
      u16(counts, channel);
      u64(counts, n);
    }
    str(c, counts);
    g = record(kStatistics, c);
  }
  return g;
}

void Writer::close() {
  if (closed_ || !f_) return;
  closed_ = true;
  flush_chunk();
  std::string end;
  u32(end, data_crc_);
  put(record(kDataEnd, end));
  const uint64_t summary_start = offset_;
  std::string summary, offsets;
  for (const uint8_t op : {kSchema, kChannel, kChunkIndex, kStatistics}) {
    const std::string g = summary_group(op);
    if (g.empty()) continue;
    std::string so;
    u8(so, op);
    u64(so, summary_start + summary.size());
    u64(so, g.size());
    offsets += record(kSummaryOffset, so);
    summary += g;
  }
  const uint64_t offset_start = summary_start + summary.size();
  std::string footer;
  u8(footer, kFooter);
  u64(footer, kFooterContent);
  u64(footer, summary_start);
  u64(footer, offset_start);
  u32(footer, crc32(summary + offsets + footer));
  put(summary + offsets + footer + kMagic);
  std::fclose(f_);
  f_ = nullptr;
}

}  // namespace maptr::records::mcap
