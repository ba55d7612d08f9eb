// `maptr experiment NAME`: the paper's experiments on the real multi-process fleet.
//
// Every scenario variant is one launch() (a whole fleet of processes, lock-step, run to its
// end). The experiment then reads what the fleet wrote (summary.json, trace.csv,
// assignments.csv, ledger-L/R.json) and writes, into its output folder:
//   <name>.csv      the experiment's table (one row per point),
//   <name>.md       the same table in markdown, with the conditions and the paper's numbers,
//   summary.json    the table as JSON (what the tests read), the conditions and every run,
//   *.png + *.gp    gnuplot plots made from the CSVs written here (series/*.csv for time series),
//   runs/<variant>/ the fleet's own results for each variant.
// A variant whose folder already holds a finished run of the identical scenario is not run
// again (an interrupted experiment resumes); delete runs/<variant>/ to force it.
#include "deploy/experiments.hpp"

#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/spdlog.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "deploy/launcher.hpp"
#include "config/scenario.hpp"

namespace maptr::deploy {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Ctrl-C / SIGTERM: the fleet running now ends (its launcher sees the signal too when it comes
// from the terminal), and no further variant starts.
volatile std::sig_atomic_t g_stop = 0;
void on_stop_signal(int) { g_stop = 1; }

// ---------------------------------------------------------------------------------------------
// The paper's Table "Straight-line power saving for a 16 agent system" (Type-I motors,
// straight line, 30 min, ~36 km): its own numbers, the only values not produced by a run.
struct PaperRow {
  double gross_kg, e_no_kJ, e_ec_kJ, saving_pct, active, mileage_no, mileage_ec;
};
const PaperRow kPaperTable[] = {
    {13.2, 92.33, 63.17, 31.58, 3, 0.4098, 0.5347},  {18.2, 111.69, 87.46, 21.70, 5, 0.3359, 0.3970},
    {23.2, 131.05, 108.94, 16.87, 6, 0.2838, 0.3171}, {28.2, 150.41, 132.81, 11.7, 8, 0.2452, 0.2633},
    {33.2, 169.77, 156.58, 7.77, 10, 0.2153, 0.2249}, {38.2, 189.13, 180.35, 4.64, 12, 0.1916, 0.1962}};

const PaperRow* paper_row(double gross_kg) {
  for (const auto& r : kPaperTable)
    if (std::fabs(r.gross_kg - gross_kg) < 1e-6) return &r;
  return nullptr;
}

// ---------------------------------------------------------------------------------------------
// Small utilities.

json num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

double get_num(const json& j, const std::string& key) {
  if (!j.is_object() || !j.contains(key) || !j[key].is_number()) return kNaN;
  return j[key].get<double>();
}

std::string fixed(double v, int prec) {
  if (!std::isfinite(v)) return "";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", prec, v);
  return buf;
}

std::string kg_label(double kg) {
  std::string s = fixed(kg, 2);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

/// A CSV of numbers with a header (non-numeric fields read as NaN).
struct Csv {
  std::vector<std::string> head;
  std::vector<std::vector<double>> rows;
  int col(const std::string& name) const {
    for (std::size_t i = 0; i < head.size(); ++i)
      if (head[i] == name) return static_cast<int>(i);
    return -1;
  }
  double at(std::size_t row, int c) const {
    return c >= 0 && static_cast<std::size_t>(c) < rows[row].size() ? rows[row][c] : kNaN;
  }
};

std::vector<std::string> split(const std::string& line, char sep = ',') {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string f; std::getline(ss, f, sep);) out.push_back(f);
  if (!line.empty() && line.back() == sep) out.emplace_back();
  return out;
}

Csv read_csv(const std::string& path) {
  Csv c;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) return c;
  c.head = split(line);
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<double> r;
    for (const auto& f : split(line)) {
      char* end = nullptr;
      const double v = std::strtod(f.c_str(), &end);
      r.push_back(end != f.c_str() ? v : kNaN);
    }
    c.rows.push_back(std::move(r));
  }
  return c;
}

json read_json_file(const std::string& path) {
  std::ifstream in(path);
  json j;
  try {
    if (in) in >> j;
  } catch (...) {
    j = nullptr;
  }
  return j;
}

std::string csv_field(const json& v, int prec) {
  if (v.is_null()) return "";
  if (v.is_string()) {
    std::string s = v.get<std::string>();
    if (s.find_first_of(",\"") == std::string::npos) return s;
    std::string q = "\"";
    for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return q + "\"";
  }
  if (v.is_boolean()) return v.get<bool>() ? "1" : "0";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) return prec >= 0 ? fixed(v.get<double>(), prec) : fixed(v.get<double>(), 6);
  return v.dump();
}

/// An experiment's table: CSV (keys as the header), markdown (human headers), JSON rows.
struct Column {
  std::string key, head;
  int prec = 2;      ///< decimals; -1 for text
  bool md = true;    ///< shown in the markdown table
};

struct Table {
  std::vector<Column> cols;
  std::vector<json> rows;

  std::string csv() const {
    std::ostringstream o;
    for (std::size_t i = 0; i < cols.size(); ++i) o << (i ? "," : "") << cols[i].key;
    o << "\n";
    for (const auto& r : rows) {
      for (std::size_t i = 0; i < cols.size(); ++i)
        o << (i ? "," : "") << csv_field(r.contains(cols[i].key) ? r[cols[i].key] : json(nullptr), cols[i].prec);
      o << "\n";
    }
    return o.str();
  }
  std::string md() const {
    std::ostringstream o;
    o << "|";
    for (const auto& c : cols)
      if (c.md) o << " " << c.head << " |";
    o << "\n|";
    for (const auto& c : cols)
      if (c.md) o << "---|";
    o << "\n";
    for (const auto& r : rows) {
      o << "|";
      for (const auto& c : cols) {
        if (!c.md) continue;
        const json v = r.contains(c.key) ? r[c.key] : json(nullptr);
        std::string s = v.is_null() ? "–" : csv_field(v, c.prec);
        if (v.is_string()) s = v.get<std::string>();
        o << " " << s << " |";
      }
      o << "\n";
    }
    return o.str();
  }
};

// ---------------------------------------------------------------------------------------------
// One fleet run and what is derived from its trace.

struct Run {
  std::string id, label, dir;
  config::Scenario s;
  json summary = json::object();
  bool reused = false;
  bool retried = false;
  // Derived from trace.csv.
  double t_reach_s = kNaN;       ///< first time within 2% of the reference speed
  double v_end_mps = kNaN;       ///< mean speed over the last 10% of the run
  double ref_end_mps = kNaN;     ///< reference at the end
  double eff_cruise = kNaN;      ///< mean per-agent efficiency (mean of eff_L, eff_R), second half
  double active_cruise = kNaN;   ///< mean active agents (L + R), second half
  double v_over_vb = kNaN;       ///< applied voltage / battery voltage, second half
  double v_applied = kNaN;       ///< mean applied voltage, second half, V

  std::string status() const { return summary.value("status", std::string("aborted: no summary")); }
  bool aborted() const { return status().rfind("aborted", 0) == 0; }
  double energy_kJ() const { return aborted() ? kNaN : get_num(summary, "energy_J") / 1000.0; }
  double mileage() const { return aborted() ? kNaN : get_num(summary, "mileage_m_per_J"); }
  double sim_s() const { return get_num(summary, "sim_time_s"); }
  int active_end() const {
    if (aborted() || !summary.contains("active_agents")) return -1;
    return summary["active_agents"].value("L", 0) + summary["active_agents"].value("R", 0);
  }
  int active_side(const char* side) const {
    if (aborted() || !summary.contains("active_agents")) return -1;
    return summary["active_agents"].value(side, 0);
  }
  /// Level-2 figures over both sides (summary.json "level2"): decisions, the median of the
  /// sides' median Ipopt solve times, and oracle checks and disagreements.
  json level2() const {
    json o = {{"decisions", 0}, {"checked", 0}, {"differs", 0}};
    if (!summary.contains("level2") || !summary["level2"].is_object()) return o;
    std::vector<double> med;
    for (const auto& [side, s] : summary["level2"].items()) {
      o["decisions"] = o["decisions"].get<int>() + s.value("decisions", 0);
      o["checked"] = o["checked"].get<int>() + s.value("oracle_checked", 0);
      o["differs"] = o["differs"].get<int>() + s.value("oracle_differs", 0);
      if (s.contains("solve_ms_median")) med.push_back(s["solve_ms_median"].get<double>());
    }
    if (!med.empty()) o["solve_ms_median"] = med.size() == 2 ? 0.5 * (med[0] + med[1]) : med[0];
    return o;
  }
  const json& plant() const {
    static const json empty = json::object();
    return summary.contains("plant") && summary["plant"].is_object() ? summary["plant"] : empty;
  }
  /// The speed stayed within 2% of the reference at the end of the run.
  bool speed_held() const {
    return std::isfinite(v_end_mps) && std::isfinite(ref_end_mps) && ref_end_mps > 0 &&
           v_end_mps >= 0.98 * ref_end_mps;
  }
};

