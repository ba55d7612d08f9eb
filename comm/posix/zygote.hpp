#pragma once
// A zygote: a process that has loaded its binary once (dynamic linking and relocation, static
// initialisers) and forks ready copies of itself on request, each of which runs the binary's
// main with the request's arguments, environment and output, as if it had been started with
// exec. Starting an agent this way skips the loader, whose relocations of Fast DDS, OpenSSL
// and libstdc++ were a fifth of an agent's start-up CPU in a fleet's discovery
// (docs/bench/HISTORY.md, "Agents forked from a zygote").
//
// The requester (the launcher) is a child subreaper (PR_SET_CHILD_SUBREAPER) and the zygote's
// parent. The zygote forks twice and reaps the middle process before it answers, so a copy is
// the requester's child from then on: the requester waits for it, signals it and reads its
// exit status as for any child it started itself. A copy dies with the requester
// (PR_SET_PDEATHSIG), runs in a process group of its own, and writes stdout and stderr to the
// request's file. The zygote itself starts no thread and opens no DDS participant: a fork copies
// the calling thread only. Plain POSIX, no DDS.
#include <sys/types.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace maptr::comm {

/// The argument a binary serves as a zygote with: `BINARY --zygote FD`, FD a SOCK_SEQPACKET
/// socket, one request per message, one reply (an int32: the copy's pid, or -errno) per request.
inline constexpr const char* kZygoteFlag = "--zygote";

struct ZygoteRequest {
  std::vector<std::string> argv;  ///< argv[0] is the program name (also the copy's process name)
  std::vector<std::string> env;   ///< the copy's whole environment, "KEY=VALUE" each
  std::string out_path;           ///< stdout and stderr, appended to (created if missing)
  pid_t parent = -1;              ///< the requester: the copy's parent once it runs
};

/// One message: the fields separated by NUL characters.
std::string encode_zygote_request(const ZygoteRequest& r);
/// nullopt if the message is not a well-formed request.
std::optional<ZygoteRequest> decode_zygote_request(const std::string& message);

/// Serves requests on `fd` until the requester closes it (returns 0) or the socket fails
/// (returns 1). Each copy returns from this function in no way: it runs `main_fn(argc, argv)`
/// and exits with its result.
int serve_zygote(int fd, const std::function<int(int, char**)>& main_fn);

/// `BINARY --zygote FD` on the command line: FD; otherwise -1 (and -2 if FD is not a number).
int zygote_fd(int argc, char** argv);

}  // namespace maptr::comm
