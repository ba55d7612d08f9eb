#include "deploy/studies/experiments/experiment.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "deploy/fleet/isolated_launch.hpp"
#include "deploy/fleet/run_history.hpp"
#include "deploy/report/gnuplot.hpp"
#include "records/run_files.hpp"

namespace maptr::deploy {

namespace fs = std::filesystem;

namespace {
/// The highest DDS domain id: a retry goes one below it instead of one above.
constexpr int kMaxDomain = 232;

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
}  // namespace

config::Scenario Experiment::base() const {
  config::Scenario s = config::load_scenario(o_.source_dir + "/deploy/scenarios/paper.yaml");
  s.tick_hz = tick_hz();
  return s;
}

void Experiment::straight(config::Scenario& s, double speed, double duration) {
  s.duration_s = duration;
  s.trajectory.segments = {config::Segment{"straight", speed, 0.0, duration}};
  s.trajectory.accel_mps2 = 0.0;
}

bool Experiment::reusable(const Run& r, const config::Scenario& s) const {
  const auto old = records::Summary::read(records::summary_path(r.dir));
  return old.has_status() && old.status().rfind("aborted", 0) != 0 &&
         file_text(r.dir + "/scenario.yaml") == config::to_yaml(s) && fs::exists(records::trace_path(r.dir));
}

void Experiment::launch_with_retry(Run& r, const std::string& head) {
  LaunchOptions l = LaunchOptions::of(r.s, r.dir, o_.bin_dir, o_.domain);
  r.summary = records::Summary(launch_isolated(l));
  // A launcher that died or a fleet that never started (discovery) is not a result of the
  // experiment: try once more, on the next DDS domain (other ports), and say so.
  const std::string first = r.status();
  if (!r.aborted() || first.find("interrupted") != std::string::npos || stop_requested()) return;
  l.domain = o_.domain < kMaxDomain ? o_.domain + 1 : o_.domain - 1;
  std::fprintf(stderr, "maptr: %s %s %s: %s; running it once more on DDS domain %d\n", head.c_str(),
               o_.name.c_str(), r.label.c_str(), first.c_str(), l.domain);
  r.summary = records::Summary(launch_isolated(l));
  r.first_attempt = first;
  r.retried = true;
}

Run Experiment::run(const std::string& id, const std::string& label, config::Scenario s) {
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
    r.summary = records::Summary(
        json{{records::summary_key::kStatus, "aborted: not run (the experiment was interrupted)"}});
    runs_.push_back(r);
    return r;
  }
  if (reusable(r, s)) {
    r.summary = records::Summary::read(records::summary_path(r.dir));
    r.reused = true;
  } else {
    launch_with_retry(r, head);
  }
  derive(r);
  check(r, head);
  const std::string st = r.status();
  if (r.aborted()) any_aborted_ = true;
  if (st.find("interrupted") != std::string::npos || stop_requested()) interrupted_ = true;
  std::fprintf(stderr, "maptr: %s %s %s: %.0f s simulated in %.0f s, status %s%s\n", head, o_.name.c_str(),
               label.c_str(), r.summary.number_or(records::summary_key::kSimTime, 0),
               r.summary.number_or(records::summary_key::kWallTime, 0), st.c_str(),
               r.reused ? " (reused: this scenario already ran in this folder)" : "");
  runs_.push_back(r);
  return r;
}

std::vector<properties::Spec> experiment_properties(const config::Scenario& s) {
  std::vector<properties::Spec> specs = {properties::parse_spec("energy_balance"),
                                         properties::parse_spec("no_false_detection")};
  if (s.control.fault_detection && !s.faults.empty()) specs.push_back(properties::parse_spec("faults_detected:1"));
  return specs;
}

void Experiment::check(Run& r, const std::string& head) {
  if (r.aborted()) return;
  try {
    const auto h = properties::load_history(r.dir);
    for (const auto& spec : experiment_properties(r.s)) r.verdicts.push_back(properties::evaluate(spec, h));
  } catch (const std::exception& e) {  // a finished run without its history is no result either
    r.verdicts = {{"history", false, -1, -1, e.what()}};
  }
  for (const auto& v : r.verdicts) {
    if (v.holds) continue;
    any_broken_ = true;
    std::fprintf(stderr, "maptr: %s %s %s: %s BROKE%s: %s\n", head.c_str(), o_.name.c_str(), r.label.c_str(),
                 v.property.c_str(), v.tick >= 0 ? (" at tick " + std::to_string(v.tick)).c_str() : "",
                 v.reason.c_str());
  }
}

