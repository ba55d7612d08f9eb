#include "deploy/top/view_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace maptr::top {

namespace {

constexpr const char* kSide[2] = {"L", "R"};
/// Lines above the agents: header, time, speed, the side table (title and two rows).
constexpr int kTopLines = 6;
/// Lines below the agents besides the events: the events' title and the status line.
constexpr int kBottomLines = 2;
/// Agent states in the order the compact counts list them.
constexpr CellState kStates[] = {CellState::kActive,    CellState::kIdle,     CellState::kHolding,
                                 CellState::kCoasting,  CellState::kStopping, CellState::kPaused,
                                 CellState::kRejoining, CellState::kFaulty,   CellState::kDead,
                                 CellState::kUnknown};

std::string fmt(const char* f, ...) {
  char buf[256];
  va_list ap;
  va_start(ap, f);
  std::vsnprintf(buf, sizeof(buf), f, ap);
  va_end(ap);
  return buf;
}

std::vector<std::string> head(const FleetView& v) {
  std::vector<std::string> out;
  std::string h = fmt("maptr top  %s  %d agents  domain %d  ", v.info().scenario.c_str(), v.info().agents,
                      v.info().domain);
  if (v.info().replay_rate > 0) h += fmt("replay %gx  ", v.info().replay_rate);
  h += phase_name(v.phase());
  if (v.phase() == Phase::kWaiting) h += fmt("  (%d ready)", v.ready_nodes());
  out.push_back(h);
  const TickStats ts = v.tick_stats();
  out.push_back(fmt("t %.2f / %.2f s  RTF %.2fx  tick median %.2f ms  p99 %.2f ms  live %d/%d", v.t_s(),
                    v.info().duration_s, v.real_time_factor(), ts.median_ms, ts.p99_ms, v.live_agents(),
                    v.info().agents));
  out.push_back(fmt("speed %.3f m/s  ref %.3f m/s (%+.1f %%)  yaw %.4f rad/s  energy %.1f J", v.v_x(),
                    v.v_x_ref(), v.speed_error_pct(), v.yaw_rate(), v.energy_J()));
  out.push_back("side battery  discharge     active  Level 2     N_a relaxed solve     Level 3");
  for (int s = 0; s < 2; ++s) {
    const SideView& sv = v.side(s);
    const char* l2 = sv.group_died       ? "group dead"
                     : v.group_silent(s) ? "silent"
                                         : control::level2_status_name(sv.level2.status);
    out.push_back(fmt("%-4s %5.2f V %9.3f mAh  %2d/%-3d  %-10s  %3d %7.2f %6.1f ms  %llu realloc", kSide[s],
                      sv.battery_V, sv.discharge_mAh, sv.n_active, static_cast<int>(sv.agents.size()), l2,
                      sv.group_n_active, sv.level2.relaxed, sv.level2.solve_ms,
                      static_cast<unsigned long long>(sv.reallocations)));
  }
  return out;
}

std::string agent_cell(const FleetView& v, int s, int i) {
  const AgentCell& a = v.side(s).agents[static_cast<std::size_t>(i)];
  std::string name = fmt("%s%d", kSide[s], i);
  return fmt("%-5s%-10s%5.1fV%6.2fA%7.1fm", name.c_str(), state_name(v.state(s, i)), a.voltage_V, a.current_A,
             a.wear_m);
}

std::vector<std::string> detailed(const FleetView& v, int width) {
  const int per_line = std::max(1, width / kCellWidth);
  std::vector<std::string> out;
  for (int s = 0; s < 2; ++s) {
    const int n = static_cast<int>(v.side(s).agents.size());
    for (int i = 0; i < n; i += per_line) {
      std::string line;
      for (int j = i; j < std::min(n, i + per_line); ++j) {
        std::string c = agent_cell(v, s, j);
        c.resize(static_cast<std::size_t>(kCellWidth), ' ');
        line += c;
      }
      while (!line.empty() && line.back() == ' ') line.pop_back();
      out.push_back(line);
    }
  }
  return out;
}

std::string side_counts(const FleetView& v, int s) {
  const SideView& sv = v.side(s);
  int n[sizeof(kStates) / sizeof(kStates[0])] = {0};
  double v_sum = 0.0, i_max = 0.0, wear_lo = 0.0, wear_hi = 0.0;
  for (std::size_t i = 0; i < sv.agents.size(); ++i) {
    const CellState st = v.state(s, static_cast<int>(i));
    for (std::size_t k = 0; k < sizeof(kStates) / sizeof(kStates[0]); ++k) n[k] += kStates[k] == st ? 1 : 0;
    const AgentCell& a = sv.agents[i];
    v_sum += a.voltage_V;
    i_max = std::max(i_max, a.current_A);
    wear_lo = i == 0 ? a.wear_m : std::min(wear_lo, a.wear_m);
    wear_hi = std::max(wear_hi, a.wear_m);
  }
  std::string line = std::string(kSide[s]) + ":";
  for (std::size_t k = 0; k < sizeof(kStates) / sizeof(kStates[0]); ++k)
    if (n[k] > 0) line += fmt(" %d %s", n[k], state_name(kStates[k]));
  const double mean_v = sv.agents.empty() ? 0.0 : v_sum / static_cast<double>(sv.agents.size());
  return line + fmt("; V mean %.1f, I max %.2f A, wear %.0f-%.0f m", mean_v, i_max, wear_lo, wear_hi);
}

std::vector<std::string> compact(const FleetView& v, int width) {
  const int per_line = std::max(1, width - 3);
  std::vector<std::string> out;
  for (int s = 0; s < 2; ++s) {
    const int n = static_cast<int>(v.side(s).agents.size());
    for (int i = 0; i < n; i += per_line) {
      std::string line = i == 0 ? std::string(kSide[s]) + "  " : "   ";
      for (int j = i; j < std::min(n, i + per_line); ++j) line += state_letter(v.state(s, j));
      out.push_back(line);
    }
    out.push_back(side_counts(v, s));
  }
  return out;
}

std::string status_line(const FleetView& v, bool compact_layout) {
  if (!v.final_status().empty())
    return fmt("final status: %s (%s) at t %.2f s, energy %.1f J, %.1f m", v.final_status().c_str(),
               v.end_reason().c_str(), v.t_s(), v.energy_J(), v.distance_m());
  if (v.phase() != Phase::kRunning && v.phase() != Phase::kWaiting)
    return fmt("run %s at t %.2f s, energy %.1f J, %.1f m", phase_name(v.phase()), v.t_s(), v.energy_J(),
               v.distance_m());
  return compact_layout ? legend() : "q quits";
}

}  // namespace

