#include "records/compression.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include "records/csv.hpp"

namespace maptr::records {

namespace {
/// Zstandard's level 3 (its default): most of the ratio for a fraction of the higher levels' CPU.
constexpr int kZstdLevel = 3;
}  // namespace

const std::vector<std::string>& compression_names() {
  static const std::vector<std::string> names = {"none", "lz4", "zstd"};
  return names;
}

std::string mcap_compression(const std::string& name) { return name == "none" ? "" : name; }

std::string compress(const std::string& mcap_name, const std::string& bytes) {
  if (mcap_name.empty()) return bytes;
  std::string out;
  if (mcap_name == "zstd") {
    out.resize(ZSTD_compressBound(bytes.size()));
    const std::size_t n = ZSTD_compress(out.data(), out.size(), bytes.data(), bytes.size(), kZstdLevel);
    if (ZSTD_isError(n)) throw RecordError(std::string("zstd compression: ") + ZSTD_getErrorName(n));
    out.resize(n);
    return out;
  }
  if (mcap_name == "lz4") {
    LZ4F_preferences_t prefs{};
    prefs.frameInfo.contentSize = bytes.size();
    out.resize(LZ4F_compressFrameBound(bytes.size(), &prefs));
    const std::size_t n = LZ4F_compressFrame(out.data(), out.size(), bytes.data(), bytes.size(), &prefs);
    if (LZ4F_isError(n)) throw RecordError(std::string("lz4 compression: ") + LZ4F_getErrorName(n));
    out.resize(n);
    return out;
  }
  throw RecordError("unknown chunk compression '" + mcap_name + "' (none, lz4 or zstd)");
}

std::string decompress(const std::string& mcap_name, const std::string& bytes, std::size_t size) {
  if (mcap_name.empty()) {
    if (bytes.size() != size) throw RecordError("chunk size differs from its records");
    return bytes;
  }
  std::string out(size, '\0');
  if (mcap_name == "zstd") {
    const std::size_t n = ZSTD_decompress(out.data(), out.size(), bytes.data(), bytes.size());
    if (ZSTD_isError(n)) throw RecordError(std::string("zstd chunk: ") + ZSTD_getErrorName(n));
    if (n != size) throw RecordError("zstd chunk: " + std::to_string(n) + " bytes, its header says " + std::to_string(size));
    return out;
  }
  if (mcap_name == "lz4") {
    LZ4F_dctx* ctx = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION))) throw RecordError("lz4: no context");
    std::size_t dst = out.size(), src = bytes.size();
    const std::size_t rc = LZ4F_decompress(ctx, out.data(), &dst, bytes.data(), &src, nullptr);
    LZ4F_freeDecompressionContext(ctx);
    if (LZ4F_isError(rc)) throw RecordError(std::string("lz4 chunk: ") + LZ4F_getErrorName(rc));
    if (rc != 0 || dst != size || src != bytes.size())
      throw RecordError("lz4 chunk: " + std::to_string(dst) + " bytes, its header says " + std::to_string(size));
    return out;
  }
  throw RecordError("unknown chunk compression '" + mcap_name + "' (this reader reads none, lz4 and zstd)");
}

}  // namespace maptr::records
