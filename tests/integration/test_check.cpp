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

}  // namespace