void derive(Run& r) {
  const Csv t = read_csv(r.dir + "/trace.csv");
  if (t.rows.empty()) return;
  const double rad = r.s.robot.wheel_radius_m;
  const int c_t = t.col("t_s"), c_v = t.col("v_x_mps"), c_rl = t.col("ref_L_radps"), c_rr = t.col("ref_R_radps"),
            c_el = t.col("eff_L"), c_er = t.col("eff_R"), c_nl = t.col("n_active_L"), c_nr = t.col("n_active_R"),
            c_vl = t.col("V_L_mean_V"), c_vr = t.col("V_R_mean_V"), c_bl = t.col("battery_V_L"),
            c_br = t.col("battery_V_R");
  const std::size_t n = t.rows.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double ref = 0.5 * (t.at(i, c_rl) + t.at(i, c_rr)) * rad;
    if (ref > 0 && std::fabs(t.at(i, c_v) - ref) < 0.02 * ref) {
      r.t_reach_s = t.at(i, c_t);
      break;
    }
  }
  const std::size_t tail = std::max<std::size_t>(1, n / 10);
  double sv = 0;
  for (std::size_t i = n - tail; i < n; ++i) sv += t.at(i, c_v);
  r.v_end_mps = sv / tail;
  r.ref_end_mps = 0.5 * (t.at(n - 1, c_rl) + t.at(n - 1, c_rr)) * rad;
  double se = 0, sa = 0, sr = 0, sva = 0;
  int ne = 0, na = 0, nr = 0;
  for (std::size_t i = n / 2; i < n; ++i) {
    const double nl = t.at(i, c_nl), nrr = t.at(i, c_nr);
    sa += nl + nrr;
    ++na;
    if (nl > 0 && nrr > 0) {
      se += 0.5 * (t.at(i, c_el) + t.at(i, c_er));
      ++ne;
      const double bl = t.at(i, c_bl), br = t.at(i, c_br);
      if (bl > 0 && br > 0) {
        sr += 0.5 * (t.at(i, c_vl) / bl + t.at(i, c_vr) / br);
        sva += 0.5 * (t.at(i, c_vl) + t.at(i, c_vr));
        ++nr;
      }
    }
  }
  if (ne) r.eff_cruise = se / ne;
  if (na) r.active_cruise = sa / na;
  if (nr) {
    r.v_over_vb = sr / nr;
    r.v_applied = sva / nr;
  }
}

/// Largest |v - v_ref| / v_ref in percent over the trace rows with t >= t0.
double max_speed_error_after(const Run& r, double t0) {
  const Csv t = read_csv(r.dir + "/trace.csv");
  const double rad = r.s.robot.wheel_radius_m;
  const int c_t = t.col("t_s"), c_v = t.col("v_x_mps"), c_rl = t.col("ref_L_radps"), c_rr = t.col("ref_R_radps");
  double m = kNaN;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const double ref = 0.5 * (t.at(i, c_rl) + t.at(i, c_rr)) * rad;
    if (t.at(i, c_t) < t0 || !(ref > 0)) continue;
    const double e = 100.0 * std::fabs(t.at(i, c_v) - ref) / ref;
    m = std::isfinite(m) ? std::max(m, e) : e;
  }
  return m;
}

/// Time series of a run, averaged over bins of bin_s, written to path (for the plots).
void write_series(const Run& r, const std::string& path, double bin_s) {
  const Csv t = read_csv(r.dir + "/trace.csv");
  const double rad = r.s.robot.wheel_radius_m;
  const int c_t = t.col("t_s"), c_v = t.col("v_x_mps"), c_rl = t.col("ref_L_radps"), c_rr = t.col("ref_R_radps"),
            c_el = t.col("eff_L"), c_er = t.col("eff_R"), c_nl = t.col("n_active_L"), c_nr = t.col("n_active_R"),
            c_vl = t.col("V_L_mean_V"), c_vr = t.col("V_R_mean_V"), c_bl = t.col("battery_V_L"),
            c_br = t.col("battery_V_R"), c_dl = t.col("discharge_L_mAh"), c_dr = t.col("discharge_R_mAh"),
            c_e = t.col("energy_J"), c_d = t.col("distance_m");
  std::ofstream o(path);
  o << "t_s,v_x_mps,ref_mps,eff_agent,n_active,battery_V,V_applied_V,discharge_mAh,energy_kJ,distance_m\n";
  std::size_t i = 0;
  while (i < t.rows.size()) {
    const long long bin = static_cast<long long>(std::floor(t.at(i, c_t) / bin_s + 1e-9));
    double st = 0, sv = 0, sref = 0, seff = 0, sn = 0, sb = 0, sva = 0;
    int k = 0, kv = 0;
    std::size_t last = i;
    for (; i < t.rows.size() && static_cast<long long>(std::floor(t.at(i, c_t) / bin_s + 1e-9)) == bin; ++i) {
      st += t.at(i, c_t);
      sv += t.at(i, c_v);
      sref += 0.5 * (t.at(i, c_rl) + t.at(i, c_rr)) * rad;
      seff += 0.5 * (t.at(i, c_el) + t.at(i, c_er));
      sn += t.at(i, c_nl) + t.at(i, c_nr);
      sb += 0.5 * (t.at(i, c_bl) + t.at(i, c_br));
      if (t.at(i, c_nl) > 0 && t.at(i, c_nr) > 0) {
        sva += 0.5 * (t.at(i, c_vl) + t.at(i, c_vr));
        ++kv;
      }
      ++k;
      last = i;
    }
    char row[512];
    std::snprintf(row, sizeof(row), "%.3f,%.5f,%.5f,%.5f,%.3f,%.4f,%s,%.3f,%.4f,%.2f\n", st / k, sv / k, sref / k,
                  seff / k, sn / k, sb / k, kv ? fixed(sva / kv, 4).c_str() : "",
                  0.5 * (t.at(last, c_dl) + t.at(last, c_dr)), t.at(last, c_e) / 1000.0, t.at(last, c_d));
    o << row;
  }
}

// ---------------------------------------------------------------------------------------------
// The experiment context: output folder, progress, runs.

class Experiment {
 public:
  Experiment(const ExperimentOptions& o) : o_(o) {}

  const ExperimentOptions& opt() const { return o_; }
  bool quick() const { return o_.quick; }
  const std::string& dir() const { return o_.out; }
  void set_total(int n) { total_ = n; }
  bool stopped() const { return interrupted_; }
  bool any_aborted() const { return any_aborted_; }

  double tick_hz() const { return o_.tick_hz > 0 ? o_.tick_hz : default_tick_hz(o_.name); }

  config::Scenario base() const {
    config::Scenario s = config::load_scenario(o_.source_dir + "/deploy/scenarios/default.yaml");
    s.tick_hz = tick_hz();
    return s;
  }

  /// Straight line at `speed` for `duration` (and nothing else on the trajectory).
  static void straight(config::Scenario& s, double speed, double duration) {
    s.duration_s = duration;
    s.trajectory.segments = {config::Segment{"straight", speed, 0.0, duration}};
    s.trajectory.accel_mps2 = 0.0;
  }

  Run run(const std::string& id, const std::string& label, config::Scenario s) {
    Run r;
    r.id = id;
    r.label = label;
    r.dir = o_.out + "/runs/" + id;
    s.name = o_.name + "-" + id;
    s.validate();
    r.s = s;
    ++done_;
    char head[64];
    std::snprintf(head, sizeof(head), "[%d/%d]", done_, std::max(total_, done_));
    if (interrupted_) {
      r.summary = {{"status", "aborted: not run (the experiment was interrupted)"}};
      runs_.push_back(r);
      return r;
    }
    // Reuse a finished run of the identical scenario in this folder.
    const json old = read_json_file(r.dir + "/summary.json");
    std::string old_yaml;
    {
      std::ifstream in(r.dir + "/scenario.yaml");
      std::stringstream ss;
      ss << in.rdbuf();
      old_yaml = ss.str();
    }
    if (old.is_object() && old.contains("status") && old["status"].is_string() &&
        old["status"].get<std::string>().rfind("aborted", 0) != 0 && old_yaml == config::to_yaml(s) &&
        fs::exists(r.dir + "/trace.csv")) {
      r.summary = old;
      r.reused = true;
    } else {
      r.summary = launch_isolated(r.dir, s, o_.domain);
      // A launcher that died or a fleet that never started (discovery) is not a result of the
      // experiment: try once more, on the next DDS domain (other ports), and say so.
      const std::string first = r.status();
      if (r.aborted() && first.find("interrupted") == std::string::npos && !g_stop) {
        const int retry_domain = o_.domain < 232 ? o_.domain + 1 : o_.domain - 1;
        std::fprintf(stderr, "maptr: %s %s %s: %s; running it once more on DDS domain %d\n", head, o_.name.c_str(),
                     label.c_str(), first.c_str(), retry_domain);
        r.summary = launch_isolated(r.dir, s, retry_domain);
        r.summary["first_attempt"] = first;
        r.retried = true;
      }
    }
    derive(r);
    const std::string st = r.status();
    if (r.aborted()) any_aborted_ = true;
    if (st.find("interrupted") != std::string::npos || g_stop) interrupted_ = true;
    std::fprintf(stderr, "maptr: %s %s %s: %.0f s simulated in %.0f s, status %s%s\n", head, o_.name.c_str(),
                 label.c_str(), r.summary.value("sim_time_s", 0.0), r.summary.value("wall_time_s", 0.0), st.c_str(),
                 r.reused ? " (reused: this scenario already ran in this folder)" : "");
    runs_.push_back(r);
    return r;
  }

