#pragma once
// A registry entry: one small JSON file per running launcher in the registry folder (its place
// and lifetime: deploy/fleet/registry.hpp). Writer and reader side by side.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace maptr::records {

/// One registered fleet.
struct RegistryEntry {
  std::string run_dir;        ///< absolute
  std::string scenario;       ///< its name
  int pid = 0;                ///< the launcher's
  long long start_ticks = 0;  ///< the launcher's start time (/proc/PID/stat field 22)
  int domain = 0;
  double started_unix_s = 0;  ///< when it registered (wall clock, for ordering)
};

/// The entry's JSON object (also what `maptr ps --json` prints, with the simulated time).
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(RegistryEntry, run_dir, scenario, pid, start_ticks, domain, started_unix_s)

/// The entry as the file's text (one JSON line).
std::string registry_entry_text(const RegistryEntry& e);
/// The entry in `text`; nullopt when it is not a well-formed entry (a pid of 1 or less, a run
/// folder that is not absolute, a field missing or of another type).
std::optional<RegistryEntry> parse_registry_entry(const std::string& text);

/// Writes `e` to `path` whole (a temporary file, then a rename: a reader never sees half an
/// entry); false when it cannot.
bool write_registry_entry(const std::string& path, const RegistryEntry& e);
/// The entry in `path`; nullopt when it is missing or not an entry.
std::optional<RegistryEntry> read_registry_entry(const std::string& path);

}  // namespace maptr::records