std::string legend() { return "A active . idle H hold C coast S stop X dead P paused R rejoining F faulty"; }

std::vector<std::string> layout(const FleetView& v, int width, int height, int events_back) {
  if (width < kMinWidth || (height > 0 && height < kMinHeight))
    return {fmt("maptr top: the terminal is %dx%d; it needs at least %dx%d", width, height, kMinWidth,
                kMinHeight)};
  std::vector<std::string> out = head(v);
  auto cells = detailed(v, width);
  const int room = height - kTopLines - kBottomLines - 1;  // at least one event line
  const bool small = height > 0 && static_cast<int>(cells.size()) > room;
  if (small) cells = compact(v, width);
  out.insert(out.end(), cells.begin(), cells.end());
  // On a screen the latest events that fit (at most kEventsShown below a tall grid); in a
  // snapshot (height 0) every event.
  const auto& ev = v.events();
  const int event_room = height > 0 ? std::min(kEventsShown, std::max(0, height - static_cast<int>(out.size()) - kBottomLines))
                                    : static_cast<int>(ev.size());
  const int shown = std::min(event_room, static_cast<int>(ev.size()));
  // Scrolled back by events_back (at most to the first event): the window ends that far before the latest.
  const int last = static_cast<int>(ev.size()) - std::clamp(events_back, 0, static_cast<int>(ev.size()) - shown);
  out.push_back(ev.empty() ? "events: none"
                : shown < static_cast<int>(ev.size())
                    ? fmt("events %d-%d of %d (up/down scroll):", last - shown + 1, last, static_cast<int>(ev.size()))
                    : std::string("events:"));
  for (int i = last - shown; i < last; ++i) {
    const ViewEvent& e = ev[static_cast<std::size_t>(i)];
    out.push_back((std::isnan(e.t_s) ? std::string("  before joining ") : fmt("  t %8.2f s    ", e.t_s)) +
                  e.text);
  }
  out.push_back(status_line(v, small));
  if (height > 0 && static_cast<int>(out.size()) > height) out.resize(static_cast<std::size_t>(height));
  for (auto& l : out)
    if (static_cast<int>(l.size()) > width) l.resize(static_cast<std::size_t>(width));
  return out;
}

}  // namespace maptr::top
