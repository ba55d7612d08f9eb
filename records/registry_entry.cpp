#include "records/registry_entry.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>

namespace maptr::records {

std::string registry_entry_text(const RegistryEntry& e) { return nlohmann::json(e).dump() + "\n"; }

std::optional<RegistryEntry> parse_registry_entry(const std::string& text) {
  const auto j = nlohmann::json::parse(text, nullptr, false);
  try {
    auto e = j.get<RegistryEntry>();
    if (e.pid <= 1 || e.run_dir.empty() || e.run_dir[0] != '/') return std::nullopt;
    return e;
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

bool write_registry_entry(const std::string& path, const RegistryEntry& e) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << registry_entry_text(e);
    if (!out.flush()) return false;
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  return !ec;
}

std::optional<RegistryEntry> read_registry_entry(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  return parse_registry_entry(std::string(std::istreambuf_iterator<char>(in), {}));
}

}  // namespace maptr::records
