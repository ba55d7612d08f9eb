// Scale test (ctest label `scale`, part of `deploy/maptr test`): a 64-agent fleet, 68 processes
// plus the discovery server, for 2 simulated seconds, its data on shared memory.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/integration/fleet_runner.hpp"

using maptr::testing::CliResult;
using maptr::testing::run_args;
using maptr::testing::run_cli;
using maptr::testing::private_domain;
using maptr::testing::TempDir;

namespace {

/// What a shell command printed; a failure of the test when it does not exit 0.
std::string shell_output(const std::string& command) {
  std::string out;
  if (FILE* p = popen(command.c_str(), "r")) {
    char buf[4096];
    while (fgets(buf, sizeof(buf), p)) out += buf;
    EXPECT_EQ(pclose(p), 0) << command << "\n" << out;
  }
  return out;
}

}  // namespace

TEST(Fleet, SixtyFourAgentProcessesJoinAndFinish) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  auto r = run_cli(run_args(out, {"--agents", "64", "--duration", "2"}), out, 400);
  ASSERT_FALSE(r.timed_out) << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.summary["status"], "ok");
  EXPECT_EQ(r.summary["ticks"], 200);
  EXPECT_EQ(r.summary["transport"], "shm");  // data on shared memory at every size
  // Every one of the 68 processes announced itself, ran the lock-step and ended cleanly.
  ASSERT_EQ(r.summary["processes"].size(), 68u);
  for (const auto& p : r.summary["processes"]) EXPECT_EQ(p["exit_code"].get<int>(), 0) << p.dump();
  EXPECT_EQ(r.summary["plant"]["live_agents"]["L"], 32);
  EXPECT_EQ(r.summary["plant"]["live_agents"]["R"], 32);
  EXPECT_EQ(r.summary["plant"]["declared_dead_by_deadline"], 0);
}

TEST(Bench, TheFloorBenchWritesOneRowPerSizeAndWorkingSet) {
  TempDir tmp;
  const std::string out = tmp.path() + "/floor";
  const CliResult r = run_cli({"bench", "floor", "--agents", "1,5", "--touch-kb", "0,64", "--out", out}, out, 300);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream csv(out + "/floor.csv");
  std::string header, line;
  ASSERT_TRUE(std::getline(csv, header));
  EXPECT_EQ(header.rfind("agents,workers,touch_kb,median_us", 0), 0u) << header;
  std::vector<std::string> rows;
  while (std::getline(csv, line)) rows.push_back(line.substr(0, line.find(',', line.find(',', line.find(',') + 1) + 1)));
  EXPECT_EQ(rows, (std::vector<std::string>{"1,4,0", "5,8,0", "1,4,64", "5,8,64"}));
  EXPECT_TRUE(std::filesystem::exists(out + "/floor.md"));
  const CliResult bad = run_cli({"bench", "floor", "--agents", "-3", "--out", out + "-bad"}, out + "-bad", 60);
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("'-3' is not a positive number"), std::string::npos) << bad.output;
}

// bench scale answers: a size that misses --min-rtf makes it exit 1, its headline says MISS with
// the figure and the bound, and the JUnit file names the failing case (read by Python's XML
// parser, with the attributes the JUnit schema requires).
TEST(Bench, TheScaleBenchFailsASizeThatMissesItsThresholdAndSaysSoInJUnit) {
  TempDir tmp;
  const std::string out = tmp.path() + "/scale", junit = tmp.path() + "/scale.xml";
  const CliResult r = run_cli({"bench", "scale", "--agents", "8", "--modes", "ec", "--duration", "5", "--min-rtf",
                               "1000000", "--junit", junit, "--out", out, "--domain", std::to_string(private_domain())},
                              out, 600);
  ASSERT_FALSE(r.timed_out) << r.output;
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("N=8 ec, 1 host: ok"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("MISS (RTF"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("< --min-rtf 1e+06"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("bench scale: 0 of 1 sizes pass"), std::string::npos) << r.output;
  const std::string check =
      "python3 -c \"import sys, xml.etree.ElementTree as E\n"
      "s = E.parse(sys.argv[1]).getroot()\n"
      "assert s.tag == 'testsuite' and all(k in s.attrib for k in ('name', 'tests', 'failures'))\n"
      "c = s.findall('testcase')\n"
      "assert s.attrib['tests'] == '1' and s.attrib['failures'] == '1' and len(c) == 1\n"
      "assert all(k in c[0].attrib for k in ('name', 'classname', 'time'))\n"
      "f = c[0].find('failure')\n"
      "print(c[0].attrib['name'], f.attrib['message'])\" " + junit + " 2>&1";
  const std::string printed = shell_output(check);
  EXPECT_NE(printed.find("N8-ec RTF"), std::string::npos) << printed;
  // The same bench with a bound it meets passes. Paced to the wall clock, so that the window
  // of its cost (20 % to 90 % of the ticks) lasts seconds whatever this machine's speed.
  const std::string out2 = tmp.path() + "/scale2";
  const CliResult ok = run_cli({"bench", "scale", "--agents", "8", "--modes", "ec", "--duration", "5", "--min-rtf", "0.001",
                                "--realtime", "--out", out2, "--domain", std::to_string(private_domain())},
                               out2, 600);
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("bench scale: 1 of 1 sizes pass"), std::string::npos) << ok.output;
  // Its row accounts for the CPU of every process (launcher and server too) both by kind and by
  // thread, the two adding up to the same total, and it holds the DDS floor measured after it.
  const std::string columns =
      "python3 -c \"import csv, sys\n"
      "r = next(csv.DictReader(open(sys.argv[1])))\n"
      "f = lambda k: float(r[k])\n"
      "assert r['dds_floor_problem'] == '' and f('dds_floor_median_us') > 0 and f('x_dds_floor') > 0, r\n"
      "assert f('dds_floor_first_round_us') > 0, r\n"
      "total = f('cpu_us_tick_processes')\n"
      "threads = sum(f('cpu_us_tick_' + k) for k in ('tick_path', 'level2', 'recorder', 'other_threads'))\n"
      "kinds = sum(f('cpu_us_tick_' + k) for k in ('plant', 'agents', 'groups', 'central', 'ds', 'launcher'))\n"
      "assert total > 0 and abs(threads - total) <= 2 and abs(kinds - total) <= 3, (total, threads, kinds)\n"
      "assert f('cpu_us_tick_tick_path') > 0 and f('cpu_us_tick_launcher') > 0 and f('cpu_us_tick_machine') > 0, r\n"
      "assert f('tick_median_us') <= f('tick_p90_us') <= f('tick_max_us') and f('period_mean_us') > 0, r\n"
      "print('columns ok', total, threads, kinds)\" " +
      out2 + "/scale.csv 2>&1";
  const std::string said = shell_output(columns);
  EXPECT_NE(said.find("columns ok"), std::string::npos) << said;
}
