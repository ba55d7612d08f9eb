// A fleet on several hosts (ctest label `hosts`): each host a network namespace of this machine.
// Needs root; without it every test is skipped with the reason.
#include <gtest/gtest.h>
#include <pwd.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "records/assignments.hpp"
#include "tests/integration/fleet_runner.hpp"

using namespace maptr::testing;

namespace {

constexpr const char* kNeedsRoot = "a fleet on several hosts makes network namespaces and needs root";

/// Why this machine cannot hold a fleet on several hosts ("" when it can): the launcher needs
/// root, network namespaces it can enter (`ip netns add` and `exec`; not in a chroot without
/// /run or /sys of its own) and a bridge with veth pairs. Everything it makes is removed.
std::string hosts_problem() {
  if (geteuid() != 0) return kNeedsRoot;
  const std::string tag = std::to_string(getpid());
  const std::string ns = "maptr-probe-" + tag, br = "mbrp" + tag, veth = "mvp" + tag;
  auto ok = [](const std::string& cmd) { return std::system((cmd + " > /dev/null 2>&1").c_str()) == 0; };
  std::string problem;
  if (!ok("command -v ip"))
    problem = "no `ip` command (iproute2)";
  else if (!ok("ip netns add " + ns))
    problem = "`ip netns add` fails here (no network namespaces, e.g. in a chroot)";
  else if (!ok("ip netns exec " + ns + " ip link set lo up"))
    problem = "`ip netns exec` fails here (e.g. a chroot without its own /run and /sys)";
  else if (!ok("ip link add " + br + " type bridge") ||
           !ok("ip link add " + veth + " type veth peer name " + veth + "p netns " + ns))
    problem = "cannot make a bridge and a veth pair into a namespace here";
  ok("ip link delete " + veth);
  ok("ip link delete " + br);
  ok("ip netns delete " + ns);
  return problem.empty() ? "" : "a fleet on several hosts needs network namespaces: " + problem;
}

/// hosts_problem(), asked once per test program.
const std::string& hosts_problem_once() {
  static const std::string p = hosts_problem();
  return p;
}

/// `j` at `path` as text, "(none)" when any key on the way is missing (a failed run may have
/// written no summary: a message must never throw).
std::string at(const nlohmann::json& j, std::initializer_list<const char*> path) {
  const nlohmann::json* v = &j;
  for (const char* k : path) {
    if (!v->is_object() || !v->contains(k)) return "(none)";
    v = &(*v)[k];
  }
  return v->dump();
}

/// True while anything of the run whose launcher had this pid is left: a namespace, its lock,
/// its bridge.
bool network_left(pid_t launcher) {
  const std::string tag = std::to_string(launcher);
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/run/netns", ec))
    if (e.path().filename().string().rfind("maptr-" + tag + "-", 0) == 0) return true;
  return std::filesystem::exists("/sys/class/net/mbr" + tag) ||
         std::filesystem::exists("/run/maptr-hosts/" + tag + ".lock");
}

/// Removes what a run left (only after a failed test; a run cleans up after itself).
void remove_network(pid_t launcher) {
  const std::string tag = std::to_string(launcher);
  for (int i = 0; i < 8; ++i)
    std::system(("ip netns delete maptr-" + tag + "-h" + std::to_string(i) + " 2>/dev/null").c_str());
  std::system(("ip link delete mbr" + tag + " 2>/dev/null").c_str());
  std::filesystem::remove("/run/maptr-hosts/" + tag + ".lock");
}

/// Runs `maptr ARGS`; returns the result and the launcher's pid (its network's tag).
CliResult run_hosts(const std::vector<std::string>& args, const std::string& out, double timeout_s,
                    pid_t& pid) {
  CliResult r;
  r.run_dir = out;
  pid = start_cli(args, out + ".out");
  const int code = wait_child(pid, timeout_s);
  r.timed_out = code == kTimedOut;
  r.exit_code = r.timed_out ? -1 : code;
  std::ifstream in(out + ".out");
  std::stringstream ss;
  ss << in.rdbuf();
  r.output = ss.str();
  std::ifstream js(out + "/summary.json");
  if (js) js >> r.summary;
  if (network_left(pid)) {
    ADD_FAILURE() << "the run left its network behind";
    remove_network(pid);
  }
  return r;
}

bool rejoined(const nlohmann::json& s, const std::string& name) {
  for (const auto& e : s["plant"]["membership_events"])
    if (e["name"] == name && e["event"] == "rejoined") return true;
  return false;
}

std::vector<std::string> on_host(const nlohmann::json& s, const std::string& host) {
  for (const auto& h : s["hosts"])
    if (h["name"] == host) return h["processes"].get<std::vector<std::string>>();
  return {};
}

class Hosts : public ::testing::Test {
 protected:
  void SetUp() override {
    if (const auto& p = hosts_problem_once(); !p.empty()) GTEST_SKIP() << p;
  }
};

}  // namespace

