// records/mcap: what the writer puts in a file the reader gets back, chunked and indexed, and
// every CRC guards what it covers.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "records/mcap.hpp"

namespace mcap = maptr::records::mcap;
using maptr::records::RecordError;

namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("maptr_test_" + std::to_string(getpid()) + "_" + name))
      .string();
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// Three channels on two schemas; message i on channel i % 3 at log time 1000 + 10 i ns.
std::vector<mcap::Message> write_sample(const std::string& path, int n, std::size_t chunk_bytes,
                                        const std::string& compression = "") {
  mcap::Writer w(path, "", "maptr test", chunk_bytes, compression);
  const uint16_t a = w.add_schema("pkg::A", "omgidl", "module pkg { struct A { long x; }; };");
  const uint16_t b = w.add_schema("pkg::B", "omgidl", "module pkg { struct B { double y; }; };");
  w.add_channel(a, "t/a", "cdr");
  w.add_channel(b, "t/b", "cdr");
  w.add_channel(a, "t/a2", "cdr");
  std::vector<mcap::Message> sent;
  for (int i = 0; i < n; ++i) {
    mcap::Message m;
    m.channel_id = static_cast<uint16_t>(i % 3);
    m.sequence = static_cast<uint32_t>(i / 3);
    m.log_time_ns = 1000 + 10 * static_cast<uint64_t>(i);
    m.publish_time_ns = m.log_time_ns - 5;
    m.data =
        std::string("\x00\x01\x00\x00", 4) + std::string(static_cast<std::size_t>(i % 7), char('a' + i % 26));
    w.write(m);
    sent.push_back(m);
  }
  w.close();
  return sent;
}

}  // namespace

TEST(Mcap, Crc32MatchesTheStandardCheckValue) {
  // CRC-32/ISO-HDLC of "123456789" is 0xCBF43926; continuing a CRC equals one pass.
  EXPECT_EQ(mcap::crc32("123456789"), 0xCBF43926u);
  EXPECT_EQ(mcap::crc32("6789", mcap::crc32("12345")), 0xCBF43926u);
}

TEST(Mcap, MessagesComeBackInOrderAcrossChunksWithTheirIndexes) {
  const std::string path = temp_path("roundtrip.mcap");
  const auto sent = write_sample(path, 500, 1024);  // about 20 messages a chunk
  const mcap::File f = mcap::read_file(path);
  ASSERT_EQ(f.messages.size(), sent.size());
  for (std::size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(f.messages[i].channel_id, sent[i].channel_id);
    EXPECT_EQ(f.messages[i].sequence, sent[i].sequence);
    EXPECT_EQ(f.messages[i].log_time_ns, sent[i].log_time_ns);
    EXPECT_EQ(f.messages[i].publish_time_ns, sent[i].publish_time_ns);
    EXPECT_EQ(f.messages[i].data, sent[i].data);
  }
  EXPECT_EQ(f.library, "maptr test");
  ASSERT_EQ(f.schemas.size(), 2u);
  EXPECT_EQ(f.schemas.at(2).name, "pkg::B");
  EXPECT_EQ(f.schemas.at(2).encoding, "omgidl");
  ASSERT_EQ(f.channels.size(), 3u);
  EXPECT_EQ(f.channels.at(2).topic, "t/a2");
  EXPECT_EQ(f.channels.at(2).schema_id, 1);
  EXPECT_EQ(f.channels.at(1).message_encoding, "cdr");
  EXPECT_GT(f.statistics.chunk_count, 10u);
  EXPECT_EQ(f.statistics.message_count, 500u);
  EXPECT_EQ(f.statistics.channel_message_counts.at(0), 167u);  // i % 3 == 0 for 167 of 0..499
  EXPECT_EQ(f.statistics.message_start_ns, 1000u);
  EXPECT_EQ(f.statistics.message_end_ns, 1000u + 10u * 499u);
  std::filesystem::remove(path);
}

TEST(Mcap, AnEmptyRecordingIsValidWithZeroCounts) {
  const std::string path = temp_path("empty.mcap");
  write_sample(path, 0, 1024);
  const mcap::File f = mcap::read_file(path);
  EXPECT_TRUE(f.messages.empty());
  EXPECT_EQ(f.statistics.chunk_count, 0u);
  EXPECT_EQ(f.statistics.channel_message_counts.at(1), 0u);
  std::filesystem::remove(path);
}

