// The bench's /proc counters (deploy/studies/bench/proc_stats.hpp) against captured /proc files, and
// the cost per tick by process kind (deploy/studies/bench/fleet_cost.hpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

#include "deploy/studies/bench/fleet_cost.hpp"
#include "deploy/studies/bench/proc_stats.hpp"

namespace maptr::deploy {
namespace {

std::string fixture(const std::string& name) {
  std::ifstream in(std::string(MAPTR_UNIT_FIXTURES) + "/" + name);
  EXPECT_TRUE(in.good()) << name;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(BenchProc, CpuTicksAreFields14And15CountedAfterTheCommand) {
  // The command "maptr (L3) x" holds spaces and parentheses; utime 1234, stime 567.
  EXPECT_EQ(parse_stat_cpu_ticks(fixture("proc_pid_stat.txt")), 1801);
}

TEST(BenchProc, ContextSwitchesAreVoluntaryPlusNonvoluntary) {
  EXPECT_EQ(parse_status_ctx_switches(fixture("proc_pid_status.txt")), 480 + 63);
}

TEST(BenchProc, TruncatedFilesAreNotRead) {
  const std::string stat = fixture("proc_pid_stat.txt");
  EXPECT_FALSE(parse_stat_cpu_ticks(stat.substr(0, stat.find(") S") + 20)));
  EXPECT_FALSE(parse_stat_cpu_ticks("2084 maptr S 1 2"));
  EXPECT_FALSE(parse_status_ctx_switches("Name:\tmaptr\nvoluntary_ctxt_switches:\t480\n"));
}

TEST(BenchProc, MachineCpuIsTheFirstEightFieldsOfTheCpuLineAndStealTheEighth) {
  // A 2-CPU VM: the "cpu" line, then the per-CPU lines and the rest of the file.
  const std::string stat =
      "cpu  185679 7 41201 271375 1706 0 1905 41470 12 0\n"
      "cpu0 92000 3 20000 135000 800 0 900 20700 6 0\nintr 1 2 3\n";
  const auto m = parse_proc_stat_cpu(stat);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->total, 185679 + 7 + 41201 + 271375 + 1706 + 0 + 1905 + 41470);
  EXPECT_EQ(m->steal, 41470);
  // A kernel without the steal field, another line first, a negative value: not read.
  EXPECT_FALSE(parse_proc_stat_cpu("cpu  1 2 3 4 5 6 7\n"));
  EXPECT_FALSE(parse_proc_stat_cpu("cpu0 1 2 3 4 5 6 7 8\n"));
  EXPECT_FALSE(parse_proc_stat_cpu("cpu  1 2 3 -4 5 6 7 8\n"));
  EXPECT_FALSE(parse_proc_stat_cpu(""));
}

TEST(BenchProc, StealPercentIsItsShareOfAllCpuTimeBetweenTwoReads) {
  const MachineCpu a{1000, 100}, b{1400, 130};
  EXPECT_DOUBLE_EQ(steal_percent(a, b), 7.5);  // 30 of 400 ticks
  EXPECT_DOUBLE_EQ(steal_percent(a, a), 0.0);
  const auto now = read_machine_cpu();
  ASSERT_TRUE(now) << "this machine's /proc/stat";
  EXPECT_GT(now->total, 0);
  EXPECT_GE(now->steal, 0);
}

TEST(BenchProc, ALiveProcessIsReadAndAnEndedOneIsNot) {
  const auto self = read_proc_counters(getpid());
  ASSERT_TRUE(self);
  EXPECT_GE(self->ctx_switches, 0);
  EXPECT_GE(self->cpu_s, 0.0);
  EXPECT_FALSE(read_proc_counters(-1));
}

TEST(BenchProc, CostPerTickByKindOverTheWindow) {
  const nlohmann::json fleet = {{"discovery_server_pid", 10},
                                {"processes",
                                 {{{"name", "plant"}, {"pid", 11}},
                                  {{"name", "central"}, {"pid", 12}},
                                  {{"name", "group-L"}, {"pid", 13}},
                                  {{"name", "group-R"}, {"pid", 14}},
                                  {{"name", "L0"}, {"pid", 15}},
                                  {{"name", "R0"}, {"pid", 16}}}}};
  const auto procs = fleet_processes(fleet);
  ASSERT_EQ(procs.size(), 7u);
  EXPECT_EQ(procs.back().kind, ProcKind::kDiscovery);
  EXPECT_EQ(procs[2].kind, ProcKind::kGroup);
  FleetSample a, b;
  a.tick = 100;
  b.tick = 300;  // 200 ticks
  for (std::size_t i = 0; i < procs.size(); ++i) {
    a.procs.push_back(ProcCounters{1.0, 1000});
    // Process i used 0.002 (i + 1) s and 400 (i + 1) switches over the window.
    b.procs.push_back(ProcCounters{1.0 + 0.002 * (i + 1), 1000 + 400 * static_cast<long long>(i + 1)});
  }
  const FleetCost c = fleet_cost(procs, a, b);
  ASSERT_TRUE(c.measured);
  EXPECT_EQ(c.ticks, 200);
  const nlohmann::json j = fleet_cost_json(c);
  EXPECT_NEAR(j["cpu_us_tick_plant"].get<double>(), 2000.0 / 200, 1e-9);
  EXPECT_NEAR(j["cs_tick_plant"].get<double>(), 400.0 / 200, 1e-9);
  EXPECT_NEAR(j["cs_tick_group"].get<double>(), (1200.0 + 1600.0) / 2 / 200, 1e-9);
  EXPECT_NEAR(j["cs_tick_agents"].get<double>(), (2000.0 + 2400.0) / 200, 1e-9);
  EXPECT_NEAR(j["cs_tick_agent"].get<double>(), (2000.0 + 2400.0) / 2 / 200, 1e-9);
  EXPECT_NEAR(j["cpu_us_tick_ds"].get<double>(), 14000.0 / 200, 1e-9);

  b.procs[5].reset();  // an agent gone before the end: no figure rather than a wrong one
  EXPECT_FALSE(fleet_cost(procs, a, b).measured);
  b.procs[5] = ProcCounters{};
  b.tick = a.tick;
  EXPECT_FALSE(fleet_cost(procs, a, b).measured);
}

}  // namespace
}  // namespace maptr::deploy
