// A fleet on several hosts, the parts free of DDS and of root: placement, the command line of
// a process on a host, the hosts' subnet, host faults in a
// scenario and on the control FIFO.
#include <gtest/gtest.h>

#include <set>

#include "config/scenario.hpp"
#include "deploy/fleet/control_fifo.hpp"
#include "deploy/fleet/fault_schedule.hpp"
#include "deploy/fleet/hosts.hpp"

namespace {

using maptr::deploy::fleet::place_processes;

std::vector<std::string> fleet_names(int per_side) {
  std::vector<std::string> n = {"plant", "central", "group-L", "group-R"};
  for (int s = 0; s < 2; ++s)
    for (int j = 0; j < per_side; ++j) n.push_back(maptr::config::agent_name(s, j));
  return n;
}

TEST(HostPlacement, ThreeHostsKeepTheLastForAgentsAndSpreadEachSide) {
  const auto names = fleet_names(8);
  const auto where = place_processes(names, 3, {});
  // Controllers round-robin over h0 and h1: plant h0, central h1, group-L h0, group-R h1.
  EXPECT_EQ(where[0], 0);
  EXPECT_EQ(where[1], 1);
  EXPECT_EQ(where[2], 0);
  EXPECT_EQ(where[3], 1);
  // Every side has agents on every host, so losing any one host leaves each side with agents.
  for (int side = 0; side < 2; ++side) {
    std::set<int> hosts;
    for (int j = 0; j < 8; ++j) hosts.insert(where[4 + side * 8 + j]);
    EXPECT_EQ(hosts, (std::set<int>{0, 1, 2}));
  }
  for (int lost = 1; lost < 3; ++lost)
    for (int side = 0; side < 2; ++side) {
      int live = 0;
      for (int j = 0; j < 8; ++j) live += where[4 + side * 8 + j] != lost;
      EXPECT_GT(live, 0);
    }
}

TEST(HostPlacement, FourOrMoreHostsPutEveryControllerOnItsOwnHost) {
  const auto where = place_processes(fleet_names(4), 5, {});
  EXPECT_EQ(std::set<int>(where.begin(), where.begin() + 4).size(), 4u);
}

TEST(HostPlacement, RulesOverrideAndBadRulesAreNamed) {
  const auto where = place_processes(fleet_names(4), 3, {"central=h2", "L1=h0"});
  EXPECT_EQ(where[1], 2);
  EXPECT_EQ(where[4 + 1], 0);
  for (const char* bad : {"central", "nobody=h1", "central=h3", "central=x1"}) {
    try {
      place_processes(fleet_names(4), 3, {bad});
      ADD_FAILURE() << bad << " accepted";
    } catch (const maptr::config::ScenarioError& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(HostCommand, PrefixThenEnvThenTheProcess) {
  const auto argv =
      maptr::deploy::fleet::host_argv({"ip", "netns", "exec", "maptr-7-h1"}, {{"MAPTR_DOMAIN", "7"}},
                                      "/opt/maptr/bin/maptr_agent", {"--id", "L0"});
  const std::vector<std::string> want = {
      "ip",   "netns", "exec", "maptr-7-h1", "env", "MAPTR_DOMAIN=7", "/opt/maptr/bin/maptr_agent",
      "--id", "L0"};
  EXPECT_EQ(argv, want);
  EXPECT_EQ(maptr::deploy::fleet::split_command("  ssh  -o BatchMode=yes pi@b1 "),
            (std::vector<std::string>{"ssh", "-o", "BatchMode=yes", "pi@b1"}));
}

TEST(HostCommand, OverSshEveryWordArrivesAsItIsAtTheRemoteShell) {
  // ssh joins the words after the destination with blanks for the remote shell: each is quoted.
  // -n keeps the launcher's terminal from it, -tt gives the process one there (it ends with its ssh).
  const auto argv = maptr::deploy::fleet::host_argv({"/usr/bin/ssh", "pi@board1"}, {{"K", "a b'c"}},
                                                    "/opt/maptr/bin/maptr_agent", {"--id", "L0;x"});
  const std::vector<std::string> want = {
      "/usr/bin/ssh", "-tt",   "-n", "pi@board1", "'env'", "'K=a b'\\''c'", "'/opt/maptr/bin/maptr_agent'",
      "'--id'",       "'L0;x'"};
  EXPECT_EQ(argv, want);
  std::string joined = "printf '%s|'";
  for (std::size_t i = 4; i < argv.size(); ++i) joined += " " + argv[i];
  FILE* sh = popen(joined.c_str(), "r");
  ASSERT_NE(sh, nullptr);
  char buf[256] = {};
  const std::size_t n = fread(buf, 1, sizeof buf - 1, sh);
  pclose(sh);
  EXPECT_EQ(std::string(buf, n), "env|K=a b'c|/opt/maptr/bin/maptr_agent|--id|L0;x|")
      << "what a shell reads back";
}

TEST(HostNetwork, SubnetIsPrivateAndDiffersBetweenTags) {
  EXPECT_EQ(maptr::deploy::fleet::subnet_of(0x0102), "10.201.2");
  EXPECT_NE(maptr::deploy::fleet::subnet_of(4242), maptr::deploy::fleet::subnet_of(4243));
}

TEST(HostFaults, ScenarioRefusesHostFaultsWithoutHostsAndUnknownHosts) {
  maptr::config::Scenario s;
  s.faults.push_back({"h1", "kill-host", 20.0});
  EXPECT_THROW(s.validate(), maptr::config::ScenarioError);  // no hosts
  s.hosts.count = 3;
  EXPECT_NO_THROW(s.validate());
  s.faults.push_back({"h3", "partition", 10.0});
  EXPECT_THROW(s.validate(), maptr::config::ScenarioError);
  s.faults.back() = {"L1", "partition", 10.0};  // a process is not a host
  EXPECT_THROW(s.validate(), maptr::config::ScenarioError);
  s.faults.back() = {"h2", "kill", 10.0};  // a host is not a process
  EXPECT_THROW(s.validate(), maptr::config::ScenarioError);
}

TEST(HostFaults, ControlFifoTakesHostCommands) {
  maptr::deploy::fleet::CommandLines lines;
  const auto cmds = lines.feed("kill-host h2\npartition h1\nheal h1\nreboot h1\n");
  ASSERT_EQ(cmds.size(), 4u);
  EXPECT_TRUE(cmds[0].valid && cmds[1].valid && cmds[2].valid);
  EXPECT_FALSE(cmds[3].valid);
  EXPECT_EQ(cmds[0].target, "h2");
}

}  // namespace

namespace {

TEST(HostsSection, ReadWrittenAndReadBack) {
  const std::string yaml =
      "name: two-boards\n"
      "hosts:\n"
      "  launcher_address: 192.168.1.10\n"
      "  machines:\n"
      "    - {address: 192.168.1.10, command: ''}\n"
      "    - {address: 192.168.1.11, command: ssh pi@192.168.1.11}\n"
      "  placement: [central=h1]\n";
  const auto s = maptr::config::parse_scenario(yaml, "test");
  EXPECT_EQ(s.hosts.count, 2);
  ASSERT_EQ(s.hosts.machines.size(), 2u);
  EXPECT_EQ(s.hosts.machines[1].command, "ssh pi@192.168.1.11");
  const auto again = maptr::config::parse_scenario(maptr::config::to_yaml(s), "again");
  EXPECT_EQ(again.hosts.count, 2);
  EXPECT_EQ(again.hosts.machines[1].address, "192.168.1.11");
  EXPECT_EQ(again.hosts.placement, std::vector<std::string>{"central=h1"});
  EXPECT_EQ(again.hosts.launcher_address, "192.168.1.10");
  EXPECT_TRUE(again.hosts.failover) << "on by default";
  const auto off = maptr::config::parse_scenario("hosts: {count: 3, failover: false}\n", "test");
  EXPECT_FALSE(off.hosts.failover);
  EXPECT_FALSE(maptr::config::parse_scenario(maptr::config::to_yaml(off), "again").hosts.failover);
}

TEST(HostsSection, BadValuesNameTheField) {
  for (const char* bad :
       {"hosts: {count: 0}\n", "hosts: {count: 3, disks: 2}\n", "hosts: {machines: [{address: 10.0.0.1}]}\n",
        "hosts: {count: 3, failover: maybe}\n"}) {
    try {
      maptr::config::parse_scenario(bad, "test");
      ADD_FAILURE() << bad << " accepted";
    } catch (const maptr::config::ScenarioError& e) {
      EXPECT_NE(std::string(e.what()).find("hosts."), std::string::npos) << e.what();
    }
  }
  // Over ssh a pause cannot be done (SIGSTOP would stop the ssh client): refused before anything
  // starts, naming the fault and the rule; a kill is accepted.
  try {
    maptr::config::parse_scenario(
        "hosts: {count: 3, ssh: true}\nfaults: [{target: L1, action: pause, at_s: 5}]\n", "test");
    ADD_FAILURE() << "a pause over ssh accepted";
  } catch (const maptr::config::ScenarioError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("faults[0].action"), std::string::npos) << m;
    EXPECT_NE(m.find("pause"), std::string::npos) << m;
    EXPECT_NE(m.find("hosts.ssh"), std::string::npos) << m;
  }
  EXPECT_NO_THROW(maptr::config::parse_scenario(
      "hosts: {count: 3, ssh: true}\nfaults: [{target: L1, action: kill, at_s: 5}]\n", "test"));
  // An unknown key: the message names it and quotes its value (read from a copy of the node,
  // not from the iterator's temporary).
  try {
    maptr::config::parse_scenario("hosts:\n  tra-ck_m: 3\n", "test");
    ADD_FAILURE() << "an unknown hosts key accepted";
  } catch (const maptr::config::ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("hosts.tra-ck_m"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("3"), std::string::npos) << e.what();
  }
}

}  // namespace

namespace {

TEST(HostFaults, ChaosOnHostsCutsOffAHostOtherThanThePlantsAndHealsIt) {
  maptr::config::Scenario s;
  s.hosts.count = 3;
  const auto plan = maptr::deploy::chaos_schedule(7, s);
  int partitions = 0;
  for (std::size_t i = 0; i < plan.size(); ++i) {
    if (plan[i].action != "partition") continue;
    ++partitions;
    EXPECT_NE(plan[i].target, "h0");
    ASSERT_LT(i + 1, plan.size());
    EXPECT_EQ(plan[i + 1].action, "heal");
    EXPECT_EQ(plan[i + 1].target, plan[i].target);
    EXPECT_GE(plan[i + 1].at_s, plan[i].at_s + 2.0 - 1e-9);
  }
  EXPECT_EQ(partitions, 1);
  s.validate();
  maptr::config::Scenario one;
  for (const auto& f : maptr::deploy::chaos_schedule(7, one))
    EXPECT_FALSE(maptr::config::is_host_action(f.action));
}

}  // namespace