TEST_F(Hosts, FaultFreeTraceOnThreeHostsIsTheOneHostTrace) {
  TempDir tmp;
  pid_t pid = 0;
  const auto one = run_cli(run_args(tmp.path() + "/one", {"--duration", "8"}), tmp.path() + "/one", 300);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const auto three = run_hosts(run_args(tmp.path() + "/three", {"--duration", "8", "--hosts", "3"}),
                               tmp.path() + "/three", 300, pid);
  ASSERT_EQ(three.exit_code, 0) << three.output;
  EXPECT_EQ(three.summary["trace_sha256"], one.summary["trace_sha256"]);
  ASSERT_EQ(three.summary["hosts"].size(), 3u);
  // Every host's data crossed its link: the ticks in, the answers out.
  const double ticks = three.summary["plant"].value("ticks", 800.0);
  for (const auto& h : three.summary["hosts"]) {
    EXPECT_GT(h["bytes_sent"].get<double>(), 100.0 * ticks) << h.dump();
    EXPECT_GT(h["bytes_received"].get<double>(), 100.0 * ticks) << h.dump();
  }
  EXPECT_FALSE(one.summary.contains("hosts"));
}

TEST_F(Hosts, KillingAHostWithAgentsOfBothSidesKeepsTheRobotGoing) {
  TempDir tmp;
  pid_t pid = 0;
  const std::string out = tmp.path() + "/run";
  const auto r =
      // The agents that drive at 20 s (L6, L7, R6, R7 in this deterministic run) are put on h2,
      // beside those the default placement puts there: its loss takes drivers of both sides.
      run_hosts(
          run_args(out, {"--agents", "16", "--duration", "40", "--hosts", "3", "--kill-host", "h2@20",
                         "--place", "L6=h2", "--place", "L7=h2", "--place", "R6=h2", "--place", "R7=h2"}),
          out, 600, pid);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto& s = r.summary;
  EXPECT_EQ(s["status"], "ok");
  ASSERT_EQ(s["failures"].size(), 1u);
  const auto& f = s["failures"][0];
  EXPECT_FALSE(f.contains("skipped")) << f.dump();
  EXPECT_FALSE(f["detected_s"].is_null()) << f.dump();
  EXPECT_FALSE(f["recovered_s"].is_null()) << "speed back within 2 %: " << f.dump();
  const auto procs = on_host(s, "h2");
  EXPECT_TRUE(std::any_of(procs.begin(), procs.end(), [](auto& n) { return n[0] == 'L'; }));
  EXPECT_TRUE(std::any_of(procs.begin(), procs.end(), [](auto& n) { return n[0] == 'R'; }));
  // The groups reallocate: agents of h2 drive on both sides when it is lost; once the loss is
  // detected no assignment names one of them, and each side ends with agents driving.
  const double kill_s = 20.0, detected = f["detected_s"].get<double>();
  const auto rows = maptr::records::read_assignments(out + "/assignments.csv");
  auto drives = [](const maptr::records::AssignmentRecord& a, const std::string& name) {
    return name[0] == a.side && a.driving.at(static_cast<std::size_t>(std::stoi(name.substr(1)))) == '1';
  };
  std::map<char, std::string> last, at_kill;
  std::map<char, int> changes_after;
  for (const auto& a : rows) {
    if (a.t_s < kill_s) at_kill[a.side] = a.driving;
    if (a.t_s > detected) ++changes_after[a.side];
    last[a.side] = a.driving;
    if (a.t_s <= detected) continue;
    for (const auto& name : procs)
      EXPECT_FALSE(drives(a, name)) << name << " of the lost host drives at t " << a.t_s;
  }
  for (char side : {'L', 'R'}) {
    const maptr::records::AssignmentRecord before{kill_s, side, at_kill[side]};
    EXPECT_TRUE(std::any_of(procs.begin(), procs.end(), [&](auto& n) { return drives(before, n); }))
        << side << ": no agent of h2 drives at the loss (" << at_kill[side] << ")";
    EXPECT_GE(changes_after[side], 1) << side << " did not reallocate";
    EXPECT_NE(last[side].find('1'), std::string::npos) << side << " ends with no agent driving";
  }
}

