// `maptr check` over a real run: the default scenario run clean holds every property, exit 0,
// and its JUnit file (read by Python's XML parser) has one passing case per property; a bound
// the run misses breaks with the tick and exit 1; a bad property or folder is exit 2.
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>

#include "tests/integration/fleet_runner.hpp"

using maptr::testing::CliResult;
using maptr::testing::private_domain;
using maptr::testing::run_cli;
using maptr::testing::TempDir;

namespace {

/// Output and exit code of a shell command.
std::pair<int, std::string> shell(const std::string& cmd) {
  std::string out;
  FILE* p = popen((cmd + " 2>&1").c_str(), "r");
  if (!p) return {-1, ""};
  char buf[512];
  while (fgets(buf, sizeof(buf), p)) out += buf;
  const int st = pclose(p);
  return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, out};
}

std::string maptr() { return std::string(MAPTR_BIN_DIR) + "/maptr"; }

/// How many properties `maptr check --list` names (one unindented line each).
int listed_properties() {
  const auto [code, out] = shell(maptr() + " check --list");
  EXPECT_EQ(code, 0) << out;
  int n = 0;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) n += !line.empty() && line[0] != ' ';
  return n;
}

TEST(Check, ACleanDefaultRunHoldsEveryPropertyAndItsJUnitFileSaysSo) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run", junit = tmp.path() + "/check.xml";
  const CliResult r =
      run_cli({"run", std::string(MAPTR_SOURCE_DIR) + "/deploy/scenarios/default.yaml", "--out", out, "--domain",
               std::to_string(private_domain()), "--quiet"},
              out, 600);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_EQ(r.summary["status"], "ok") << r.summary.dump(2);

  const int n = listed_properties();
  ASSERT_GE(n, 8);
  auto [code, printed] = shell(maptr() + " check " + out + " --junit " + junit);
  EXPECT_EQ(code, 0) << printed;
  EXPECT_NE(printed.find(std::to_string(n) + " properties, 0 broke"), std::string::npos) << printed;
  const auto [py, parsed] = shell(
      "python3 -c \"import sys, xml.etree.ElementTree as E\n"
      "s = E.parse(sys.argv[1]).getroot()\n"
      "c = s.findall('testcase')\n"
      "assert s.tag == 'testsuite' and s.attrib['failures'] == '0' and int(s.attrib['tests']) == len(c)\n"
      "assert all(x.find('failure') is None and 'classname' in x.attrib and 'time' in x.attrib for x in c)\n"
      "print(len(c), 'passing')\" " +
      junit);
  EXPECT_EQ(py, 0) << parsed;
  EXPECT_EQ(parsed, std::to_string(n) + " passing\n");

  // A speed band narrower than the run's own error breaks, at a tick, and says by how much.
  std::tie(code, printed) = shell(maptr() + " check " + out + " --property speed_band:0.5 --property path_tracked");
  EXPECT_EQ(code, 1) << printed;
  EXPECT_NE(printed.find("speed_band:0.5           BROKE  tick "), std::string::npos) << printed;
  EXPECT_NE(printed.find("% off its reference"), std::string::npos) << printed;
  EXPECT_NE(printed.find("path_tracked             holds"), std::string::npos) << printed;
  EXPECT_NE(printed.find("2 properties, 1 broke"), std::string::npos) << printed;

  // Bad input: exit 2, naming the option or the folder.
  std::tie(code, printed) = shell(maptr() + " check " + out + " --property speed_band:fast");
  EXPECT_EQ(code, 2) << printed;
  EXPECT_NE(printed.find("--property 'speed_band:fast'"), std::string::npos) << printed;
  std::tie(code, printed) = shell(maptr() + " check " + tmp.path() + "/no-such-run");
  EXPECT_EQ(code, 2) << printed;
  EXPECT_NE(printed.find("no-such-run: not a folder"), std::string::npos) << printed;
}

/// The first "BROKE  tick N" of maptr's output, "" when none.
std::string broken_tick(const std::string& out) {
  const auto at = out.find("BROKE  tick ");
  if (at == std::string::npos) return "";
  return out.substr(at + 12, out.find(' ', at + 12) - (at + 12));
}

