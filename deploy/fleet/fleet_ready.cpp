// The launcher's readiness: a NodeReady counts only from the participant the launcher expects
// for that process (deploy/fleet/ready_check.hpp); forged and stale ones are counted and logged.
// A process that does not get ready in time is started again.
#include <algorithm>

#include "comm/dds/fleet_guid.hpp"
#include "deploy/fleet/fleet.hpp"
#include "idl/rules.hpp"

namespace maptr::deploy::fleet {

namespace {
/// Rejected NodeReady samples logged one by one; the rest only counted.
constexpr long kLoggedRejects = 20;
}  // namespace

ReadyClaim Fleet::claim_of(const msg::NodeReady& r, const eprosima::fastrtps::rtps::InstanceHandle_t& writer,
                           Child*& c) {
  ReadyClaim claim;
  claim.well_formed = msg::well_formed(r);
  if (!claim.well_formed) return claim;
  c = find(r.name());
  if (!c) return claim;
  claim.known_name = true;
  claim.external = c->external;
  const int agents = sc_.robot.agents;
  if (secure()) {
    // The prefix names the writer's certificate: the same at every start.
    claim.from_current_participant = comm::written_by(dds_.fleet_id, agents, writer, c->name);
  } else {
    const auto id = comm::fleet_participant(dds_.fleet_id, writer);
    claim.from_current_participant = id && *id == c->participant_id;
    claim.from_earlier_participant =
        id && !claim.from_current_participant && comm::written_by(dds_.fleet_id, agents, writer, c->name);
  }
  const auto pid = static_cast<pid_t>(r.pid());
  // A process started over ssh (or on a real machine) has a pid of its machine, not the one of
  // the launcher's child (its ssh client): there its participant id, given to this start only,
  // is what says it is the launcher's.
  const bool remote = c->host >= 0 && on_hosts() && (is_ssh_prefix(c->prefix) || !hosts_->namespaces());
  claim.pid_matches = c->running && (remote ? claim.from_current_participant : pid == c->pid);
  if (remote && claim.pid_matches) c->remote_pid = pid;
  // A secure process's earlier start has the same certificate: its old pid tells it apart.
  if (secure() && !c->external && claim.from_current_participant && !claim.pid_matches)
    claim.from_earlier_participant = true, claim.from_current_participant = false;
  if (c->external && claim.from_current_participant) {
    bool unreadable = false;
    const auto problem = external_pid_problem(pid, c->binary, dds_.fleet_id, c->participant_id, unreadable);
    claim.external_pid_ok = !problem || unreadable;
    if (!problem) {
      c->pid = pid;  // verified: its executable and its environment are this fleet's
    } else if (unreadable) {
      log_.warn("external {}: {}; ready, but the launcher will not take its pid", c->name, *problem);
    } else {
      log_.warn("external {}: {}", c->name, *problem);
    }
  }
  return claim;
}

std::vector<Child*> Fleet::believed_ready() {
  std::vector<Child*> out;
  for (auto& [r, h] : domain_->take_ready()) {
    Child* c = nullptr;
    const ReadyVerdict v = judge_ready(claim_of(r, h, c));
    if (v == ReadyVerdict::kTaken) {
      if (r.ready() && std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
      if (!r.ready() && c->kind == ChildKind::kPlant) plant_unmatched_ = r.unmatched();
      continue;
    }
    const long n = ++rec_.ready_rejected[verdict_name(v)];
    if (n <= kLoggedRejects)
      log_.warn("rejected a {} NodeReady: name '{}', pid {}, writer {}{}", verdict_name(v),
                r.name().substr(0, 64), r.pid(), comm::prefix_text(h),
                n == kLoggedRejects ? " (no more of this kind are logged)" : "");
  }
  return out;
}

bool Fleet::restart_dead(Child& c) {
  if (c.discovery_deaths >= cfg_.discovery_death_restarts) return false;
  ++c.discovery_deaths;
  const std::string how = describe_end(c, o_.run_dir);
  ready_names_.erase(c.name);
  if (&c == &kids_.front()) plant_done_ = false;  // a plant that ended during discovery starts again too
  spawn_child(c);
  write_fleet();
  rec_.rematched.push_back(c.name);
  log_.warn("{} ended during discovery ({}); started again (pid {}), as one that never gets ready is", c.name,
            how, c.pid);
  return true;
}

void Fleet::take_ready() {
  for (Child* c : believed_ready()) ready_names_.insert(c->name);
  // Over ssh a process's pid on its host comes with its readiness: fleet.json names it for the
  // tools that read a process's /proc (the benches), as the launcher's child is its ssh client.
  const auto known =
      std::count_if(kids_.begin(), kids_.end(), [](const Child& c) { return c.remote_pid > 0; });
  if (known != host_pids_written_) {
    host_pids_written_ = known;
    write_fleet();
  }
}

void Fleet::announce_restarted() {
  // Restarted processes report ready: the plant may wait for them from now on.
  for (Child* c : believed_ready()) {
    if (!c->awaiting_ready) continue;
    c->awaiting_ready = false;
    publish_member(*c, msg::MEMBER_STARTED);
    log_.info("{} (pid {}) restarted and ready", c->name, c->pid);
    failed_over(*c);
  }
}

std::string Fleet::not_ready() const {
  std::string missing;
  for (const auto& c : kids_)
    if (!ready_names_.count(c.name)) missing += (missing.empty() ? "" : " ") + c.name;
  return missing;
}

pid_t Fleet::start_again(Child& c) {
  // SIGTERM, not SIGKILL: a process killed inside a shared-memory operation leaves its lock held
  // and the others' transport aborts.
  const pid_t old = c.pid;
  stop_process(c.pid, cfg_.end_term_s);
  c.running = false;
  spawn_child(c);
  write_fleet();
  return old;
}

void Fleet::rematch_unready() {
  // Before the run starts: end and start again, with the next participant id of its window,
  // every started process that is not ready; the plant (ready once it matched everyone) only
  // when it is the last one, and then the members it says it has not matched, if it names any.
  std::vector<std::string> unready;
  std::set<std::string> ready;
  for (std::size_t i = 0; i < waves_->started(); ++i) {
    const Child& c = kids_[i];
    if (c.external || !c.running) continue;
    if (ready_names_.count(c.name))
      ready.insert(c.name);
    else
      unready.push_back(c.name);
  }
  const bool plant_asks = unready.size() == 1 && unready.front() == kids_.front().name;
  for (const auto& name : rematch_choice(unready, plant_unmatched_, ready)) {
    Child* c = find(name);
    if (!c) continue;
    ready_names_.erase(c->name);
    start_again(*c);
    rec_.rematched.push_back(c->name);
    log_.warn("{} {} within {:.0f} s of discovery's last progress; started again (pid {})", c->name,
              c->kind != ChildKind::kPlant && plant_asks ? "was not matched by the plant" : "did not match the fleet",
              cfg_.rematch_s(sc_.robot.agents, secure()), c->pid);
  }
  plant_unmatched_.clear();  // only a report after these starts counts
  last_progress_ = Clock::now();
}

}  // namespace maptr::deploy::fleet