TEST_F(Hosts, PartitionedHostRejoinsAfterTheHeal) {
  TempDir tmp;
  pid_t pid = 0;
  const std::string out = tmp.path() + "/run";
  const auto r = run_hosts(run_args(out, {"--agents", "8", "--duration", "40", "--hosts", "3", "--partition",
                                          "h2@10", "--heal", "h2@20"}),
                           out, 600, pid);
  // On failure: who left and came back when, and every process's end.
  ASSERT_EQ(r.exit_code, 0) << r.output
                            << "\nmembership events: " << at(r.summary, {"plant", "membership_events"})
                            << "\nprocesses: " << at(r.summary, {"processes"});
  const auto& s = r.summary;
  EXPECT_EQ(s["status"], "ok");
  for (const auto& name : on_host(s, "h2")) EXPECT_TRUE(rejoined(s, name)) << name << " did not rejoin";
  // The cut holds until the heal: nobody answers from the cut-off host before it.
  for (const auto& e : s["plant"]["membership_events"]) {
    if (e["event"] != "rejoined") continue;
    EXPECT_GE(e["t_s"].get<double>(), 20.0) << "through the cut: " << e.dump();
  }
  ASSERT_EQ(s["failures"].size(), 2u);
  EXPECT_FALSE(s["failures"][1]["detected_s"].is_null()) << s["failures"].dump();
}

TEST_F(Hosts, APartitionOfAboutOneLeaseCostsNoProcessOfTheOtherHosts) {
  // Paced to the wall clock, the cut lasts 1.8 s against a 2-s lease: the cut-off host's
  // discovery server lets the leases of the clients it tracks run out just after the heal. When
  // every client registered with every server, it then announced the processes of the other
  // hosts as gone, and the plant lost them all although none had stopped.
  TempDir tmp;
  pid_t pid = 0;
  const std::string out = tmp.path() + "/run";
  const auto r = run_hosts(run_args(out, {"--agents", "8", "--duration", "10", "--hosts", "3", "--realtime",
                                          "--partition", "h2@5", "--heal", "h2@6.8"}),
                           out, 600, pid);
  ASSERT_EQ(r.exit_code, 0) << r.output
                            << "\nmembership events: " << at(r.summary, {"plant", "membership_events"});
  const auto& s = r.summary;
  EXPECT_EQ(s["status"], "ok");
  EXPECT_DOUBLE_EQ(read_json(out + "/fleet.json")["lease_s"].get<double>(), 2.0) << "the cut is sized to it";
  const auto cut = on_host(s, "h2");
  ASSERT_FALSE(cut.empty());
  for (const auto& name : cut) EXPECT_TRUE(rejoined(s, name)) << name << " did not rejoin";
  for (const auto& e : s["plant"]["membership_events"]) {
    const std::string name = e["name"];
    EXPECT_NE(std::find(cut.begin(), cut.end(), name), cut.end())
        << "a process off the cut host: " << e.dump();
  }
}

TEST_F(Hosts, ProcessOfALostHostRestartsElsewhereThroughTheOtherDiscoveryServers) {
  TempDir tmp;
  pid_t pid = 0;
  const std::string out = tmp.path() + "/run";
  const auto r = run_hosts(run_args(out, {"--agents", "8", "--duration", "30", "--hosts", "3", "--kill-host",
                                          "h2@10", "--restart", "L2@15"}),
                           out, 600, pid);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto& s = r.summary;
  EXPECT_EQ(s["status"], "ok");
  EXPECT_TRUE(rejoined(s, "L2"));
  for (const auto& p : s["processes"]) {
    if (p["name"] == "L2") {
      EXPECT_NE(p["host"], "h2") << p.dump();
    }
  }
}

