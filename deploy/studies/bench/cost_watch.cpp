#include "deploy/studies/bench/cost_watch.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <thread>

#include "records/run_files.hpp"
#include "records/trace.hpp"

namespace maptr::deploy {

namespace {

using Clock = std::chrono::steady_clock;
/// How often trace.csv is polled for the end of the window, and how often every process is
/// read meanwhile (the end of a run that stops early).
constexpr auto kTracePoll = std::chrono::milliseconds(20);
constexpr auto kFallbackEvery = std::chrono::seconds(2);
/// Bytes read from the end of trace.csv to find its last row.
constexpr std::streamoff kTailBytes = 4096;
constexpr auto kGiveUpAfter = std::chrono::minutes(30);

FleetSample sample(const std::vector<FleetProc>& procs, const std::string& trace) {
  FleetSample s;
  s.tick = last_trace_tick(trace);
  for (const auto& p : procs) s.procs.push_back(read_proc_counters(p.pid));
  s.machine = read_machine_cpu();
  if (const auto self = read_proc_counters(getpid())) s.watcher_cpu_s = self->cpu_s;
  return s;
}

bool all_read(const FleetSample& s) {
  for (const auto& p : s.procs)
    if (!p) return false;
  return !s.procs.empty();
}

}  // namespace

TickWindow cost_window(long long ticks) {
  constexpr double kStart = 0.2, kEnd = 0.9;
  return {static_cast<long long>(kStart * static_cast<double>(ticks)),
          static_cast<long long>(kEnd * static_cast<double>(ticks))};
}

long long last_trace_tick(const std::string& trace_path) {
  std::ifstream in(trace_path, std::ios::binary);
  std::string header;
  if (!std::getline(in, header)) return -1;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(std::max<std::streamoff>(0, size - kTailBytes));
  std::string tail(static_cast<std::size_t>(size - in.tellg()), '\0');
  in.read(&tail[0], static_cast<std::streamsize>(tail.size()));
  const auto end = tail.rfind('\n');
  if (end == std::string::npos || end == 0) return -1;
  const auto begin = tail.rfind('\n', end - 1);
  if (begin == std::string::npos) return -1;
  const std::string row = tail.substr(begin + 1, end - begin);
  if (row.rfind(header, 0) == 0) return -1;  // only the header so far
  try {
    const auto rows = records::parse_trace(header + "\n" + row);
    return rows.empty() ? -1 : static_cast<long long>(rows.back().tick);
  } catch (const std::exception&) {
    return -1;
  }
}

/// Waits until trace.csv reaches `tick`; false when the run ended first.
bool wait_for_tick(const std::string& trace, long long tick, const std::atomic<bool>& done) {
  const auto give_up = Clock::now() + kGiveUpAfter;
  while (!done.load() && Clock::now() < give_up) {
    if (last_trace_tick(trace) >= tick) return true;
    std::this_thread::sleep_for(kTracePoll);
  }
  return false;
}

FleetCost watch_fleet_cost(const std::string& run_dir, const TickWindow& w, const std::atomic<bool>& done) {
  const std::string trace = records::trace_path(run_dir);
  if (!wait_for_tick(trace, w.start_tick, done)) return {};
  const auto fleet = records::read_fleet_file(run_dir);
  if (!fleet) return {};
  const std::vector<FleetProc> procs = fleet_processes(*fleet);
  const FleetSample start = sample(procs, trace);
  FleetSample end;
  auto next_fallback = Clock::now() + kFallbackEvery;
  while (!done.load()) {
    if (last_trace_tick(trace) >= w.end_tick) {
      const FleetSample s = sample(procs, trace);
      if (all_read(s)) end = s;
      break;
    }
    if (Clock::now() >= next_fallback) {
      const FleetSample s = sample(procs, trace);
      if (all_read(s) && s.tick > end.tick) end = s;
      next_fallback = Clock::now() + kFallbackEvery;
    }
    std::this_thread::sleep_for(kTracePoll);
  }
  return fleet_cost(procs, start, end);
}

}  // namespace maptr::deploy
