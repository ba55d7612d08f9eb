#include "deploy/studies/bench/proc_stats.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace maptr::deploy {

namespace {

namespace fs = std::filesystem;

/// Fields of /proc/PID/stat after the command: the state is the first (field 3 of the file).
constexpr std::size_t kFirstFieldAfterComm = 3;
constexpr std::size_t kUtimeField = 14, kStimeField = 15;

std::optional<std::string> read_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The number after "key:" on its own line of a status text.
std::optional<long long> status_value(const std::string& status, const std::string& key) {
  std::istringstream in(status);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key + ":", 0) == 0) {
      try {
        return std::stoll(line.substr(key.size() + 1));
      } catch (...) {
        return std::nullopt;
      }
    }
  return std::nullopt;
}

}  // namespace

std::optional<long long> parse_stat_cpu_ticks(const std::string& stat) {
  const auto close = stat.rfind(')');
  if (close == std::string::npos) return std::nullopt;
  std::istringstream in(stat.substr(close + 1));
  std::vector<std::string> f;
  for (std::string x; in >> x;) f.push_back(x);
  const std::size_t utime = kUtimeField - kFirstFieldAfterComm, stime = kStimeField - kFirstFieldAfterComm;
  if (f.size() <= stime) return std::nullopt;
  try {
    return std::stoll(f[utime]) + std::stoll(f[stime]);
  } catch (...) {
    return std::nullopt;
  }
}

std::optional<long long> parse_status_ctx_switches(const std::string& status) {
  const auto v = status_value(status, "voluntary_ctxt_switches");
  const auto nv = status_value(status, "nonvoluntary_ctxt_switches");
  if (!v || !nv) return std::nullopt;
  return *v + *nv;
}

namespace {

bool is_named(const std::string& comm) {
  for (const char* n : kNamedThreads)
    if (comm == n) return true;
  return false;
}

}  // namespace

double clock_ticks_s(long long ticks) {
  return static_cast<double>(ticks) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

std::optional<long long> parse_schedstat_ns(const std::string& schedstat) {
  std::istringstream in(schedstat);
  long long ns = -1;
  if (!(in >> ns) || ns < 0) return std::nullopt;
  return ns;
}

std::optional<ProcCounters> read_proc_counters(long pid) {
  const std::string dir = "/proc/" + std::to_string(pid);
  const auto stat = read_text(dir + "/stat");
  if (!stat) return std::nullopt;
  const auto close = stat->rfind(')');
  if (close == std::string::npos || stat->compare(close + 1, 2, " Z") == 0) return std::nullopt;
  const auto ticks = parse_stat_cpu_ticks(*stat);
  if (!ticks) return std::nullopt;
  ProcCounters c;
  double threads_s = 0.0;
  bool every_thread_timed = true;
  std::error_code ec;
  for (const auto& task : fs::directory_iterator(dir + "/task", ec)) {
    const std::string tdir = task.path().string();
    const auto status = read_text(tdir + "/status");
    if (!status) continue;  // a thread that ended meanwhile
    if (const auto cs = parse_status_ctx_switches(*status)) c.ctx_switches += *cs;
    const auto sched = read_text(tdir + "/schedstat");
    const auto ns = sched ? parse_schedstat_ns(*sched) : std::nullopt;
    if (!ns) {
      every_thread_timed = false;
      continue;
    }
    const double s = static_cast<double>(*ns) * 1e-9;
    threads_s += s;
    if (task.path().filename() == std::to_string(pid)) {
      c.main_cpu_s = s;
    } else if (const auto name = read_text(tdir + "/comm")) {
      const std::string comm = name->substr(0, name->find('\n'));
      if (is_named(comm)) c.named_cpu_s[comm] += s;
    }
  }
  if (ec) return std::nullopt;
  c.cpu_s = every_thread_timed && threads_s > 0.0 ? threads_s : clock_ticks_s(*ticks);
  return c;
}

std::optional<MachineCpu> parse_proc_stat_cpu(const std::string& stat) {
  std::istringstream in(stat.substr(0, stat.find('\n')));
  std::string name;
  if (!(in >> name) || name != "cpu") return std::nullopt;
  constexpr int kFields = 8;  // user nice system idle iowait irq softirq steal (guest is in user)
  MachineCpu m;
  for (int i = 0; i < kFields; ++i) {
    long long v = 0;
    if (!(in >> v) || v < 0) return std::nullopt;
    m.total += v;
    if (i == kFields - 1) m.steal = v;
    constexpr int kIdle = 3, kIowait = 4;
    if (i != kIdle && i != kIowait && i != kFields - 1) m.busy += v;
  }
  return m;
}

std::optional<MachineCpu> read_machine_cpu() {
  const auto stat = read_text("/proc/stat");
  return stat ? parse_proc_stat_cpu(*stat) : std::nullopt;
}

double steal_percent(const MachineCpu& before, const MachineCpu& after) {
  const long long total = after.total - before.total;
  return total > 0 ? 100.0 * static_cast<double>(after.steal - before.steal) / static_cast<double>(total)
                   : 0.0;
}

std::optional<long long> read_main_thread_ctx_switches(long pid) {
  const auto status = read_text("/proc/" + std::to_string(pid) + "/status");
  if (!status) return std::nullopt;
  return parse_status_ctx_switches(*status);
}

}  // namespace maptr::deploy
