#pragma once
#include <algorithm>
// Runs the real `maptr` CLI (and so the real fleet of processes) for integration tests: a
// private DDS domain, a temporary results folder, a wall-clock timeout after which the
// launcher is killed by its PID (its children die with it), and the folder removed afterwards.
#include <fcntl.h>
#include <linux/capability.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "records/summary_fields.hpp"

namespace maptr::testing {

struct CliResult {
  int exit_code = -1;
  bool timed_out = false;
  std::string output;        ///< stdout + stderr
  nlohmann::json summary;    ///< summary.json when written
  std::string run_dir;
};

/// A fresh folder under the system temp dir, removed on destruction.
class TempDir {
 public:
  TempDir() {
    std::string tmpl = (std::filesystem::temp_directory_path() / "maptr-test-XXXXXX").string();
    path_ = mkdtemp(tmpl.data());
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// A DDS domain no other test run uses at the same time (derived from the PID and a counter).
/// The whole text of a file ("" when it cannot be read).
inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline int private_domain() {
  static int counter = 0;
  return 100 + (static_cast<int>(getpid()) * 7 + counter++) % 120;
}

/// `maptr run EXTRA... --out OUT --domain <private> --quiet`; without a scenario file in EXTRA,
/// the paper's straight line (deploy/scenarios/paper.yaml), which these tests are written for.
inline std::vector<std::string> run_args(const std::string& out, std::vector<std::string> extra) {
  std::vector<std::string> a = {"run"};
  const bool has_scenario = std::any_of(extra.begin(), extra.end(), [](const std::string& e) {
    return e.size() > 5 && e.compare(e.size() - 5, 5, ".yaml") == 0;
  });
  if (!has_scenario) a.push_back(std::string(MAPTR_SOURCE_DIR) + "/deploy/scenarios/paper.yaml");
  a.insert(a.end(), extra.begin(), extra.end());
  for (const std::string& s : {std::string("--out"), out, std::string("--domain"), std::to_string(private_domain()),
                               std::string("--quiet")})
    a.push_back(s);
  return a;
}

/// What a started `maptr` may do beside the default.
enum class Privilege {
  kAsIs,
  /// No real-time scheduling for it and its children: CAP_SYS_NICE gone from the capability
  /// bounding set (possible as root) and RLIMIT_RTPRIO 0, as for a user without either.
  kNoRealtime,
};

/// The folder whose `maptr` the runners start: the product's (MAPTR_BIN_DIR) unless a
/// HookedBinaries is in scope.
inline std::string& cli_bin_dir() {
  static std::string dir = MAPTR_BIN_DIR;
  return dir;
}

#ifdef MAPTR_HOOKED_BIN_DIR
/// While in scope, the runners start the tests' hooked binaries (tests/hooks: the product's
/// code with the MAPTR_TEST_* hooks of tests/hooks/hooks.hpp) with `name`=`value` in their
/// environment.
class HookedBinaries {
 public:
  HookedBinaries(const char* name, const std::string& value) : name_(name) {
    setenv(name, value.c_str(), 1);
    cli_bin_dir() = MAPTR_HOOKED_BIN_DIR;
  }
  ~HookedBinaries() {
    unsetenv(name_);
    cli_bin_dir() = MAPTR_BIN_DIR;
  }
  HookedBinaries(const HookedBinaries&) = delete;
  HookedBinaries& operator=(const HookedBinaries&) = delete;

 private:
  const char* name_;
};
#endif

/// Starts `maptr ARGS` in the background (output to OUT_LOG); returns its PID.
inline pid_t start_cli(std::vector<std::string> args, const std::string& out_log,
                       Privilege privilege = Privilege::kAsIs) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (privilege == Privilege::kNoRealtime) {
      prctl(PR_CAPBSET_DROP, CAP_SYS_NICE, 0, 0, 0);  // refused without CAP_SETPCAP: then not held anyway
      const rlimit none{0, 0};
      setrlimit(RLIMIT_RTPRIO, &none);
    }
    const int fd = open(out_log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    std::vector<char*> argv;
    std::string bin = cli_bin_dir() + "/maptr";
    argv.push_back(bin.data());
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(bin.c_str(), argv.data());
    _exit(127);
  }
  return pid;
}

/// wait_child's answer for a child that had to be killed.
inline constexpr int kTimedOut = -2;

/// Waits for a child to exit within timeout_s (killed by its PID after that, and the fleet with
/// it: PR_SET_PDEATHSIG); returns its exit code, -1 for a signal, kTimedOut.
inline int wait_child(pid_t pid, double timeout_s) {
  const auto t0 = std::chrono::steady_clock::now();
  int st = 0;
  while (waitpid(pid, &st, WNOHANG) != pid) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > timeout_s) {
      kill(pid, SIGKILL);
      waitpid(pid, &st, 0);
      return kTimedOut;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/// Runs `maptr ARGS` to its end (killed by its PID after timeout_s); output and summary.json.
inline CliResult run_cli(std::vector<std::string> args, const std::string& run_dir, double timeout_s,
                         Privilege privilege = Privilege::kAsIs) {
  CliResult r;
  r.run_dir = run_dir;
  const std::string log = run_dir + ".out";
  const int code = wait_child(start_cli(std::move(args), log, privilege), timeout_s);
  r.timed_out = code == kTimedOut;
  r.exit_code = r.timed_out ? -1 : code;
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  r.output = ss.str();
  std::filesystem::remove(log);
  std::ifstream js(run_dir + "/summary.json");
  if (js) js >> r.summary;
  // Every key a run writes is in docs/SUMMARY.md (records/summary_fields.cpp). An experiment's
  // or a comparison's summary.json is another file: only a run's (it has a status and a plant).
  if (r.summary.is_object() && r.summary.contains("status") && r.summary.contains("processes") &&
      !r.summary.contains("rows"))
    for (const auto& k : maptr::records::undocumented_summary_keys(r.summary))
      ADD_FAILURE() << run_dir << "/summary.json: key " << k << " is not in docs/SUMMARY.md (records/summary_fields.cpp)";
  return r;
}

/// Polls until pred() holds or timeout_s passes.
template <class Pred>
inline bool wait_for(Pred pred, double timeout_s) {
  const auto t0 = std::chrono::steady_clock::now();
  while (!pred()) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > timeout_s) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return true;
}

/// Lines in a file (0 if it does not exist).
inline int count_lines(const std::string& path) {
  std::ifstream in(path);
  int n = 0;
  for (std::string l; std::getline(in, l);) ++n;
  return n;
}

/// True while a process exists and is not a zombie.
inline bool process_running(pid_t pid) {
  std::ifstream st("/proc/" + std::to_string(pid) + "/stat");
  if (!st) return false;
  std::string line;
  std::getline(st, line);
  const auto close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] != 'Z';
}

inline nlohmann::json read_json(const std::string& path) {
  std::ifstream in(path);
  nlohmann::json j;
  try {
    if (in) in >> j;
  } catch (const nlohmann::json::exception&) {
    j = nullptr;  // being written: not there yet
  }
  return j;
}

inline void write_file(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

}  // namespace maptr::testing
