#include "deploy/fleet/run_properties.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>
#include <stdexcept>

namespace maptr::deploy::properties {

namespace {

std::string num(double v, int decimals = 2) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  return b;
}

double number(const nlohmann::json& j, const char* key, double fallback) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

double tick_hz(const History& h) { return number(h.summary, "tick_hz", 100.0); }
int per_side(const History& h) { return static_cast<int>(number(h.summary, "agents", 0.0)) / 2; }

/// A verdict that broke at simulated time t_s (the tick it falls in).
Verdict broke(const Spec& s, const History& h, double t_s, std::string why) {
  Verdict v{s.text(), false, std::llround(t_s * tick_hz(h)), t_s, std::move(why)};
  return v;
}
Verdict held(const Spec& s, std::string what) { return {s.text(), true, -1, -1, std::move(what)}; }

/// The simulated windows in which a fault's effect is excused: from each fault's act to its
/// recovery (to the end when it never recovered).
std::vector<std::pair<double, double>> recovery_windows(const History& h) {
  std::vector<std::pair<double, double>> w;
  if (!h.summary.contains("failures") || !h.summary["failures"].is_array()) return w;
  for (const auto& f : h.summary["failures"]) {
    const double at = number(f, "at_s", -1);
    if (at < 0) continue;
    const double rec = number(f, "recovered_s", 1e300);
    w.push_back({at, std::max(at, rec)});
  }
  return w;
}

bool excused(const std::vector<std::pair<double, double>>& w, double t) {
  for (const auto& [a, b] : w)
    if (t >= a && t <= b) return true;
  return false;
}

Verdict speed_band(const Spec& s, const History& h) {
  const double band = *s.arg;
  const auto windows = recovery_windows(h);
  bool reached = false;
  int checked = 0;
  double worst = 0;
  for (const auto& r : h.trace) {
    const double ref = 0.5 * (r.ref_L_radps + r.ref_R_radps);
    if (ref <= 1e-9) continue;
    const double speed = 0.5 * (r.phidot_L_radps + r.phidot_R_radps);
    const double err = 100.0 * std::fabs(speed - ref) / ref;
    // From the first time the speed reaches the reference (the start is a ramp from rest that
    // the wheels follow a little behind).
    if (!reached && speed < ref) continue;
    reached = true;
    if (excused(windows, r.t_s)) continue;
    ++checked;
    worst = std::max(worst, err);
    if (err > band)
      return broke(s, h, r.t_s,
                   "wheel speed " + num(err) + " % off its reference at t=" + num(r.t_s) + " s (band " +
                       num(band, 1) + " %, outside " + std::to_string(windows.size()) + " recovery window(s))");
  }
  if (!reached) return broke(s, h, h.trace.empty() ? 0.0 : h.trace.back().t_s, "the reference speed was never reached");
  return held(s, "largest error " + num(worst) + " % over " + std::to_string(checked) + " trace rows");
}

Verdict path_tracked(const Spec& s, const History& h) {
  const double tol = s.arg ? *s.arg : h.path_tolerance_m;
  double worst = 0;
  for (const auto& r : h.trace) {
    worst = std::max(worst, std::fabs(r.cross_track_m));
    if (std::fabs(r.cross_track_m) > tol)
      return broke(s, h, r.t_s,
                   "cross-track error " + num(std::fabs(r.cross_track_m), 3) + " m at t=" + num(r.t_s) +
                       " s, above the tolerance " + num(tol, 3) + " m");
  }
  return held(s, "largest cross-track error " + num(worst, 3) + " m (tolerance " + num(tol, 3) + " m)");
}

/// A failure entry is a fault that must be detected when it says when it was detected.
Verdict faults_detected(const Spec& s, const History& h) {
  const double limit = *s.arg;
  int n = 0;
  const auto& f = h.summary.contains("failures") ? h.summary["failures"] : nlohmann::json::array();
  static const std::set<std::string> kEnds = {"restart", "resume", "clear", "heal"};  // the end of a fault
  for (const auto& e : f) {
    if (!e.contains("detected_s") || kEnds.count(e.value("action", ""))) continue;
    const std::string what = e.value("target", "?") + " " + e.value("action", "?") +
                             (e.contains("mode") && e["mode"].is_string() ? " " + e["mode"].get<std::string>() : "");
    const double at = number(e, "at_s", 0);
    ++n;
    if (!e["detected_s"].is_number())
      return broke(s, h, at + limit, what + " at t=" + num(at) + " s was never detected");
    const double late = e["detected_s"].get<double>() - at;
    if (late > limit + 1e-9)
      return broke(s, h, at + limit,
                   what + " at t=" + num(at) + " s detected after " + num(late) + " s (limit " + num(limit) + " s)");
  }
  return held(s, std::to_string(n) + " fault(s) detected within " + num(limit) + " s");
}

Verdict no_false_detection(const Spec& s, const History& h) {
  const nlohmann::json none = nlohmann::json::array();
  const auto& af = h.summary.contains("plant") ? h.summary["plant"].value("agent_faults", nlohmann::json::object())
                                               : nlohmann::json::object();
  const auto& d = af.contains("diagnoses") ? af["diagnoses"] : none;
  for (const auto& e : d)
    if (e.value("false_detection", false)) {
      const double t = number(e, "t_s", 0);
      return broke(s, h, t,
                   "healthy " + e.value("target", "?") + " isolated at t=" + num(t) + " s as " +
                       e.value("diagnosed", "?"));
    }
  return held(s, std::to_string(d.size()) + " diagnosis event(s), none of a healthy agent");
}

Verdict recording_complete(const Spec& s, const History& h) {
  if (h.record == "none") return held(s, "no recording asked (record: none)");
  if (!h.recording_file) return broke(s, h, 0, "run.mcap is missing (record: " + h.record + ")");
  const auto& rec = h.summary.contains("recording") ? h.summary["recording"] : nlohmann::json();
  if (!rec.is_object() || !rec.contains("incomplete"))
    return broke(s, h, 0, "the summary does not say what run.mcap holds");
  std::string missing;
  for (const auto& [topic, c] : rec["incomplete"].items())
    missing += (missing.empty() ? "" : ", ") + topic + " " + std::to_string(c.value("recorded", 0LL)) + " of " +
               std::to_string(c.value("taken_by_plant", 0LL));
  if (!missing.empty()) return broke(s, h, 0, "run.mcap holds fewer samples than the plant used: " + missing);
  return held(s, "run.mcap holds every sample the plant used");
}

Verdict ledger_monotone(const Spec& s, const History& h) {
  const auto& plant = h.summary.contains("plant") ? h.summary["plant"] : nlohmann::json::object();
  if (!plant.contains("group_wear")) return broke(s, h, 0, "the summary has no plant.group_wear");
  for (const char* side : {"L", "R"}) {
    const auto& g = plant["group_wear"].value(side, nlohmann::json::object());
    const auto n = g.value("regressions", 0LL);
    if (n > 0) {
      const double t = number(g, "first_regression_s", 0);
      return broke(s, h, t,
                   std::string("group-") + side + "'s wear ledger went backwards " + std::to_string(n) +
                       " time(s), first at t=" + num(t) + " s, by up to " + num(number(g, "largest_drop_m", 0), 3) +
                       " m");
    }
  }
  return held(s, "both wear ledgers never went backwards");
}

/// A process ended that no fault ended: a death the launcher did not cause and no lost host
/// explains (lease, deadline, unknown, external signal), or a process that exited with an error.
Verdict no_unexpected_exit(const Spec& s, const History& h) {
  double host_lost_s = 1e300;  // the first kill-host or partition: its processes' deaths follow
  if (h.summary.contains("failures"))
    for (const auto& f : h.summary["failures"]) {
      const std::string a = f.value("action", "");
      if (a == "kill-host" || a == "partition") host_lost_s = std::min(host_lost_s, number(f, "at_s", 0));
    }
  static const std::set<std::string> kUnexplained = {"lease", "deadline", "unknown", "external signal"};
  if (h.summary.contains("membership_events"))
    for (const auto& e : h.summary["membership_events"]) {
      if (e.value("kind", "") != "died") continue;
      const std::string cause = e.value("cause", "unknown");
      const double t = number(e, "t_s", 0);
      if (kUnexplained.count(cause) && t < host_lost_s)
        return broke(s, h, t, e.value("process", "?") + " died at t=" + num(t) + " s (" + cause + ") and no fault ended it");
    }
  if (h.summary.contains("processes"))
    for (const auto& p : h.summary["processes"])
      if (p.value("exit_code", 0) > 0)
        return broke(s, h, number(h.summary, "sim_time_s", 0),
                     p.value("name", "?") + " exited with code " + std::to_string(p.value("exit_code", 0)));
  return held(s, "every process that ended was ended by a fault or at the end of the run");
}

Verdict max_dead_per_side(const Spec& s, const History& h) {
  const int n = per_side(h);
  const int limit = s.arg ? static_cast<int>(*s.arg) : std::max(0, n - 1);
  int worst = 0;
  for (const auto& r : h.trace) {
    const int dead[2] = {n - static_cast<int>(r.n_live_L), n - static_cast<int>(r.n_live_R)};
    for (int side = 0; side < 2; ++side) {
      worst = std::max(worst, dead[side]);
      if (dead[side] > limit)
        return broke(s, h, r.t_s,
                     std::to_string(dead[side]) + " of side " + (side == 0 ? "L" : "R") + "'s " + std::to_string(n) +
                         " agents dead at t=" + num(r.t_s) + " s (at most " + std::to_string(limit) + ")");
    }
  }
  return held(s, "at most " + std::to_string(worst) + " dead per side (limit " + std::to_string(limit) + ")");
}

Verdict energy_balance(const Spec& s, const History& h) {
  const double tol = *s.arg;
  const double end_t = number(h.summary, "sim_time_s", h.trace.empty() ? 0.0 : h.trace.back().t_s);
  const nlohmann::json plant = h.summary.value("plant", nlohmann::json::object());
  if (!plant.is_object() || !plant.contains("energy_ledger") || !plant["energy_ledger"].is_object())
    return broke(s, h, end_t, "the plant left no energy ledger (summary plant.energy_ledger)");
  const auto& e = plant["energy_ledger"];
  const double drawn = number(e, "drawn_J", NAN);
  const double kinetic = number(e, "kinetic_end_J", NAN) - number(e, "kinetic_start_J", NAN);
  const double losses = number(e, "joule_loss_J", NAN) + number(e, "mech_loss_J", NAN) + number(e, "emf_loss_J", NAN);
  const double accounted = kinetic + losses;
  const double scale = std::max({std::fabs(drawn), std::fabs(accounted), 1.0});
  const double off_pct = 100.0 * std::fabs(drawn - accounted) / scale;
  const std::string figures = "drawn " + num(drawn, 1) + " J, kinetic " + num(kinetic, 1) + " J + losses " +
                              num(losses, 1) + " J = " + num(accounted, 1) + " J: " + num(off_pct, 4) + " % apart";
  if (!std::isfinite(off_pct)) return broke(s, h, end_t, "the energy ledger is incomplete: " + e.dump());
  if (off_pct > tol) return broke(s, h, end_t, figures + " (at most " + num(tol, 3) + " %)");
  return held(s, figures);
}

using Check = Verdict (*)(const Spec&, const History&);
struct Entry {
  Property p;
  Check check;
};

const std::vector<Entry>& entries() {
  static const std::vector<Entry> e = {
      {{"speed_band", "band, % of the reference", 10.0, 0.01, 1000,
        "The mean wheel speed of the two sides stays within ARG % of the mean of their references on every trace "
        "row from the first time it reaches that reference (the start from rest), except inside the recovery window of each fault (from "
        "its act to the time the summary says the speed recovered; to the end if it never did)."},
       speed_band},
      {{"path_tracked", "tolerance, m", std::nullopt, 1e-6, 1e3,
        "The cross-track error stays within ARG m on every trace row (default: the scenario's "
        "control.path_tolerance_m)."},
       path_tracked},
      {{"faults_detected", "limit, simulated s", 1.0, 0.0, 1e6,
        "Every fault of the summary's failures that is to be detected (a kill, a pause, an agent fault: those "
        "with detected_s; not a restart, resume, clear or heal) is detected within ARG simulated seconds of its act."},
       faults_detected},
      {{"no_false_detection", "", std::nullopt, 0, 0,
        "No group isolated a healthy agent (plant.agent_faults.diagnoses[].false_detection)."},
       no_false_detection},
      {{"recording_complete", "", std::nullopt, 0, 0,
        "run.mcap exists unless the scenario asked for none, and holds on every topic at least the samples the "
        "plant used (summary recording.incomplete empty)."},
       recording_complete},
      {{"ledger_monotone", "", std::nullopt, 0, 0,
        "Neither group's wear ledger, as the plant received it, ever went backwards "
        "(plant.group_wear.<side>.regressions)."},
       ledger_monotone},
      {{"energy_balance", "tolerance, % of the energy drawn", 0.1, 0.0, 100,
        "The energy drawn from the batteries (net of regeneration) equals the robot's gain of kinetic energy plus "
        "the Joule, mechanical and K_e/K_T losses, within ARG % (plant.energy_ledger, the plant's integrated "
        "ledgers at the end of the run)."},
       energy_balance},
      {{"no_unexpected_exit", "", std::nullopt, 0, 0,
        "No process died of a lost lease, a missed deadline, an external signal or an unknown cause before a "
        "host was killed or cut off, and none exited with an error code."},
       no_unexpected_exit},
      {{"max_dead_per_side", "agents", std::nullopt, 0, 1e6,
        "At no trace row are more than ARG agents of one side dead (default: the side's agents less one)."},
       max_dead_per_side},
  };
  return e;
}

const Entry* find(const std::string& name) {
  for (const auto& e : entries())
    if (e.p.name == name) return &e;
  return nullptr;
}

}  // namespace

