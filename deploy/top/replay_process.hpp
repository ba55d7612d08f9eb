#pragma once
// The replayer of `maptr top --run` on a finished run: `maptr replay RUN --domain D --rate X
// --wait-reader S --quiet` as a child process. It publishes over UDP only (no shared-memory
// files to leave behind), its output is discarded (it would tear the full-screen view), it is
// killed when `maptr top` dies (PR_SET_PDEATHSIG) and is ended by its PID when the watch ends
// (SIGTERM, which lets it stop while the watcher still acknowledges, then SIGKILL after
// kStopGrace_s).
#include <sys/types.h>

#include <string>

namespace maptr::top {

/// How long the replayer waits for the watcher's tick reader before its first message, s.
inline constexpr double kReplayWaitReader_s = 60.0;
/// How long a replayer may take to stop after SIGTERM before it is killed, s.
inline constexpr double kStopGrace_s = 10.0;

/// Lowest DDS domain searched for a free one.
inline constexpr int kLowestReplayDomain = 1;

/// True when a DDS participant of this host uses `domain`: its simple-discovery multicast port,
/// or the unicast ports of one of its lowest participant ids, is taken.
bool domain_in_use(int domain);
/// The highest domain from `highest` down to kLowestReplayDomain that is not in use; throws
/// std::runtime_error when every one is.
int free_domain(int highest);

class ReplayProcess {
 public:
  /// Starts `maptr replay` (`maptr`: the executable) of `run_dir` on `domain` at `rate`.
  /// Throws std::runtime_error when fork fails.
  ReplayProcess(const std::string& maptr, const std::string& run_dir, int domain, double rate);
  /// Ends the replayer if it still runs.
  ~ReplayProcess();
  ReplayProcess(const ReplayProcess&) = delete;
  ReplayProcess& operator=(const ReplayProcess&) = delete;

  /// True once the replayer has exited (reaps it without waiting).
  bool exited();
  /// Its exit code once exited; -1 after a signal or while it runs.
  int exit_code() const { return exit_code_; }
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int exit_code_ = -1;
};

}  // namespace maptr::top