  /// One launch() in a child process of its own: the experiment process never holds a DDS
  /// participant, so a fault inside Fast DDS ends one run, not the experiment, and no DDS state
  /// is carried from one fleet to the next. The child dies with the experiment.
  json launch_isolated(const std::string& run_dir, const config::Scenario& s, int domain) {
    std::error_code ec;
    fs::remove_all(run_dir, ec);  // a stale wear ledger would be resumed by the group controllers
    fs::create_directories(run_dir + "/logs");
    std::fflush(nullptr);
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid < 0) return {{"status", "aborted: fork failed"}};
    if (pid == 0) {
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (getppid() != parent) _exit(1);
      std::signal(SIGINT, SIG_DFL);
      std::signal(SIGTERM, SIG_DFL);
      int rc = 0;
      try {
        auto log = std::make_shared<spdlog::logger>(
            "launcher", std::make_shared<spdlog::sinks::basic_file_sink_mt>(run_dir + "/logs/launcher.log", true));
        log->flush_on(spdlog::level::info);
        LaunchOptions lo;
        lo.scenario = s;
        lo.run_dir = run_dir;
        lo.bin_dir = o_.bin_dir;
        lo.domain = domain;
        lo.progress = false;
        launch(lo, *log);  // writes run_dir/summary.json
        log->flush();
      } catch (const std::exception& e) {
        std::ofstream(run_dir + "/summary.json") << json{{"status", std::string("aborted: ") + e.what()}}.dump(2);
        rc = 1;
      }
      std::fflush(nullptr);
      _exit(rc);
    }
    int st = 0;
    bool forwarded = false;
    while (waitpid(pid, &st, 0) < 0 && errno == EINTR) {
      if (g_stop && !forwarded) {  // the launcher ends its fleet and writes an "interrupted" summary
        kill(pid, SIGTERM);
        forwarded = true;
      }
    }
    json sum = read_json_file(run_dir + "/summary.json");
    if (!sum.is_object() || !sum.contains("status")) {
      std::string why = WIFSIGNALED(st) ? "the launcher died of signal " + std::to_string(WTERMSIG(st))
                                        : "the launcher exited with " + std::to_string(WEXITSTATUS(st));
      sum = {{"status", "aborted: " + why + " without a summary (see runs/" + fs::path(run_dir).filename().string() +
                            "/logs)"}};
    }
    return sum;
  }

  /// Writes <name>.csv, <name>.md and summary.json.
  void write(const Table& t, const std::string& md_intro, const std::string& md_after, json extra = json::object()) {
    fs::create_directories(o_.out);
    std::ofstream(o_.out + "/" + o_.name + ".csv") << t.csv();
    std::ostringstream md;
    md << "# " << o_.name << (o_.quick ? " (quick)" : "") << "\n\n"
       << "Command: `" << command() << "`\n\n"
       << md_intro << " Level-1 control and plant tick: " << fixed(tick_hz(), 0) << " Hz.\n\n"
       << t.md() << "\n"
       << md_after << (md_after.empty() ? "" : "\n\n") << "Runs (each a whole fleet of processes):\n\n"
       << "| variant | status | simulated s | wall s | folder |\n|---|---|---|---|---|\n";
    for (const auto& r : runs_)
      md << "| " << r.label << " | " << r.status() << (r.reused ? " (reused)" : "")
         << (r.retried ? " (second attempt; the first: " + r.summary.value("first_attempt", std::string()) + ")" : "")
         << " | "
         << fixed(r.summary.value("sim_time_s", 0.0), 1) << " | " << fixed(r.summary.value("wall_time_s", 0.0), 0)
         << " | runs/" << r.id << " |\n";
    std::ofstream(o_.out + "/" + o_.name + ".md") << md.str();
    json s = {{"experiment", o_.name}, {"quick", o_.quick}, {"command", command()}, {"tick_hz", tick_hz()},
              {"rows", t.rows}};
    for (auto& [k, v] : extra.items()) s[k] = v;
    json runs = json::array();
    for (const auto& r : runs_)
      runs.push_back({{"id", r.id},
                      {"label", r.label},
                      {"folder", "runs/" + r.id},
                      {"status", r.status()},
                      {"reused", r.reused},
                      {"retried", r.retried},
                      {"sim_time_s", r.summary.value("sim_time_s", 0.0)},
                      {"wall_time_s", r.summary.value("wall_time_s", 0.0)},
                      {"real_time_factor", r.summary.value("real_time_factor", 0.0)}});
    s["runs"] = runs;
    std::ofstream(o_.out + "/summary.json") << s.dump(2) << "\n";
  }

  /// Writes STEM.gp next to the PNG and runs gnuplot in the output folder.
  bool plot(const std::string& stem, const std::string& body) {
    const std::string gp = o_.out + "/" + stem + ".gp";
    std::ofstream(gp) << "# made by `" << command() << "`; run in this folder: gnuplot " << stem << ".gp\n"
                      << "set terminal pngcairo size 900,600 font ',11' noenhanced\n"
                      << "set output '" << stem << ".png'\n"
                      << "set datafile separator ','\n"
                      << "set datafile columnheaders\n"
                      << "set grid\nset key outside right top\n"
                      << body;
    const std::string cmd = "cd '" + o_.out + "' && gnuplot '" + stem + ".gp' > '" + stem + ".gnuplot.log' 2>&1";
    const int rc = std::system(cmd.c_str());
    if (rc != 0) {
      std::fprintf(stderr, "maptr: gnuplot failed for %s/%s.gp (see %s.gnuplot.log); the CSV and markdown are written\n",
                   o_.out.c_str(), stem.c_str(), stem.c_str());
      return false;
    }
    std::error_code ec;
    fs::remove(o_.out + "/" + stem + ".gnuplot.log", ec);
    plots_.push_back(stem + ".png");
    return true;
  }
  const std::vector<std::string>& plots() const { return plots_; }

  std::string command() const {
    return "maptr experiment " + o_.name + (o_.quick ? " --quick" : "") +
           (o_.tick_hz > 0 ? " --tick-hz " + fixed(o_.tick_hz, 0) : "") + " --out " + o_.out;
  }

  int exit_code() const { return any_aborted_ ? 1 : 0; }

 private:
  const ExperimentOptions& o_;
  int total_ = 0, done_ = 0;
  bool interrupted_ = false, any_aborted_ = false;
  std::vector<Run> runs_;
  std::vector<std::string> plots_;
};

/// "plot for" over series/<id>.csv files with titles.
std::string series_plot(const std::vector<std::pair<std::string, std::string>>& files_titles, const std::string& ycol,
                        const std::string& style = "lines lw 2") {
  std::string p = "plot ";
  for (std::size_t i = 0; i < files_titles.size(); ++i)
    p += (i ? ", \\\n     " : "") + std::string("'series/") + files_titles[i].first + ".csv' using \"t_s\":\"" + ycol +
         "\" with " + style + " title '" + files_titles[i].second + "'";
  return p + "\n";
}

double bin_for(double duration) { return duration <= 120 ? 0.5 : duration <= 900 ? 2.0 : duration <= 3600 ? 10.0 : 60.0; }
int trace_every_for(double duration) { return duration <= 120 ? 10 : 100; }

// ---------------------------------------------------------------------------------------------
// 1. table-pow: the paper's Table, NO vs EC at six gross masses.

