#pragma once
// What every MAPTR process shares at start-up: its command line (scenario, run folder, name,
// DDS options), its spdlog logger (one file per process in the run folder), and a stop flag
// set by SIGTERM/SIGINT.
#include <spdlog/logger.h>

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "comm/dds/dds.hpp"
#include "config/scenario.hpp"
#include "idl/maptr.h"

namespace maptr::comm {

struct ProcessArgs {
  std::string config;   ///< resolved scenario file
  std::string run_dir;  ///< results folder
  std::string name;     ///< process name (L3, group-L, central, plant)
  DdsOptions dds;
  config::Scenario scenario;
};

/// Parses `--config FILE --run-dir DIR --name NAME [--domain D] [--discovery-server H:P]`
/// (DDS options default to the environment the launcher sets). Exits 2 with a message on
/// bad input.
ProcessArgs parse_process_args(int argc, char** argv, const std::string& what);

/// A logger named after the process writing to RUN_DIR/logs/NAME.log (and stderr for errors).
std::shared_ptr<spdlog::logger> make_logger(const ProcessArgs& a);

/// Installs SIGTERM/SIGINT handlers that set the returned flag.
std::atomic<bool>& stop_flag();

/// Puts the calling thread (only it) under SCHED_FIFO at `priority` (1 to 99), with
/// SCHED_RESET_ON_FORK (a thread or process it creates later runs under normal scheduling), and
/// keeps it on the CPU it runs on, whose caches then hold its data from one turn to the next.
/// Priority 0 leaves it as it is. Needs CAP_SYS_NICE (root) or an RLIMIT_RTPRIO of at least
/// `priority`; without, the thread stays as it is. Returns what the thread runs under, e.g.
/// "SCHED_FIFO 1 on CPU 0" or "normal (SCHED_FIFO 1 refused: Operation not permitted)".
std::string make_thread_realtime(int priority);

}  // namespace maptr::comm

namespace maptr::comm {

/// Decides, just before a process publishes its NodeReady, whether it does (true) or withholds
/// it (false); it may also end the process. Without one every process announces. A seam for
/// the tests' hooked binaries (tests/hooks), whose first start of a process hangs or dies in
/// discovery; the product installs none.
using ReadyGate = bool (*)(const std::string& name);
void set_ready_gate(ReadyGate gate);

/// Publishes this process's NodeReady (once every needed endpoint is matched), unless the ready
/// gate withholds it.
void announce_ready(eprosima::fastdds::dds::DataWriter* w, const std::string& name, msg::NodeKind kind);

/// Writes this process's NodeReady (ready) on `w`, whatever the ready gate says: for the plant's
/// hello (topic::kHello); the gate is about the readiness the launcher waits for.
void write_ready(eprosima::fastdds::dds::DataWriter* w, const std::string& name, msg::NodeKind kind);

/// Publishes a NodeReady that is not ready and names the members this process has not matched
/// yet (at most msg::kMaxUnmatched of them): the plant, while its discovery waits.
void report_unmatched(eprosima::fastdds::dds::DataWriter* w, const std::string& name, msg::NodeKind kind,
                      const std::vector<std::string>& unmatched);

/// Follows the plant's liveliness on a reader of its ticks. The plant counts as lost once a
/// tick of it was received, then it was reported gone (lease expired or writer unmatched) and not heard from
/// again for `grace_s` of wall time: a liveliness flap of a live but starved plant is not a loss.
class PlantWatch {
 public:
  explicit PlantWatch(double grace_s) : grace_(grace_s) {}
  void update(const std::vector<LivelinessEvent>& events) {
    for (const auto& e : events) {
      if (e.alive) down_ = false;
      if (!e.alive && seen_ && !down_) {
        down_ = true;
        since_ = std::chrono::steady_clock::now();
      }
    }
  }
  /// A tick: the plant is there.
  void heard() {
    seen_ = true;
    down_ = false;
  }
  bool lost() const {
    return down_ && std::chrono::duration<double>(std::chrono::steady_clock::now() - since_).count() > grace_;
  }

 private:
  double grace_;
  bool seen_ = false, down_ = false;
  std::chrono::steady_clock::time_point since_{};
};

/// main() of a process whose name is fixed (plant, central): parses the shared arguments,
/// sets up the logger and runs Node(args, log).run(), turning exceptions into exit code 1.
template <class Node>
int run_named_process(int argc, char** argv, const std::string& name, const std::string& what) {
  std::vector<std::string> store{"--name", name};
  std::vector<char*> args(argv, argv + argc);
  bool named = false;
  for (int i = 0; i < argc; ++i)
    if (std::string(argv[i]) == "--name") named = true;
  if (!named)
    for (auto& s : store) args.push_back(s.data());
  auto pa = parse_process_args(static_cast<int>(args.size()), args.data(), what);
  auto log = make_logger(pa);
  try {
    return Node(pa, log).run();
  } catch (const std::exception& e) {
    log->critical("{}", e.what());
    return 1;
  }
}

}  // namespace maptr::comm
