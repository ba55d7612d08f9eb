#include "deploy/cli/fleet_signal.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "deploy/fleet/launcher.hpp"
#include "deploy/fleet/registry.hpp"

namespace maptr::deploy::cli {

namespace fs = std::filesystem;

CLI::App* add_signal_command(CLI::App& app, const std::string& action, SignalArgs& a) {
  static const std::map<std::string, std::string> kWhat = {
      {"kill", "SIGKILL a process of a running fleet (e.g. L3, group-R, central)"},
      {"restart", "start a killed process of a running fleet again"},
      {"pause", "SIGSTOP a process of a running fleet (the plant drops it at once)"},
      {"resume", "SIGCONT a paused process of a running fleet (the plant expects it again)"},
      {"kill-host", "kill every process of a host of a running fleet and cut its link (e.g. h2)"},
      {"partition", "cut the link of a host of a running fleet; its processes keep running"},
      {"heal", "link a cut (or killed) host of a running fleet again"}};
  const std::string what = kWhat.at(action);
  auto* c = app.add_subcommand(action, what);
  c->add_option("target", a.target, action == "kill" || action == "restart" ? "process name" : "host (h0, h1, ...)")
      ->required();
  c->add_option("--run", a.run_dir, "run folder (default: the newest running fleet, `maptr ps`)");
  return c;
}

CLI::App* add_ps_command(CLI::App& app, PsArgs& a) {
  auto* c = app.add_subcommand("ps", "list the running fleets: folder, scenario, launcher pid, DDS domain, simulated time");
  c->add_flag("--json", a.json, "one JSON object per fleet, one per line");
  return c;
}

int cmd_ps(const PsArgs& a) {
  const auto fleets = fleet::running_fleets();
  if (!a.json) {
    if (fleets.empty()) {
      std::cout << "no running fleet\n";
      return 0;
    }
    std::printf("%-8s %-6s %10s  %-20s %s\n", "PID", "DOMAIN", "SIM TIME", "SCENARIO", "FOLDER");
  }
  for (const auto& f : fleets) {
    const double t = fleet::trace_time_s(f.run_dir);
    if (a.json) {
      nlohmann::json j = f;
      j["sim_time_s"] = std::isfinite(t) ? nlohmann::json(t) : nlohmann::json(nullptr);
      std::cout << j.dump() << "\n";
      continue;
    }
    char sim[32];
    if (std::isfinite(t))
      std::snprintf(sim, sizeof(sim), "%.1f s", t);
    else
      std::snprintf(sim, sizeof(sim), "starting");
    std::printf("%-8d %-6d %10s  %-20s %s\n", f.pid, f.domain, sim, f.scenario.c_str(), f.run_dir.c_str());
  }
  std::fflush(stdout);
  return 0;
}

std::string latest_live_run() {
  if (const auto fleets = fleet::running_fleets(); !fleets.empty()) return fleets.front().run_dir;
  std::string best;
  fs::file_time_type best_t{};
  std::error_code ec;
  if (!fs::exists("runs", ec)) return "";
  for (const auto& d : fs::directory_iterator("runs", ec)) {
    const fs::path fifo = d.path() / "control";
    if (!fs::is_fifo(fifo, ec)) continue;
    const auto t = fs::last_write_time(d.path(), ec);
    if (best.empty() || t > best_t) best = d.path().string(), best_t = t;
  }
  return best;
}

int cmd_signal(const std::string& action, const SignalArgs& a) {
  const std::string run_dir = a.run_dir.empty() ? latest_live_run() : a.run_dir;
  if (run_dir.empty()) {
    std::cerr << "maptr: " << kNoRunningFleet << "\n";
    return 2;
  }
  try {
    send_command(run_dir, action, a.target);
  } catch (const std::exception& e) {
    std::cerr << "maptr: " << e.what() << "\n";
    return 1;
  }
  std::cout << "maptr: sent '" << action << " " << a.target << "' to the fleet in " << run_dir << "\n";
  return 0;
}

}  // namespace maptr::deploy::cli