int exp_table_pow(Experiment& e) {
  const bool q = e.quick();
  const std::vector<double> masses = q ? std::vector<double>{13.2, 38.2}
                                       : std::vector<double>{13.2, 18.2, 23.2, 28.2, 33.2, 38.2};
  const double speed = q ? 10.0 : 20.0, duration = q ? 60.0 : 1800.0;
  e.set_total(static_cast<int>(masses.size()) * 2);
  Table t;
  t.cols = {{"gross_kg", "gross kg", 1},
            {"E_NO_kJ", "E_NO kJ", 2},
            {"E_NO_paper_kJ", "E_NO paper", 2},
            {"E_EC_kJ", "E_EC kJ", 2},
            {"E_EC_paper_kJ", "E_EC paper", 2},
            {"saving_pct", "saving %", 2},
            {"saving_paper_pct", "saving paper", 2},
            {"active_EC_end", "active EC (end, L+R)", 0},
            {"active_EC_mean", "active EC (mean, 2nd half)", 1},
            {"active_paper", "active paper", 0},
            {"mileage_NO", "mileage NO m/J", 4},
            {"mileage_NO_paper", "NO paper", 4},
            {"mileage_EC", "mileage EC m/J", 4},
            {"mileage_EC_paper", "EC paper", 4},
            {"eff_NO", "eff NO", 3},
            {"eff_EC", "eff EC", 3},
            {"V_over_VB_EC", "V/V_B EC", 3},
            {"v_end_NO_mps", "v end NO m/s", 2},
            {"v_end_EC_mps", "v end EC m/s", 2},
            {"distance_NO_m", "distance NO m", 0, false},
            {"distance_EC_m", "distance EC m", 0, false},
            {"status_NO", "status NO", -1},
            {"status_EC", "status EC", -1}};
  std::vector<std::string> not_held;
  for (double m : masses) {
    Run runs[2];
    for (int k = 0; k < 2; ++k) {
      config::Scenario s = e.base();
      s.robot.agents = 16;
      s.robot.gross_mass_kg = m;
      s.mode = k == 0 ? "all" : "ec";
      Experiment::straight(s, speed, duration);
      s.trace_every = trace_every_for(duration);
      runs[k] = e.run(kg_label(m) + "kg-" + (k == 0 ? "no" : "ec"), kg_label(m) + " kg " + (k == 0 ? "NO" : "EC"), s);
    }
    const Run &no = runs[0], &ec = runs[1];
    const PaperRow* p = paper_row(m);
    json row = {{"gross_kg", m},
                {"E_NO_kJ", num(no.energy_kJ())},
                {"E_EC_kJ", num(ec.energy_kJ())},
                {"saving_pct", num(100.0 * (no.energy_kJ() - ec.energy_kJ()) / no.energy_kJ())},
                {"active_EC_end", ec.active_end() >= 0 ? json(ec.active_end()) : json(nullptr)},
                {"active_EC_mean", num(ec.active_cruise)},
                {"mileage_NO", num(no.mileage())},
                {"mileage_EC", num(ec.mileage())},
                {"eff_NO", num(no.eff_cruise)},
                {"eff_EC", num(ec.eff_cruise)},
                {"V_over_VB_EC", num(ec.v_over_vb)},
                {"v_end_NO_mps", num(no.v_end_mps)},
                {"v_end_EC_mps", num(ec.v_end_mps)},
                {"distance_NO_m", num(get_num(no.summary, "distance_m"))},
                {"distance_EC_m", num(get_num(ec.summary, "distance_m"))},
                {"speed_held_NO", no.speed_held()},
                {"speed_held_EC", ec.speed_held()},
                {"status_NO", no.status()},
                {"status_EC", ec.status()}};
    if (p) {
      row["E_NO_paper_kJ"] = p->e_no_kJ;
      row["E_EC_paper_kJ"] = p->e_ec_kJ;
      row["saving_paper_pct"] = p->saving_pct;
      row["active_paper"] = p->active;
      row["mileage_NO_paper"] = p->mileage_no;
      row["mileage_EC_paper"] = p->mileage_ec;
    }
    if (!no.aborted() && !no.speed_held()) not_held.push_back(kg_label(m) + " kg NO");
    if (!ec.aborted() && !ec.speed_held()) not_held.push_back(kg_label(m) + " kg EC");
    t.rows.push_back(row);
  }
  std::ostringstream intro;
  intro << "16 agents, Type-I motors, straight line at " << speed << " m/s for " << duration
        << " s simulated (step reference from rest), battery from full (V_B(0) = 23.4 V). NO: every agent drives "
           "(the paper's baseline); EC: Levels 2 and 3. Energy is drawn from both batteries over the whole run. "
           "Mileage = distance / energy. eff: mean per-agent efficiency (mean of the two sides) over the second half "
           "of the run; V/V_B: applied voltage over battery voltage of the active agents, second half (1 = the "
           "agents are at the supply limit). v end: mean speed over the last 10% of the run."
        << (q ? " Quick variant: the paper's numbers are for 1800 s at 20 m/s and are shown for reference only." : "");
  std::ostringstream after;
  if (not_held.empty())
    after << "Every run held its reference speed (within 2% at the end).";
  else {
    after << "**Speed not held** (mean speed over the last 10% of the run more than 2% below the reference): ";
    for (std::size_t i = 0; i < not_held.size(); ++i) after << (i ? ", " : "") << not_held[i];
    after << ". These rows compare runs that did not cover the paper's distance; their mileage is the fair "
             "comparison.";
  }
  e.write(t, intro.str(), after.str(),
          {{"conditions", {{"agents", 16}, {"speed_mps", speed}, {"duration_s", duration}, {"motor", "I"}}}});
  e.plot("table-pow-energy",
         "set title 'Energy over the run, NO vs EC (16 agents, " + fixed(speed, 0) + " m/s, " + fixed(duration, 0) +
             " s)'\nset xlabel 'gross mass (kg)'\nset ylabel 'energy drawn (kJ)'\n"
             "plot 'table-pow.csv' using \"gross_kg\":\"E_NO_kJ\" with linespoints lw 2 pt 7 title 'NO (this model)', \\\n"
             "     '' using \"gross_kg\":\"E_EC_kJ\" with linespoints lw 2 pt 5 title 'EC (this model)', \\\n"
             "     '' using \"gross_kg\":\"E_NO_paper_kJ\" with points pt 6 ps 2 title 'NO (paper)', \\\n"
             "     '' using \"gross_kg\":\"E_EC_paper_kJ\" with points pt 4 ps 2 title 'EC (paper)'\n");
  e.plot("table-pow-saving",
         "set title 'Energy saving of EC over NO'\nset xlabel 'gross mass (kg)'\nset ylabel 'saving (%)'\n"
         "plot 'table-pow.csv' using \"gross_kg\":\"saving_pct\" with linespoints lw 2 pt 7 title 'this model', \\\n"
         "     '' using \"gross_kg\":\"saving_paper_pct\" with points pt 6 ps 2 title 'paper'\n");
  e.plot("table-pow-active",
         "set title 'Active agents chosen by EC (L + R)'\nset xlabel 'gross mass (kg)'\nset ylabel 'active agents'\n"
         "set yrange [0:17]\n"
         "plot 'table-pow.csv' using \"gross_kg\":\"active_EC_end\" with linespoints lw 2 pt 7 title 'this model (end)', \\\n"
         "     '' using \"gross_kg\":\"active_EC_mean\" with linespoints lw 1 dt 2 pt 1 title 'this model (mean, 2nd half)', \\\n"
         "     '' using \"gross_kg\":\"active_paper\" with points pt 6 ps 2 title 'paper'\n");
  return e.exit_code();
}

// ---------------------------------------------------------------------------------------------
// 2./3. weights and voltages: EC time series (efficiency, active agents).

struct SeriesVariant {
  std::string id, label;
  config::Scenario s;
  double x = 0;  ///< the swept value (gross kg or supply V)
};

