#pragma once
// The launcher's side of the agents' zygote (comm/posix/zygote.hpp): one `maptr_agent --zygote 3`
// started like any child, to which the launcher sends a request per agent to start, and gets
// back the pid of a copy that is the launcher's own child from then on. The launcher becomes a
// child subreaper for that. A zygote that has died or stopped answering is dropped, and its
// agents start with exec again. Plain POSIX, no DDS.
#include <sys/types.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "comm/posix/environment.hpp"
#include "deploy/fleet/children.hpp"

namespace maptr::deploy::fleet {

/// MAPTR_AGENT_START=exec: the launcher starts every agent with exec (no zygote); default zygote.
inline constexpr const char* kAgentStartEnv = comm::kEnvAgentStart;

class Zygote {
 public:
  /// Starts `binary --zygote 3` with the environment env (stdout and stderr appended to
  /// out_path). nullptr if it cannot start.
  static std::unique_ptr<Zygote> start(const std::string& binary, const std::vector<std::string>& env,
                                       const std::string& out_path);
  /// Closes the socket (the zygote ends at that), waits for it, SIGKILL after a few seconds.
  ~Zygote();
  Zygote(const Zygote&) = delete;
  Zygote& operator=(const Zygote&) = delete;

  pid_t pid() const { return pid_; }
  /// Whether it is alive (as far as the launcher knows) and a zygote of `binary`.
  bool serves(const std::string& binary) const { return fd_ >= 0 && binary == binary_; }
  /// A copy running argv (argv[0] the binary) with environment env, its output appended to
  /// out_path: its pid, or -1 (the zygote is then dropped).
  pid_t fork_copy(const std::vector<std::string>& argv, const std::vector<std::string>& env,
                  const std::string& out_path);
  /// The launcher reaped the zygote (it died): it is dropped, and its pid never signalled.
  void lost();
  /// Copies it forked, and requests it failed.
  int forked() const { return forked_; }
  int failed() const { return failed_; }

 private:
  Zygote(std::string binary, int fd, pid_t pid) : binary_(std::move(binary)), fd_(fd), pid_(pid) {}
  void drop();
  std::string binary_;
  int fd_ = -1;
  pid_t pid_ = -1;
  bool reaped_ = false;
  int forked_ = 0, failed_ = 0;
};

}  // namespace maptr::deploy::fleet
