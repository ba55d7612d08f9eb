// Experiment tests (ctest label `experiments`): `maptr experiment NAME --quick` on real fleets,
// and the trends of the paper that the results must show. Each test reads the experiment's
// summary.json (its table as JSON) and the files it wrote.
#include <gtest/gtest.h>

#include <map>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "records/assignments.hpp"
#include "tests/integration/fleet_runner.hpp"

using namespace maptr::testing;
namespace fs = std::filesystem;

namespace {

/// Runs an experiment's quick variant. Every run it made that finished was checked against the
/// experiment properties (energy_balance and no_false_detection; faults_detected:1 with
/// detection on), and each held.
CliResult run_experiment(const std::string& name, const std::string& out, double timeout_s) {
  auto r = run_cli({"experiment", name, "--quick", "--out", out, "--domain", std::to_string(private_domain())},
                   out, timeout_s);
  for (const auto& run : r.summary.value("runs", nlohmann::json::array())) {
    if (run.value("status", "").rfind("aborted", 0) == 0) continue;
    EXPECT_GE(run["properties"].size(), 2u) << run.dump();
    for (const auto& v : run["properties"]) EXPECT_TRUE(v["holds"].get<bool>()) << name << " " << run["label"] << ": " << v.dump();
  }
  return r;
}

/// Runs the quick variant into r and checks that it finished, exited 0 and wrote two rows.
void run_quick(const std::string& name, const std::string& out, double timeout_s, CliResult& r) {
  r = run_experiment(name, out, timeout_s);
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_EQ(r.summary["rows"].size(), 2u) << r.summary.dump(2);
}

double num(const nlohmann::json& row, const std::string& key) {
  if (!row.contains(key) || !row[key].is_number()) return std::nan("");
  return row[key].get<double>();
}

/// A PNG that gnuplot wrote from the experiment's CSV (the 8-byte PNG signature, some content).
bool is_png(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char sig[8] = {0};
  in.read(sig, 8);
  return in && static_cast<unsigned char>(sig[0]) == 0x89 && sig[1] == 'P' && sig[2] == 'N' && sig[3] == 'G' &&
         fs::file_size(path) > 2000;
}

/// The driving mask of one side in force at time t, from assignments.csv ("" if none).
std::string mask_at(const std::string& assignments_csv, char side, double t) {
  std::string mask;
  for (const auto& a : maptr::records::read_assignments(assignments_csv)) {
    if (a.t_s > t) break;
    if (a.side == side) mask = a.driving;
  }
  return mask;
}

}  // namespace