int ec_time_series(Experiment& e, const std::vector<SeriesVariant>& vars, const std::string& xkey,
                   const std::string& xhead, const std::string& intro, const std::string& what) {
  e.set_total(static_cast<int>(vars.size()));
  Table t;
  t.cols = {{xkey, xhead, 1},
            {"energy_kJ", "energy kJ", 2},
            {"mileage", "mileage m/J", 4},
            {"eff_cruise", "eff (mean, 2nd half)", 3},
            {"active_mean", "active (mean, 2nd half)", 2},
            {"active_end", "active (end, L+R)", 0},
            {"V_applied_V", "applied V (2nd half)", 2},
            {"V_over_VB", "V/V_B", 3},
            {"v_end_mps", "v end m/s", 2},
            {"l2_decisions", "Level-2 decisions", 0},
            {"l2_solve_ms", "Ipopt solve ms (median)", 1},
            {"oracle_differs", "Ipopt != oracle", 0},
            {"oracle_checked", "oracle checks", 0},
            {"status", "status", -1}};
  std::vector<std::pair<std::string, std::string>> files;
  fs::create_directories(e.dir() + "/series");
  for (const auto& v : vars) {
    config::Scenario sv = v.s;
    sv.control.oracle = true;  // every Level-2 decision is checked against the exhaustive search
    const Run r = e.run(v.id, v.label, sv);
    const json l2 = r.level2();
    if (!r.aborted()) {
      write_series(r, e.dir() + "/series/" + v.id + ".csv", bin_for(v.s.duration_s));
      files.push_back({v.id, v.label});
    }
    t.rows.push_back({{xkey, v.x},
                      {"energy_kJ", num(r.energy_kJ())},
                      {"mileage", num(r.mileage())},
                      {"eff_cruise", num(r.eff_cruise)},
                      {"active_mean", num(r.active_cruise)},
                      {"active_end", r.active_end() >= 0 ? json(r.active_end()) : json(nullptr)},
                      {"V_applied_V", num(r.v_applied)},
                      {"V_over_VB", num(r.v_over_vb)},
                      {"v_end_mps", num(r.v_end_mps)},
                      {"l2_decisions", l2["decisions"]},
                      {"l2_solve_ms", l2.contains("solve_ms_median") ? l2["solve_ms_median"] : json(nullptr)},
                      {"oracle_differs", l2["differs"]},
                      {"oracle_checked", l2["checked"]},
                      {"speed_held", r.speed_held()},
                      {"status", r.status()}});
  }
  e.write(t,
          intro + " Level 2 runs at 1 Hz per side; every decision was also solved by the exhaustive search "
                  "(the oracle), and 'Ipopt != oracle' counts the decisions where Ipopt's integer differed.",
          "");
  if (!files.empty()) {
    e.plot(e.opt().name + "-efficiency",
           "set title 'Per-agent efficiency, EC, " + what + "'\nset xlabel 'time (s)'\n"
           "set ylabel 'efficiency of an active agent (mean of L and R)'\nset yrange [0:1]\n" +
               series_plot(files, "eff_agent"));
    e.plot(e.opt().name + "-active",
           "set title 'Active agents (L + R), EC, " + what + "'\nset xlabel 'time (s)'\nset ylabel 'active agents'\n"
           "set yrange [0:*]\n" + series_plot(files, "n_active"));
  }
  return e.exit_code();
}

int exp_weights(Experiment& e) {
  const bool q = e.quick();
  const std::vector<double> masses = q ? std::vector<double>{13.2, 33.2} : std::vector<double>{13.2, 23.2, 33.2};
  const double speed = 10.0, duration = q ? 30.0 : 600.0;
  std::vector<SeriesVariant> vars;
  for (double m : masses) {
    config::Scenario s = e.base();
    s.robot.agents = 16;
    s.robot.gross_mass_kg = m;
    s.mode = "ec";
    Experiment::straight(s, speed, duration);
    s.trace_every = trace_every_for(duration);
    vars.push_back({kg_label(m) + "kg", kg_label(m) + " kg", s, m});
  }
  std::ostringstream intro;
  intro << "EC, 16 agents, Type-I motors, straight line at " << speed << " m/s for " << duration
        << " s simulated, battery from full. The plots show the mean efficiency of an active agent and the number of "
           "active agents against time for each gross mass (paper: Fig. 'Level-2: different payload weights').";
  return ec_time_series(e, vars, "gross_kg", "gross kg", intro.str(), "gross masses at " + fixed(speed, 0) + " m/s");
}

int exp_voltages(Experiment& e) {
  const bool q = e.quick();
  const std::vector<double> volts = q ? std::vector<double>{12.0, 23.4} : std::vector<double>{12.0, 16.0, 20.0, 23.4};
  const double speed = 8.0, duration = q ? 30.0 : 600.0, gross = 14.4;
  std::vector<SeriesVariant> vars;
  for (double y : volts) {
    config::Scenario s = e.base();
    s.robot.agents = 16;
    s.robot.gross_mass_kg = gross;
    s.robot.battery.y = y;
    s.mode = "ec";
    Experiment::straight(s, speed, duration);
    s.trace_every = trace_every_for(duration);
    vars.push_back({kg_label(y) + "V", kg_label(y) + " V", s, y});
  }
  std::ostringstream intro;
  intro << "EC, 16 agents, Type-I motors, 10 kg payload: gross mass " << gross
        << " kg (payload + 4.4 kg of robot: 16 motors of 0.21 kg, 16 wheels of 0.05 kg and a light chassis), straight "
           "line at "
        << speed << " m/s for " << duration
        << " s simulated. The supply is set through the battery fit's y coefficient, V_B(0) = y + h ≈ y, with the "
           "discharge curve otherwise unchanged (paper: Fig. 'Level-2: different input voltages').";
  return ec_time_series(e, vars, "supply_V", "supply V", intro.str(),
                        fixed(gross, 1) + " kg at " + fixed(speed, 0) + " m/s, several supply voltages");
}

// ---------------------------------------------------------------------------------------------
// 4. agents: energy advantage vs N.

int exp_agents(Experiment& e) {
  const bool q = e.quick();
  const std::vector<int> ns = q ? std::vector<int>{8, 16} : std::vector<int>{8, 16, 32, 64, 128};
  struct Series {
    std::string key, label;
    double per_agent_kg;  ///< > 0: gross = per_agent_kg * N
    double fixed_kg;      ///< otherwise this gross mass
  };
  std::vector<Series> series;
  if (q)
    series = {{"1.5kg-per-agent", "1.5 kg/agent", 1.5, 0}};
  else
    series = {{"0.8kg-per-agent", "0.8 kg/agent", 0.8, 0},
              {"1.5kg-per-agent", "1.5 kg/agent", 1.5, 0},
              {"2.2kg-per-agent", "2.2 kg/agent", 2.2, 0},
              {"13.2kg-fixed", "13.2 kg for every N", 0, 13.2}};
  const double speed = 10.0, duration = q ? 30.0 : 120.0;
  e.set_total(static_cast<int>(ns.size() * series.size() * 2));
  Table t;
  t.cols = {{"series", "payload", -1},
            {"agents", "N", 0},
            {"gross_kg", "gross kg", 1},
            {"E_NO_kJ", "E_NO kJ", 3},
            {"E_EC_kJ", "E_EC kJ", 3},
            {"saving_pct", "saving %", 2},
            {"active_EC_end", "active EC (end)", 0},
            {"active_EC_mean", "active EC (mean, 2nd half)", 1},
            {"eff_NO", "eff NO", 3},
            {"eff_EC", "eff EC", 3},
            {"status_NO", "status NO", -1},
            {"status_EC", "status EC", -1}};
  for (const auto& se : series)
    for (int n : ns) {
      const double gross = se.per_agent_kg > 0 ? se.per_agent_kg * n : se.fixed_kg;
      Run runs[2];
      for (int k = 0; k < 2; ++k) {
        config::Scenario s = e.base();
        s.robot.agents = n;
        s.robot.gross_mass_kg = gross;
        s.mode = k == 0 ? "all" : "ec";
        Experiment::straight(s, speed, duration);
        s.trace_every = trace_every_for(duration);
        runs[k] = e.run(se.key + "-N" + std::to_string(n) + (k == 0 ? "-no" : "-ec"),
                        "N=" + std::to_string(n) + " " + kg_label(gross) + " kg " + (k == 0 ? "NO" : "EC"), s);
      }
      const Run &no = runs[0], &ec = runs[1];
      t.rows.push_back({{"series", se.label},
                        {"agents", n},
                        {"gross_kg", gross},
                        {"E_NO_kJ", num(no.energy_kJ())},
                        {"E_EC_kJ", num(ec.energy_kJ())},
                        {"saving_pct", num(100.0 * (no.energy_kJ() - ec.energy_kJ()) / no.energy_kJ())},
                        {"active_EC_end", ec.active_end() >= 0 ? json(ec.active_end()) : json(nullptr)},
                        {"active_EC_mean", num(ec.active_cruise)},
                        {"eff_NO", num(no.eff_cruise)},
                        {"eff_EC", num(ec.eff_cruise)},
                        {"status_NO", no.status()},
                        {"status_EC", ec.status()}});
    }
  std::ostringstream intro;
  intro << "NO vs EC for N in {";
  for (std::size_t i = 0; i < ns.size(); ++i) intro << (i ? ", " : "") << ns[i];
  intro << "} agents, straight line at " << speed << " m/s for " << duration
        << " s simulated (acceleration from rest included), Type-I motors. Payload series: the gross mass scaled with "
           "N (kg per agent: the same load per motor at every N)"
        << (q ? "." : ", and one fixed gross mass of 13.2 kg for every N (the same robot load spread over more motors).")
        << (q ? " The full run goes up to 128 agents (132 processes per fleet)." : "");
  e.write(t, intro.str(), "");
  std::string p = "plot ";
  for (std::size_t i = 0; i < series.size(); ++i)
    p += (i ? ", \\\n     " : "") + std::string("'agents.csv' using \"agents\":(strcol(\"series\") eq '") +
         series[i].label + "' ? column(\"saving_pct\") : NaN) with linespoints lw 2 pt " + std::to_string(5 + 2 * i) +
         " title '" + series[i].label + "'";
  e.plot("agents-saving", "set title 'Energy advantage of EC over NO vs number of agents (" + fixed(speed, 0) +
                              " m/s, " + fixed(duration, 0) + " s)'\nset xlabel 'agents N'\nset ylabel 'saving (%)'\n"
                              "set logscale x 2\nset xrange [" + fixed(ns.front() * 0.75, 0) + ":" +
                              fixed(ns.back() * 1.25, 0) + "]\nset yrange [0:*]\n" + p + "\n");
  // The paper's form of the figure: saving against the load, one curve per N (a flatter curve
  // keeps the advantage over a wider range of payloads). Rows are series-major, so the rows of
  // the i-th N are every ns.size()-th row from row i.
  std::string pm = "plot ";
  for (std::size_t i = 0; i < ns.size(); ++i)
    pm += (i ? ", \\\n     " : "") + std::string("'agents.csv' every ") + std::to_string(ns.size()) + "::" + std::to_string(i) +
          " using \"gross_kg\":\"saving_pct\" smooth unique with linespoints lw 2 pt " +
          std::to_string(5 + 2 * static_cast<int>(i)) + " title 'N = " + std::to_string(ns[i]) + "'";
  e.plot("agents-saving-vs-mass", "set title 'Energy advantage of EC over NO vs gross mass, per number of agents (" +
                                      fixed(speed, 0) + " m/s, " + fixed(duration, 0) +
                                      " s)'\nset xlabel 'gross mass (kg)'\nset ylabel 'saving (%)'\n"
                                      "set logscale x 2\nset yrange [0:*]\n" + pm + "\n");
  return e.exit_code();
}