TEST_F(Hosts, TheControllersOfALostHostFailOverAndTheRunEndsOk) {
  // The default placement on three hosts puts controllers on h1; its loss at 10 s takes them.
  TempDir tmp;
  pid_t pid = 0;
  const std::string out = tmp.path() + "/run";
  const auto r =
      run_hosts(run_args(out, {"--agents", "16", "--duration", "30", "--hosts", "3", "--kill-host", "h1@10"}),
                out, 600, pid);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto& s = r.summary;
  EXPECT_EQ(s["status"], "ok") << at(s, {"failovers"});
  ASSERT_TRUE(s.contains("failovers")) << s.dump();
  ASSERT_FALSE(s["failovers"].empty()) << "no controller on h1? hosts: " << at(s, {"hosts"});
  std::map<std::string, std::string> host_at_end;
  for (const auto& p : s["processes"]) host_at_end[p["name"]] = p.value("host", "");
  for (const auto& f : s["failovers"]) {
    const std::string name = f["name"];
    EXPECT_TRUE(name == "central" || name == "group-L" || name == "group-R") << f.dump();
    EXPECT_EQ(f["from"], "h1") << f.dump();
    ASSERT_TRUE(f["to"].is_string()) << f.dump();
    EXPECT_NE(f["to"], "h1") << f.dump();
    EXPECT_EQ(host_at_end[name], f["to"]) << name << " does not end on the host it failed over to";
    EXPECT_DOUBLE_EQ(f["detected_at_s"].get<double>(), 10.0) << f.dump();
    // The loss acts at a fault gate, which holds the simulated time until the controller is back.
    ASSERT_TRUE(f["running_at_s"].is_number()) << f.dump();
    EXPECT_DOUBLE_EQ(f["running_at_s"].get<double>(), 10.0) << f.dump();
    EXPECT_TRUE(rejoined(s, name)) << name << " did not rejoin the plant";
  }
  // The gate waits for the new copies, not for the lost ones to end (they share their names).
  std::ifstream log(out + "/logs/launcher.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("a killed process did not end"), std::string::npos) << "the gate waited out its limit";
}

TEST_F(Hosts, WithoutFailoverALostHostsControllersStayDeadAndTheRunSaysSo) {
  TempDir tmp;
  pid_t pid = 0;
  const std::string out = tmp.path() + "/run", scen = tmp.path() + "/no-failover.yaml";
  write_file(scen, "name: no-failover\nagents: 16\nduration_s: 30\nhosts: {count: 3, failover: false}\n");
  const auto r = run_hosts(run_args(out, {scen, "--kill-host", "h1@10"}), out, 600, pid);
  const auto& s = r.summary;
  ASSERT_TRUE(s.contains("status")) << r.output;
  EXPECT_EQ(s["status"].get<std::string>().rfind("degraded", 0), 0u) << s["status"];
  EXPECT_TRUE(s["failovers"].empty()) << s["failovers"];
}

TEST_F(Hosts, NothingIsLeftAfterTheLauncherIsKilled) {
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  const pid_t pid =
      start_cli(run_args(out, {"--hosts", "3", "--realtime", "--duration", "120"}), out + ".out");
  ASSERT_TRUE(wait_for([&] { return read_json(out + "/fleet.json").contains("processes"); }, 120));
  ASSERT_TRUE(network_left(pid));
  std::vector<pid_t> kids;
  for (const auto& p : read_json(out + "/fleet.json")["processes"]) kids.push_back(p["pid"].get<pid_t>());
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  EXPECT_TRUE(wait_for(
      [&] { return std::none_of(kids.begin(), kids.end(), [](pid_t k) { return process_running(k); }); },
      30));
  // The next run on hosts removes what the killed one left.
  pid_t next = 0;
  const auto r = run_hosts(run_args(tmp.path() + "/next", {"--hosts", "2", "--duration", "1"}),
                           tmp.path() + "/next", 300, next);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(network_left(pid));
  if (network_left(pid)) remove_network(pid);
}

/// Why the ssh rehearsal cannot run here ("" : it can).
std::string ssh_problem() {
  if (access("/usr/sbin/sshd", X_OK) != 0) return "no /usr/sbin/sshd (Debian: openssh-server)";
  if (std::system("command -v ssh >/dev/null 2>&1 && command -v ssh-keygen >/dev/null 2>&1") != 0)
    return "no ssh or ssh-keygen (Debian: openssh-client)";
  return "";
}

/// True while a process runs whose command line holds `text`.
bool running_with(const std::string& text) {
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/proc", ec)) {
    std::ifstream f(e.path() / "cmdline");
    const std::string cmd((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (cmd.find(text) != std::string::npos) return true;
  }
  return false;
}

/// True when a process's mount table still holds a mount at or under `path` (a host's disk).
bool mounted_anywhere(const std::string& path) {
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/proc", ec)) {
    std::ifstream f(e.path() / "mountinfo");
    for (std::string line; std::getline(f, line);)
      if (line.find(" " + path) != std::string::npos) return true;
  }
  return false;
}

std::string ssh_dir_of(pid_t launcher) { return "/run/maptr-hosts/" + std::to_string(launcher) + "-ssh"; }

/// True while a server of this launcher's run runs or its folder of keys is there.
bool ssh_server_left(pid_t launcher) {
  return running_with(ssh_dir_of(launcher)) || std::filesystem::exists(ssh_dir_of(launcher));
}

TEST_F(Hosts, OverSshEveryProcessStartsBySshAndTheTraceIsTheOneHostTrace) {
  if (const auto p = ssh_problem(); !p.empty()) GTEST_SKIP() << p;
  TempDir tmp;
  pid_t pid = 0;
  const auto one =
      run_cli(run_args(tmp.path() + "/one", {"--agents", "16", "--duration", "8"}), tmp.path() + "/one", 300);
  ASSERT_EQ(one.exit_code, 0) << one.output;
  const auto ssh =
      run_hosts(run_args(tmp.path() + "/ssh", {"--agents", "16", "--duration", "8", "--hosts", "3", "--ssh"}),
                tmp.path() + "/ssh", 300, pid);
  ASSERT_EQ(ssh.exit_code, 0) << ssh.output;
  EXPECT_EQ(ssh.summary["status"], "ok");
  EXPECT_EQ(ssh.summary["trace_sha256"], one.summary["trace_sha256"]);
  ASSERT_EQ(ssh.summary["processes"].size(), 20u);
  for (const auto& p : ssh.summary["processes"]) {
    EXPECT_EQ(p.value("started_by", ""), "ssh") << p.dump();
    // Its pid on its host came with its readiness; the launcher's child is its ssh client.
    EXPECT_GT(p.value("host_pid", 0L), 0L) << p.dump();
    EXPECT_NE(p.value("host_pid", 0L), p.value("pid", 0L)) << p.dump();
  }
  for (const auto& h : ssh.summary["hosts"]) EXPECT_EQ(h.value("started_by", ""), "ssh") << h.dump();
  // No host saw the launcher's run folder (each had a disk of its own and did not see the
  // launcher's marker file); every host's logs and files came home: under hosts/<name>/, and
  // merged into the run folder (the trace above is the plant's host's, collected).
  const std::string out = tmp.path() + "/ssh";
  for (const auto& h : ssh.summary["hosts"]) {
    EXPECT_EQ(h.value("run_folder", "").rfind("its own: collected ", 0), 0u) << h.dump();
    EXPECT_TRUE(std::filesystem::is_directory(out + "/hosts/" + h.value("name", "") + "/logs")) << h.dump();
  }
  for (const auto& p : ssh.summary["processes"])
    EXPECT_TRUE(std::filesystem::exists(out + "/logs/" + p.value("name", "") + ".log")) << p.dump();
  for (const char* f : {"trace.csv", "plant.json", "ledger-L.json", "level2-L.csv"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + f)) << f;
  EXPECT_FALSE(ssh_server_left(pid)) << "an ssh server, key or configuration of the run is left";
  EXPECT_FALSE(network_left(pid));
  EXPECT_FALSE(mounted_anywhere(out)) << "a host's disk is still mounted";
}

TEST_F(Hosts, OverSshTheControllersOfALostHostFailOver) {
  if (const auto p = ssh_problem(); !p.empty()) GTEST_SKIP() << p;
  TempDir tmp;
  pid_t pid = 0;
  const std::string out = tmp.path() + "/run";
  const auto r = run_hosts(
      run_args(out, {"--agents", "16", "--duration", "20", "--hosts", "3", "--ssh", "--kill-host", "h1@8"}),
      out, 600, pid);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.summary["status"], "ok") << at(r.summary, {"failovers"});
  ASSERT_FALSE(r.summary["failovers"].empty());
  for (const auto& f : r.summary["failovers"]) {
    EXPECT_EQ(f["from"], "h1") << f.dump();
    EXPECT_TRUE(f["running_at_s"].is_number()) << f.dump();
  }
  // The lost host's disk could not be reached; the others' came home.
  for (const auto& h : r.summary["hosts"])
    EXPECT_EQ(h.value("run_folder", "")
                  .rfind(h["name"] == "h1" ? "its own: not collected" : "its own: collected", 0),
              0u)
        << h.dump();
  EXPECT_EQ(r.summary["plant"]["group_wear"]["L"]["regressions"], 0);
  EXPECT_FALSE(ssh_server_left(pid));
  EXPECT_FALSE(mounted_anywhere(out));
}

