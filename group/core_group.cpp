#include "group/core_group.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <stdexcept>

#include "model/allocation.hpp"

namespace maptr::group {

namespace {
constexpr uint8_t kL2None = 0, kL2Ok = 1, kL2Infeasible = 2, kL2Failed = 3;  // msg::L2_*

int count(const std::vector<uint8_t>& m) { return static_cast<int>(std::count(m.begin(), m.end(), 1)); }
}  // namespace

bool Ledger::load(const std::string& path, int per_side) {
  std::ifstream in(path);
  if (!in) return false;
  nlohmann::json j;
  try {
    in >> j;
    wear_m = j.at("wear_m").get<std::vector<double>>();
    active_time_s = j.at("active_time_s").get<std::vector<double>>();
    assignment = j.at("assignment").get<std::vector<uint8_t>>();
    last_t = j.at("last_t").get<double>();
    last_alloc_t = j.at("last_alloc_t").get<double>();
    n_target = j.at("n_target").get<int>();
    decisions = j.at("decisions").get<uint64_t>();
    reallocations = j.at("reallocations").get<uint64_t>();
  } catch (const std::exception& e) {
    throw std::runtime_error("wear ledger " + path + " is corrupt: " + e.what());
  }
  if (static_cast<int>(wear_m.size()) != per_side || static_cast<int>(active_time_s.size()) != per_side)
    throw std::runtime_error("wear ledger " + path + " has " + std::to_string(wear_m.size()) +
                             " agents, the scenario " + std::to_string(per_side));
  if (static_cast<int>(assignment.size()) != per_side) assignment.assign(per_side, 0);
  return true;
}

void Ledger::save(const std::string& path) const {
  nlohmann::json j;
  j["wear_m"] = wear_m;
  j["active_time_s"] = active_time_s;
  j["assignment"] = assignment;
  j["last_t"] = last_t;
  j["last_alloc_t"] = last_alloc_t;
  j["n_target"] = n_target;
  j["decisions"] = decisions;
  j["reallocations"] = reallocations;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error("cannot write wear ledger " + tmp);
    out << j.dump(1) << "\n";
  }
  std::filesystem::rename(tmp, path);
}

GroupCore::GroupCore(int side, const config::Scenario& s, std::string ledger_path)
    : side_(side), s_(s), ledger_path_(std::move(ledger_path)) {
  const int n = s.robot.per_side();
  ledger_.wear_m.assign(n, 0.0);
  ledger_.active_time_s.assign(n, 0.0);
  ledger_.assignment.assign(n, 0);
  if (!ledger_path_.empty()) resumed_ = ledger_.load(ledger_path_, n);
}

void GroupCore::save() const {
  if (!ledger_path_.empty()) ledger_.save(ledger_path_);
}

GroupDecision GroupCore::step(const GroupInput& in) {
  const int n = s_.robot.per_side();
  // 1. Ledger: the assignment in force over [t_{k-1}, t_k] drove |v_side| dt each.
  if (ledger_.last_t >= 0.0 && in.t > ledger_.last_t) {
    const double dt = in.t - ledger_.last_t;
    const double ds = std::fabs(in.phidot_side) * s_.robot.wheel_radius_m * dt;
    for (int j = 0; j < n; ++j) {
      if (j < static_cast<int>(in.active.size()) && in.active[j]) {
        ledger_.wear_m[j] += ds;
        ledger_.active_time_s[j] += dt;
      } else {
        ledger_.active_time_s[j] = 0.0;
      }
    }
  }
  ledger_.last_t = in.t;

  GroupDecision d = last_;  // the last solve's diagnostics stay on the status topic
  d.level2_ran = false;
  d.n_live = count(in.live);
  std::vector<uint8_t> next = ledger_.assignment;
  for (int j = 0; j < n; ++j)
    if (!in.live[j]) next[j] = 0;

  if (s_.mode == "all") {
    next = in.live;
    d.level2_status = kL2None;
  } else {
    const double ref = side_ == 0 ? in.phidot_ref_L : in.phidot_ref_R;
    // Cruise with hysteresis: enter within 5% of the reference, leave beyond 20%.
    const double err = ref > 0.0 ? std::fabs(in.phidot_side - ref) / ref : 1.0;
    if (err <= 0.05) cruise_ = true;
    if (err > 0.20) cruise_ = false;
    const bool cruising = cruise_;
    bool realloc = false;
    int target = ledger_.n_target;
    if (!cruising) {
      // Accelerating, braking or recovering: every live agent helps.
      target = d.n_live;
      realloc = next != in.live;
      last_l2_t_ = -1e300;  // decide as soon as cruise is reached
    } else if (in.t - last_l2_t_ >= s_.control.level2_period_s - 1e-9) {
      last_l2_t_ = in.t;
      model::Level2Problem p;
      p.robot = s_.robot;
      p.side = side_;
      p.live = d.n_live;
      p.n_other = in.n_other;
      p.v_x = in.v_x;
      p.w = in.w;
      p.phidot_ref_L = in.phidot_ref_L;
      p.phidot_ref_R = in.phidot_ref_R;
      p.battery_V = in.battery_V;
      p.horizon = s_.control.horizon;
      p.step_s = s_.control.horizon_step_s;
      if (p.live > 0) {
        const Level2Result r = solver_.solve(p);
        d.level2_relaxed = r.n_relaxed;
        d.level2_ran = true;
        d.ipopt_n_active = r.n_active;
        d.solve_time_ms = r.solve_time_ms;
        d.level2_status = !r.feasible ? kL2Infeasible : (r.ipopt_status >= 0 || r.ipopt_status == kLevel2NotSolved)
                                                            ? kL2Ok
                                                            : kL2Failed;
        target = r.feasible ? r.n_active : d.n_live;
        if (s_.control.oracle) d.oracle_n_active = model::exhaustive_level2(p).n_active;
      } else {
        target = 0;
        d.level2_status = kL2Infeasible;
      }
      ++ledger_.decisions;
    }
    target = std::min(target, d.n_live);
    const int have = count(next);
    bool overheated = false;
    for (int j = 0; j < n; ++j)
      if (next[j] && ledger_.active_time_s[j] >= s_.control.thermal_limit_s) overheated = true;
    realloc = realloc || target != ledger_.n_target || have != target || overheated ||
              in.t - ledger_.last_alloc_t >= s_.control.t_on_s - 1e-9;
    ledger_.n_target = target;
    if (realloc) {
      model::AllocationInput ai;
      ai.distance_m = ledger_.wear_m;
      ai.live = in.live;
      ai.active_time_s = ledger_.active_time_s;
      ai.thermal_limit_s = s_.control.thermal_limit_s;
      ai.n_active = target;
      next = model::allocate(ai);
      ledger_.last_alloc_t = in.t;
      ++ledger_.reallocations;
    }
  }
  const bool changed = next != ledger_.assignment;
  ledger_.assignment = next;
  d.active = next;
  d.n_active = count(next);
  d.decisions = ledger_.decisions;
  d.reallocations = ledger_.reallocations;
  last_ = d;
  // Persist on every change and once per decision period.
  const long long period_ticks = std::max(1LL, std::llround(s_.control.level2_period_s * s_.tick_hz));
  if (changed || in.tick % period_ticks == 0) save();
  return d;
}

}  // namespace maptr::group
