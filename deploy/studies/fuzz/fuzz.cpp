#include "deploy/studies/fuzz/fuzz.hpp"

#include <errno.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "deploy/studies/fuzz/fuzz_log.hpp"

namespace maptr::deploy {

namespace {

namespace fs = std::filesystem;

/// libFuzzer options common to every target: a slow input (s) and memory (MB) count as crashes.
constexpr const char* kTimeoutOption = "-timeout=10";
constexpr const char* kRssLimitOption = "-rss_limit_mb=2048";

const std::vector<std::string> kTargets = {"scenario", "samples"};

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The target's own options (tests/fuzz/fuzz_<name>.flags: whitespace-separated).
std::vector<std::string> target_flags(const FuzzOptions& o, const std::string& name) {
  std::istringstream in(read_text(o.source_dir + "/tests/fuzz/fuzz_" + name + ".flags"));
  std::vector<std::string> flags;
  for (std::string f; in >> f;) flags.push_back(f);
  return flags;
}

/// Runs argv with stdout and stderr into `log`; returns the exit status (128 + signal if killed).
int run_logged(const std::vector<std::string>& args, const std::string& log) {
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fuzz: fork failed");
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
    }
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::size_t count_files(const std::string& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) ++n;
  return n;
}

/// One target's run; returns whether it ended clean (no crash, libFuzzer exit 0).
bool fuzz_one(const FuzzOptions& o, const std::string& name) {
  const std::string corpus = o.out + "/corpus/" + name, crashes = o.out + "/crashes/" + name,
                    log = o.out + "/fuzz_" + name + ".log";
  fs::create_directories(corpus);
  fs::create_directories(crashes);
  std::vector<std::string> args = {o.fuzz_build + "/bin/fuzz_" + name, corpus,
                                   o.source_dir + "/tests/fuzz/corpus/" + name,
                                   "-max_total_time=" + std::to_string(o.seconds)};
  for (const auto& f : target_flags(o, name)) args.push_back(f);
  for (const char* f : {kTimeoutOption, kRssLimitOption, "-print_final_stats=1"}) args.push_back(f);
  args.push_back("-artifact_prefix=" + crashes + "/");
  std::cerr << "maptr: fuzz " << name << " for " << o.seconds << " s ..." << std::flush;
  const int rc = run_logged(args, log);
  const FuzzStats s = parse_fuzz_log(read_text(log));
  const std::size_t found = count_files(crashes);
  std::cerr << "\n";
  std::cout << name << ": " << s.executions << " executions in " << o.seconds << " s (" << s.exec_per_s
            << " exec/s), " << found << " crash(es)";
  if (found > 0 || rc != 0)
    std::cout << ": inputs in " << crashes << "/, log " << log << " (exit " << rc << ")";
  std::cout << "\n";
  return found == 0 && rc == 0;
}

}  // namespace

std::vector<std::string> fuzz_targets(const std::string& target) {
  if (target == "all") return kTargets;
  return {target};
}

int run_fuzz(const FuzzOptions& o) {
  const std::vector<std::string> targets = fuzz_targets(o.target);
  for (const auto& name : targets)
    if (!fs::exists(o.fuzz_build + "/bin/fuzz_" + name)) {
      std::cerr << "maptr: fuzz: " << o.fuzz_build << "/bin/fuzz_" << name
                << " is not built (the fuzz targets need a clang build of their own).\n"
                << "Build them with:  " << o.source_dir << "/tests/fuzz/run.sh --build\n"
                << "(clang-14 and libfuzzer-14-dev; or give --fuzz-build DIR of an existing build)\n";
      return 2;
    }
  bool clean = true;
  for (const auto& name : targets) clean = fuzz_one(o, name) && clean;
  std::cout << "results: " << o.out << "/ (corpus/, crashes/, fuzz_*.log)\n";
  return clean ? 0 : 1;
}

}  // namespace maptr::deploy