TEST_F(Hosts, OverSshNothingIsLeftAfterTheLauncherIsKilled) {
  if (const auto p = ssh_problem(); !p.empty()) GTEST_SKIP() << p;
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  const pid_t pid =
      start_cli(run_args(out, {"--hosts", "3", "--ssh", "--realtime", "--duration", "120"}), out + ".out");
  ASSERT_TRUE(wait_for([&] { return read_json(out + "/fleet.json").contains("processes"); }, 120));
  ASSERT_TRUE(ssh_server_left(pid));
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  // The servers end with the launcher, and the processes on the hosts with their ssh clients,
  // before any other run sweeps (the folder of keys stays until then).
  EXPECT_TRUE(wait_for([&] { return !running_with(ssh_dir_of(pid)); }, 30))
      << "an ssh server outlived the launcher";
  EXPECT_TRUE(wait_for([&] { return !running_with(out); }, 30))
      << "a process of the run outlived the launcher";
  EXPECT_TRUE(wait_for([&] { return !mounted_anywhere(out); }, 30)) << "a host's disk outlived the launcher";
  pid_t next = 0;
  const auto r = run_hosts(run_args(tmp.path() + "/next", {"--hosts", "2", "--duration", "1"}),
                           tmp.path() + "/next", 300, next);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(network_left(pid));
  EXPECT_FALSE(ssh_server_left(pid));
  if (network_left(pid)) remove_network(pid);
}

