#include "deploy/cli/top_command.hpp"

#include <chrono>
#include <iostream>

#include "deploy/cli/fleet_signal.hpp"
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

int print_once(top::Watch& w, const TopArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  while (!w.view().ticked() && !w.ended() && since(t0) < a.timeout_s) {
    w.wait(0.1);
    w.poll();
  }
  if (!w.view().ticked()) {
    std::cerr << "maptr: no tick from the fleet in " << w.view().info().run_dir << " within " << a.timeout_s
              << " s" << (w.ended() ? " (it has ended)" : "") << "\n";
    return 1;
  }
  const auto t1 = std::chrono::steady_clock::now();
  while ((!w.complete() || since(t1) < kOnceWatch_s) && !w.ended() && since(t1) < kOnceSettle_s) {
    w.wait(0.1);
    w.poll();
  }
  for (const auto& line : top::layout(w.view(), a.width, 0)) std::cout << line << "\n";
  return 0;
}

}  // namespace

CLI::App* add_top_command(CLI::App& app, TopArgs& a) {
  auto* c = app.add_subcommand("top", "live view of a running fleet (q quits)");
  c->add_option("--run", a.run_dir, "run folder (default: the newest running one under runs/)");
  c->add_flag("--once", a.once, "print one plain-text snapshot and exit");
  c->add_option("--timeout", a.timeout_s, "--once: seconds to wait for the fleet's first tick")
      ->check(CLI::PositiveNumber);
  c->add_option("--width", a.width, "--once: line width")->check(CLI::Range(top::kMinWidth, 1000));
  return c;
}

int cmd_top(const TopArgs& a) {
  const std::string run_dir = a.run_dir.empty() ? latest_live_run() : a.run_dir;
  if (run_dir.empty()) {
    std::cerr << "maptr: no running fleet found under runs/ (give its folder with --run DIR)\n";
    return 2;
  }
  top::FleetCoordinates c;
  try {
    c = top::read_fleet(run_dir);
  } catch (const std::exception& e) {
    std::cerr << "maptr: --run " << run_dir << ": " << e.what() << "\n";
    return 2;
  }
  if (!top::run_is_live(run_dir)) {
    std::string why;
    const auto replay = top::start_replay(run_dir, why);
    if (!replay) {
      std::cerr << "maptr: --run " << run_dir << ": " << why << "\n";
      return 2;
    }
    c = *replay;
  }
  top::Watch w(c);
  return a.once ? print_once(w, a) : top::run_screen(w);
}

}  // namespace maptr::deploy::cli
