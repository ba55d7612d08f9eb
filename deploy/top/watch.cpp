#include "deploy/top/watch.hpp"

#include <signal.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <thread>

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
           !records::Summary::read(run_dir + "/summary.json").has_status();
  } catch (const std::exception&) {
    return false;
  }
}

std::optional<FleetCoordinates> start_replay(const std::string& run_dir, std::string& why) {
  why = run_dir +
        " has ended, and watching a finished run replays its recording, which this build "
        "does not make yet (no recording support)";
  return std::nullopt;
}

Watch::Watch(FleetCoordinates c) : c_(std::move(c)), view_(c_.info) {}

void Watch::poll() {
  const std::string dir = c_.info.run_dir;
  if (!reader_ && !ended_ && std::filesystem::exists(dir + "/trace.csv"))
    reader_ = std::make_unique<FleetReader>(c_);
  if (reader_) reader_->drain_into(view_);
  view_.observe(steady_now_s());
  if (ended_) return;
  const records::Summary s = records::Summary::read(dir + "/summary.json");
  if (s.has_status()) {
    view_.on_summary(s.status(), s.end_reason());
    ended_ = true;
  } else if (!pid_alive(c_.launcher_pid)) {
    view_.on_fleet_gone();
    ended_ = true;
  }
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