/// group-L on h1 with central and group-R; h1 cut off at 8 s for 10 s, then healed.
void partition_of_the_controllers_host(bool ssh) {
  TempDir tmp;
  pid_t pid = 0;
  const std::string out = tmp.path() + "/run";
  std::vector<std::string> args = {"--agents", "16",         "--duration",  "30",   "--hosts", "3",
                                   "--place",  "group-L=h1", "--partition", "h1@8", "--heal",  "h1@18"};
  if (ssh) args.push_back("--ssh");
  const auto r = run_hosts(run_args(out, args), out, 600, pid);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto& s = r.summary;
  EXPECT_EQ(s["status"], "ok") << at(s, {"failovers"});
  std::set<std::string> moved;
  for (const auto& f : s["failovers"]) {
    moved.insert(f["name"].get<std::string>());
    EXPECT_EQ(f["from"], "h1") << f.dump();
    EXPECT_DOUBLE_EQ(f["detected_at_s"].get<double>(), 8.0) << f.dump();
    EXPECT_TRUE(f["running_at_s"].is_number()) << f.dump();
  }
  EXPECT_EQ(moved, (std::set<std::string>{"central", "group-L", "group-R"}));
  // One group-L at the end: the copy started on a reachable host, which ended cleanly.
  for (const auto& p : s["processes"])
    if (p["name"] == "group-L") {
      EXPECT_NE(p["host"], "h1") << p.dump();
      EXPECT_EQ(p["exit_code"], 0) << p.dump();
    }
  // The stranded copies were ended at the heal (over ssh: the ssh client and the copy on the host).
  std::ifstream log(out + "/logs/launcher.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  for (const std::string name : {"central", "group-L", "group-R"}) {
    const std::string line = name + ": the stranded copy on h1 ended (pid ";
    const auto at = text.find(line);
    EXPECT_NE(at, std::string::npos) << name << "'s stranded copy was not ended";
    if (ssh && at != std::string::npos)
      EXPECT_NE(text.substr(at, 120).find(", on the host "), std::string::npos) << text.substr(at, 120);
  }
  // The ledgers go on from the ones before the cut: never a step back.
  for (const char* side : {"L", "R"})
    EXPECT_EQ(s["plant"]["group_wear"][side]["regressions"], 0) << at(s, {"plant", "group_wear"});
  EXPECT_FALSE(network_left(pid));
  EXPECT_FALSE(ssh_server_left(pid));
}

