// The MCAP reader of records/mcap.hpp: summary first (through the footer), then every chunk
// its chunk indexes point at, each checked against its CRC and its message indexes.
#include <fstream>
#include <iterator>

#include "records/mcap.hpp"
#include "records/compression.hpp"

namespace maptr::records::mcap {

using namespace op;

namespace {

/// Bytes of a record's opcode and length prefix.
constexpr std::size_t kRecordPrefix = 9;
/// Bytes of the Footer and DataEnd records, prefix included.
constexpr std::size_t kFooterRecord = kRecordPrefix + 20;
constexpr std::size_t kDataEndRecord = kRecordPrefix + 4;

/// Little-endian reads within [pos, end) of a buffer; any read past `end` throws.
class Cursor {
 public:
  Cursor(const std::string& buf, std::size_t pos, std::size_t end, const std::string& what)
      : b_(buf), pos_(pos), end_(end), what_(what) {
    if (end > buf.size() || pos > end) fail("record beyond the end of the file");
  }
  uint64_t le(int bytes) {
    need(bytes);
    uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v |= static_cast<uint64_t>(static_cast<uint8_t>(b_[pos_ + i])) << (8 * i);
    pos_ += bytes;
    return v;
  }
  uint8_t u8() { return static_cast<uint8_t>(le(1)); }
  uint16_t u16() { return static_cast<uint16_t>(le(2)); }
  uint32_t u32() { return static_cast<uint32_t>(le(4)); }
  uint64_t u64() { return le(8); }
  std::string bytes(uint64_t n) {
    need(n);
    std::string s = b_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  std::string str() { return bytes(u32()); }
  std::size_t pos() const { return pos_; }
  std::size_t end() const { return end_; }
  bool done() const { return pos_ >= end_; }
  [[noreturn]] void fail(const std::string& why) const {
    throw RecordError(what_ + ": " + why + " (byte " + std::to_string(pos_) + ")");
  }

 private:
  void need(uint64_t n) const {
    if (n > end_ - pos_) fail("record shorter than its fields");
  }
  const std::string& b_;
  std::size_t pos_, end_;
  std::string what_;
};

struct ChunkIndexEntry {
  uint64_t start_ns, end_ns, offset, length;
  std::map<uint16_t, uint64_t> index_offsets;
};

/// One record at the cursor: its opcode and a cursor over its content (the outer one moves on).
std::pair<uint8_t, Cursor> next_record(Cursor& c, const std::string& buf, const std::string& what) {
  const uint8_t op = c.u8();
  const uint64_t len = c.u64();
  if (len > c.end() - c.pos()) c.fail("record longer than its section");
  Cursor inner(buf, c.pos(), c.pos() + len, what);
  c.bytes(len);
  return {op, inner};
}

Schema parse_schema(Cursor& c) {
  Schema s;
  s.id = c.u16();
  s.name = c.str();
  s.encoding = c.str();
  s.data = c.str();
  return s;
}

Channel parse_channel(Cursor& c, const std::string& buf, const std::string& what) {
  Channel ch;
  ch.id = c.u16();
  ch.schema_id = c.u16();
  ch.topic = c.str();
  ch.message_encoding = c.str();
  const uint32_t len = c.u32();
  Cursor m(buf, c.pos(), c.pos() + len, what);
  while (!m.done()) {
    std::string k = m.str();
    ch.metadata[k] = m.str();
  }
  c.bytes(len);
  return ch;
}

Message parse_message(Cursor& c) {
  Message m;
  m.channel_id = c.u16();
  m.sequence = c.u32();
  m.log_time_ns = c.u64();
  m.publish_time_ns = c.u64();
  m.data = c.bytes(c.end() - c.pos());
  return m;
}

ChunkIndexEntry parse_chunk_index(Cursor& c, const std::string& buf, const std::string& what) {
  ChunkIndexEntry e;
  e.start_ns = c.u64();
  e.end_ns = c.u64();
  e.offset = c.u64();
  e.length = c.u64();
  const uint32_t len = c.u32();
  Cursor m(buf, c.pos(), c.pos() + len, what);
  while (!m.done()) {
    const uint16_t channel = m.u16();
    e.index_offsets[channel] = m.u64();
  }
  c.bytes(len);
  return e;
}

Statistics parse_statistics(Cursor& c, const std::string& buf, const std::string& what) {
  Statistics s;
  s.message_count = c.u64();
  s.schema_count = c.u16();
  s.channel_count = c.u32();
  c.u32();  // attachments
  c.u32();  // metadata
  s.chunk_count = c.u32();
  s.message_start_ns = c.u64();
  s.message_end_ns = c.u64();
  const uint32_t len = c.u32();
  Cursor m(buf, c.pos(), c.pos() + len, what);
  while (!m.done()) {
    const uint16_t channel = m.u16();
    s.channel_message_counts[channel] = m.u64();
  }
  c.bytes(len);
  return s;
}

/// Reads the chunk `e` points at and checks its CRC, its time range and its message indexes.
void read_chunk(const std::string& buf, const ChunkIndexEntry& e, const std::string& what, File& out) {
  Cursor at(buf, e.offset, e.offset + e.length, what);
  auto [op, c] = next_record(at, buf, what);
  if (op != kChunk) at.fail("chunk index points at a record that is not a chunk");
  const uint64_t start = c.u64(), end = c.u64(), size = c.u64();
  const uint32_t crc = c.u32();
  const std::string compression = c.str();
  std::string records;
  try {
    records = decompress(compression, c.bytes(c.u64()), size);
  } catch (const RecordError& err) {
    c.fail(err.what());
  }
  if (crc != 0 && crc32(records) != crc) c.fail("chunk CRC does not match its records");
  if (start != e.start_ns || end != e.end_ns) c.fail("chunk times differ from its index");
  std::map<uint64_t, Message> by_offset;
  Cursor r(records, 0, records.size(), what + " chunk");
  while (!r.done()) {
    const std::size_t off = r.pos();
    auto [rop, rc] = next_record(r, records, what);
    if (rop == kMessage) by_offset.emplace(off, parse_message(rc));
    if (rop == kMessage && (by_offset.at(off).log_time_ns < start || by_offset.at(off).log_time_ns > end))
      r.fail("message outside its chunk's time range");
  }
  std::size_t indexed = 0;
  for (const auto& [channel, offset] : e.index_offsets) {
    Cursor ic(buf, offset, buf.size(), what);
    auto [iop, mi] = next_record(ic, buf, what);
    if (iop != kMessageIndex || mi.u16() != channel)
      ic.fail("message index offset does not point at its index");
    const uint32_t len = mi.u32();
    for (uint32_t k = 0; k < len / 16; ++k) {
      const uint64_t t = mi.u64(), off = mi.u64();
      const auto it = by_offset.find(off);
      if (it == by_offset.end() || it->second.channel_id != channel || it->second.log_time_ns != t)
        mi.fail("message index entry does not point at its message");
      ++indexed;
    }
  }
  if (indexed != by_offset.size()) at.fail("chunk holds messages its message indexes do not list");
  for (auto& [off, m] : by_offset) out.messages.push_back(std::move(m));
}

/// Reads the summary section [start, end) into `out` and returns its chunk indexes.
std::vector<ChunkIndexEntry> read_summary(const std::string& buf, std::size_t start, std::size_t end,
                                          const std::string& what, File& out) {
  std::vector<ChunkIndexEntry> chunks;
  Cursor c(buf, start, end, what);
  while (!c.done()) {
    auto [op, r] = next_record(c, buf, what);
    if (op == kSchema) {
      const Schema s = parse_schema(r);
      out.schemas[s.id] = s;
    } else if (op == kChannel) {
      const Channel ch = parse_channel(r, buf, what);
      out.channels[ch.id] = ch;
    } else if (op == kChunkIndex) {
      chunks.push_back(parse_chunk_index(r, buf, what));
    } else if (op == kStatistics) {
      out.statistics = parse_statistics(r, buf, what);
    }
  }
  return chunks;
}

/// The statistics must count what the chunks hold.
void check_statistics(const File& f, std::size_t chunks, const std::string& what) {
  const Statistics& s = f.statistics;
  std::map<uint16_t, uint64_t> counts;
  for (const auto& [id, ch] : f.channels) counts[id] = 0;
  for (const auto& m : f.messages) ++counts[m.channel_id];
  if (s.message_count != f.messages.size() || s.chunk_count != chunks || s.channel_message_counts != counts ||
      s.channel_count != f.channels.size() || s.schema_count != f.schemas.size())
    throw RecordError(what + ": statistics differ from the messages, channels and chunks of the file");
}

}  // namespace

File read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RecordError("cannot read " + path);
  const std::string buf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string what = path;
  if (buf.size() < 2 * kMagic.size() + kFooterRecord || buf.compare(0, kMagic.size(), kMagic) != 0 ||
      buf.compare(buf.size() - kMagic.size(), kMagic.size(), kMagic) != 0)
    throw RecordError(what + ": not an MCAP file (magic bytes missing)");
  File out;
  Cursor head(buf, kMagic.size(), buf.size(), what);
  auto [hop, h] = next_record(head, buf, what);
  if (hop != kHeader) head.fail("the first record is not a header");
  out.profile = h.str();
  out.library = h.str();

