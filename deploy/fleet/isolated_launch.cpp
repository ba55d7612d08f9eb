#include "deploy/fleet/isolated_launch.hpp"

#include <fcntl.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <thread>

#include "deploy/fleet/launcher.hpp"
#include "records/run_files.hpp"
#include "records/summary.hpp"

namespace maptr::deploy {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_stop_signal(int) { g_stop = 1; }

/// The child: runs launch() (which writes RUN_DIR/summary.json) and exits.
[[noreturn]] void run_child(const LaunchOptions& o, const std::string& output_file, pid_t parent) {
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(1);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (!output_file.empty()) {
    const int fd = ::open(output_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
    }
  }
  int rc = 0;
  try {
    auto log = std::make_shared<spdlog::logger>(
        "launcher",
        std::make_shared<spdlog::sinks::basic_file_sink_mt>(o.run_dir + "/logs/launcher.log", true));
    log->flush_on(spdlog::level::info);
    launch(o, *log);
    log->flush();
  } catch (const std::exception& e) {
    records::write_json_file(records::summary_path(o.run_dir),
                             json{{"status", std::string("aborted: ") + e.what()}});
    rc = 1;
  }
  std::fflush(nullptr);
  _exit(rc);
}

/// Waits for the child; a stop request is passed on to it once.
int wait_child(pid_t pid) {
  int st = 0;
  bool forwarded = false;
  while (waitpid(pid, &st, 0) < 0 && errno == EINTR) {
    if (g_stop && !forwarded) {  // the launcher ends its fleet and writes an "interrupted" summary
      kill(pid, SIGTERM);
      forwarded = true;
    }
  }
  return st;
}

}  // namespace

json launch_isolated(const LaunchOptions& options, const std::string& output_file,
                     const LaunchWatcher& watch) {
  LaunchOptions l = options;
  l.progress = false;
  std::error_code ec;
  fs::remove_all(l.run_dir, ec);  // no file of an earlier fleet may pass for this one's
  fs::create_directories(l.run_dir + "/logs");
  std::fflush(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();  // the watcher thread starts after the fork
  if (pid < 0) return {{records::summary_key::kStatus, "aborted: fork failed"}};
  if (pid == 0) run_child(l, output_file, parent);
  std::atomic<bool> done{false};
  std::thread watcher;
  if (watch) watcher = std::thread([&] { watch(done); });
  const int st = wait_child(pid);
  done.store(true);
  if (watcher.joinable()) watcher.join();
  const records::Summary sum = records::Summary::read(records::summary_path(l.run_dir));
  if (sum.has_status()) return sum.data();
  const std::string why = WIFSIGNALED(st) ? "the launcher died of signal " + std::to_string(WTERMSIG(st))
                                          : "the launcher exited with " + std::to_string(WEXITSTATUS(st));
  return {{records::summary_key::kStatus, "aborted: " + why + " without a summary (see runs/" +
                                              fs::path(l.run_dir).filename().string() + "/logs)"}};
}

void install_stop_handler() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: waitpid returns EINTR and the signal is passed on
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

bool stop_requested() { return g_stop != 0; }

}  // namespace maptr::deploy
