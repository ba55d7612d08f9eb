#include "deploy/cli/record_commands.hpp"

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "deploy/cli/paths.hpp"
#include "deploy/report/run_plot.hpp"
#include "recorder/replay.hpp"
#include "records/mcap.hpp"

namespace maptr::deploy::cli {

namespace {
constexpr int kExitOk = 0, kExitFailed = 1, kExitBadInput = 2;

std::atomic<bool>& replay_stop() {
  static std::atomic<bool> flag{false};
  return flag;
}
void on_signal(int) { replay_stop().store(true); }

std::string mcap_path(const std::string& run) {
  return std::filesystem::is_directory(run) ? run + "/run.mcap" : run;
}
}  // namespace

CLI::App* add_replay_command(CLI::App& app, ReplayArgs& a) {
  auto* c =
      app.add_subcommand("replay", "publish a recorded run (RUN/run.mcap) again on a DDS domain, as if live");
  c->add_option("run", a.run, "run folder or .mcap file")->required();
  c->add_option("--rate", a.rate, "simulated seconds per second (default 1: the run's own simulated pace)")
      ->check(CLI::PositiveNumber);
  c->add_option("--domain", a.domain, "DDS domain id (default $MAPTR_DOMAIN or 0)")
      ->check(CLI::Range(0, kMaxDomain));
  c->add_option("--wait-reader", a.wait_reader_s, "wait up to this many seconds for a reader of the ticks")
      ->check(CLI::NonNegativeNumber);
  c->add_flag("--quiet", a.quiet, "no progress lines");
  return c;
}

CLI::App* add_plot_command(CLI::App& app, PlotArgs& a) {
  auto* c =
      app.add_subcommand("plot", "draw RUN/run.png again from the run folder's trace.csv and summary.json");
  c->add_option("run", a.run, "run folder")->required();
  return c;
}

int cmd_replay(const ReplayArgs& a) {
  const std::string path = mcap_path(a.run);
  records::mcap::File file;
  try {
    file = records::mcap::read_file(path);
  } catch (const records::RecordError& e) {
    std::cerr << "maptr: replay " << a.run << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  comm::DdsOptions o = comm::options_from_env();
  o.domain = resolve_domain(a.domain);
  o.discovery_server.clear();  // readers find the replay by simple discovery on its domain
  o.participant_id = -1;
  o.fleet_id = 0;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  if (!a.quiet)
    std::fprintf(stderr, "maptr: replaying %s (%zu messages on %zu topics) on domain %d, %g simulated s per s\n",
                 path.c_str(), file.messages.size(), file.channels.size(), o.domain, a.rate);
  const auto progress = [&](uint64_t n) {
    if (!a.quiet)
      std::fprintf(stderr, "maptr: replayed %llu of %zu\n", static_cast<unsigned long long>(n),
                   file.messages.size());
  };
  recorder::ReplayOptions r;
  r.rate = a.rate;
  r.wait_reader_s = a.wait_reader_s;
  const auto res = recorder::replay(file, o, r, replay_stop(), progress);
  std::printf("replayed    %llu messages, %.1f simulated s in %.1f s (the run took %.1f s)\n",
              static_cast<unsigned long long>(res.messages), res.simulated_s, res.wall_s, res.recorded_s);
  return res.messages == file.messages.size() ? kExitOk : kExitFailed;
}

int cmd_plot(const PlotArgs& a) {
  if (!report::draw_run_plot(a.run)) return kExitFailed;
  std::printf("picture     %s/run.png\n", a.run.c_str());
  return kExitOk;
}

}  // namespace maptr::deploy::cli
