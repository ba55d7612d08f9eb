#pragma once
// A group controller's wear ledger on disk (control/level3/ledger.hpp): RUN_DIR/ledger-L.json and
// ledger-R.json, JSON, written atomically (a temporary file, then a rename) by the plant at the
// end of a run from the groups' last statuses, for the studies and the soak to read each agent's
// wear.
#include <optional>
#include <string>

#include "control/level3/ledger.hpp"

namespace maptr::records {

/// RUN_DIR/ledger-L.json (side 0) or ledger-R.json (side 1).
std::string ledger_path(const std::string& run_dir, int side);

/// The ledger in `path`; nullopt when there is no such file. Throws std::runtime_error on a
/// corrupt file, or, with per_side >= 0, one written for another number of agents per side.
std::optional<control::Ledger> load_ledger(const std::string& path, int per_side = -1);

/// Writes `ledger` to `path` atomically; throws std::runtime_error if it cannot be written.
void save_ledger(const std::string& path, const control::Ledger& ledger);

}  // namespace maptr::records
