// The bench's /proc counters (deploy/studies/bench/proc_stats.hpp) against captured /proc files, and
// the cost per tick by process kind (deploy/studies/bench/fleet_cost.hpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <pthread.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <thread>
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

TEST(BenchProc, SchedstatGivesTheNanosecondsOnTheCpuAndAThreadNamedByTheProjectIsToldApart) {
  EXPECT_EQ(parse_schedstat_ns("11056525 10803818 8\n"), 11056525);
  EXPECT_FALSE(parse_schedstat_ns(""));
  EXPECT_FALSE(parse_schedstat_ns("-5 1 1\n"));
  // A thread of this process named "level2" that spins for a while: its CPU is listed by name,
  // apart from the main thread's.
  std::atomic<bool> named{false}, stop{false};
  std::thread t([&] {
    pthread_setname_np(pthread_self(), "level2");
    named = true;
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(50);
    while (std::chrono::steady_clock::now() < end) {
    }
    while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  });
  while (!named) std::this_thread::yield();
  std::this_thread::sleep_for(std::chrono::milliseconds(60));
  const auto c = read_proc_counters(getpid());
  stop = true;
  t.join();
  ASSERT_TRUE(c);
  ASSERT_TRUE(c->named_cpu_s.count("level2"));
  EXPECT_GT(c->named_cpu_s.at("level2"), 0.0);
  EXPECT_GE(c->cpu_s + 1e-9, c->main_cpu_s + c->named_cpu_s.at("level2"));
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
  nlohmann::json with_launcher = fleet;
  with_launcher["launcher_pid"] = 9;  // the launcher (and its recorder) counts when the file names it
  const auto all = fleet_processes(with_launcher);
  ASSERT_EQ(all.size(), 8u);
  EXPECT_EQ(all.back().kind, ProcKind::kLauncher);
  EXPECT_EQ(all.back().pid, 9);
  FleetSample a, b;
  a.tick = 100;
  b.tick = 300;  // 200 ticks
  for (std::size_t i = 0; i < procs.size(); ++i) {
    ProcCounters start, end;
    start.cpu_s = 1.0;
    start.ctx_switches = 1000;
    // Process i used 0.002 (i + 1) s and 400 (i + 1) switches over the window, half of its CPU
    // in its main thread; the groups 0.001 s of it in their "level2" thread.
    end.cpu_s = 1.0 + 0.002 * (i + 1);
    end.ctx_switches = 1000 + 400 * static_cast<long long>(i + 1);
    end.main_cpu_s = 0.001 * (i + 1);
    if (procs[i].kind == ProcKind::kGroup) end.named_cpu_s["level2"] = 0.001;
    a.procs.push_back(start);
    b.procs.push_back(end);
  }
  a.machine = MachineCpu{0, 0, 0};
  b.machine = MachineCpu{0, 0, 0};
  b.machine->busy = static_cast<long long>(0.2 * static_cast<double>(sysconf(_SC_CLK_TCK)));  // 0.2 s
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
  // By thread: the main threads of the six lock-step processes (2+4+6+8+10+12 ms / 2), the
  // groups' solvers (2 x 1 ms), the rest (the server whole, the other halves less Level 2).
  EXPECT_NEAR(j["cpu_us_tick_tick_path"].get<double>(), 21000.0 / 200, 1e-9);
  EXPECT_NEAR(j["cpu_us_tick_level2"].get<double>(), 2000.0 / 200, 1e-9);
  EXPECT_NEAR(j["cpu_us_tick_other_threads"].get<double>(), (21000.0 - 2000.0 + 14000.0) / 200, 1e-9);
  EXPECT_NEAR(j["cpu_us_tick_processes"].get<double>(), 56000.0 / 200, 1e-9);
  EXPECT_NEAR(j["cpu_us_tick_machine"].get<double>(), 200000.0 / 200, 1e-6);
  EXPECT_NEAR(j["cpu_accounted_pct"].get<double>(), 28.0, 1e-6);  // 56 of 200 ms, no watch

  b.procs[5].reset();  // an agent gone before the end: no figure rather than a wrong one
  EXPECT_FALSE(fleet_cost(procs, a, b).measured);
  b.procs[5] = ProcCounters{};
  b.tick = a.tick;
  EXPECT_FALSE(fleet_cost(procs, a, b).measured);
}

}  // namespace
}  // namespace maptr::deploy
