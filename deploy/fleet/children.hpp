#pragma once
// The launcher's child processes: started with clone(CLONE_VM | CLONE_VFORK) and exec, the
// launcher's memory never copied (dying with the launcher through
// PR_SET_PDEATHSIG, in a process group of their own, stdout and stderr to
// RUN_DIR/logs/NAME.stderr, the fleet's environment plus MAPTR_PARTICIPANT_ID), reaped with
// wait4 (exit code, signal, peak resident memory), and ended at the end of a run.
#include <sys/types.h>

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "comm/dds/fleet_ids.hpp"

namespace maptr::deploy::fleet {

/// What a child process is (the launcher's DDS side names it with msg::NodeKind).
enum class ChildKind : uint8_t { kAgent, kGroup, kCentral, kPlant };

struct Child {
  std::string name, binary;
  std::vector<std::string> args;
  ChildKind kind = ChildKind::kPlant;
  int side = 0;        ///< agents and groups: 0 = left, 1 = right
  uint16_t index = 0;  ///< agents: index within the side
  pid_t pid = -1;
  bool running = false;
  bool paused = false;    ///< stopped by a pause fault (SIGSTOP), not resumed yet
  bool external = false;  ///< started by the user, not by the launcher
  int exit_code = -1, signal = 0;
  long max_rss_kB = 0;
  int starts = 0;
  int discovery_deaths = 0;         ///< ends during discovery that were answered by a new start
  int base_id = 0;                  ///< DDS participant id of its first start
  int participant_id = -1;          ///< DDS participant id of its current start (external: base_id)
  bool awaiting_ready = false;      ///< restarted: MEMBER_STARTED goes out once it reports ready
  int host = -1;                    ///< fleet on several hosts: the host it runs on (-1: this machine)
  std::vector<std::string> prefix;  ///< command prefix that starts it on its host ("": directly)
  pid_t remote_pid = -1;            ///< started over ssh: its pid on its machine (from its NodeReady)
  std::map<std::string, std::string> host_env;  ///< environment its host adds (MAPTR_INTERFACE)
};

/// How a reaped process ended.
struct Exit {
  pid_t pid = -1;
  int exit_code = -1;  ///< exit status, or -1 if it did not exit
  int signal = 0;      ///< the signal that ended it, or 0
  long max_rss_kB = 0;
};

/// Exit from a wait status (as wait4 gives it) and the peak resident memory.
Exit exit_of(pid_t pid, int wait_status, long max_rss_kB);
/// Records an exit in its child (which no longer runs).
void record_exit(Child& c, const Exit& e);
/// A clean end: exit 0 without a signal (a process that saw the plant's last tick).
bool ended_cleanly(const Child& c);
/// How c ended and why, for a status line: "group-L exited 1: <its last critical or error log
/// line>" or "L3 was killed by signal 9" (the log is RUN_DIR/logs/NAME.log).
std::string describe_end(const Child& c, const std::string& run_dir);

using Environment = std::map<std::string, std::string>;

class Zygote;

/// Starts c (again): its environment is the launcher's with env, c.host_env and
/// MAPTR_PARTICIPANT_ID; with a command prefix (a host), through it (deploy/fleet/hosts.hpp).
/// With a zygote of c's binary (deploy/fleet/zygote_client.hpp), forked from it, else clone and exec.
/// Throws std::runtime_error if the start fails.
void spawn(Child& c, const std::string& run_dir, const Environment& env, int participant_id,
           Zygote* zygote = nullptr);

/// The environment c starts with: the launcher's, with env, c.host_env and MAPTR_PARTICIPANT_ID.
std::vector<std::string> child_environment(const Child& c, const Environment& env, int participant_id);

/// True once process `pid` of this machine runs the program `binary` (it has made its last exec;
/// a pid reused by another program is not it).
bool runs_binary(pid_t pid, const std::string& binary);

/// The descriptor number a child started with `pass_fd` finds it under.
inline constexpr int kPassedFd = 3;

/// Starts argv (argv[0] a path) as the launcher's child, with clone and exec: environment env,
/// stdout and stderr appended to out_path, and, if pass_fd >= 0, that descriptor as kPassedFd.
/// Returns its pid, or -1.
pid_t start_process(std::vector<std::string> argv, std::vector<std::string> env, const std::string& out_path,
                    int pass_fd);

/// The next ended child of the launcher, without waiting; nullopt if none has ended.
std::optional<Exit> reap_one();

/// Sends sig to every running child.
void signal_all(const std::vector<Child>& kids, int sig);
/// Waits until no child runs or `seconds` have passed, calling reap in between.
void wait_all(const std::vector<Child>& kids, double seconds, const std::function<void()>& reap);

/// True while a fault gate must hold: a process killed at it still runs, or a process restarted
/// at it has not reported ready. A process restarted at an earlier gate that never reported
/// ready does not hold later gates.
bool gate_pending(const std::vector<Child>& kids, const std::vector<std::string>& killed,
                  const std::vector<std::string>& restarted);

/// Ends one process: SIGTERM, then SIGKILL after term_s; reaps it.
void stop_process(pid_t pid, double term_s);

/// DDS participants of a fleet: discovery server, launcher, plant, central, 2 groups, agents.
inline int fleet_participants(int agents) { return comm::fleet_stride(agents); }

/// DDS participant ids: a fresh id (and so fresh ports) at every start of a process, so that a
/// restarted process never reuses the shared-memory ports its killed predecessor left behind.
/// Ids cycle through `windows` windows of `stride` ids (as many as keep the ports below 65536).
class ParticipantIds {
 public:
  ParticipantIds(int stride, int windows) : stride_(stride), windows_(windows) {}
  /// The id of the start number `starts` of the process of base id `base`; remembers the highest.
  int take(int base, int starts);
  int highest() const { return highest_; }

 private:
  int stride_, windows_, highest_ = 1;
};

}  // namespace maptr::deploy::fleet