// table-pow --quick: 16 agents at 13.2 and 38.2 kg, 10 m/s, 60 s, NO and EC (four fleets).
TEST(Experiments, TablePowQuickEcSavesEnergyAndTheSavingFallsWithWeight) {
  TempDir tmp;
  const std::string out = tmp.path() + "/table-pow";
  CliResult r;
  ASSERT_NO_FATAL_FAILURE(run_quick("table-pow", out, 900, r));
  const auto& rows = r.summary["rows"];
  for (const auto& row : rows) {
    EXPECT_EQ(row["status_NO"], "ok") << row.dump();
    EXPECT_EQ(row["status_EC"], "ok") << row.dump();
    EXPECT_TRUE(row["speed_held_NO"].get<bool>() && row["speed_held_EC"].get<bool>()) << row.dump();
    // The point of the paper: the energy-conscious robot draws less energy over the same run.
    EXPECT_LT(num(row, "E_EC_kJ"), num(row, "E_NO_kJ")) << "EC must save energy at " << row["gross_kg"] << " kg: "
                                                         << row.dump();
    // The paper's numbers are carried along for the two rows it has.
    EXPECT_FALSE(row["E_NO_paper_kJ"].is_null());
  }
  const auto &light = rows[0], &heavy = rows[1];
  ASSERT_LT(num(light, "gross_kg"), num(heavy, "gross_kg"));
  // The saving falls as the load rises (more agents are needed near the efficient load).
  EXPECT_GT(num(light, "saving_pct"), num(heavy, "saving_pct")) << light.dump() << "\n" << heavy.dump();
  // The EC active count does not fall as the weight rises, and it rises strictly from 13.2 to 38.2 kg.
  EXPECT_GT(num(heavy, "active_EC_end"), num(light, "active_EC_end")) << light.dump() << "\n" << heavy.dump();
  EXPECT_LT(num(light, "active_EC_end"), 16) << "EC must leave agents idle at the light load";
  // Outputs: the table in three forms and the plots made from the CSV.
  for (const char* f : {"table-pow.csv", "table-pow.md", "summary.json", "table-pow-energy.gp"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  for (const char* f : {"table-pow-energy.png", "table-pow-saving.png", "table-pow-active.png"})
    EXPECT_TRUE(is_png(out + "/" + f)) << f;
  EXPECT_EQ(r.summary["runs"].size(), 4u);
  for (const auto& run : r.summary["runs"]) EXPECT_TRUE(fs::exists(out + "/" + run["folder"].get<std::string>() + "/trace.csv"));
}

// wear --quick: EC at 13.2 kg, 10 m/s, 30 s, T_ON = 5 s, N = 8 and 16.
//
// Spread bound. Level 3 gives the N_a least-worn live agents the work at every reallocation,
// and reallocations are at most T_ON apart (also on every change of N_a). All agents of a side
// turn at the same speed, so between two reallocations every chosen agent gains the same
// distance d <= v_max T_ON and the others gain 0. If max - min <= D before, and the chosen are
// the least worn (max of chosen <= min of the others), then after the interval
// max - min <= max(D, d): the chosen rise by d but start at or below the others' minimum. While
// the robot accelerates every live agent drives (the spread does not change). So at any time
// max - min of a side's wear <= v_max T_ON. v_max: the reference (10 m/s) plus the overshoot of
// the speed loop after the step start (a few percent); X = 1.1 x 10 m/s x 5 s = 55 m. An
// allocation that kept the same agents would let them run ~25 s of cruise ahead: ~250 m.
TEST(Experiments, WearQuickIdleGrowsWithNAndLevel3SpreadsDistance) {
  TempDir tmp;
  const std::string out = tmp.path() + "/wear";
  CliResult r;
  ASSERT_NO_FATAL_FAILURE(run_quick("wear", out, 600, r));
  const auto& rows = r.summary["rows"];
  const auto &n8 = rows[0], &n16 = rows[1];
  ASSERT_EQ(n8["agents"], 8);
  ASSERT_EQ(n16["agents"], 16);
  // Idle time per agent grows with N at a fixed payload (paper, Fig. "average idle time").
  EXPECT_GT(num(n16, "idle_mean_steps"), num(n8, "idle_mean_steps")) << n8.dump() << "\n" << n16.dump();
  const double t_on = 5.0, speed = 10.0, bound = 1.1 * speed * t_on;
  for (const auto& row : rows) {
    EXPECT_EQ(row["status"], "ok") << row.dump();
    const int per_side = row["agents"].get<int>() / 2;
    for (const char* side : {"L", "R"}) {
      const std::string s(side);
      // Not trivial: some agents of the side were idle at the end.
      EXPECT_LT(num(row, "active_end_" + s), per_side) << row.dump();
      EXPECT_LE(num(row, "wear_spread_" + s + "_m"), bound) << "side " << s << ": " << row.dump();
      // The work rotated: more agents drove during cruise than were active at the end.
      EXPECT_GT(num(row, "drove_in_cruise_" + s), num(row, "active_end_" + s)) << row.dump();
    }
    // And every agent drove some distance (its ledger is not empty).
    EXPECT_GT(num(row, "wear_min_m"), 0.0) << row.dump();
  }
  for (const char* f : {"wear.csv", "wear.md", "transitions-N8.csv", "transitions-N16.csv"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  for (const char* f : {"wear-idle.png", "wear-transitions-N8.png", "wear-transitions-N16.png"})
    EXPECT_TRUE(is_png(out + "/" + f)) << f;
}

// failures --quick: 16 agents EC at 23.2 kg, 10 m/s, 30 s; 0 and 1 agent per side killed at 15 s.
TEST(Experiments, FailuresQuickDetectsAndRecovers) {
  TempDir tmp;
  const std::string out = tmp.path() + "/failures";
  CliResult r;
  ASSERT_NO_FATAL_FAILURE(run_quick("failures", out, 600, r));
  const auto& rows = r.summary["rows"];
  const auto &none = rows[0], &one = rows[1];
  EXPECT_EQ(none["killed_per_side"], 0);
  EXPECT_EQ(one["killed_per_side"], 1);
  EXPECT_EQ(none["status"], "ok");
  EXPECT_EQ(one["status"], "ok") << one.dump();
  // The tolerance N_i - N_a,i was read from the fault-free run: at least one spare per side.
  ASSERT_TRUE(r.summary["tolerance"].is_number());
  EXPECT_GE(r.summary["tolerance"].get<int>(), 1);
  // Both kills detected at once (the launcher sees its child die) and the speed recovered.
  EXPECT_EQ(one["detected"], 2) << one.dump();
  EXPECT_EQ(one["recovered"], 2) << one.dump();
  EXPECT_LT(num(one, "detect_wall_ms_max"), 1000.0) << one.dump();
  EXPECT_LT(num(one, "max_speed_error_pct"), 10.0) << one.dump();
  EXPECT_NEAR(num(one, "final_speed_mps"), 10.0, 0.2) << one.dump();
  EXPECT_EQ(one["live_end"]["L"], 7);
  EXPECT_EQ(one["live_end"]["R"], 7);
  // The killed agents were driving at that moment (the active ones die first): check against
  // the fault-free run, which the faulty one repeats exactly up to the kill.
  const std::string killed = one["killed"];
  ASSERT_EQ(killed.size(), 5u) << killed;  // "Lj Rk"
  const std::string a0 = out + "/runs/kill-0/assignments.csv";
  for (const std::string& name : {killed.substr(0, 2), killed.substr(3, 2)}) {
    const std::string mask = mask_at(a0, name[0], 15.0);
    const int j = name[1] - '0';
    ASSERT_LT(j, static_cast<int>(mask.size())) << name << " " << mask;
    EXPECT_EQ(mask[j], '1') << name << " was not driving at 15 s: " << mask;
  }
  for (const char* f : {"failures-speed.png", "failures-energy.png"}) EXPECT_TRUE(is_png(out + "/" + f)) << f;
}

// weights --quick and voltages --quick: the oracle runs beside Ipopt at every Level-2 decision;
// Ipopt's integer must equal the oracle's at every one of them.
TEST(Experiments, WeightsAndVoltagesQuickIpoptEqualsTheOracleAtEveryDecision) {
  for (const char* name : {"weights", "voltages"}) {
    TempDir tmp;
    const std::string out = tmp.path() + "/" + name;
    CliResult r;
    ASSERT_NO_FATAL_FAILURE(run_quick(name, out, 600, r));
    for (const auto& row : r.summary["rows"]) {
      EXPECT_EQ(row["status"], "ok") << name << ": " << row.dump();
      EXPECT_GT(num(row, "oracle_checked"), 0) << name << ": " << row.dump();
      EXPECT_EQ(num(row, "oracle_differs"), 0) << name << ": " << row.dump();
    }
  }
}

// turns --quick: (a) the tightest radius against speed at four speeds, no fleet; (b) the warehouse
// loop with its straights shortened, 16 agents at 30 kg, NO and EC (two fleets at 100 Hz).
TEST(Experiments, TurnsQuickReachTableAndTheLoopFollowedByNoAndEc) {
  TempDir tmp;
  const std::string out = tmp.path() + "/turns";
  CliResult r;
  ASSERT_NO_FATAL_FAILURE(run_quick("turns", out, 600, r));
  const auto& reach = r.summary["reach"]["rows"];
  ASSERT_EQ(reach.size(), 4u) << r.summary["reach"].dump(2);
  for (const auto& row : reach)
    for (const char* m : {"13.2", "30", "38.2"}) {
      const double bi = num(row, std::string("R_bi_") + m + "kg_m"), uni = num(row, std::string("R_uni_") + m + "kg_m");
      // An H-bridge brakes the inner side: it turns at least as tightly as a driver that cannot.
      ASSERT_TRUE(std::isfinite(bi)) << row.dump();
      if (std::isfinite(uni)) EXPECT_LE(bi, uni + 1e-9) << row.dump();
    }
  // The radius the bidirectional robot needs grows with speed (lateral friction, back-EMF).
  EXPECT_LE(num(reach[0], "R_bi_30kg_m"), num(reach[3], "R_bi_30kg_m")) << r.summary["reach"].dump(2);
  const auto& rows = r.summary["rows"];
  EXPECT_EQ(rows[0]["mode"], "NO");
  EXPECT_EQ(rows[1]["mode"], "EC");
  for (const auto& row : rows) {
    EXPECT_EQ(row["status"], "ok") << row.dump();
    // The loop was followed: within the scenario's 0.5 m path tolerance, the end near its end.
    EXPECT_LT(num(row, "cross_track_max_m"), 0.5) << row.dump();
    EXPECT_GE(num(row, "cross_track_max_m"), num(row, "cross_track_rms_m")) << row.dump();
    EXPECT_GT(num(row, "energy_kJ"), 0.0) << row.dump();
    EXPECT_EQ(row["trace_sha256"].get<std::string>().size(), 64u) << row.dump();
  }
  // NO drives every agent. At 30 kg and 1 m/s Level 2 picks every agent of a side on the
  // straights and in the turns (`maptr level2`, `maptr level2 --radius 4`): EC is NO here, up to
  // transients, and never drives more agents than NO.
  EXPECT_GT(num(rows[0], "active_mean"), 15.9) << rows[0].dump();
  EXPECT_LE(num(rows[1], "active_mean"), num(rows[0], "active_mean") + 1e-9) << rows[1].dump();
  EXPECT_NEAR(num(rows[1], "energy_kJ"), num(rows[0], "energy_kJ"), 0.05 * num(rows[0], "energy_kJ"));
  for (const char* f : {"turns.csv", "turns.md", "turns-reach.csv", "turns-reach.md", "summary.json"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  for (const char* f : {"turns-reach.png", "turns-energy.png", "turns-active.png", "turns-difference.png"})
    EXPECT_TRUE(is_png(out + "/" + f)) << f;
}

// faults --quick: the warehouse loop at 30 kg, one agent of side L broken at 20 s: open and
// sensor=5 with the groups' detection on and off, and the crash of the same agent.
TEST(Experiments, FaultsQuickDetectsWhatRunsSilentOtherwise) {
  TempDir tmp;
  const std::string out = tmp.path() + "/faults";
  const CliResult r = run_experiment("faults", out, 600);
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto& rows = r.summary["rows"];
  ASSERT_EQ(rows.size(), 5u) << rows.dump();
  std::map<std::string, nlohmann::json> by;
  for (const auto& row : rows) by[row["mode"].get<std::string>() + "/" + row["detection"].get<std::string>()] = row;
  for (const char* k : {"open/on", "sensor=5/on", "kill/plant"}) {
    EXPECT_EQ(by[k]["detected"], 1) << k << by[k].dump();
    EXPECT_LE(num(by[k], "detect_s_max"), 1.0) << k;
    EXPECT_EQ(by[k]["status"], "ok") << k;
  }
  EXPECT_EQ(by["open/on"]["diagnosed"], "open");
  EXPECT_EQ(by["sensor=5/on"]["diagnosed"], "sensor");
  for (const char* k : {"open/off", "sensor=5/off"}) EXPECT_EQ(by[k]["detected"], 0) << k;
  // A silent wrong sensor makes its PID fight the others: isolating it saves energy.
  EXPECT_GT(num(by["sensor=5/off"], "energy_penalty_J"), num(by["sensor=5/on"], "energy_penalty_J") + 100.0)
      << by["sensor=5/off"].dump() << by["sensor=5/on"].dump();
  for (const char* f : {"faults-energy.png", "faults-detection.png"}) EXPECT_TRUE(is_png(out + "/" + f)) << f;
}

TEST(Experiments, UnknownNameExitsWith2AndListsTheExperiments) {
  TempDir tmp;
  const auto r = run_cli({"experiment", "no-such-experiment", "--out", tmp.path() + "/x"}, tmp.path() + "/x", 30);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  for (const char* n : {"table-pow", "weights", "voltages", "agents", "battery", "wear", "failures", "turns", "faults"})
    EXPECT_NE(r.output.find(n), std::string::npos) << n << " missing from: " << r.output;
}

// compare: the user's own scenario, EC against NO, in one command; each variant's energy is
// that of a separate `maptr run` of the same settings to the last digit; a second call reuses
// both fleets; a bad --set is refused before anything starts.
TEST(Experiments, CompareRunsEachVariantAsMaptrRunDoesAndResumes) {
  TempDir tmp;
  const std::string out = tmp.path() + "/compare";
  const std::string scenario = std::string(MAPTR_SOURCE_DIR) + "/deploy/scenarios/default.yaml";
  const std::string domain = std::to_string(private_domain());
  auto r = run_cli({"compare", scenario, "--duration", "10", "--out", out, "--domain", domain}, out, 600);
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto rows = r.summary["rows"];
  ASSERT_EQ(rows.size(), 2u) << r.summary.dump(2);
  EXPECT_EQ(rows[0]["variant"], "mode=ec");
  EXPECT_EQ(rows[1]["variant"], "mode=all");
  for (const char* f : {"compare.md", "compare.csv", "summary.json", "compare.png"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  EXPECT_TRUE(is_png(out + "/compare.png"));
  EXPECT_EQ(num(rows[0], "saving_pct"), 0.0);
  EXPECT_GT(num(rows[1], "saving_pct"), -100.0);
  const char* modes[] = {"ec", "all"};
  for (int i = 0; i < 2; ++i) {
    const std::string run = tmp.path() + "/run-" + modes[i];
    auto single = run_cli(run_args(run, {scenario, "--mode", modes[i], "--duration", "10"}), run, 300);
    ASSERT_EQ(single.exit_code, 0) << single.output;
    EXPECT_EQ(rows[i]["energy_J"].get<double>(), single.summary["energy_J"].get<double>()) << modes[i];
    EXPECT_EQ(rows[i]["trace_sha256"], single.summary["trace_sha256"]) << modes[i];
  }
  // Again into the same folder: both variants reused, the same table.
  auto again = run_cli({"compare", scenario, "--duration", "10", "--out", out, "--domain", domain}, out, 300);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(again.summary["rows"], rows);
  for (const auto& run : again.summary["runs"]) EXPECT_TRUE(run["reused"].get<bool>()) << run.dump();
  // A field that is not one, and a value outside its range: exit 2, the option named, no folder.
  for (const auto& [set, words] : {std::pair<std::string, std::string>{"colour=red,blue", "colour"},
                                   std::pair<std::string, std::string>{"gross_mass_kg=20,-5", "-5"}}) {
    const std::string bad = tmp.path() + "/bad";
    auto b = run_cli({"compare", scenario, "--set", set, "--out", bad}, bad, 60);
    EXPECT_EQ(b.exit_code, 2) << b.output;
    EXPECT_NE(b.output.find("--set " + set), std::string::npos) << b.output;
    EXPECT_NE(b.output.find(words), std::string::npos) << b.output;
    EXPECT_FALSE(fs::exists(bad));
  }
}
