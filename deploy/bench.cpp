#include "deploy/bench.hpp"

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>
#include <sys/resource.h>
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "deploy/launcher.hpp"
#include "config/scenario.hpp"

namespace maptr::deploy {

namespace fs = std::filesystem;

namespace {

double cpu_seconds(int who) {
  rusage ru{};
  getrusage(who, &ru);
  return ru.ru_utime.tv_sec + ru.ru_utime.tv_usec * 1e-6 + ru.ru_stime.tv_sec + ru.ru_stime.tv_usec * 1e-6;
}

/// Proportional set size of a process, kB (shared pages split among their users).
long pss_kB(long pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/smaps_rollup");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("Pss:", 0) == 0) return std::stol(line.substr(4));
  return -1;
}

struct Memory {
  std::vector<long> agent_pss_kB;
  long total_pss_kB = 0;
};

/// Samples the fleet's PSS once the run is under way (fleet.json names the processes).
Memory sample_memory(const std::string& run_dir, const std::atomic<bool>& done) {
  Memory m;
  const auto t0 = std::chrono::steady_clock::now();
  // Wait for the lock-step to run for a while: memory after discovery and warm-up.
  while (!done.load()) {
    std::error_code ec;
    if (fs::exists(run_dir + "/trace.csv", ec) && fs::file_size(run_dir + "/trace.csv", ec) > 6000) break;  // ~2 s simulated
    if (std::chrono::steady_clock::now() - t0 > std::chrono::minutes(30)) return m;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  if (done.load()) return m;
  nlohmann::json fleet;
  try {
    std::ifstream(run_dir + "/fleet.json") >> fleet;
  } catch (...) {
    return m;
  }
  for (const auto& p : fleet["processes"]) {
    const long kb = pss_kB(p["pid"].get<long>());
    if (kb < 0) continue;
    m.total_pss_kB += kb;
    const std::string name = p["name"];
    if (name[0] == 'L' || name[0] == 'R') m.agent_pss_kB.push_back(kb);
  }
  if (fleet.contains("launcher_pid")) {
    const long launcher = pss_kB(fleet["launcher_pid"].get<long>());
    if (launcher > 0) m.total_pss_kB += launcher;
  }
  return m;
}

double median(std::vector<long> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::shared_ptr<spdlog::logger> file_logger(const std::string& dir) {
  fs::create_directories(dir + "/logs");
  auto log = std::make_shared<spdlog::logger>(
      "launcher", std::make_shared<spdlog::sinks::basic_file_sink_mt>(dir + "/logs/launcher.log"));
  log->flush_on(spdlog::level::info);
  return log;
}

void plot(const std::string& dir) {
  const std::string gp = dir + "/scale.gp";
  // Relative paths: the script runs in the output folder (`cd DIR && gnuplot scale.gp`).
  std::ofstream(gp) << "# made by `maptr bench scale`; redraw with `maptr bench scale --replot --out DIR`\n"
                       "set terminal pngcairo size 1100,800 noenhanced\n"
                       "set output 'scale.png'\n"
                       "set datafile separator ','\n"
                       "set key autotitle columnhead\n"
                       "set multiplot layout 2,2 title 'MAPTR scale-up on this machine (lock-step, EC mode)'\n"
                       "set logscale x 2\nset grid\nset xlabel 'agent processes N'\n"
                       "set ylabel 'seconds'\nset title 'launch to all matched'\n"
                       "plot 'scale.csv' using 1:3 with linespoints title 'all processes matched'\n"
                       "set ylabel 'simulated s per wall s'\nset title 'real-time factor at 100 Hz (log scale)'\nset logscale y\n"
                       "plot 'scale.csv' using 1:5 with linespoints title 'RTF', 1 with lines dt 2 title 'real time'\n"
                       "set ylabel 'CPU s per simulated s'\nset title 'CPU cost (log scale)'\n"
                       "plot 'scale.csv' using 1:6 with linespoints title 'all processes'\n"
                       "unset logscale y\nset ylabel 'MB'\nset title 'proportional memory (PSS) per agent process'\nset yrange [0:14]\n"
                       "plot 'scale.csv' using 1:($7/1024) with linespoints title 'median', "
                       "'' using 1:($8/1024) with linespoints title 'max', 12 with lines dt 2 title 'target 12 MB'\n"
                       "unset multiplot\n";
  const std::string cmd = "cd '" + dir + "' && gnuplot scale.gp 2>/dev/null";
  if (std::system(cmd.c_str()) != 0) std::cerr << "maptr: gnuplot failed; the CSV and markdown are written\n";
}

int bench_scale(const BenchOptions& o) {
  if (o.replot) {
    if (!fs::exists(o.out + "/scale.csv")) {
      std::cerr << "maptr: bench scale --replot: no " << o.out << "/scale.csv\n";
      return 2;
    }
    plot(o.out);
    std::cerr << "maptr: redrew " << o.out << "/scale.png\n";
    return 0;
  }
  fs::create_directories(o.out);
  std::ofstream csv(o.out + "/scale.csv");
  csv << "agents,status,discovery_s,ticks_per_wall_s,real_time_factor,cpu_s_per_sim_s,pss_agent_median_kB,"
         "pss_agent_max_kB,pss_total_kB,samples_per_tick,tick_median_us,tick_p99_us\n";
  std::ostringstream md;
  md << "| N | status | discovery s | ticks / wall s | RTF (100 Hz) | CPU s / sim s | PSS agent median MB | "
        "PSS agent max MB | PSS total MB | DDS samples / tick | tick median ms | tick p99 ms |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  int worst = 0;
  for (int n : o.agents) {
    // Each fleet size runs as its own `maptr run` process: a launcher that fails at this size
    // (Fast DDS aborts at 128+ agents here) is recorded, not fatal to the bench.
    const std::string run_dir = o.out + "/runs/N" + std::to_string(n);
    fs::create_directories(run_dir);
    const std::string dur = std::to_string(o.duration_s);
    std::vector<std::string> args = {o.bin_dir + "/maptr", "run", "--agents", std::to_string(n), "--duration", dur,
                                     "--speed", "10", "--trace-every", "10", "--out", run_dir, "--domain",
                                     std::to_string(o.domain), "--quiet"};
    std::atomic<bool> done{false};
    Memory mem;
    const double cpu0 = cpu_seconds(RUSAGE_CHILDREN);
    std::cerr << "maptr: bench scale N=" << n << " ..." << std::flush;
    int wstatus = 0;
    const std::string log = run_dir + "/maptr.out";
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t pid = fork();  // single-threaded here: the sampler starts after the fork
    if (pid == 0) {
      const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd >= 0) {
        dup2(fd, 1);
        dup2(fd, 2);
      }
      execv(argv[0], argv.data());
      _exit(127);
    }
    std::thread sampler([&] { mem = sample_memory(run_dir, done); });
    waitpid(pid, &wstatus, 0);
    nlohmann::json sum;
    try {
      std::ifstream(run_dir + "/summary.json") >> sum;
    } catch (...) {
      sum = nlohmann::json::object();
    }
    if (!sum.contains("status"))
      sum["status"] = WIFSIGNALED(wstatus) ? "aborted: the launcher died of signal " + std::to_string(WTERMSIG(wstatus)) +
                                                 " (see " + run_dir + "/maptr.out)"
                                           : "aborted: no summary (exit " + std::to_string(WEXITSTATUS(wstatus)) + ")";
    done.store(true);
    sampler.join();
    const double cpu = cpu_seconds(RUSAGE_CHILDREN) - cpu0;
    const double sim = sum.value("sim_time_s", 0.0), wall = sum.value("wall_time_s", 0.0);
    const std::string status = sum.value("status", "unknown");
    const auto timing = sum.contains("plant") ? sum["plant"].value("tick_timing_us", nlohmann::json::object())
                                              : nlohmann::json::object();
    const double tick_med = timing.contains("tick") ? timing["tick"].value("median", 0.0) : 0.0;
    const double tick_p99 = timing.contains("tick") ? timing["tick"].value("p99", 0.0) : 0.0;
    const double rtf = sum.value("real_time_factor", 0.0);
    const long pss_max = mem.agent_pss_kB.empty() ? 0 : *std::max_element(mem.agent_pss_kB.begin(), mem.agent_pss_kB.end());
    const int samples = n + 4;  // one PlantTick, N AgentReply, 2 GroupStatus, 1 CentralCommand
    char row[512];
    std::snprintf(row, sizeof(row), "%d,%s,%.2f,%.1f,%.2f,%.2f,%.0f,%ld,%ld,%d,%.0f,%.0f\n", n,
                  status.substr(0, status.find(':')).c_str(), sum.value("discovery_s", 0.0),
                  wall > 0 ? sum.value("ticks", 0) / wall : 0.0, rtf, sim > 0 ? cpu / sim : 0.0,
                  median(mem.agent_pss_kB), pss_max, mem.total_pss_kB, samples, tick_med, tick_p99);
    csv << row << std::flush;
    std::snprintf(row, sizeof(row), "| %d | %s | %.2f | %.1f | %.2f | %.2f | %.1f | %.1f | %.0f | %d | %.2f | %.2f |\n",
                  n, (status.size() > 70 ? status.substr(0, 70) + "..." : status).c_str(), sum.value("discovery_s", 0.0), wall > 0 ? sum.value("ticks", 0) / wall : 0.0, rtf,
                  sim > 0 ? cpu / sim : 0.0, median(mem.agent_pss_kB) / 1024.0, pss_max / 1024.0,
                  mem.total_pss_kB / 1024.0, samples, tick_med / 1000.0, tick_p99 / 1000.0);
    md << row;
    std::cerr << " " << status << ", discovery " << sum.value("discovery_s", 0.0) << " s, RTF " << rtf << "\n";
    if (status != "ok") worst = 1;
  }
  std::ofstream(o.out + "/scale.md") << md.str();
  plot(o.out);
  std::cout << md.str() << "results: " << o.out << "/scale.csv, scale.md, scale.png\n";
  return worst;
}

int bench_tick(const BenchOptions& o) {
  const int n = o.agents.size() == 1 ? o.agents.front() : 16;
  config::Scenario s = config::load_scenario(o.source_dir + "/deploy/scenarios/default.yaml");
  s.name = "tick-" + std::to_string(n);
  s.robot.agents = n;
  s.duration_s = o.duration_s;
  s.trajectory.segments = {config::Segment{"straight", 10.0, 0.0, o.duration_s}};
  s.validate();
  LaunchOptions lo;
  lo.scenario = s;
  lo.run_dir = o.out + "/runs/tick-N" + std::to_string(n);
  lo.bin_dir = o.bin_dir;
  lo.domain = o.domain;
  lo.progress = false;
  auto log = file_logger(lo.run_dir);
  const nlohmann::json sum = launch(lo, *log);
  const auto t = sum["plant"].value("tick_timing_us", nlohmann::json::object());
  std::ostringstream md;
  md << "Lock-step tick, N = " << n << ", " << o.duration_s << " s simulated at 100 Hz (" << sum.value("ticks", 0)
     << " ticks), status " << sum.value("status", "") << "\n\n"
     << "| part | median µs | p90 µs | p99 µs |\n|---|---|---|---|\n";
  const std::pair<const char*, const char*> parts[] = {
      {"publish", "plant publishes PlantTick k (write returns)"},
      {"first_reply", "first agent reply after the write returned"},
      {"barrier", "write returned -> every live agent, group and central answered"},
      {"integrate", "CVODE over [t_k, t_k+1] + trace row"},
      {"tick", "whole tick"}};
  for (const auto& [key, what] : parts) {
    if (!t.contains(key)) continue;
    char row[256];
    std::snprintf(row, sizeof(row), "| %s (%s) | %.0f | %.0f | %.0f |\n", key, what, t[key].value("median", 0.0),
                  t[key].value("p90", 0.0), t[key].value("p99", 0.0));
    md << row;
  }
  fs::create_directories(o.out);
  std::ofstream(o.out + "/tick.md") << md.str();
  std::ofstream(o.out + "/tick.json") << t.dump(2) << "\n";
  std::cout << md.str() << "results: " << o.out << "/tick.md, tick.json\n";
  return sum.value("status", "") == "ok" ? 0 : 1;
}

}  // namespace

int run_bench(const BenchOptions& o) {
  try {
    if (o.what == "scale") return bench_scale(o);
    if (o.what == "tick") return bench_tick(o);
  } catch (const std::exception& e) {
    std::cerr << "maptr: bench " << o.what << ": " << e.what() << "\n";
    return 1;
  }
  std::cerr << "maptr: bench " << o.what << ": unknown (scale, tick)\n";
  return 2;
}

}  // namespace maptr::deploy
