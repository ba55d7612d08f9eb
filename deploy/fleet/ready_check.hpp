#pragma once
// Whom the launcher believes when a process says it is ready (maptr/ready): only the
// participant it expects for that process's current start, carrying the pid it started, or,
// for a process the user started (--external), a pid whose executable and environment show it
// is that process. Everything else is rejected and counted, by kind. Free of DDS: the caller
// says what the sample's writer is.
#include <sys/types.h>

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace maptr::deploy::fleet {

enum class ReadyVerdict {
  kTaken,      ///< the process is ready
  kForged,     ///< not from the participant expected for that name, or a pid that does not match
  kStale,      ///< from that process's participant of an earlier start (it was started again since)
  kMalformed,  ///< breaks NodeReady's rule (idl/rules.hpp): not looked at further
};

/// What the launcher knows of one NodeReady sample.
struct ReadyClaim {
  bool well_formed = true;  ///< NodeReady's rule holds
  bool known_name = false;  ///< it names a process of the fleet
  /// Its writer is the participant the launcher expects for that process now (on a plain
  /// domain the fleet prefix of its current participant id; on a secure domain its certificate).
  bool from_current_participant = false;
  /// Its writer is that process's participant of an earlier start (plain domain only).
  bool from_earlier_participant = false;
  bool external = false;     ///< the user starts the process, not the launcher
  bool pid_matches = false;  ///< the launcher's own child: the pid it carries is the one started
  /// An external process: its pid was checked (external_pid_problem gave nothing), or could not
  /// be read at all (then the readiness counts, the pid is never taken).
  bool external_pid_ok = false;
};

ReadyVerdict judge_ready(const ReadyClaim& c);

/// "forged", "stale" or "malformed" ("taken" for kTaken).
const char* verdict_name(ReadyVerdict v);

/// Why pid is not the process the launcher printed the command for, nullopt when it is: its
/// executable (/proc/PID/exe) must be `binary` and its environment (/proc/PID/environ) must
/// hold MAPTR_FLEET_ID=fleet_id and MAPTR_PARTICIPANT_ID=participant_id. `unreadable` is set
/// when /proc could not be read (another user's process): nothing is known then.
std::optional<std::string> external_pid_problem(pid_t pid, const std::string& binary, uint32_t fleet_id,
                                                int participant_id, bool& unreadable,
                                                const std::string& proc = "/proc");

/// The NodeReady samples the launcher rejected, by kind ("forged", "stale", "malformed").
using ReadyRejects = std::map<std::string, long>;

/// Whom the launcher starts again when discovery made no progress for a while. `unready`: the
/// launcher's own started processes that are not ready, in launch order ("plant" first). Every
/// one of them, but the plant only when it is the last one. When it is, and its latest report
/// (NodeReady.unmatched) names members that are all in `ready` (ready and the launcher's own),
/// those members instead: their endpoints never reached the plant (Fast DDS's discovery server
/// drops the endpoints it hears before their participant), while the plant, which may have
/// matched hundreds of others, keeps them. A report naming anyone else leaves the plant's own
/// start as the answer.
std::vector<std::string> rematch_choice(const std::vector<std::string>& unready,
                                        const std::vector<std::string>& plant_unmatched,
                                        const std::set<std::string>& ready);

}  // namespace maptr::deploy::fleet