TEST(Mcap, ACorruptByteInAChunkIsCaughtByItsCrc) {
  const std::string path = temp_path("corrupt.mcap");
  write_sample(path, 50, 1u << 20);
  std::string bytes = slurp(path);
  // Message 13 carries "nnnnnn" (13 % 26 is n, 13 % 7 is 6).
  const std::size_t at = bytes.find(std::string("\x00\x01\x00\x00", 4) + "nnnnnn");
  ASSERT_NE(at, std::string::npos);
  bytes[at + 5] = 'y';
  std::ofstream(path, std::ios::binary) << bytes;
  try {
    mcap::read_file(path);
    FAIL() << "a corrupt chunk was read";
  } catch (const RecordError& e) {
    EXPECT_NE(std::string(e.what()).find("CRC"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

TEST(Mcap, ATruncatedFileIsRefused) {
  const std::string path = temp_path("truncated.mcap");
  write_sample(path, 50, 1u << 20);
  const std::string bytes = slurp(path);
  std::ofstream(path, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_THROW(mcap::read_file(path), RecordError);
  std::filesystem::remove(path);
}

TEST(Mcap, CompressedChunksReadBackTheSameMessagesAndAreSmaller) {
  const std::string plain = temp_path("plain.mcap");
  const auto sent = write_sample(plain, 3000, 1u << 16);
  for (const std::string c : {"zstd", "lz4"}) {
    SCOPED_TRACE(c);
    const std::string path = temp_path(c + ".mcap");
    write_sample(path, 3000, 1u << 16, c);
    const mcap::File f = mcap::read_file(path);
    ASSERT_EQ(f.messages.size(), sent.size());
    for (std::size_t i = 0; i < sent.size(); ++i) {
      EXPECT_EQ(f.messages[i].data, sent[i].data);
      EXPECT_EQ(f.messages[i].log_time_ns, sent[i].log_time_ns);
    }
    // The records compress; the message indexes and the summary beside them do not.
    EXPECT_LT(std::filesystem::file_size(path) * (c == "zstd" ? 2 : 1), std::filesystem::file_size(plain));
    // The chunk record names its compression as the MCAP specification does.
    EXPECT_NE(slurp(path).find(std::string(1, static_cast<char>(c.size())) + std::string(3, '\0') + c),
              std::string::npos);
    std::filesystem::remove(path);
  }
  std::filesystem::remove(plain);
}

TEST(Mcap, ACorruptCompressedChunkIsRefusedAndAnUnknownCompressionToo) {
  const std::string path = temp_path("corrupt-zstd.mcap");
  write_sample(path, 500, 1u << 20, "zstd");
  std::string bytes = slurp(path);
  const std::size_t at = bytes.find("zstd");
  ASSERT_NE(at, std::string::npos);
  bytes[at + 4 + 8 + 6] ^= 0x5a;  // inside the compressed records, after their length
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_THROW(mcap::read_file(path), RecordError);
  std::filesystem::remove(path);
  EXPECT_THROW(mcap::Writer(temp_path("bz2.mcap"), "", "maptr test", 1024, "bz2"), RecordError);
}

TEST(Mcap, AChannelAddedBetweenMessagesKeepsItsMetadataAndItsMessages) {
  // The recorder adds a channel at the first sample of a writer, while a chunk is open.
  const std::string path = temp_path("late_channel.mcap");
  for (const std::string compression : {"", "zstd"}) {
    {
      mcap::Writer w(path, "", "maptr test", 256, compression);
      const uint16_t a = w.add_schema("pkg::A", "omgidl", "module pkg { struct A { long x; }; };");
      const uint16_t first = w.add_channel(a, "t/a", "cdr", {{"writer", "0001"}, {"verdict", "taken"}});
      for (uint32_t i = 0; i < 40; ++i) {
        if (i == 25) {
          EXPECT_EQ(w.add_channel(a, "t/a", "cdr", {{"writer", "0002"}, {"verdict", "forged"}}), 1);
        }
        mcap::Message m;
        m.channel_id = i < 25 ? first : static_cast<uint16_t>(i % 2);
        m.sequence = i;
        m.log_time_ns = 100 + i;
        m.data = std::string(20, char('a' + i % 26));
        w.write(m);
      }
    }
    const auto f = mcap::read_file(path);
    ASSERT_EQ(f.channels.size(), 2u) << compression;
    EXPECT_EQ(f.channels.at(0).topic, "t/a");
    EXPECT_EQ(f.channels.at(1).topic, "t/a");
    EXPECT_EQ(f.channels.at(0).metadata.at("verdict"), "taken");
    EXPECT_EQ(f.channels.at(1).metadata.at("writer"), "0002");
    EXPECT_EQ(f.channels.at(1).metadata.at("verdict"), "forged");
    ASSERT_EQ(f.messages.size(), 40u);
    EXPECT_EQ(f.statistics.channel_message_counts.at(1), 8u) << "messages 25, 27, ..., 39";
  }
  std::filesystem::remove(path);
}
