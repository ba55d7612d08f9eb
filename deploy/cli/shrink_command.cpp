#include "deploy/cli/shrink_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "config/scenario.hpp"
#include "deploy/cli/check_command.hpp"
#include "deploy/cli/paths.hpp"
#include "deploy/fleet/isolated_launch.hpp"
#include "deploy/fleet/run_history.hpp"
#include "deploy/fleet/shrink.hpp"
#include "model/params.hpp"
#include "records/result_table.hpp"
#include "records/run_files.hpp"

namespace maptr::deploy::cli {

namespace {
constexpr int kExitOk = 0, kExitFailed = 1, kExitBadInput = 2, kExitInterrupted = 130;
namespace fs = std::filesystem;
namespace props = deploy::properties;

/// One fleet's outcome: whether it broke a property, where first, and its trace.
struct Outcome {
  bool breaks = false;
  double t_s = -1;
  std::string why, sha;
};

struct Shrinker {
  const ShrinkArgs& a;
  std::string bin, out;
  int domain = 0;
  std::vector<props::Spec> specs;
  config::Scenario original;
  nlohmann::json cache = nlohmann::json::object();  ///< candidate key -> outcome (resumes)
  nlohmann::json steps = nlohmann::json::array();
  int fleets = 0;
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();

  std::string cache_path() const { return out + "/shrink-cache.json"; }

  /// Runs `sc` once (or takes its outcome from the cache) under `label`.
  Outcome run(config::Scenario sc, const std::string& label) {
    const std::string k = label;
    if (cache.contains(k)) {
      const auto& c = cache[k];
      return {c["breaks"], c["t_s"], c["why"], c["sha"]};
    }
    Outcome o;
    try {
      sc.validate();
    } catch (const config::ScenarioError& e) {
      o.why = std::string("not a valid scenario: ") + e.what();  // e.g. a restart without its kill
      remember(k, o, sc);
      return o;
    } catch (const model::ParamError& e) {
      o.why = std::string("not a valid robot: ") + e.what();  // e.g. too few agents for the mass
      remember(k, o, sc);
      return o;
    }
    const std::string dir = out + "/fleet-" + std::to_string(fleets++);
    const auto summary = launch_isolated(LaunchOptions::of(sc, dir, bin, domain), dir + ".log");
    if (stop_requested()) return o;
    o.sha = summary.value("trace_sha256", "");
    try {
      const auto h = props::load_history(dir);
      for (const auto& s : specs) {
        const auto v = props::evaluate(s, h);
        if (!v.holds && (!o.breaks || v.t_s < o.t_s)) {
          o.breaks = true;
          o.t_s = v.t_s;
          o.why = v.property + " at tick " + std::to_string(v.tick) + ": " + v.reason;
        }
      }
      if (!o.breaks) o.why = "holds";
    } catch (const std::exception& e) {
      o.why = std::string("no history: ") + e.what() + " (status " + summary.value("status", "?") + ")";
    }
    remember(k, o, sc, dir);
    return o;
  }

  void remember(const std::string& k, const Outcome& o, const config::Scenario& sc, const std::string& dir = "") {
    cache[k] = {{"breaks", o.breaks}, {"t_s", o.t_s}, {"why", o.why}, {"sha", o.sha}};
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    steps.push_back({{"step", steps.size()}, {"candidate", k}, {"faults", sc.faults.size()},
                     {"duration_s", sc.duration_s}, {"agents", sc.robot.agents}, {"breaks", o.breaks},
                     {"why", o.why}, {"fleet", dir}, {"wall_s", wall}});
    std::printf("shrink: step %3zu  %2zu faults  %6.1f s  %3d agents  %s  %s\n", steps.size() - 1, sc.faults.size(),
                sc.duration_s, sc.robot.agents, o.breaks ? "BREAKS" : "holds ", o.why.c_str());
    std::fflush(stdout);
    records::write_json_file(cache_path(), cache);
  }