// `maptr run --chaos SEED --property ...`: a property that breaks gives exit 1 and repro.yaml,
// the chaos drawn into scheduled faults; running repro.yaml gives the same trace and the same
// break at the same tick.
TEST(Check, AChaosRunThatBreaksAPropertyLeavesAReproducerThatBreaksItAgain) {
  TempDir tmp;
  const std::string first = tmp.path() + "/chaos", again = tmp.path() + "/again";
  const CliResult r = run_cli({"run", "--agents", "8", "--duration", "20", "--chaos", "5", "--property",
                               "max_dead_per_side:0", "--out", first, "--domain", std::to_string(private_domain())},
                              first, 600);
  ASSERT_EQ(r.exit_code, 1) << r.output;
  const std::string tick = broken_tick(r.output);
  ASSERT_FALSE(tick.empty()) << r.output;
  EXPECT_NE(r.output.find("properties  1 of 1 broke; reproducer " + first + "/repro.yaml"), std::string::npos)
      << r.output;
  const CliResult rerun = run_cli({"run", first + "/repro.yaml", "--property", "max_dead_per_side:0", "--out", again,
                                   "--domain", std::to_string(private_domain())},
                                  again, 600);
  EXPECT_EQ(rerun.exit_code, 1) << rerun.output;
  EXPECT_EQ(rerun.summary["trace_sha256"], r.summary["trace_sha256"]) << "repro.yaml ran another fleet";
  EXPECT_EQ(broken_tick(rerun.output), tick) << rerun.output;
  EXPECT_EQ(rerun.summary["failures"].size(), r.summary["failures"].size());
}

// From a failing run to its smallest scenario: seven faults of which three kills of one side's
// agents, dead together, break max_dead_per_side:2; `maptr shrink` of the run's repro.yaml
// keeps exactly those three, cuts the run to a second after the break, and its minimal.yaml
// breaks the property again.
TEST(Check, ShrinkReducesAFailingRunToTheThreeKillsThatBreakIt) {
  TempDir tmp;
  const std::string run = tmp.path() + "/run", shrunk = tmp.path() + "/shrink", again = tmp.path() + "/again";
  const CliResult r = run_cli({"run", "--agents", "8", "--duration", "10", "--pause", "R2@1", "--resume", "R2@2",
                               "--kill", "L1@2", "--kill", "L2@3", "--kill", "L3@4", "--kill", "R1@5", "--restart",
                               "R1@6", "--property", "max_dead_per_side:2", "--out", run, "--domain",
                               std::to_string(private_domain())},
                              run, 600);
  ASSERT_EQ(r.exit_code, 1) << r.output;
  ASSERT_EQ(broken_tick(r.output), "400") << r.output;
  const auto [code, printed] = shell(maptr() + " shrink " + run + "/repro.yaml --property max_dead_per_side:2 --out " +
                                     shrunk + " --domain " + std::to_string(private_domain()));
  ASSERT_EQ(code, 0) << printed;
  EXPECT_NE(printed.find("shrink: 7 -> 3 faults, 10.0 -> 5.0 s"), std::string::npos) << printed;
  for (const char* kept : {"kill L1 at 2.00 s", "kill L2 at 3.00 s", "kill L3 at 4.00 s"})
    EXPECT_NE(printed.find(kept), std::string::npos) << printed;
  const auto report = maptr::testing::read_json(shrunk + "/shrink.json");
  EXPECT_EQ(report["faults_after"], 3);
  // Three kills of L1..L3 need four agents a side: the fleet stays at 8.
  EXPECT_EQ(report["agents_after"], 8);
  EXPECT_GE(report["fleets_run"].get<int>(), 3);
  const CliResult min = run_cli({"run", shrunk + "/minimal.yaml", "--property", "max_dead_per_side:2", "--out", again,
                                 "--domain", std::to_string(private_domain())},
                                again, 600);
  EXPECT_EQ(min.exit_code, 1) << min.output;
  EXPECT_EQ(broken_tick(min.output), "400") << min.output;
  EXPECT_EQ(min.summary["trace_sha256"], report["trace_sha256"]);
}

}  // namespace
