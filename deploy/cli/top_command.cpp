#include "deploy/cli/top_command.hpp"

#include <chrono>
#include <iostream>

#include "deploy/cli/fleet_signal.hpp"
#include "deploy/cli/paths.hpp"
#include "deploy/top/screen.hpp"
#include "deploy/top/view_text.hpp"
#include "deploy/top/watch.hpp"

namespace maptr::deploy::cli {

namespace {

/// --once: after the first tick, watch at least kOnceWatch_s (tick statistics, the events'
/// history) and at most kOnceSettle_s for every agent's and group's sample, s.
constexpr double kOnceWatch_s = 1.0, kOnceSettle_s = 5.0;

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

constexpr int kExitOk = 0, kExitNoData = 1, kExitBadInput = 2;
/// Wait between two looks at the watched run, s.
constexpr double kPoll_s = 0.1;

/// Waits for the first tick; false (with the reason on stderr) when none came.
bool wait_first_tick(top::Watch& w, const TopArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  while (!w.view().ticked() && !w.ended() && since(t0) < a.timeout_s) {
    w.wait(kPoll_s);
    w.poll();
  }
  if (w.view().ticked()) return true;
  const std::string failure = w.replay_failure();
  std::cerr << "maptr: no tick from the " << (w.replaying() ? "replay of " : "fleet in ")
            << w.view().info().run_dir << " within " << a.timeout_s << " s"
            << (failure.empty() ? (w.ended() ? " (it has ended)" : "") : " (" + failure + ")") << "\n";
  return false;
}

void print(const top::Watch& w, const TopArgs& a) {
  for (const auto& line : top::layout(w.view(), a.width, 0)) std::cout << line << "\n";
}

/// A replay: the snapshot once the replay is over (after the recording's last tick), as long
/// as ticks keep coming at least every --timeout seconds.
int print_replay_once(top::Watch& w, const TopArgs& a) {
  if (!wait_first_tick(w, a)) return kExitNoData;
  auto last_progress = std::chrono::steady_clock::now();
  long long tick = w.view().tick();
  while (!w.ended() && since(last_progress) < a.timeout_s) {
    w.wait(kPoll_s);
    w.poll();
    if (w.view().tick() != tick) {
      tick = w.view().tick();
      last_progress = std::chrono::steady_clock::now();
    }
  }
  print(w, a);
  const std::string failure = w.replay_failure();
  if (w.ended() && failure.empty()) return kExitOk;
  std::cerr << "maptr: the replay of " << w.view().info().run_dir << " "
            << (failure.empty() ? "sent no tick for " + std::to_string(a.timeout_s) + " s" : failure) << "\n";
  return kExitNoData;
}

int print_once(top::Watch& w, const TopArgs& a) {
  if (w.replaying()) return print_replay_once(w, a);
  if (!wait_first_tick(w, a)) return kExitNoData;
  const auto t1 = std::chrono::steady_clock::now();
  while ((!w.complete() || since(t1) < kOnceWatch_s) && !w.ended() && since(t1) < kOnceSettle_s) {
    w.wait(kPoll_s);
    w.poll();
  }
  print(w, a);
  return kExitOk;
}

/// Watches the finished run in `run_dir` through a replay of its recording.
int watch_replay(const std::string& run_dir, const TopArgs& a, const std::string& bin_dir) {
  top::ReplayRequest r;
  r.maptr = bin_dir + "/maptr";
  r.rate = a.rate > 0 ? a.rate : 1.0;
  try {
    r.domain = a.domain >= 0 ? a.domain : top::free_domain(kMaxDomain);
  } catch (const std::exception& e) {
    std::cerr << "maptr: --run " << run_dir << ": " << e.what() << " (give one with --domain D)\n";
    return kExitBadInput;
  }
  std::string why;
  const auto c = top::replay_coordinates(run_dir, r, why);
  if (!c) {
    std::cerr << "maptr: --run " << run_dir << ": " << why << "\n";
    return kExitBadInput;
  }
  top::Watch w(*c, r);
  return a.once ? print_once(w, a) : top::run_screen(w);
}

}  // namespace

CLI::App* add_top_command(CLI::App& app, TopArgs& a) {
  auto* c = app.add_subcommand("top", "live view of a running fleet (q quits)");
  c->add_option("--run", a.run_dir, "run folder (default: the newest running fleet, `maptr ps`)");
  c->add_flag("--once", a.once, "print one plain-text snapshot and exit");
  c->add_option("--timeout", a.timeout_s, "--once: seconds to wait for the fleet's first tick")
      ->check(CLI::PositiveNumber);
  c->add_option("--width", a.width, "--once: line width")->check(CLI::Range(top::kMinWidth, 1000));
  c->add_option("--rate", a.rate, "a finished run: replay it at X simulated seconds per second (default 1)")
      ->check(CLI::PositiveNumber);
  c->add_option("--domain", a.domain, "a finished run: the replay's DDS domain (default: a free one)")
      ->check(CLI::Range(0, kMaxDomain));
  return c;
}

int cmd_top(const TopArgs& a, const std::string& bin_dir) {
  const std::string run_dir = a.run_dir.empty() ? latest_live_run() : a.run_dir;
  if (run_dir.empty()) {
    std::cerr << "maptr: " << kNoRunningFleet << "\n";
    return kExitBadInput;
  }
  top::FleetCoordinates c;
  try {
    c = top::read_fleet(run_dir);
  } catch (const std::exception& e) {
    std::cerr << "maptr: --run " << run_dir << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  if (!top::run_is_live(run_dir)) return watch_replay(run_dir, a, bin_dir);
  if (a.rate > 0 || a.domain >= 0) {
    std::cerr << "maptr: " << (a.rate > 0 ? "--rate" : "--domain") << " " << (a.rate > 0 ? a.rate : a.domain)
              << ": only for a finished run (a replay); " << run_dir << " is running\n";
    return kExitBadInput;
  }
  top::Watch w(c);
  return a.once ? print_once(w, a) : top::run_screen(w);
}

}  // namespace maptr::deploy::cli