/// A run's verdicts in a cell: how many held, or the first that broke and why.
static std::string verdicts_cell(const Run& r) {
  if (r.verdicts.empty()) return "not checked";
  for (const auto& v : r.verdicts)
    if (!v.holds) return "**" + v.property + " broke**: " + v.reason;
  std::string names;
  for (const auto& v : r.verdicts) names += (names.empty() ? "" : ", ") + v.property;
  return "hold: " + names;
}

std::string Experiment::runs_md() const {
  std::ostringstream md;
  md << "Runs (each a whole fleet of processes):\n\n"
     << "| variant | status | simulated s | wall s | properties (maptr check) | folder |\n|---|---|---|---|---|---|\n";
  for (const auto& r : runs_)
    md << "| " << r.label << " | " << r.status() << (r.reused ? " (reused)" : "")
       << (r.retried ? " (second attempt; the first: " + r.first_attempt + ")" : "") << " | "
       << fixed(r.summary.number_or(records::summary_key::kSimTime, 0), 1) << " | "
       << fixed(r.summary.number_or(records::summary_key::kWallTime, 0), 0) << " | " << verdicts_cell(r)
       << " | runs/" << r.id << " |\n";
  return md.str();
}

json Experiment::runs_json() const {
  json runs = json::array();
  for (const auto& r : runs_) {
    json verdicts = json::array();
    for (const auto& v : r.verdicts)
      verdicts.push_back({{"property", v.property}, {"holds", v.holds}, {"tick", v.tick}, {"reason", v.reason}});
    runs.push_back({{"id", r.id},
                    {"label", r.label},
                    {"folder", "runs/" + r.id},
                    {"status", r.status()},
                    {"reused", r.reused},
                    {"retried", r.retried},
                    {"sim_time_s", r.summary.number_or(records::summary_key::kSimTime, 0)},
                    {"wall_time_s", r.summary.number_or(records::summary_key::kWallTime, 0)},
                    {"real_time_factor", r.summary.number_or(records::summary_key::kRealTimeFactor, 0)},
                    {"properties", verdicts}});
  }
  return runs;
}

void Experiment::write(const records::ResultTable& t, const std::string& md_intro,
                       const std::string& md_after, json extra) {
  fs::create_directories(o_.out);
  t.write_csv(o_.out + "/" + o_.name + ".csv");
  std::ostringstream md;
  md << "# " << o_.name << (o_.quick ? " (quick)" : "") << "\n\n"
     << "Command: `" << command() << "`\n\n"
     << md_intro << " Level-1 control and plant tick: " << fixed(tick_hz(), 0) << " Hz.\n\n"
     << t.md() << "\n"
     << md_after << (md_after.empty() ? "" : "\n\n") << runs_md();
  records::write_text_file(o_.out + "/" + o_.name + ".md", md.str());
  json s = {{"experiment", o_.name},
            {"quick", o_.quick},
            {"command", command()},
            {"tick_hz", tick_hz()},
            {"rows", t.rows}};
  for (auto& [k, v] : extra.items()) s[k] = v;
  s["runs"] = runs_json();
  records::write_json_file(records::summary_path(o_.out), s);
}

bool Experiment::plot(const std::string& stem, const std::string& body, const report::PlotFrame& frame) {
  const std::string comment = "made by `" + command() + "`; run in this folder: gnuplot " + stem + ".gp";
  if (!report::draw_plot(o_.out, stem, comment, frame,
                         "set datafile columnheaders\nset grid\nset key outside right top\n" + body))
    return false;
  plots_.push_back(stem + ".png");
  return true;
}

std::string Experiment::command() const {
  if (!o_.command.empty()) return o_.command;
  return "maptr experiment " + o_.name + (o_.quick ? " --quick" : "") +
         (o_.tick_hz > 0 ? " --tick-hz " + fixed(o_.tick_hz, 0) : "") + " --out " + o_.out;
}

std::string series_plot(const std::vector<std::pair<std::string, std::string>>& files_titles,
                        const std::string& ycol, const std::string& style) {
  std::vector<report::Curve> curves;
  for (const auto& [file, title] : files_titles)
    curves.push_back({"series/" + file + ".csv", "t_s", ycol, style, title, ""});
  return report::plot_command(curves);
}

std::string kg_label(double kg) {
  std::string s = fixed(kg, 2);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

double bin_for(double duration) {
  return duration <= 120 ? 0.5 : duration <= 900 ? 2.0 : duration <= 3600 ? 10.0 : 60.0;
}

int trace_every_for(double duration) { return duration <= 120 ? 10 : 100; }

}  // namespace maptr::deploy
