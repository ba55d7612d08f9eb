#include "deploy/top/watch.hpp"

#include <signal.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <thread>

#include "deploy/top/run_events.hpp"
#include "records/run_files.hpp"
#include "records/summary.hpp"

namespace maptr::top {

namespace {
/// Wait while the fleet has not started its lock-step, s.
constexpr double kJoinPoll_s = 0.2;

bool pid_alive(int pid) { return pid > 0 && (kill(pid, 0) == 0 || errno == EPERM); }
}  // namespace

bool run_is_live(const std::string& run_dir) {
  try {
    return pid_alive(read_fleet(run_dir).launcher_pid) &&
           !records::Summary::read(records::summary_path(run_dir)).has_status();
  } catch (const std::exception&) {
    return false;
  }
}

std::optional<FleetCoordinates> replay_coordinates(const std::string& run_dir, const ReplayRequest& r,
                                                   std::string& why) {
  if (!std::filesystem::exists(records::mcap_path(run_dir))) {
    why = run_dir +
          " has ended and has no recording to replay (no run.mcap: it ran with --record none, or "
          "before runs were recorded)";
    return std::nullopt;
  }
  FleetCoordinates c;
  try {
    c = read_fleet(run_dir);
  } catch (const std::exception& e) {
    why = e.what();
    return std::nullopt;
  }
  c.info.domain = r.domain;
  c.info.replay_rate = r.rate;
  c.discovery_server.clear();
  c.fleet_id = 0;
  c.launcher_pid = 0;
  return c;
}

Watch::Watch(FleetCoordinates c) : c_(std::move(c)), view_(c_.info) {
  // A gate's event names the faults the scenario schedules at its tick.
  try {
    view_.set_gate_faults(gate_faults(config::load_scenario(c_.info.run_dir + "/scenario.yaml")));
  } catch (const std::exception&) {
    // no scenario.yaml (a run folder of an older build): gates show as "scheduled fault"
  }
}

Watch::Watch(FleetCoordinates c, const ReplayRequest& r)
    : c_(std::move(c)),
      view_(c_.info),
      reader_(std::make_unique<FleetReader>(c_)),
      replay_(std::make_unique<ReplayProcess>(r.maptr, c_.info.run_dir, r.domain, r.rate)) {
  // A replay shows the run's own record of its events, as the replayed ticks reach them.
  const records::Summary s = records::Summary::read(records::summary_path(c_.info.run_dir));
  view_.set_recorded_events(recorded_events(s.data(), s.number_or("tick_hz", 100.0)));
}

void Watch::end_run() {
  const records::Summary s = records::Summary::read(records::summary_path(c_.info.run_dir));
  if (s.has_status())
    view_.on_summary(s.status(), s.end_reason());
  else
    view_.on_fleet_gone();
  ended_ = true;
}

void Watch::poll() {
  if (replay_) {
    // Whether the replayer has exited is read before the drain: every sample it sent was
    // acknowledged by then, so this drain folds the recording's last tick.
    const bool over = !ended_ && replay_->exited();
    reader_->drain_into(view_);
    view_.observe(steady_now_s());
    if (over) end_run();
    return;
  }
  const std::string dir = c_.info.run_dir;
  if (!reader_ && !ended_ && std::filesystem::exists(records::trace_path(dir)))
    reader_ = std::make_unique<FleetReader>(c_);
  if (reader_) reader_->drain_into(view_);
  view_.observe(steady_now_s());
  if (ended_) return;
  if (records::Summary::read(records::summary_path(dir)).has_status() || !pid_alive(c_.launcher_pid))
    end_run();
}

std::string Watch::replay_failure() const {
  if (!replay_ || !ended_ || replay_->exit_code() == 0) return "";
  if (replay_->exit_code() < 0) return "maptr replay was ended by a signal";
  return "maptr replay exited with code " + std::to_string(replay_->exit_code());
}

void Watch::wait(double max_s) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                            std::chrono::duration<double>(reader_ ? max_s : std::min(max_s, kJoinPoll_s)));
  if (reader_)
    reader_->signal().wait_until(reader_->signal().count(), deadline);
  else
    std::this_thread::sleep_until(deadline);
}

bool Watch::complete() const {
  if (!view_.ticked()) return false;
  for (int s = 0; s < 2; ++s) {
    const SideView& sv = view_.side(s);
    if (!sv.group_heard && !sv.group_died) return false;
    for (std::size_t i = 0; i < sv.agents.size(); ++i)
      if (view_.state(s, static_cast<int>(i)) == CellState::kUnknown) return false;
  }
  return true;
}

}  // namespace maptr::top