// ---------------------------------------------------------------------------------------------
// 5. battery: NO vs EC until the speed can no longer be held.

int exp_battery(Experiment& e) {
  const bool q = e.quick();
  const double gross = 34.4, speed = 15.0;
  // Quick: from 6000 mAh (V_B = 20.45 V), a few hundred seconds before the knee of the
  // discharge curve where 15 m/s can no longer be held (about 18.2 V).
  const double initial = q ? 6000.0 : 0.0, duration = q ? 1500.0 : 30000.0;
  e.set_total(2);
  Table t;
  t.cols = {{"mode", "mode", -1},
            {"lasted_s", "lasted s", 0},
            {"distance_km", "distance km", 2},
            {"energy_kJ", "energy kJ", 1},
            {"mileage", "mileage m/J", 4},
            {"drawn_mAh", "drawn mAh (L)", 0},
            {"battery_V_end", "V_B at end", 2},
            {"eff_mean", "eff (mean, 2nd half)", 3},
            {"active_mean", "active (mean, 2nd half)", 2},
            {"end_reason", "end", -1},
            {"status", "status", -1}};
  std::vector<std::pair<std::string, std::string>> files;
  fs::create_directories(e.dir() + "/series");
  double lasted[2] = {kNaN, kNaN};
  bool ended_by_speed[2] = {false, false};
  for (int k = 0; k < 2; ++k) {
    config::Scenario s = e.base();
    s.robot.agents = 16;
    s.robot.gross_mass_kg = gross;
    s.mode = k == 0 ? "all" : "ec";
    s.initial_discharge_mAh = initial;
    s.stop_below_speed_pct = 5.0;
    Experiment::straight(s, speed, duration);
    s.trace_every = q ? 10 : 100;
    const std::string id = k == 0 ? "no" : "ec";
    const Run r = e.run(id, k == 0 ? "NO" : "EC", s);
    if (!r.aborted()) {
      write_series(r, e.dir() + "/series/" + id + ".csv", q ? 2.0 : 60.0);
      files.push_back({id, k == 0 ? "NO" : "EC"});
      lasted[k] = r.sim_s();
    }
    const std::string reason = r.plant().value("end_reason", std::string());
    ended_by_speed[k] = reason.find("below its reference") != std::string::npos;
    double vb = kNaN;
    if (r.plant().contains("battery_V")) vb = 0.5 * (get_num(r.plant()["battery_V"], "L") + get_num(r.plant()["battery_V"], "R"));
    double drawn = kNaN;
    if (r.plant().contains("battery_discharge_mAh")) drawn = get_num(r.plant()["battery_discharge_mAh"], "L");
    t.rows.push_back({{"mode", k == 0 ? "NO" : "EC"},
                      {"lasted_s", num(lasted[k])},
                      {"distance_km", num(get_num(r.summary, "distance_m") / 1000.0)},
                      {"energy_kJ", num(r.energy_kJ())},
                      {"mileage", num(r.mileage())},
                      {"drawn_mAh", num(drawn)},
                      {"battery_V_end", num(vb)},
                      {"eff_mean", num(r.eff_cruise)},
                      {"active_mean", num(r.active_cruise)},
                      {"ended_by_speed_loss", ended_by_speed[k]},
                      {"end_reason", reason},
                      {"status", r.status()}});
  }
  const double diff = lasted[1] - lasted[0];
  std::ostringstream intro;
  intro << "16 agents, Type-I motors, 30 kg payload: gross mass " << gross
        << " kg (payload + 4.4 kg of robot), straight line at " << speed
        << " m/s, battery 6395 mAh per side starting at " << initial
        << " mAh discharged. Each run ends when the speed has stayed more than 5% below the reference for 5 s "
           "(stop_below_speed_pct: 5) or at "
        << duration << " s simulated. 'lasted' is the simulated time at the end (it includes those 5 s).";
  std::ostringstream after;
  if (std::isfinite(diff))
    after << "**EC lasted " << fixed(diff, 0) << " s " << (diff >= 0 ? "longer" : "shorter") << " than NO** ("
          << fixed(lasted[1], 0) << " s vs " << fixed(lasted[0], 0) << " s"
          << (ended_by_speed[0] && ended_by_speed[1] ? "" : "; at least one run did not end by losing its speed")
          << "). Paper: about 800 s longer (6395 mAh, 30 kg payload, speed not stated).";
  e.write(t, intro.str(), after.str(), {{"ec_minus_no_s", num(diff)}});
  if (!files.empty()) {
    e.plot("battery-voltage", "set title 'Battery voltage, NO vs EC (" + fixed(gross, 1) + " kg, " + fixed(speed, 0) +
                                  " m/s)'\nset xlabel 'time (s)'\nset ylabel 'battery voltage (V, mean of L and R)'\n" +
                                  series_plot(files, "battery_V"));
    e.plot("battery-speed", "set title 'Speed, NO vs EC (" + fixed(gross, 1) + " kg, " + fixed(speed, 0) +
                                " m/s reference)'\nset xlabel 'time (s)'\nset ylabel 'speed (m/s)'\nset yrange [0:*]\n" +
                                series_plot(files, "v_x_mps"));
    e.plot("battery-active", "set title 'Active agents (L + R), NO vs EC'\nset xlabel 'time (s)'\n"
                             "set ylabel 'active agents'\nset yrange [0:17]\n" +
                                 series_plot(files, "n_active"));
    e.plot("battery-efficiency", "set title 'Per-agent efficiency, NO vs EC'\nset xlabel 'time (s)'\n"
                                 "set ylabel 'efficiency of an active agent'\nset yrange [0:1]\n" +
                                     series_plot(files, "eff_agent"));
  }
  return e.exit_code();
}

// ---------------------------------------------------------------------------------------------
// 6. wear: Level-3 task allocation, transitions and idle time.

struct Interval {
  double t0, t1;
};

/// Per agent (L0.., then R0..), the intervals during which it drove, from assignments.csv.
std::vector<std::vector<Interval>> driving_intervals(const std::string& path, int per_side, double t_end) {
  std::vector<std::vector<Interval>> out(2 * per_side);
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::pair<double, std::string>> changes[2];
  while (std::getline(in, line)) {
    const auto f = split(line);
    if (f.size() < 3 || f[1].empty()) continue;
    changes[f[1][0] == 'L' ? 0 : 1].push_back({std::strtod(f[0].c_str(), nullptr), f[2]});
  }
  for (int s = 0; s < 2; ++s)
    for (std::size_t i = 0; i < changes[s].size(); ++i) {
      const double t0 = changes[s][i].first, t1 = i + 1 < changes[s].size() ? changes[s][i + 1].first : t_end;
      const std::string& m = changes[s][i].second;
      for (int j = 0; j < per_side && j < static_cast<int>(m.size()); ++j)
        if (m[j] == '1' && t1 > t0) out[s * per_side + j].push_back({t0, t1});
    }
  return out;
}

