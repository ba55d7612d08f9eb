#pragma once
// The chunk compressions of MCAP that run.mcap may use: "" (none), "zstd" (a Zstandard frame)
// and "lz4" (an LZ4 frame), as the MCAP specification names them and Foxglove reads them.
#include <string>
#include <vector>

namespace maptr::records {

/// The compressions, as the scenario field record_compression names them: none, lz4, zstd.
const std::vector<std::string>& compression_names();
/// The MCAP name of a compression ("" for none).
std::string mcap_compression(const std::string& name);

/// `bytes` compressed with `mcap_name` ("" returns them as they are). Throws RecordError.
std::string compress(const std::string& mcap_name, const std::string& bytes);
/// `bytes` decompressed; the result must be `size` bytes long. Throws RecordError naming the
/// compression and what went wrong (an unknown compression, a corrupt frame, a size that differs).
std::string decompress(const std::string& mcap_name, const std::string& bytes, std::size_t size);

}  // namespace maptr::records