const std::vector<Property>& table() {
  static const std::vector<Property> t = [] {
    std::vector<Property> v;
    for (const auto& e : entries()) v.push_back(e.p);
    return v;
  }();
  return t;
}

std::string Spec::text() const {
  if (!arg) return name;
  std::ostringstream os;
  os << name << ':' << *arg;
  return os.str();
}

Spec parse_spec(const std::string& text) {
  const auto colon = text.find(':');
  Spec s{text.substr(0, colon), std::nullopt};
  const Entry* e = find(s.name);
  if (!e) {
    std::string known;
    for (const auto& p : table()) known += (known.empty() ? "" : ", ") + p.name;
    throw std::invalid_argument("'" + text + "': no property '" + s.name + "' (known: " + known + ")");
  }
  if (colon == std::string::npos) {
    s.arg = e->p.default_arg;
    return s;
  }
  if (e->p.arg.empty()) throw std::invalid_argument("'" + text + "': " + s.name + " takes no argument");
  const std::string a = text.substr(colon + 1);
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(a, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (a.empty() || used != a.size() || !std::isfinite(v))
    throw std::invalid_argument("'" + text + "': the argument of " + s.name + " (" + e->p.arg + ") must be a number");
  if (v < e->p.arg_min || v > e->p.arg_max)
    throw std::invalid_argument("'" + text + "': the argument of " + s.name + " must be in [" + num(e->p.arg_min, 2) +
                                ", " + num(e->p.arg_max, 0) + "]");
  s.arg = v;
  return s;
}

std::vector<Spec> all_specs() {
  std::vector<Spec> v;
  for (const auto& p : table()) v.push_back({p.name, p.default_arg});
  return v;
}

Verdict evaluate(const Spec& spec, const History& h) {
  const Entry* e = find(spec.name);
  if (!e) throw std::invalid_argument("no property '" + spec.name + "'");
  return e->check(spec, h);
}

std::string reference(bool markdown) {
  std::ostringstream os;
  if (markdown)
    os << "# Run properties\n\n"
          "What `maptr check RUN --property NAME[:ARG]` checks over a finished run's summary.json, trace.csv and\n"
          "run.mcap: each gives holds or breaks, the first tick where it broke and a one-line reason. Generated by\n"
          "`maptr check --list --markdown` from the table in `deploy/fleet/run_properties.cpp` (do not edit by\n"
          "hand: a unit test fails when this file differs).\n\n"
          "| property | argument | default | definition |\n|---|---|---|---|\n";
  for (const auto& p : table()) {
    const std::string def = p.arg.empty() ? "–" : p.default_arg ? num(*p.default_arg, 1) : "from the run";
    if (markdown)
      os << "| `" << p.name << "` | " << (p.arg.empty() ? "–" : p.arg) << " | " << def << " | " << p.definition
         << " |\n";
    else
      os << p.name << (p.arg.empty() ? "" : ":ARG  (ARG: " + p.arg + ", default " + def + ")") << "\n    "
         << p.definition << "\n";
  }
  return os.str();
}

}  // namespace maptr::deploy::properties
