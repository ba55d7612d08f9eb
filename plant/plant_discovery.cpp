// The plant's discovery: every endpoint of the fleet matched, the hello, the launcher's start;
// what it still misses, for its log and for the launcher (plant/discovery_wait.hpp).
#include <algorithm>
#include <tuple>

#include "comm/dds/fleet_guid.hpp"
#include "comm/dds/fleet_ids.hpp"
#include "comm/lockstep/lockstep.hpp"
#include "idl/rules.hpp"
#include "plant/discovery_wait.hpp"
#include "plant/plant_loop.hpp"

namespace maptr::plant {

namespace {

std::string& hidden_agent() {
  static std::string name;
  return name;
}

}  // namespace

void hide_first_answer_writer_of(const std::string& name) { hidden_agent() = name; }

// Every endpoint of the fleet matched, then tell the launcher; true once it says start.
bool PlantLoop::discover() {
  const int n_agents = sc_.robot.agents;
  const auto t_launch = Clock::now();
  seen_ = signal_.count();
  bool announced = false, started = false;
  // The tick goes to the agents, 2 groups, central, the launcher and the recorder (lockstep.hpp).
  const int tick_readers = n_agents + 4 + comm::recorder_readers(sc_.record, true);
  // Without progress for a while, the log says what is still missing (the launcher starts a
  // process again after a longer stall; this line tells which endpoints were never matched).
  auto counts = std::make_tuple(-1, -1, -1, -1);
  auto last_change = t_launch, last_report = t_launch, last_unmatched = t_launch;
  bool missed_reported = false;  // a report named someone: the launcher hears when no one is left
  while (!stop_.load() && !started) {
    wait(c_.discovery_poll);
    const int replies = replies_.matched() - hidden_replies();
    const auto now_counts = std::make_tuple(replies, groups_.matched(), centrals_.matched(), tick_match_.matched());
    if (now_counts != counts) {
      counts = now_counts;
      last_change = Clock::now();
    }
    if (!announced && Clock::now() - last_change >= c_.discovery_report &&
        Clock::now() - last_report >= c_.discovery_report) {
      last_report = Clock::now();
      log_.warn("discovery: no progress for {:.0f} s; matched {}",
                std::chrono::duration<double>(last_report - last_change).count(),
                discovery_wait_report(n_agents, discovery_view(tick_readers)));
    }
    // The launcher hears whom the plant still misses: when only the plant is not ready, it starts
    // those members again rather than the plant (Fleet::rematch_unready).
    if (!announced && Clock::now() - last_unmatched >= c_.discovery_report) {
      last_unmatched = Clock::now();
      const auto missing = discovery_unmatched(n_agents, discovery_view(tick_readers), msg::kMaxUnmatched);
      comm::report_unmatched(w_ready_, "plant", msg::NODE_PLANT, missing);
      missed_reported = missed_reported || !missing.empty();
    }
    if (!announced && replies >= n_agents && groups_.matched() >= 2 && centrals_.matched() >= 1 &&
        tick_match_.matched() >= tick_readers) {
      // A report of no one, so that an earlier one naming members now matched is not acted on.
      if (missed_reported) comm::report_unmatched(w_ready_, "plant", msg::NODE_PLANT, {});
      say_hello(tick_readers - 1);  // every tick reader but the launcher's
      comm::announce_ready(w_ready_, "plant", msg::NODE_PLANT);
      announced = true;
      log_.info("all {} agents, 2 groups and central matched after {:.2f} s", n_agents,
                std::chrono::duration<double>(Clock::now() - t_launch).count());
    }
    for (const auto& c : take_controls())
      if (c.command() == msg::CONTROL_START) started = true;
  }
  return started;
}

void PlantLoop::say_hello(int members) {
  // Best effort reaches only the readers matched by now.
  const auto until = Clock::now() + c_.hello_wait;
  while (hello_match_.matched() < members && Clock::now() < until && !stop_.load()) wait(c_.discovery_poll);
  const auto t0 = Clock::now();
  comm::write_ready(w_hello_, "plant", msg::NODE_PLANT);
  log_.info("hello to {} of {} readers in {:.3f} s (their ports open before tick 0)", hello_match_.matched(), members,
            std::chrono::duration<double>(Clock::now() - t0).count());
}

DiscoveryView PlantLoop::discovery_view(int tick_readers) const {
  const uint32_t fleet = p_.options().fleet_id;
  const auto ids = [fleet](const std::vector<Handle>& handles) {
    std::vector<int> out;
    for (const auto& h : handles)
      if (const auto id = comm::fleet_participant(fleet, h)) out.push_back(*id);
    return out;
  };
  DiscoveryView v;
  v.reply_writers = ids(replies_.matched_writers());
  if (!hidden_agent().empty()) {
    const int hidden = comm::base_participant_id(hidden_agent(), sc_.robot.agents);
    v.reply_writers.erase(std::remove(v.reply_writers.begin(), v.reply_writers.end(), hidden), v.reply_writers.end());
  }
  v.group_writers = ids(groups_.matched_writers());
  v.central_writers = ids(centrals_.matched_writers());
  v.tick_readers = ids(tick_match_.matched_readers());
  v.tick_readers_expected = tick_readers;
  return v;
}

int PlantLoop::hidden_replies() const {
  if (hidden_agent().empty()) return 0;
  const int hidden = comm::base_participant_id(hidden_agent(), sc_.robot.agents);
  const auto writers = replies_.matched_writers();
  return static_cast<int>(std::count_if(writers.begin(), writers.end(), [&](const Handle& h) {
    return comm::fleet_participant(p_.options().fleet_id, h) == hidden;
  }));
}

}  // namespace maptr::plant
