#include "deploy/cli/soak_command.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <thread>

#include "comm/posix/shm_files.hpp"
#include "config/scenario.hpp"
#include "deploy/cli/check_command.hpp"
#include "deploy/cli/paths.hpp"
#include "deploy/cli/soak_leftovers.hpp"
#include "deploy/fleet/children.hpp"
#include "deploy/fleet/launcher.hpp"
#include "deploy/fleet/shm_segments.hpp"
#include "deploy/fleet/soak.hpp"
#include "deploy/fleet/summary_build.hpp"
#include "model/params.hpp"
#include "records/junit.hpp"
#include "records/result_table.hpp"
#include "records/run_files.hpp"

namespace maptr::deploy::cli {

namespace fs = std::filesystem;

namespace {

constexpr int kExitOk = 0, kExitFailed = 1, kExitBadInput = 2;
constexpr std::chrono::milliseconds kPoll{100};
/// Wall time a launcher gets to end its fleet after SIGTERM before it is killed, s (its own end
/// of a fleet takes at most about 25 s).
constexpr double kLauncherEndGraceS = 60.0;
/// Period of the samples of the shared-memory segments the fleet's processes map, s.
constexpr double kSegmentSampleS = 0.5;

std::atomic<bool> g_interrupted{false};
void on_interrupt(int) { g_interrupted.store(true); }

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// One `maptr run` of the soak.
struct FleetRun {
  int exit_code = -1;
  bool timed_out = false;
  bool killed = false;             ///< the launcher did not end after SIGTERM and was killed
  std::set<std::string> segments;  ///< shared-memory segments the fleet's processes mapped
  double wall_s = 0.0;
  nlohmann::json summary = nlohmann::json::object();
};

/// Runs `maptr run yaml --out dir --domain d --quiet` (output to dir.log) and waits for it.
FleetRun run_fleet(const std::string& bin, const std::string& yaml, const std::string& dir, int domain,
                   double timeout_s) {
  const std::string maptr = bin + "/maptr", log = dir + ".log", dom = std::to_string(domain);
  std::vector<std::string> args = {maptr, "run", yaml, "--out", dir, "--domain", dom, "--quiet"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  FleetRun r;
  const auto t0 = Clock::now();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    execv(argv[0], argv.data());
    _exit(127);
  }
  int st = 0;
  auto last_sample = Clock::now() - std::chrono::hours(1);
  while (waitpid(pid, &st, WNOHANG) != pid) {
    const soak::Deadline d = soak::fleet_deadline(since(t0), timeout_s, kLauncherEndGraceS);
    if (d == soak::Deadline::kTerm && !r.timed_out) {
      r.timed_out = true;
      kill(pid, SIGTERM);  // the launcher ends its fleet; its children die with it in any case
    } else if (d == soak::Deadline::kKill && !r.killed) {
      r.killed = true;
      kill(pid, SIGKILL);  // check_leftovers() then kills what is left of the fleet
    }
    if (since(last_sample) >= kSegmentSampleS) {
      sample_segments(pid, dir, r.segments);
      last_sample = Clock::now();
    }
    std::this_thread::sleep_for(kPoll);
  }
  r.wall_s = since(t0);
  r.exit_code = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  r.summary = records::read_json_object(records::summary_path(dir));
  return r;
}

/// The soak's scenario with `faults`, written where its fleet's `maptr run` reads it.
std::string write_scenario(config::Scenario s, std::vector<config::FaultSpec> faults,
                           const std::string& path) {
  s.faults = std::move(faults);
  s.validate();
  std::ofstream(path) << config::to_yaml(s);
  return path;
}

/// Running totals of the soak.
struct Totals {
  int fleets = 0, failed_fleets = 0;
  std::map<std::string, int> faults;         ///< applied by kind, and "skipped"
  std::map<std::string, int> failed_checks;  ///< by check
  std::map<std::string, int> statuses;       ///< "ok", "degraded"
  long long applied() const {
    long long n = 0;
    for (const auto& [k, v] : faults)
      if (k != "skipped") n += v;
    return n;
  }
};

struct Soak {
  Soak(const SoakArgs& args, std::string bin_dir) : a(args), bin(std::move(bin_dir)) {}
  const SoakArgs& a;
  std::string bin, out;
  int domain = 0;
  config::Scenario sc;
  soak::Band band;
  nlohmann::json reference, fleets = nlohmann::json::array();
  Totals totals;
  std::vector<properties::Spec> specs;  ///< --property
  std::vector<records::JunitCase> cases;  ///< one per fleet, for --junit
};

}  // namespace

CLI::App* add_soak_command(CLI::App& app, SoakArgs& a) {
  auto* c = app.add_subcommand(
      "soak", "fleets back to back with seeded random kills, restarts, pauses, resumes and agent faults; checks each one");
  c->add_option("--seed", a.seed, "seed of the fault schedules")->check(CLI::Range(0LL, 4294967295LL));
  c->add_option("--faults", a.faults, "faults to apply over the whole soak")
      ->check(CLI::Range(1LL, 1000000LL));
  c->add_option("--agents", a.agents, "agents per fleet (multiple of 4)");
  c->add_option("--outages", a.outages, "random outages drawn per fleet")->check(CLI::Range(1, 100));
  c->add_option("--scenario", a.scenario, "scenario YAML (default: deploy/scenarios/soak.yaml)");
  c->add_option("--out", a.out, "soak folder (default runs/<date>-soak-<seed>)");
  c->add_option("--domain", a.domain, "DDS domain id (default $MAPTR_DOMAIN or 0)")
      ->check(CLI::Range(0, kMaxDomain));
  c->add_option("--fleet-timeout", a.fleet_timeout_s, "wall seconds after which a fleet fails")
      ->check(CLI::Range(10.0, 86400.0));
  c->add_option("--property", a.properties,
                "also check NAME[:ARG] over each fleet, as `maptr check` does (repeatable; maptr check --list)");
  c->add_option("--junit", a.junit, "also write a JUnit XML file, one test case per fleet");
  return c;
}

namespace {

/// The --property checks of a fleet: their verdicts, and a failure per broken one in `failed`.
nlohmann::json check_properties(const Soak& s, const std::string& dir,
                                std::vector<std::pair<std::string, std::string>>& failed) {
  nlohmann::json verdicts = nlohmann::json::array();
  if (s.specs.empty()) return verdicts;
  try {
    for (const auto& v : check_run(dir, s.specs)) {
      verdicts.push_back({{"property", v.property}, {"holds", v.holds}, {"tick", v.tick}, {"reason", v.reason}});
      if (!v.holds) failed.push_back({"property", v.property + " at tick " + std::to_string(v.tick) + ": " + v.reason});
    }
  } catch (const std::exception& e) {
    failed.push_back({"property", std::string("no history to check: ") + e.what()});
  }
  return verdicts;
}

/// DIR/repro.yaml of a fleet that failed a check, "" when it passed them all.
std::string fleet_repro(const std::string& dir, const std::vector<std::pair<std::string, std::string>>& failed,
                        const nlohmann::json& summary) {
  if (failed.empty()) return "";
  std::vector<std::string> lines;
  for (const auto& [check, why] : failed) lines.push_back(check + ": " + why);
  return write_repro(dir, lines, summary.value("trace_sha256", ""), dir + ".yaml");
}

/// The soak's own checks of one fleet (run, processes, shared memory, wear, band, detection): (check, why).
std::vector<std::pair<std::string, std::string>> soak_checks(const Soak& s, const FleetRun& r,
                                                             const std::string& dir, const ShmCount& before) {
  std::vector<std::pair<std::string, std::string>> failed;  // (check, why)
  if (r.timed_out) failed.push_back({"timeout", "still running after the fleet timeout"});
  if (r.killed)
    failed.push_back({"timeout", "the launcher did not end within " +
                                     std::to_string(int(kLauncherEndGraceS)) + " s of SIGTERM: killed"});
  if (const auto why = soak::check_status(r.summary); !why.empty()) failed.push_back({"status", why});
  if (const auto why = check_leftovers(dir); !why.empty()) failed.push_back({"processes", why});
  if (const auto why = check_shm(before, count_shm(s.domain)); !why.empty()) failed.push_back({"shm", why});
  if (const auto why = check_segments(r.segments); !why.empty()) failed.push_back({"shm", why});
  for (const auto& why : soak::check_wear(r.summary, dir, s.sc.robot.per_side()))
    failed.push_back({"wear", why});
  for (const auto& why : soak::check_band(r.summary, s.reference, s.band)) failed.push_back({"band", why});
  for (const auto& why : soak::check_detection(r.summary)) failed.push_back({"detection", why});
  return failed;
}

/// One fleet's checks, printed and recorded; true when all of them passed.
bool check_fleet(Soak& s, int index, const FleetRun& r, const std::string& dir, const ShmCount& before) {
  auto failed = soak_checks(s, r, dir, before);
  const nlohmann::json verdicts = check_properties(s, dir, failed);
  const auto kinds = soak::faults_by_kind(r.summary);
  for (const auto& [k, v] : kinds) s.totals.faults[k] += v;
  const std::string status = r.summary.value("status", "none");
  ++s.totals.statuses[status.substr(0, status.find(':'))];
  ++s.totals.fleets;
  if (!failed.empty()) ++s.totals.failed_fleets;
  nlohmann::json rec = {{"index", index},
                        {"seed", soak::fleet_seed(static_cast<unsigned>(s.a.seed), index)},
                        {"dir", dir},
                        {"status", status},
                        {"exit_code", r.exit_code},
                        {"wall_s", r.wall_s},
                        {"shm_segments", r.segments.size()},
                        {"faults", kinds},
                        {"distance_m", r.summary.value("distance_m", 0.0)},
                        {"energy_J", r.summary.value("energy_J", 0.0)},
                        {"distance_dev_pct", soak::deviation_pct(r.summary.value("distance_m", 0.0),
                                                                 s.reference.value("distance_m", 0.0))},
                        {"energy_dev_pct", soak::deviation_pct(r.summary.value("energy_J", 0.0),
                                                               s.reference.value("energy_J", 0.0))},
                        {"failures", nlohmann::json::array()}};
  rec["properties"] = verdicts;
  if (!failed.empty()) rec["repro"] = fleet_repro(dir, failed, r.summary);
  std::string failures;
  for (const auto& [check, why] : failed) failures += (failures.empty() ? "" : "\n") + check + ": " + why;
  s.cases.push_back({"fleet-" + std::to_string(index), "maptr.soak", r.wall_s, failures});
  std::set<std::string> checks;
  for (const auto& [check, why] : failed) {
    checks.insert(check);
    rec["failures"].push_back({{"check", check}, {"why", why}});
  }
  for (const auto& check : checks) ++s.totals.failed_checks[check];
  std::printf(
      "soak: fleet %3d  faults %2lld (kill %d restart %d pause %d resume %d, skipped %d)  %-9s  "
      "distance %+6.1f%%  energy %+6.1f%%  %5.1f s  %s  [total %lld/%lld]\n",
      index,
      static_cast<long long>(kinds.at("kill") + kinds.at("restart") + kinds.at("pause") + kinds.at("resume")),
      kinds.at("kill"), kinds.at("restart"), kinds.at("pause"), kinds.at("resume"), kinds.at("skipped"),
      status.substr(0, status.find(':')).c_str(), rec["distance_dev_pct"].get<double>(),
      rec["energy_dev_pct"].get<double>(), r.wall_s, failed.empty() ? "PASS" : "FAIL", s.totals.applied(),
      s.a.faults);
  for (const auto& [check, why] : failed) std::printf("soak:   %s: %s\n", check.c_str(), why.c_str());
  if (rec.contains("repro") && !rec["repro"].get<std::string>().empty())
    std::printf("soak:   reproducer %s\n", rec["repro"].get<std::string>().c_str());
  std::fflush(stdout);
  s.fleets.push_back(rec);
  return failed.empty();
}

void print_table(const Soak& s) {
  const Totals& t = s.totals;
  std::printf("\nsoak seed %lld, %d agents, scenario %s\n", s.a.seed, s.sc.robot.agents, s.sc.name.c_str());
  std::printf("  fleets          %d (ok %d, degraded %d, failed checks %d)\n", t.fleets,
              t.statuses.count("ok") ? t.statuses.at("ok") : 0,
              t.statuses.count("degraded") ? t.statuses.at("degraded") : 0, t.failed_fleets);
  std::printf("  faults applied  %lld\n", t.applied());
  for (const auto& [k, v] : t.faults) std::printf("    %-13s %d\n", k.c_str(), v);
  std::printf("  failed checks   %s\n", t.failed_checks.empty() ? "none" : "");
  for (const auto& [k, v] : t.failed_checks) std::printf("    %-13s %d fleet(s)\n", k.c_str(), v);
  std::printf("  report          %s/soak.json\n", s.out.c_str());
}

void write_report(const Soak& s) {
  nlohmann::json j = {{"seed", s.a.seed},
                      {"faults_requested", s.a.faults},
                      {"faults_applied", s.totals.applied()},
                      {"faults_by_kind", s.totals.faults},
                      {"agents", s.sc.robot.agents},
                      {"outages_per_fleet", s.a.outages},
                      {"scenario", s.sc.name},
                      {"band",
                       {{"distance_below_pct", s.band.distance_below_pct},
                        {"distance_above_pct", s.band.distance_above_pct},
                        {"energy_pct", s.band.energy_pct}}},
                      {"reference",
                       {{"status", s.reference.value("status", "")},
                        {"distance_m", s.reference.value("distance_m", 0.0)},
                        {"energy_J", s.reference.value("energy_J", 0.0)},
                        {"trace_sha256", s.reference.value("trace_sha256", "")}}},
                      {"fleets", s.fleets.size()},
                      {"failed_fleets", s.totals.failed_fleets},
                      {"failed_checks", s.totals.failed_checks},
                      {"statuses", s.totals.statuses},
                      {"fleet_results", s.fleets}};
  records::write_json_file(s.out + "/soak.json", j);
  if (!s.a.junit.empty()) records::write_text_file(s.a.junit, records::junit_xml("maptr soak " + s.out, s.cases));
}

/// The soak's scenario and folder, checked; throws config::ScenarioError on bad input.
void set_up(Soak& s) {
  s.sc = config::load_scenario(s.a.scenario.empty() ? source_dir() + "/deploy/scenarios/soak.yaml"
                                                    : s.a.scenario);
  config::set_field(s.sc, "agents", std::to_string(s.a.agents), "--agents");
  s.sc.faults.clear();
  s.sc.validate();
  try {
    s.specs = property_specs(s.a.properties);
  } catch (const std::invalid_argument& e) {
    throw config::ScenarioError(e.what());
  }
  s.domain = resolve_domain(s.a.domain);
  if (const std::string why = domain_problem(s.domain, s.sc.robot.agents); !why.empty())
    throw config::ScenarioError(why);
  s.out = s.a.out.empty() ? unique_run_dir("runs", "soak-" + std::to_string(s.a.seed)) : s.a.out;
  fs::create_directories(s.out);
  if (!s.a.junit.empty()) {
    try {
      records::write_text_file(s.a.junit, records::junit_xml("maptr soak " + s.out, {}));
    } catch (const records::RecordError& e) {
      throw config::ScenarioError(std::string("--junit ") + e.what());
    }
  }
}

}  // namespace

int cmd_soak(const SoakArgs& a, const std::string& bin_dir) {
  Soak s{a, bin_dir};
  if (!input_read([&] { set_up(s); })) return kExitBadInput;
  std::signal(SIGINT, on_interrupt);  // the fleet's launcher gets it too and ends its run
  std::signal(SIGTERM, on_interrupt);
  std::printf("soak: folder %s, domain %d; the fault-free run first\n", s.out.c_str(), s.domain);
  std::fflush(stdout);
  const std::string ref_dir = s.out + "/reference";
  const FleetRun ref = run_fleet(bin_dir, write_scenario(s.sc, {}, s.out + "/reference.yaml"), ref_dir,
                                 s.domain, a.fleet_timeout_s);
  s.reference = ref.summary;
  if (s.reference.value("status", "") != "ok") {
    std::printf("soak: the fault-free run ended '%s' (see %s): no reference\n",
                s.reference.value("status", "none").c_str(), ref_dir.c_str());
    return kExitFailed;
  }
  std::printf("soak: fault-free: distance %.1f m, energy %.1f J, %.1f s wall\n",
              s.reference.value("distance_m", 0.0), s.reference.value("energy_J", 0.0), ref.wall_s);
  for (int i = 0; s.totals.applied() < a.faults; ++i) {
    const std::string dir = s.out + "/fleet-" + std::to_string(i);
    const auto faults = soak::fleet_faults(static_cast<unsigned>(a.seed), i, s.sc, a.outages);
    const ShmCount before = count_shm(s.domain);
    const FleetRun r =
        run_fleet(bin_dir, write_scenario(s.sc, faults, dir + ".yaml"), dir, s.domain, a.fleet_timeout_s);
    check_fleet(s, i, r, dir, before);
    write_report(s);
    if (g_interrupted.load()) break;
  }
  print_table(s);
  write_report(s);
  return s.totals.failed_fleets == 0 ? kExitOk : kExitFailed;
}

}  // namespace maptr::deploy::cli