int exp_wear(Experiment& e) {
  const bool q = e.quick();
  const std::vector<int> ns = q ? std::vector<int>{8, 16} : std::vector<int>{8, 16, 32};
  const double t_on = q ? 5.0 : 100.0, duration = q ? 30.0 : 1800.0, speed = 10.0, gross = 13.2;
  e.set_total(static_cast<int>(ns.size()));
  Table t;
  t.cols = {{"agents", "N", 0},
            {"active_mean", "active (mean, 2nd half)", 2},
            {"active_end", "active (end, L+R)", 0},
            {"idle_mean_steps", "idle per agent (T_ON steps)", 2},
            {"idle_min_steps", "idle min", 2},
            {"idle_max_steps", "idle max", 2},
            {"idle_mean_s", "idle per agent s", 1},
            {"wear_min_m", "wear min m", 1},
            {"wear_max_m", "wear max m", 1},
            {"wear_spread_L_m", "spread L m", 1},
            {"wear_spread_R_m", "spread R m", 1},
            {"spread_bound_m", "bound m", 1},
            {"drove_in_cruise_L", "agents that drove in cruise L", 0},
            {"drove_in_cruise_R", "R", 0},
            {"status", "status", -1}};
  for (int n : ns) {
    config::Scenario s = e.base();
    s.robot.agents = n;
    s.robot.gross_mass_kg = gross;
    s.mode = "ec";
    s.control.t_on_s = t_on;
    Experiment::straight(s, speed, duration);
    s.trace_every = trace_every_for(duration);
    const std::string id = "N" + std::to_string(n);
    const Run r = e.run(id, "N=" + std::to_string(n), s);
    json row = {{"agents", n}, {"status", r.status()}, {"t_on_s", t_on}};
    if (!r.aborted()) {
      const int per_side = n / 2;
      const double T = r.sim_s();
      // Idle time per agent from the plant's driving time.
      std::vector<double> idle;
      for (const char* side : {"L", "R"})
        if (r.plant().contains("agent_active_s"))
          for (const auto& a : r.plant()["agent_active_s"][side]) idle.push_back(T - a.get<double>());
      if (!idle.empty()) {
        double sum = 0;
        for (double v : idle) sum += v;
        row["idle_mean_s"] = sum / idle.size();
        row["idle_mean_steps"] = sum / idle.size() / t_on;
        row["idle_min_steps"] = *std::min_element(idle.begin(), idle.end()) / t_on;
        row["idle_max_steps"] = *std::max_element(idle.begin(), idle.end()) / t_on;
      }
      // Wear ledgers of the group controllers.
      double wmin = 1e300, wmax = -1e300;
      for (int side = 0; side < 2; ++side) {
        const json led = read_json_file(r.dir + "/ledger-" + std::string(side ? "R" : "L") + ".json");
        if (!led.is_object() || !led.contains("wear_m")) continue;
        const auto w = led["wear_m"].get<std::vector<double>>();
        const auto [lo, hi] = std::minmax_element(w.begin(), w.end());
        row[side ? "wear_spread_R_m" : "wear_spread_L_m"] = *hi - *lo;
        row[side ? "wear_R_m" : "wear_L_m"] = w;
        wmin = std::min(wmin, *lo);
        wmax = std::max(wmax, *hi);
      }
      if (wmax >= wmin) {
        row["wear_min_m"] = wmin;
        row["wear_max_m"] = wmax;
      }
      // Greedy least-worn allocation at most T_ON apart: no agent gets more than one period's
      // driving ahead of the least worn (see docs/results/RESULTS.md).
      row["spread_bound_m"] = speed * t_on;
      row["active_mean"] = num(r.active_cruise);
      row["active_end"] = r.active_end();
      row["active_end_L"] = r.active_side("L");
      row["active_end_R"] = r.active_side("R");
      // Transitions: driving fraction of every agent in every T_ON step.
      const auto iv = driving_intervals(r.dir + "/assignments.csv", per_side, T);
      const int steps = static_cast<int>(std::ceil(T / t_on - 1e-9));
      std::ofstream tr(e.dir() + "/transitions-N" + std::to_string(n) + ".csv");
      tr << "step,t_start_s,agent,name,driving_fraction\n";
      for (int a = 0; a < n; ++a)  // gnuplot's "with image" wants x (the step) to vary fastest
        for (int k = 0; k < steps; ++k) {
          const double s0 = k * t_on, s1 = std::min(T, (k + 1) * t_on);
          double on = 0;
          for (const auto& x : iv[a]) on += std::max(0.0, std::min(x.t1, s1) - std::max(x.t0, s0));
          tr << k << "," << fixed(s0, 1) << "," << a << "," << config::agent_name(a / per_side, a % per_side) << ","
             << fixed(s1 > s0 ? on / (s1 - s0) : 0.0, 4) << "\n";
        }
      // Agents that drove once the robot cruised (after the speed first came within 2%, plus the
      // first Level-2 decision): more than N_a of them means Level 3 rotated the work.
      const double cruise_t = (std::isfinite(r.t_reach_s) ? r.t_reach_s : 0.0) + 2.0;
      for (int side = 0; side < 2; ++side) {
        int drove = 0;
        for (int j = 0; j < per_side; ++j)
          for (const auto& x : iv[side * per_side + j])
            if (x.t1 > cruise_t) {
              ++drove;
              break;
            }
        row[side ? "drove_in_cruise_R" : "drove_in_cruise_L"] = drove;
      }
      std::ostringstream yt;
      for (int a = 0; a < n; ++a)
        yt << (a ? ", " : "") << "\"" << config::agent_name(a / per_side, a % per_side) << "\" " << a;
      e.plot("wear-transitions-N" + std::to_string(n),
             "set title 'Which agents drive, EC, N = " + std::to_string(n) + " (1 step = T_ON = " + fixed(t_on, 0) +
                 " s)'\nset xlabel 'step (T_ON = " + fixed(t_on, 0) + " s)'\nset ylabel 'agent'\nset ytics (" +
                 yt.str() +
                 ") font ',8'\nset cblabel 'fraction of the step spent driving'\nset cbrange [0:1]\n"
                 "set palette defined (0 'white', 1 'dark-blue')\nset xrange [-0.5:" + fixed(steps - 0.5, 1) +
                 "]\nset yrange [-0.5:" + fixed(n - 0.5, 1) + "]\nunset grid\nset key off\n"
                 // Columns by number: gnuplot 5.4 draws nothing "with image" when they are named.
                 "plot 'transitions-N" + std::to_string(n) + ".csv' using 1:3:5 with image\n");
    }
    t.rows.push_back(row);
  }
  std::ostringstream intro;
  intro << "EC, gross mass " << gross << " kg, Type-I motors, straight line at " << speed << " m/s for " << duration
        << " s simulated, T_ON = " << t_on
        << " s. Idle time per agent: run time minus the time the agent drove (plant's ledger), in T_ON steps. Wear: "
           "distance each agent drove while active (the group controllers' ledgers); spread = max - min within a "
           "side; bound = one T_ON of driving at the reference speed. The transition plots (wear-transitions-N*.png) "
           "show, per T_ON step, the fraction of the step each agent drove.";
  e.write(t, intro.str(), "");
  e.plot("wear-idle", "set title 'Average idle time per agent vs number of agents (EC, " + kg_label(gross) +
                          " kg, " + fixed(duration, 0) + " s)'\nset xlabel 'agents N'\n"
                          "set ylabel 'idle time per agent (steps of T_ON = " + fixed(t_on, 0) + " s)'\n"
                          "set logscale x 2\nset xrange [6:40]\nset yrange [0:*]\n"
                          "plot 'wear.csv' using \"agents\":\"idle_mean_steps\":\"idle_min_steps\":\"idle_max_steps\" "
                          "with yerrorlines lw 2 pt 7 title 'mean (bars: min and max agent)'\n");
  return e.exit_code();
}

// ---------------------------------------------------------------------------------------------
// 7. failures: kill 0, 1, 2, ... agents per side, the active ones first.

