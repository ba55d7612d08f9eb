#include "control/diagnosis.hpp"

#include <algorithm>
#include <cmath>

#include "model/motor.hpp"

namespace maptr::control {

namespace {
constexpr const char* kNames[kDiagnosisCount] = {"",      "open",   "short",   "torque", "resistance",
                                                 "stuck", "sensor", "erratic", "liar"};
/// A, V, rad/s: what counts as none, or as steady, in the classification (the plant's figures
/// travel as floats: about 1e-7 relative).
constexpr double kNoCurrentA = 1e-6;
constexpr double kZeroVoltsV = 0.1;
constexpr double kSteadyV = 0.05;
constexpr double kSteadyRadps = 0.05;
/// The factors a weak magnet (torque) and a larger resistance plausibly have.
constexpr double kLeastFactor = 0.02, kMostFactor = 100.0;

double spread(const std::vector<double>& v) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *hi - *lo;
}
double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}
}  // namespace

const char* diagnosis_name(Diagnosis d) {
  const auto i = static_cast<int>(d);
  return i >= 0 && i < kDiagnosisCount ? kNames[i] : "?";
}

SideDiagnosis::SideDiagnosis(int per_side, const DiagnosisConfig& c)
    : c_(c),
      need_(std::max(1, static_cast<int>(std::lround(c.fault_persistence_s / c.dt_s)))),
      agents_(static_cast<std::size_t>(per_side)),
      flags_(static_cast<std::size_t>(per_side), 0) {
  for (auto& a : agents_) a.probation_s = c.fault_probation_s;
}

void SideDiagnosis::reset(Agent& a) {
  a.a.clear();
  a.b.clear();
  a.jitter.clear();
  a.has_c = false;
  a.last_drove = false;
}

Diagnosis SideDiagnosis::classify_a(const std::deque<Sample>& w) const {
  const double R = c_.motor.resistance_ohm, Ke = c_.motor.back_emf_Vs;
  bool none = true;
  std::vector<double> v_eff, v_cmd;
  double above = 0.0;  // how much more current than the model, in the model's direction
  for (const Sample& s : w) {
    none = none && std::fabs(s.measured_A) < kNoCurrentA;
    v_eff.push_back(s.measured_A * R + Ke * s.phidot);
    v_cmd.push_back(s.drove ? s.drive_V : 0.0);
    above += (s.measured_A - s.expected_A) * (s.expected_A >= 0.0 ? 1.0 : -1.0);
  }
  if (none) return Diagnosis::kOpen;
  const double v_mean = mean(v_eff), steady = spread(v_eff);
  if (std::fabs(v_mean) < kZeroVoltsV && steady < kZeroVoltsV) return Diagnosis::kShort;
  // Which parameter change would explain the current: a weaker magnet (torque F in (0, 1)) gives
  // more current, a larger resistance (F > 1) less. A stuck driver fits neither, or is steady while
  // the agent's voltage is not what the winding sees.
  double f_torque = 0.0, f_resistance = 0.0;
  int n = 0;
  for (const Sample& s : w) {
    if (!s.drove || s.phidot == 0.0 || s.measured_A == 0.0) continue;
    f_torque += (s.drive_V - s.measured_A * R) / (Ke * s.phidot);
    f_resistance += (s.drive_V - Ke * s.phidot) / (s.measured_A * R);
    ++n;
  }
  if (n > 0) {
    f_torque /= n;
    f_resistance /= n;
  }
  const bool torque = n > 0 && above > 0.0 && f_torque > kLeastFactor && f_torque < 1.0;
  const bool resistance = n > 0 && above <= 0.0 && f_resistance > 1.0 && f_resistance <= kMostFactor;
  if (torque) return Diagnosis::kTorque;
  if (resistance) return Diagnosis::kResistance;
  if (steady < kSteadyV && std::fabs(v_mean - mean(v_cmd)) > kZeroVoltsV) return Diagnosis::kStuck;
  return above > 0.0 ? Diagnosis::kTorque : Diagnosis::kResistance;
}

