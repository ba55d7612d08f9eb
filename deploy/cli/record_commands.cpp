#include "deploy/cli/record_commands.hpp"

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>

#include "deploy/cli/paths.hpp"
#include "deploy/report/run_plot.hpp"
#include "recorder/recorder.hpp"
#include "recorder/replay.hpp"
#include "records/mcap.hpp"
#include "records/run_files.hpp"

namespace maptr::deploy::cli {

namespace {
constexpr int kExitOk = 0, kExitFailed = 1, kExitBadInput = 2;

std::atomic<bool>& replay_stop() {
  static std::atomic<bool> flag{false};
  return flag;
}
void on_signal(int) { replay_stop().store(true); }

std::string mcap_path(const std::string& run) {
  return std::filesystem::is_directory(run) ? records::mcap_path(run) : run;
}

/// What a replay will leave out: "" when nothing, else e.g. "12 forged, 3 undecodable".
std::string left_out_text(const records::mcap::File& file) {
  std::map<std::string, std::size_t> n;
  std::map<uint16_t, std::string> verdict;
  for (const auto& [id, ch] : file.channels)
    if (!recorder::taken(ch)) verdict[id] = ch.metadata.at(recorder::kVerdictKey);
  for (const auto& m : file.messages)
    if (const auto v = verdict.find(m.channel_id); v != verdict.end()) ++n[v->second];
  std::string out;
  for (const auto& [kind, count] : n) out += (out.empty() ? "" : ", ") + std::to_string(count) + " " + kind;
  return out;
}

/// Whether the recording names its writers (run.mcap of this version; older ones do not).
bool names_writers(const records::mcap::File& file) {
  for (const auto& [id, ch] : file.channels)
    if (!ch.metadata.count(recorder::kVerdictKey)) return false;
  return true;
}

void say_what_is_replayed(const records::mcap::File& file, const ReplayArgs& a) {
  const std::string dropped = left_out_text(file);
  if (!names_writers(file))
    std::fprintf(stderr, "maptr: %s names no writers: every sample is replayed, whoever sent it\n",
                 a.run.c_str());
  else if (!dropped.empty() && !a.with_rejected)
    std::fprintf(stderr,
                 "maptr: leaving out the samples the fleet dropped (%s); --with-rejected sends them too\n",
                 dropped.c_str());
  else if (!dropped.empty())
    std::fprintf(stderr, "maptr: replaying the samples the fleet dropped too (%s)\n", dropped.c_str());
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
  c->add_flag(
      "--with-rejected", a.with_rejected,
      "also publish the samples the fleet dropped (forged, undecodable, malformed: run.mcap marks them)");
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
  if (!a.quiet) {
    std::set<std::string> topics;
    for (const auto& [id, ch] : file.channels) topics.insert(ch.topic);
    std::fprintf(stderr,
                 "maptr: replaying %s (%zu messages on %zu topics) on domain %d, %g simulated s per s\n",
                 path.c_str(), file.messages.size(), topics.size(), o.domain, a.rate);
  }
  say_what_is_replayed(file, a);
  const auto progress = [&](uint64_t n) {
    if (!a.quiet)
      std::fprintf(stderr, "maptr: replayed %llu of %zu\n", static_cast<unsigned long long>(n),
                   file.messages.size());
  };
  recorder::ReplayOptions r;
  r.rate = a.rate;
  r.wait_reader_s = a.wait_reader_s;
  r.with_rejected = a.with_rejected;
  const auto res = recorder::replay(file, o, r, replay_stop(), progress);
  std::printf("replayed    %llu messages, %.1f simulated s in %.1f s (the run took %.1f s)\n",
              static_cast<unsigned long long>(res.messages), res.simulated_s, res.wall_s, res.recorded_s);
  if (res.left_out > 0)
    std::printf("left out    %llu messages the fleet dropped\n",
                static_cast<unsigned long long>(res.left_out));
  return res.messages + res.left_out == file.messages.size() ? kExitOk : kExitFailed;
}

int cmd_plot(const PlotArgs& a) {
  if (!report::draw_run_plot(a.run)) return kExitFailed;
  std::printf("picture     %s/run.png\n", a.run.c_str());
  return kExitOk;
}

}  // namespace maptr::deploy::cli