  const std::size_t footer_at = buf.size() - kMagic.size() - kFooterRecord;
  Cursor fc(buf, footer_at, footer_at + kFooterRecord, what);
  auto [fop, footer] = next_record(fc, buf, what);
  if (fop != kFooter) fc.fail("no footer before the trailing magic");
  const uint64_t summary_start = footer.u64(), offset_start = footer.u64();
  const uint32_t summary_crc = footer.u32();
  if (summary_start == 0) throw RecordError(what + ": no summary section");
  if (summary_start < kDataEndRecord || summary_start > footer_at)
    footer.fail("summary start outside the file");
  if (summary_crc != 0 &&
      crc32(buf.substr(summary_start, footer_at + kRecordPrefix + 16 - summary_start)) != summary_crc)
    footer.fail("summary CRC does not match");
  Cursor de(buf, summary_start - kDataEndRecord, summary_start, what);
  auto [dop, d] = next_record(de, buf, what);
  const uint32_t data_crc = d.u32();
  if (dop != kDataEnd) de.fail("no data-end record before the summary");
  if (data_crc != 0 && crc32(buf.substr(0, summary_start - kDataEndRecord)) != data_crc)
    de.fail("data section CRC does not match");

  const auto chunks = read_summary(buf, summary_start, offset_start ? offset_start : footer_at, what, out);
  for (const auto& e : chunks) read_chunk(buf, e, what, out);
  check_statistics(out, chunks.size(), what);
  return out;
}

}  // namespace maptr::records::mcap
