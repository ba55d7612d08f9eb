#pragma once
// CPU time and context switches of processes, from /proc: user + system time of the whole
// process (/proc/PID/stat, fields 14 and 15, in clock ticks) and voluntary + nonvoluntary
// context switches summed over its threads (/proc/PID/task/TID/status: a process's own status
// counts its main thread only, and a DDS process works in its other threads).
#include <map>
#include <optional>
#include <string>

#include "comm/posix/thread_name.hpp"

namespace maptr::deploy {

/// utime + stime of a /proc/PID/stat text, clock ticks; nullopt when malformed. The command
/// (field 2) may hold spaces and parentheses: fields are counted after its last ')'.
std::optional<long long> parse_stat_cpu_ticks(const std::string& stat);

/// voluntary_ctxt_switches + nonvoluntary_ctxt_switches of a /proc/PID/status text; nullopt
/// when either line is missing.
std::optional<long long> parse_status_ctx_switches(const std::string& status);

/// The threads the project names (comm/posix/thread_name.hpp): their CPU is told apart from
/// the rest of a process's threads (Fast DDS's event, receive and discovery threads, logging).
inline constexpr const char* kNamedThreads[] = {comm::kLevel2Thread, comm::kRecorderThread};

/// The first field of a /proc/.../schedstat text: time the task ran on a CPU, ns (the
/// scheduler's own count, not rounded to clock ticks); nullopt when malformed.
std::optional<long long> parse_schedstat_ns(const std::string& schedstat);

/// What a process has used so far. CPU times are the scheduler's per-thread counts
/// (/proc/PID/task/TID/schedstat, ns) summed over its live threads, where the kernel keeps them;
/// else /proc/PID/stat's (10 ms clock ticks, too coarse for a tick of a few hundred µs).
struct ProcCounters {
  double cpu_s = 0.0;          ///< the whole process, s
  long long ctx_switches = 0;  ///< voluntary + nonvoluntary, over its live threads
  double main_cpu_s = 0.0;     ///< its main thread's (the lock-step thread of a fleet process), s
  std::map<std::string, double> named_cpu_s;  ///< live threads named in kNamedThreads, by name, s
};

/// A live process's counters; nullopt when it is gone, a zombie, or /proc cannot be read.
std::optional<ProcCounters> read_proc_counters(long pid);

/// The machine's CPU time so far, from the "cpu" line of /proc/stat (clock ticks): all of it, and
/// the part a hypervisor ran something else while this machine had work for a CPU ("steal").
/// On a shared VM steal is what makes two sittings differ (BENCHMARKS.md).
struct MachineCpu {
  long long total = 0;  ///< user + nice + system + idle + iowait + irq + softirq + steal
  long long steal = 0;
  long long busy = 0;  ///< user + nice + system + irq + softirq: what this machine's CPUs ran
};

/// The first line of a /proc/stat text; nullopt when it is not the "cpu" line with at least the
/// eight fields up to steal.
std::optional<MachineCpu> parse_proc_stat_cpu(const std::string& stat);

/// This machine's now; nullopt when /proc/stat cannot be read.
std::optional<MachineCpu> read_machine_cpu();

/// Clock ticks (of /proc/stat and /proc/PID/stat) in seconds.
double clock_ticks_s(long long ticks);

/// Steal between two reads as a share of all CPU time between them, %; 0 when no time passed.
double steal_percent(const MachineCpu& before, const MachineCpu& after);

/// The same for one task's status only (/proc/PID/status: its main thread), as the floor
/// probe's single-threaded workers need.
std::optional<long long> read_main_thread_ctx_switches(long pid);

}  // namespace maptr::deploy
