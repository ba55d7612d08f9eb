// The run of a fleet: the plant's clock, commands, fault gates, deaths and restarts.
#include <algorithm>
#include <csignal>
#include <cstdio>

#include "comm/lockstep/side.hpp"
#include "deploy/fleet/fleet.hpp"
#include "idl/rules.hpp"

namespace maptr::deploy::fleet {

namespace {
double wall_ms_now() {
  return std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

Child* Fleet::find(const std::string& name) {
  for (auto& c : kids_)
    if (c.name == name) return &c;
  return nullptr;
}

void Fleet::publish_member(const Child& c, msg::MemberEvent kind) {
  domain_->publish_member(c, kind, since(t_launch_));
}

void Fleet::reap(bool expected) {
  for (auto& ds : ds_) {
    bool started = false;
    if (expected || !ds->restart_if_due(env_, ids_, started)) continue;
    if (started)
      log_.info("the discovery server {} runs again (pid {})", ds->address(), ds->pid());
    else
      log_.error("the discovery server {} did not start again", ds->address());
  }
  while (const auto e = reap_one()) on_exit(*e, expected);
}

void Fleet::on_exit(const Exit& e, bool expected) {
  if (zygote_ && e.pid == zygote_->pid()) {
    zygote_->lost();
    log_.warn("the agents' zygote (pid {}) ended: exit {} signal {}; agents start with exec from now on", e.pid,
              e.exit_code, e.signal);
    return;
  }
  for (auto& ds : ds_) {
    if (!ds->on_exit(e, expected)) continue;
    ds_paused_ = false;
    // Established matches survive; the restarted server lets the clients re-register.
    if (!expected)
      log_.warn("the discovery server (pid {}) died: exit {} signal {}", e.pid, e.exit_code, e.signal);
    return;
  }
  forget_stranded(e.pid);
  Child* c = nullptr;
  for (auto& k : kids_)
    if (k.pid == e.pid && k.running) c = &k;
  if (!c) return;
  record_exit(*c, e);
  if (c == &kids_.front()) plant_done_ = true;
  // A clean exit is a process that saw the plant's last tick; anything else is a failure.
  // During discovery the plant waits for nobody yet: a process that ends then is started again
  // (restart_dead) or the run aborts, and no death is announced.
  if (!expected && !ended_cleanly(*c) && c != &kids_.front() && discovered_) {
    publish_member(*c, msg::MEMBER_DIED);
    log_.warn("{} (pid {}) died: exit {} signal {}", c->name, e.pid, c->exit_code, c->signal);
  }
}

TargetState Fleet::state_of(const std::string& target) {
  if (target == kDiscoveryTarget)
    return ds_.empty() ? TargetState{}
                       : TargetState{true, false, ds_.front()->running(), ds_paused_,
                                     on_hosts() && is_ssh_prefix(hosts_->host(0).prefix)};
  const Child* c = find(target);
  return c ? TargetState{true, c->external, c->running, c->paused, is_ssh_prefix(c->prefix)} : TargetState{};
}

pid_t Fleet::pid_of(const std::string& target) {
  if (target == kDiscoveryTarget) return ds_.empty() ? -1 : ds_.front()->pid();
  const Child* c = find(target);
  return c ? c->pid : -1;
}

void Fleet::kill_target(const std::string& target) {
  if (target != kDiscoveryTarget) {
    kill(find(target)->pid, SIGKILL);
    return;
  }
  kill(ds_.front()->pid(), SIGCONT);  // a stopped server would not end on SIGTERM
  ds_paused_ = false;
  ds_.front()->kill_now();
}

void Fleet::restart_target(const std::string& target) {
  Child& c = *find(target);
  if (on_hosts()) hosts_->move_off_unreachable(c);
  spawn_child(c);
  c.awaiting_ready = true;
}

void Fleet::pause_target(const std::string& target, bool pause) {
  pause_or_resume(target == kDiscoveryTarget ? nullptr : find(target), pid_of(target), pause);
}

void Fleet::apply_fault(const config::FaultSpec& f, double at_s, const std::string& origin) {
  const FaultOutcome o = faults_.apply(f, at_s, wall_ms_now(), origin);
  if (!o.line.empty()) log_.warn("{}", o.line);
}

void Fleet::pause_or_resume(Child* c, pid_t pid, bool pause) {
  // The event reaches the plant before the gate opens: the member is out from this tick on
  // (paused) or waited for again from this tick on (resumed).
  if (pid <= 0) return;  // never kill(-1, ...): that is every process
  kill(pid, pause ? SIGSTOP : SIGCONT);
  if (!c) {
    ds_paused_ = pause;
    return;
  }
  c->paused = pause;
  publish_member(*c, pause ? msg::MEMBER_PAUSED : msg::MEMBER_RESUMED);
}

bool Fleet::restart_unready(const std::vector<std::string>& restarted) {
  // A process restarted at this gate that did not report ready in time: ended and started once
  // more, with the next participant id (the plant still counts it dead and waits for its start).
  bool any = false;
  for (auto& c : kids_) {
    if (!c.awaiting_ready || !c.running ||
        std::find(restarted.begin(), restarted.end(), c.name) == restarted.end())
      continue;
    const pid_t old = start_again(c);
    log_.warn(
        "fault gate: restarted {} (pid {}) did not report ready within {:.0f} s; started again (pid {})",
        c.name, old, cfg_.restart_ready_s(sc_.robot.agents), c.pid);
    any = true;
  }
  return any;
}

void Fleet::open_gate(const msg::FaultGate& g) {
  // Apply every scheduled fault due at the gate's time, wait until each killed process is
  // reaped (its death published) and each restarted one is ready, then let the plant go on.
  std::vector<std::string> killed, restarted;
  for (const auto& f : faults_.due(g.t())) {
    if (f.action == "kill") killed.push_back(f.target);
    if (f.action == "restart") restarted.push_back(f.target);
    if (config::is_host_action(f.action)) {
      for (const auto& k : apply_host_fault(f, g.t())) killed.push_back(k);
      continue;
    }
    apply_fault(f, g.t(), o_.chaos_seed >= 0 ? "chaos" : "scheduled");
  }
  auto t0 = Clock::now();
  const double limit = cfg_.restart_ready_s(sc_.robot.agents);
  int retries = 0;
  for (;;) {
    reap(false);
    for (auto& name : fail_over()) {  // killed with its host, running again elsewhere
      restarted.push_back(name);
      killed.erase(std::remove(killed.begin(), killed.end(), name), killed.end());
    }
    announce_restarted();
    if (!gate_pending(kids_, killed, restarted) || interrupted().load() || plant_done_) break;
    if (since(t0) > limit && retries < cfg_.restart_unready_retries && restart_unready(restarted)) {
      ++retries;
      t0 = Clock::now();
      continue;
    }
    if (since(t0) > limit) {
      log_.error(
          "fault gate at t={:.2f} s: a killed process did not end or a restarted one did not report ready "
          "within {:.0f} s; the plant goes on",
          g.t(), limit);
      break;
    }
    domain_->wait_until(Clock::now() + cfg_.gate_poll);
  }
  domain_->open_gate(g.tick());
}

void Fleet::take_ticks() {
  for (auto& [t, h] : domain_->take_ticks()) {
    learn_secure_plant(h);
    clock_.on_tick(writer_prefix(h), {t.t(), t.v_x(), t.energy_J(), t.sides()[msg::SIDE_L].n_active(),
                                      t.sides()[msg::SIDE_R].n_active()});
  }
}

void Fleet::take_commands() {
  // Commands from `maptr kill|restart NAME` act at once, at the current simulated time.
  for (const auto& c : fifo_->read()) {
    if (!c.valid) {
      log_.warn("ignored control command '{}'", c.action + " " + c.target);
      continue;
    }
    log_.info("command: {} {}", c.action, c.target);
    const config::FaultSpec f = config::FaultSpec::of(c.target, c.action, clock_.state().t);
    if (config::is_host_action(c.action))
      apply_host_fault(f, clock_.state().t);
    else
      apply_fault(f, clock_.state().t, "command");
  }
}

void Fleet::print_progress() {
  if (clock_.rejected() > reported_rejected_) {
    log_.warn("ignored {} ticks or fault gates from a participant other than the plant's",
              clock_.rejected() - reported_rejected_);
    reported_rejected_ = clock_.rejected();
  }
  if (!o_.progress || since(last_print_) < cfg_.progress_period_s) return;
  last_print_ = Clock::now();
  const PlantState& s = clock_.state();
  const double rtf = s.t / std::max(1e-9, since(t_run_));
  std::fprintf(stderr, "maptr: t=%7.1f/%.0f s  RTF %6.1f  v=%6.3f m/s  active L%d R%d  E=%.1f kJ\n", s.t,
               sc_.duration_s, rtf, s.v_x, s.active_L, s.active_R, s.energy_J / 1000.0);
}

void Fleet::run() {
  // Scheduled faults act at the plant's fault gates (the first tick at or after their time,
  // held until they are applied), so that they hit the same tick in every run.
  t_run_ = last_print_ = Clock::now();
  stall_.start(0.0);
  while (rec_.status == "ok" && !plant_done_) {
    domain_->wait_until(Clock::now() + cfg_.run_poll);
    take_ticks();
    take_commands();
    for (auto& [g, h] : domain_->take_gates()) {
      learn_secure_plant(h);
      if (!clock_.from_plant(writer_prefix(h))) continue;
      if (!msg::well_formed(g)) {  // the rule beside the IDL type (idl/rules.hpp)
        ++rec_.launcher_by_kind["malformed"];
        log_.warn("rejected a malformed fault gate from the plant's participant (tick {}, t {})", g.tick(),
                  g.t());
        continue;
      }
      clock_.on_gate(g.t());
      ++gates_seen_;
      open_gate(g);
      stall_.held_until(since(t_run_));  // the launcher held the run while it answered the gate
    }
    announce_restarted();
    reap(false);
    fail_over();  // the controllers of a host lost by a command, outside any gate
    if (interrupted().load()) rec_.status = "aborted: interrupted";
    stall_.observe(clock_.state().t, gates_seen_, since(t_run_));
    if (rec_.status == "ok" && !plant_done_ && stall_.stalled(since(t_run_))) {
      rec_.status = stalled_status(stall_);
      log_.error("the run stalled: no tick or fault gate from the plant for {:.0f} s (last at t={:.2f} s)",
                 stall_.idle_s(since(t_run_)), clock_.state().t);
    }
    print_progress();
  }
  rec_.run_wall_s = since(t_run_);
  faults_.schedule().close();
}

}  // namespace maptr::deploy::fleet
