#include "comm/dds/process.hpp"

#include <sched.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_sinks.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace maptr::comm {

namespace {
std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop.store(true); }
}  // namespace

std::atomic<bool>& stop_flag() {
  std::signal(SIGTERM, on_signal);
  std::signal(SIGINT, on_signal);
  std::signal(SIGHUP,
              on_signal);  // started over ssh: the launcher's SIGTERM to the client arrives as a hang-up
  return g_stop;
}

std::string make_thread_realtime(int priority) {
  if (priority <= 0) return "normal";
  const std::string wanted = "SCHED_FIFO " + std::to_string(priority);
  sched_param p{};
  p.sched_priority = priority;
  // pid 0: the calling thread only (Linux schedules threads one by one).
  if (sched_setscheduler(0, SCHED_FIFO | SCHED_RESET_ON_FORK, &p) != 0)
    return "normal (" + wanted + " refused: " + std::strerror(errno) + ")";
  const int cpu = sched_getcpu();
  cpu_set_t one;
  CPU_ZERO(&one);
  if (cpu >= 0) CPU_SET(cpu, &one);
  if (cpu < 0 || sched_setaffinity(0, sizeof(one), &one) != 0)
    return wanted + " (on any CPU: " + std::strerror(errno) + ")";
  return wanted + " on CPU " + std::to_string(cpu);
}

ProcessArgs parse_process_args(int argc, char** argv, const std::string& what) {
  ProcessArgs a;
  a.dds = options_from_env();
  CLI::App app{what};
  app.add_option("--config", a.config, "resolved scenario file")->required();
  app.add_option("--run-dir", a.run_dir, "results folder")->required();
  app.add_option("--name", a.name, "process name")->required();
  app.add_option("--domain", a.dds.domain, "DDS domain id");
  app.add_option("--discovery-server", a.dds.discovery_server, "HOST:PORT of the discovery server");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::exit(app.exit(e));
  }
  try {
    a.scenario = config::load_scenario(a.config);
  } catch (const config::ScenarioError& e) {
    std::cerr << a.name << ": " << e.what() << "\n";
    std::exit(2);
  }
  return a;
}

std::shared_ptr<spdlog::logger> make_logger(const ProcessArgs& a) {
  const std::string dir = a.run_dir + "/logs";
  std::filesystem::create_directories(dir);
  auto file = std::make_shared<spdlog::sinks::basic_file_sink_mt>(dir + "/" + a.name + ".log", false);
  auto err = std::make_shared<spdlog::sinks::stderr_sink_mt>();
  err->set_level(spdlog::level::err);
  auto log = std::make_shared<spdlog::logger>(a.name, spdlog::sinks_init_list{file, err});
  log->set_pattern("%Y-%m-%d %H:%M:%S.%e [%n] %l: %v");
  log->flush_on(spdlog::level::info);
  return log;
}

}  // namespace maptr::comm

#include <unistd.h>

#include "idl/maptrPubSubTypes.h"
#include "idl/rules.hpp"

namespace maptr::comm {

namespace {
ReadyGate ready_gate = nullptr;
}  // namespace

void set_ready_gate(ReadyGate gate) { ready_gate = gate; }

void write_ready(eprosima::fastdds::dds::DataWriter* w, const std::string& name, msg::NodeKind kind) {
  msg::NodeReady r;
  r.name(name);
  r.kind(kind);
  r.pid(static_cast<uint32_t>(getpid()));
  r.ready(true);
  w->write(&r);
}

void announce_ready(eprosima::fastdds::dds::DataWriter* w, const std::string& name, msg::NodeKind kind) {
  if (ready_gate != nullptr && !ready_gate(name)) return;
  write_ready(w, name, kind);
}

void report_unmatched(eprosima::fastdds::dds::DataWriter* w, const std::string& name, msg::NodeKind kind,
                      const std::vector<std::string>& unmatched) {
  msg::NodeReady r;
  r.name(name);
  r.kind(kind);
  r.pid(static_cast<uint32_t>(getpid()));
  r.ready(false);
  const std::size_t n = std::min(unmatched.size(), msg::kMaxUnmatched);
  r.unmatched().assign(unmatched.begin(), unmatched.begin() + static_cast<std::ptrdiff_t>(n));
  w->write(&r);
}

}  // namespace maptr::comm