int exp_failures(Experiment& e) {
  const bool q = e.quick();
  const double gross = 23.2, speed = 10.0, duration = q ? 30.0 : 60.0, kill_at = q ? 15.0 : 20.0;
  const int n = 16, per_side = n / 2;
  // Kill order per side: the agents driving at the kill time in the fault-free run (which the
  // faulty runs repeat exactly up to the kill: the lock-step is deterministic), then the others.
  std::vector<int> order[2];
  for (int side = 0; side < 2; ++side)
    for (int j = 0; j < per_side; ++j) order[side].push_back(j);
  auto scenario = [&](int k) {
    config::Scenario s = e.base();
    s.robot.agents = n;
    s.robot.gross_mass_kg = gross;
    s.mode = "ec";
    Experiment::straight(s, speed, duration);
    s.trace_every = 10;
    for (int side = 0; side < 2; ++side)
      for (int j = 0; j < k; ++j)
        s.faults.push_back(config::FaultSpec{config::agent_name(side, order[side][j]), "kill", kill_at});
    return s;
  };
  Table t;
  t.cols = {{"killed_per_side", "killed per side", 0},
            {"tolerance", "tolerance N_i - N_a,i", 0},
            {"killed", "killed", -1},
            {"detected", "detected", 0},
            {"detect_wall_ms_max", "detection wall ms (max)", 1},
            {"recovered", "recovered", 0},
            {"recovered_s_max", "recovered at s (latest)", 2},
            {"max_speed_error_pct", "max speed error % after kill", 2},
            {"final_speed_mps", "final speed m/s", 3},
            {"active_end_L", "active L (end)", 0},
            {"active_end_R", "active R (end)", 0},
            {"energy_kJ", "energy kJ", 3},
            {"eff_cruise", "eff (2nd half)", 3},
            {"status", "status", -1}};
  std::vector<int> ks = {0};
  int tolerance = -1;
  if (q) ks.push_back(1);
  e.set_total(q ? 2 : 1);
  for (std::size_t i = 0; i < ks.size(); ++i) {
    const int k = ks[i];
    const Run r = e.run("kill-" + std::to_string(k), std::to_string(k) + " killed per side", scenario(k));
    if (k == 0 && !r.aborted()) {
      const auto iv = driving_intervals(r.dir + "/assignments.csv", per_side, r.sim_s());
      for (int side = 0; side < 2; ++side) {
        std::vector<int> on, off;
        for (int j = 0; j < per_side; ++j) {
          bool driving = false;
          for (const auto& x : iv[side * per_side + j])
            if (x.t0 <= kill_at && kill_at < x.t1) driving = true;
          (driving ? on : off).push_back(j);
        }
        order[side] = on;
        order[side].insert(order[side].end(), off.begin(), off.end());
      }
    }
    if (k == 0 && !q) {
      // Tolerance from the fault-free run: N_i - N_a,i (the smaller of the two sides).
      const int na = std::max(r.active_side("L"), r.active_side("R"));
      tolerance = na >= 0 ? per_side - na : per_side - 1;
      const int kmax = std::min(per_side, tolerance + 2);
      for (int kk = 1; kk <= kmax; ++kk) ks.push_back(kk);
      e.set_total(1 + kmax);
    } else if (k == 0) {
      const int na = std::max(r.active_side("L"), r.active_side("R"));
      tolerance = na >= 0 ? per_side - na : -1;
    }
    json row = {{"killed_per_side", k}, {"tolerance", tolerance >= 0 ? json(tolerance) : json(nullptr)},
                {"status", r.status()}};
    std::string killed;
    for (int side = 0; side < 2; ++side)
      for (int j = 0; j < k; ++j) killed += (killed.empty() ? "" : " ") + config::agent_name(side, order[side][j]);
    row["killed"] = killed;
    if (!r.aborted()) {
      int detected = 0, recovered = 0;
      double wall_max = kNaN, rec_max = kNaN, err_max = 0;
      const json fails = r.summary.value("failures", json::array());
      for (const auto& f : fails) {
        if (!f["detected_s"].is_null()) ++detected;
        if (!f["recovered_s"].is_null()) {
          ++recovered;
          rec_max = std::isfinite(rec_max) ? std::max(rec_max, f["recovered_s"].get<double>()) : f["recovered_s"].get<double>();
        }
        if (f.contains("detect_wall_ms") && f["detect_wall_ms"].is_number())
          wall_max = std::isfinite(wall_max) ? std::max(wall_max, f["detect_wall_ms"].get<double>())
                                             : f["detect_wall_ms"].get<double>();
        err_max = std::max(err_max, f.value("max_speed_error_pct", 0.0));
      }
      row["failures"] = fails;
      row["detected"] = detected;
      row["recovered"] = recovered;
      row["detect_wall_ms_max"] = num(wall_max);
      row["recovered_s_max"] = num(rec_max);
      (void)err_max;  // the launcher's per-fault value; the table uses one window for every k
      row["max_speed_error_pct"] = num(max_speed_error_after(r, kill_at));
      row["final_speed_mps"] = num(get_num(r.plant(), "final_speed_mps"));
      row["active_end_L"] = r.active_side("L");
      row["active_end_R"] = r.active_side("R");
      row["energy_kJ"] = num(r.energy_kJ());
      row["eff_cruise"] = num(r.eff_cruise);
      if (r.plant().contains("live_agents")) row["live_end"] = r.plant()["live_agents"];
    }
    t.rows.push_back(row);
  }
  std::ostringstream intro;
  intro << "EC, 16 agents, gross mass " << gross << " kg, straight line at " << speed << " m/s for " << duration
        << " s simulated. At t = " << kill_at
        << " s the launcher SIGKILLs k agents per side: first those driving at that moment in the fault-free run "
           "(the faulty runs repeat it exactly up to the kill), then idle ones by index (column 'killed'). The tolerance N_i - N_a,i is read from the fault-free run (k = 0); the "
           "experiment goes up to two kills beyond it (at most every agent of a side). 'max speed error' is the "
           "largest deviation from the reference between the kill time and the end of the run (the same window for k = 0, "
           "where it shows what Level 2 alone does to the speed); 'recovered' counts the kills after which the speed came back within "
           "2% of the reference.";
  e.write(t, intro.str(), "", {{"tolerance", tolerance >= 0 ? json(tolerance) : json(nullptr)}});
  e.plot("failures-speed",
         "set title 'Speed tracking vs killed agents per side (EC, 16 agents, " + kg_label(gross) + " kg, " +
             fixed(speed, 0) + " m/s)'\nset xlabel 'agents killed per side at t = " + fixed(kill_at, 0) +
             " s'\nset ylabel 'max speed error after the kill (%)'\nset y2label 'final speed (m/s)'\n"
             "set ytics nomirror\nset y2tics\nset xtics 1\nset yrange [0:*]\nset y2range [0:" + fixed(speed * 1.2, 1) +
             "]\n" + (tolerance >= 0 ? "set arrow from " + std::to_string(tolerance) + ", graph 0 to " +
                                           std::to_string(tolerance) + ", graph 1 nohead dt 2\nset label 'tolerance' at " +
                                           std::to_string(tolerance) + ", graph 0.95 offset 0.5,0\n"
                                     : std::string()) +
             "plot 'failures.csv' using \"killed_per_side\":\"max_speed_error_pct\" with linespoints lw 2 pt 7 axes "
             "x1y1 title 'max speed error', \\\n     '' using \"killed_per_side\":\"final_speed_mps\" with linespoints "
             "lw 2 pt 5 axes x1y2 title 'final speed'\n");
  e.plot("failures-energy",
         "set title 'Energy vs killed agents per side (EC, " + fixed(duration, 0) + " s)'\n"
         "set xlabel 'agents killed per side'\nset ylabel 'energy drawn (kJ)'\nset xtics 1\n"
         "plot 'failures.csv' using \"killed_per_side\":\"energy_kJ\" with linespoints lw 2 pt 7 title 'energy'\n");
  return e.exit_code();
}

}  // namespace

double default_tick_hz(const std::string& name) {
  return name == "failures" ? 100.0 : 20.0;
}

std::vector<std::string> experiment_names() {
  return {"table-pow", "weights", "voltages", "agents", "battery", "wear", "failures"};
}

int run_experiment(const ExperimentOptions& o) {
  const auto names = experiment_names();
  if (std::find(names.begin(), names.end(), o.name) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    std::cerr << "maptr: unknown experiment '" << o.name << "'; known: " << list << "\n";
    return 2;
  }
  try {
    fs::create_directories(o.out);
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;  // no SA_RESTART: waitpid returns EINTR and the signal is passed on
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
    Experiment e(o);
    std::fprintf(stderr, "maptr: experiment %s%s, results in %s\n", o.name.c_str(), o.quick ? " (quick)" : "",
                 o.out.c_str());
    int rc = 1;
    if (o.name == "table-pow") rc = exp_table_pow(e);
    if (o.name == "weights") rc = exp_weights(e);
    if (o.name == "voltages") rc = exp_voltages(e);
    if (o.name == "agents") rc = exp_agents(e);
    if (o.name == "battery") rc = exp_battery(e);
    if (o.name == "wear") rc = exp_wear(e);
    if (o.name == "failures") rc = exp_failures(e);
    std::fprintf(stderr, "maptr: experiment %s done: %s/%s.md, %s.csv, summary.json", o.name.c_str(), o.out.c_str(),
                 o.name.c_str(), o.name.c_str());
    for (const auto& p : e.plots()) std::fprintf(stderr, ", %s", p.c_str());
    std::fprintf(stderr, "\n");
    if (e.stopped()) return 1;
    return rc;
  } catch (const std::exception& e) {
    std::cerr << "maptr: experiment " << o.name << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace maptr::deploy