TEST_F(Hosts, APartitionOfTheControllersHostFailsThemOverAndTheHealLeavesOneOfEach) {
  partition_of_the_controllers_host(false);
}

TEST_F(Hosts, OverSshAPartitionOfTheControllersHostLeavesOneOfEachAfterTheHeal) {
  if (const auto p = ssh_problem(); !p.empty()) GTEST_SKIP() << p;
  partition_of_the_controllers_host(true);
}

TEST_F(Hosts, AHostWithoutABinaryStopsTheRunBeforeAnythingStarts) {
  // h1's command runs each process in a mount namespace of its own where maptr_agent is
  // /dev/null (not executable): a machine without the agent's binary at this machine's path.
  TempDir tmp;
  const std::string agent = cli_bin_dir() + "/maptr_agent";
  const std::string hide = tmp.path() + "/hide.sh";
  write_file(hide, "#!/bin/sh\nexec unshare -m sh -c 'mount --bind /dev/null \"$0\" && exec \"$@\"' " +
                       agent + " \"$@\"\n");
  chmod(hide.c_str(), 0755);
  const std::string scenario = tmp.path() + "/two.yaml";
  write_file(scenario,
             "name: hide\nduration_s: 5\nhosts:\n  launcher_address: 127.0.0.1\n  machines:\n"
             "    - {address: 127.0.0.1, command: \"\"}\n    - {address: 127.0.0.2, command: \"" +
                 hide + "\"}\n");
  const std::string out = tmp.path() + "/run";
  const auto r = run_cli(run_args(out, {scenario}), out, 120);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("host h1 (127.0.0.2): " + agent + ": missing or not executable there"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(std::filesystem::exists(out + "/fleet.json")) << "a process started";
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/proc", ec)) {
    std::ifstream f(e.path() / "cmdline");
    const std::string cmd((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_EQ(cmd.find(out), std::string::npos) << "left running: " << e.path();
  }
}

TEST(HostsRefused, ASecureFleetOnSeveralHostsExitsTwoBeforeAnythingStarts) {
  // Several hosts find each other through discovery servers, which a secure fleet does not have:
  // the combination is refused rather than run silently on one host.
  TempDir tmp;
  const std::string out = tmp.path() + "/run";
  const auto r = run_cli(run_args(out, {"--secure", "--hosts", "3", "--duration", "1"}), out, 60);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--secure with hosts"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out + "/fleet.json")) << "a process started";
}

TEST(HostsWithoutRoot, ExitTwoAndSayWhy) {
  TempDir tmp;
  const passwd* nobody = getpwnam("nobody");
  if (!nobody) GTEST_SKIP() << "no user 'nobody' to run without root";
  const std::string log = tmp.path() + "/out";
  chmod(tmp.path().c_str(), 0777);
  const pid_t pid = fork();
  if (pid == 0) {
    if (setgid(nobody->pw_gid) != 0 || setuid(nobody->pw_uid) != 0) _exit(99);
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
    dup2(fd, 1);
    dup2(fd, 2);
    const std::string bin = std::string(MAPTR_BIN_DIR) + "/maptr";
    execl(bin.c_str(), bin.c_str(), "run", "--hosts", "3", "--out", "/nonexistent/never", nullptr);
    _exit(127);
  }
  const int code = wait_child(pid, 60);
  if (code == 99 || code == 127) GTEST_SKIP() << "cannot run the CLI as 'nobody' here";
  EXPECT_EQ(code, 2);
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("needs root"), std::string::npos) << ss.str();
}