Diagnosis SideDiagnosis::classify_b(const std::deque<Sample>& w) const {
  const double R = c_.motor.resistance_ohm, Ke = c_.motor.back_emf_Vs;
  std::vector<double> offset;  // the speed the report implies minus the measured one
  for (const Sample& s : w)
    if (s.drove && s.reported_A != 0.0) offset.push_back((s.drive_V - s.reported_A * R) / Ke - s.phidot_prev);
  if (offset.size() == w.size() && spread(offset) < kSteadyRadps) return Diagnosis::kSensor;
  return Diagnosis::kLiar;
}

void SideDiagnosis::watch_jitter(Agent& a, const DriveSample& d, double median, bool side_steps) {
  if (d.drove && a.last_drove && side_steps) {
    // Its step apart from the side's, and how that changed since the last tick: a steady
    // difference (a sensor's offset winding the PID's integrator up) is no jitter.
    const double c = d.drive_V - a.last_V - median;
    if (a.has_c) {
      a.jitter.push_back(std::fabs(c - a.last_c));
      if (static_cast<int>(a.jitter.size()) > need_) a.jitter.pop_front();
    }
    a.last_c = c;
    a.has_c = true;
  } else {
    a.jitter.clear();
    a.has_c = false;
  }
  a.last_drove = d.drove;
  a.last_V = d.drive_V;
}

Diagnosis SideDiagnosis::verdict(const Agent& a) const {
  if (static_cast<int>(a.a.size()) >= need_) return classify_a(a.a);
  if (static_cast<int>(a.b.size()) >= need_) return classify_b(a.b);
  if (static_cast<int>(a.jitter.size()) < need_) return Diagnosis::kNone;
  // The median, not the mean: one step (a sensor's offset, a new assignment) is no jitter.
  std::vector<double> v(a.jitter.begin(), a.jitter.end());
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2] > c_.fault_jitter_V ? Diagnosis::kErratic : Diagnosis::kNone;
}

std::vector<DiagnosisChange> SideDiagnosis::step(double t, const SideSample& s) {
  std::vector<DiagnosisChange> changes;
  const std::size_t n = std::min(agents_.size(), s.agents.size());
  // Channel C: each driving agent's voltage step against the side's median step.
  std::vector<double> steps;
  for (std::size_t j = 0; j < n; ++j)
    if (!flags_[j] && s.agents[j].drove && agents_[j].last_drove) steps.push_back(s.agents[j].drive_V - agents_[j].last_V);
  double median = 0.0;
  if (!steps.empty()) {
    std::nth_element(steps.begin(), steps.begin() + static_cast<long>(steps.size() / 2), steps.end());
    median = steps[steps.size() / 2];
  }
  for (std::size_t j = 0; j < n; ++j) {
    Agent& a = agents_[j];
    const DriveSample& d = s.agents[j];
    if (flags_[j]) {
      if (t - a.isolated_t < a.probation_s - 1e-9) continue;
      flags_[j] = 0;  // probation over: let back, watched afresh
      reset(a);
      changes.push_back({static_cast<int>(j), Diagnosis::kNone});
      continue;
    }
    const double expected = d.drove ? model::armature_current(c_.motor, c_.driver, d.drive_V, s.phidot) : 0.0;
    const double reported_model =
        d.drove ? model::armature_current(c_.motor, c_.driver, d.drive_V, s.phidot_prev) : 0.0;
    const Sample smp{d.drove, d.drive_V, d.measured_A, expected, d.reported_A, s.phidot, s.phidot_prev};
    auto track = [this](std::deque<Sample>& w, bool beyond, const Sample& x) {
      if (!beyond) {
        w.clear();
        return;
      }
      w.push_back(x);
      if (static_cast<int>(w.size()) > need_) w.pop_front();
    };
    track(a.a, std::fabs(d.measured_A - expected) > c_.fault_current_A, smp);
    track(a.b, d.reported && std::fabs(d.reported_A - reported_model) > c_.fault_current_A, smp);
    watch_jitter(a, d, median, steps.size() >= 2);
    const Diagnosis flag = verdict(a);
    if (flag == Diagnosis::kNone) continue;
    flags_[j] = static_cast<uint8_t>(flag);
    if (a.flagged++ > 0) a.probation_s *= 2.0;  // a relapse
    a.isolated_t = t;
    reset(a);
    changes.push_back({static_cast<int>(j), flag});
  }
  return changes;
}

}  // namespace maptr::control