  config::Scenario with_faults(const std::vector<int>& subset) const {
    config::Scenario sc = original;
    sc.faults.clear();
    for (const int i : subset) sc.faults.push_back(original.faults[static_cast<std::size_t>(i)]);
    return sc;
  }
};
}  // namespace

CLI::App* add_shrink_command(CLI::App& app, ShrinkArgs& a) {
  auto* c = app.add_subcommand(
      "shrink", "reduce a failing scenario (a repro.yaml) to a smallest one that still breaks a property");
  c->add_option("scenario", a.scenario, "the failing scenario YAML")->required();
  c->add_option("--property", a.properties, "NAME[:ARG] it breaks (repeatable: any of them)")->required();
  c->add_option("--out", a.out, "shrink folder (default runs/<date>-shrink-<name>); run again to resume");
  c->add_option("--domain", a.domain, "DDS domain id (default $MAPTR_DOMAIN or 0)")->check(CLI::Range(0, kMaxDomain));
  return c;
}

namespace {
/// The properties, the scenario and the folder, checked; false (after saying why) on bad input.
bool set_up(Shrinker& s) {
  const ShrinkArgs& a = s.a;
  const bool read = input_read([&] {
    s.specs = property_specs(a.properties);
    s.original = config::load_scenario(a.scenario);
    s.original.validate();
  });
  if (!read) return false;
  s.domain = resolve_domain(a.domain);
  s.out = a.out.empty() ? unique_run_dir("runs", "shrink-" + s.original.name) : a.out;
  fs::create_directories(s.out);
  s.cache = records::read_json_object(s.cache_path());
  if (!s.cache.empty()) std::printf("shrink: resuming: %zu outcomes known from %s\n", s.cache.size(), s.cache_path().c_str());
  return true;
}

/// The run's end cut to a second after the break, without the faults after it, when it still breaks.
void cut_duration(Shrinker& s, const std::vector<int>& kept, config::Scenario& best, Outcome& best_outcome) {
  const double cut = std::ceil(best_outcome.t_s) + 1.0;
  if (cut >= best.duration_s) return;
  config::Scenario shorter = best;
  shorter.duration_s = cut;
  auto& f = shorter.faults;
  f.erase(std::remove_if(f.begin(), f.end(), [&](const config::FaultSpec& x) { return x.at_s >= cut; }), f.end());
  const Outcome o = s.run(shorter, "faults:" + shrink::key(kept) + " duration:" + std::to_string(cut));
  if (o.breaks) {
    best = shorter;
    best_outcome = o;
  }
}

/// The fleet cut to the fewest agents that still break, smallest first (each fleet size from the
/// fewest the faults allow up to one four below the scenario's).
void cut_agents(Shrinker& s, const std::vector<int>& kept, config::Scenario& best, Outcome& best_outcome) {
  std::vector<std::string> targets;
  for (const auto& f : best.faults) targets.push_back(f.target);
  for (int n = shrink::fewest_agents(targets); n < best.robot.agents; n += 4) {
    config::Scenario smaller = best;
    smaller.robot.agents = n;
    const Outcome o = s.run(smaller, "faults:" + shrink::key(kept) + " duration:" + records::fixed(best.duration_s, 1) +
                                         " agents:" + std::to_string(n));
    if (stop_requested()) return;
    if (o.breaks) {
      best = smaller;
      best_outcome = o;
      return;
    }
  }
}

/// minimal.yaml and shrink.json, and the closing lines.
void write_result(const Shrinker& s, const config::Scenario& best, const Outcome& best_outcome) {
  const int n = static_cast<int>(s.original.faults.size());
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - s.t0).count();
  const std::string minimal = s.out + "/minimal.yaml";
  records::write_text_file(minimal, props::repro_yaml(config::to_yaml(best), {best_outcome.why}, best_outcome.sha));
  const nlohmann::json report = {{"scenario", s.a.scenario},
                                 {"properties", s.a.properties},
                                 {"faults_before", n},
                                 {"faults_after", best.faults.size()},
                                 {"duration_before_s", s.original.duration_s},
                                 {"duration_after_s", best.duration_s},
                                 {"agents_before", s.original.robot.agents},
                                 {"agents_after", best.robot.agents},
                                 {"fleets_run", s.fleets},
                                 {"steps", s.steps},
                                 {"wall_s", wall},
                                 {"minimal", minimal},
                                 {"breaks", best_outcome.why},
                                 {"trace_sha256", best_outcome.sha}};
  records::write_json_file(s.out + "/shrink.json", report);
  std::printf("shrink: %d -> %zu faults, %.1f -> %.1f s, %d -> %d agents; %d fleets, %zu steps, %.0f s wall\n", n,
              best.faults.size(), s.original.duration_s, best.duration_s, s.original.robot.agents, best.robot.agents,
              s.fleets, s.steps.size(), wall);
  for (const auto& f : best.faults) std::printf("shrink:   %s %s at %.2f s\n", f.action.c_str(), f.target.c_str(), f.at_s);
  std::printf("shrink: %s (maptr run %s breaks: %s)\n", minimal.c_str(), minimal.c_str(), best_outcome.why.c_str());
}
}  // namespace

int cmd_shrink(const ShrinkArgs& a, const std::string& bin_dir) {
  Shrinker s{a, bin_dir, {}, 0, {}, {}};
  if (!set_up(s)) return kExitBadInput;
  install_stop_handler();
  const int n = static_cast<int>(s.original.faults.size());
  std::printf("shrink: %s, %d faults, %.1f s, %d agents; folder %s\n", a.scenario.c_str(), n, s.original.duration_s,
              s.original.robot.agents, s.out.c_str());
  std::vector<int> all(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) all[static_cast<std::size_t>(i)] = i;
  const Outcome first = s.run(s.with_faults(all), "faults:" + shrink::key(all));
  if (stop_requested()) return kExitInterrupted;
  if (!first.breaks) {
    std::printf("shrink: the scenario does not break %s (%s): nothing to shrink\n", a.properties[0].c_str(),
                first.why.c_str());
    return kExitFailed;
  }
  // 1. The faults: a 1-minimal subset that still breaks.
  const auto kept = shrink::ddmin(n, [&](const std::vector<int>& subset) {
    if (stop_requested()) return false;
    return s.run(s.with_faults(subset), "faults:" + shrink::key(subset)).breaks;
  });
  if (stop_requested()) {
    std::printf("shrink: interrupted; run the same command again to resume\n");
    return kExitInterrupted;
  }
  config::Scenario best = s.with_faults(kept);
  Outcome best_outcome = s.run(best, "faults:" + shrink::key(kept));
  // 2. The run's end.
  cut_duration(s, kept, best, best_outcome);
  if (stop_requested()) return kExitInterrupted;
  // 3. The fleet.
  cut_agents(s, kept, best, best_outcome);
  if (stop_requested()) return kExitInterrupted;
  write_result(s, best, best_outcome);
  return kExitOk;
}

}  // namespace maptr::deploy::cli
