// The agents' zygote (comm/posix/zygote.hpp, deploy/fleet/zygote.hpp): a copy it forks is the
// launcher's own child, with what an exec'd child has (its own process group, the parent-death
// signal, the request's environment, arguments and output), and a zygote that is gone leaves
// the launcher starting children with exec.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "comm/posix/zygote.hpp"
#include "deploy/fleet/children.hpp"
#include "deploy/fleet/zygote_client.hpp"

namespace {

namespace fs = std::filesystem;
using maptr::comm::decode_zygote_request;
using maptr::comm::encode_zygote_request;
using maptr::comm::ZygoteRequest;
using maptr::deploy::fleet::Child;
using maptr::deploy::fleet::Zygote;

const std::string kProbe = MAPTR_ZYGOTE_PROBE;

struct Dir {
  fs::path path;
  Dir() : path(fs::temp_directory_path() / ("maptr-zygote-" + std::to_string(getpid()))) {
    fs::create_directories(path / "logs");
  }
  ~Dir() { fs::remove_all(path); }
  std::string out(const std::string& name) const { return (path / "logs" / (name + ".stderr")).string(); }
};

/// The probe's KEY=VALUE lines.
std::map<std::string, std::string> read_probe(const std::string& path) {
  std::ifstream f(path);
  std::map<std::string, std::string> kv;
  for (std::string line; std::getline(f, line);)
    if (const auto eq = line.find('='); eq != std::string::npos) kv[line.substr(0, eq)] = line.substr(eq + 1);
  return kv;
}

int wait_exit(pid_t pid) {
  int st = 0;
  EXPECT_EQ(waitpid(pid, &st, 0), pid) << "a copy is the launcher's child";
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

TEST(Zygote, ACopyIsTheLaunchersChildWithTheRequestsArgumentsEnvironmentAndOutput) {
  Dir dir;
  auto z = Zygote::start(kProbe, {"MAPTR_PROBE=zygote"}, dir.out("zygote"));
  ASSERT_TRUE(z);
  ASSERT_TRUE(z->serves(kProbe));
  EXPECT_FALSE(z->serves("/bin/true"));
  const pid_t pid = z->fork_copy({kProbe, "7", "second"}, {"MAPTR_PROBE=copy"}, dir.out("c1"));
  ASSERT_GT(pid, 0);
  EXPECT_EQ(wait_exit(pid), 7) << "its main's result is its exit status";
  auto kv = read_probe(dir.out("c1"));
  EXPECT_EQ(kv["pid"], std::to_string(pid));
  EXPECT_EQ(kv["ppid"], std::to_string(getpid()));
  EXPECT_EQ(kv["pgrp"], std::to_string(pid)) << "a process group of its own";
  EXPECT_EQ(kv["pdeathsig"], std::to_string(SIGKILL));
  EXPECT_EQ(kv["comm"], "zygote_probe") << "named after its program, not the zygote";
  EXPECT_EQ(kv["forked"], "1");
  EXPECT_EQ(kv["probe"], "copy");
  EXPECT_EQ(kv["home"], "unset") << "the request's environment only";
  EXPECT_EQ(kv["argc"], "3");
  EXPECT_EQ(kv["argv2"], "second");
  EXPECT_EQ(z->forked(), 1);
}

TEST(Zygote, ManyCopiesInARowEachStartOnceWithItsOwnEnvironment) {
  Dir dir;
  auto z = Zygote::start(kProbe, {}, dir.out("zygote"));
  ASSERT_TRUE(z);
  std::set<pid_t> pids;
  for (int i = 0; i < 30; ++i) {
    const std::string name = "c" + std::to_string(i);
    const pid_t pid = z->fork_copy({kProbe, std::to_string(i)}, {"MAPTR_PROBE=" + name}, dir.out(name));
    ASSERT_GT(pid, 0);
    pids.insert(pid);
    EXPECT_EQ(wait_exit(pid), i);
    EXPECT_EQ(read_probe(dir.out(name))["probe"], name);
  }
  EXPECT_EQ(pids.size(), 30u);
  EXPECT_EQ(z->forked(), 30);
  EXPECT_EQ(z->failed(), 0);
}

TEST(Zygote, SpawnForksFromTheZygoteAndFallsBackToExecOnceItIsGone) {
  Dir dir;
  auto z = Zygote::start(kProbe, {}, dir.out("zygote"));
  ASSERT_TRUE(z);
  Child c;
  c.name = "A1";
  c.binary = kProbe;
  c.args = {"3"};
  maptr::deploy::fleet::spawn(c, dir.path.string(), {{"MAPTR_PROBE", "spawned"}}, 17, z.get());
  ASSERT_GT(c.pid, 0);
  EXPECT_EQ(wait_exit(c.pid), 3);
  auto kv = read_probe(dir.out("A1"));
  EXPECT_EQ(kv["forked"], "1");
  EXPECT_EQ(kv["probe"], "spawned");

  // The zygote dies; the launcher reaps it and tells it so; the next start is an exec.
  kill(z->pid(), SIGKILL);
  ASSERT_EQ(waitpid(z->pid(), nullptr, 0), z->pid());
  z->lost();
  EXPECT_FALSE(z->serves(kProbe));
  Child d = c;
  d.name = "A2";
  maptr::deploy::fleet::spawn(d, dir.path.string(), {{"MAPTR_PROBE", "execd"}}, 18, z.get());
  ASSERT_GT(d.pid, 0);
  EXPECT_EQ(wait_exit(d.pid), 3);
  kv = read_probe(dir.out("A2"));
  EXPECT_EQ(kv["forked"], "0");
  EXPECT_EQ(kv["probe"], "execd");
}

TEST(Zygote, AZygoteKilledUnseenMakesTheRequestFailAndIsDropped) {
  Dir dir;
  auto z = Zygote::start(kProbe, {}, dir.out("zygote"));
  ASSERT_TRUE(z);
  kill(z->pid(), SIGKILL);
  ASSERT_EQ(waitpid(z->pid(), nullptr, 0), z->pid());
  EXPECT_EQ(z->fork_copy({kProbe}, {}, dir.out("c")), -1);
  EXPECT_FALSE(z->serves(kProbe));
  EXPECT_EQ(z->failed(), 1);
  z->lost();
}

TEST(Zygote, RequestsRoundTripAndMalformedOnesAreRefused) {
  ZygoteRequest r{{"/bin/agent", "--id", "L3", ""}, {"A=1", "B=x=y"}, "/tmp/out", 1234};
  const auto back = decode_zygote_request(encode_zygote_request(r));
  ASSERT_TRUE(back);
  EXPECT_EQ(back->argv, r.argv);
  EXPECT_EQ(back->env, r.env);
  EXPECT_EQ(back->out_path, r.out_path);
  EXPECT_EQ(back->parent, 1234);

  const std::string good = encode_zygote_request(r);
  EXPECT_FALSE(decode_zygote_request(""));
  EXPECT_FALSE(decode_zygote_request(good.substr(0, good.size() - 1))) << "a field without its NUL";
  ZygoteRequest bad = r;
  bad.parent = 1;
  EXPECT_FALSE(decode_zygote_request(encode_zygote_request(bad))) << "init is no requester";
  bad = r;
  bad.env.push_back("NOEQUALS");
  EXPECT_FALSE(decode_zygote_request(encode_zygote_request(bad)));
  bad = r;
  bad.out_path.clear();
  EXPECT_FALSE(decode_zygote_request(encode_zygote_request(bad)));
  bad = r;
  bad.argv[0].clear();
  EXPECT_FALSE(decode_zygote_request(encode_zygote_request(bad)));
  // argc larger than the fields there are
  std::string m = std::string("1234") + '\0' + "/tmp/out" + '\0' + "9" + '\0' + "/bin/agent" + '\0';
  EXPECT_FALSE(decode_zygote_request(m));
}

}  // namespace
