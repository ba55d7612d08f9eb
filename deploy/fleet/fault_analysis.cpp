#include "deploy/fleet/fault_analysis.hpp"

#include <algorithm>
#include <cmath>

#include "records/trace.hpp"

namespace maptr::deploy {

namespace {

struct Row {
  double t, err_pct;
};

/// Speed error of every row of the trace, %. None when the trace is missing or broken (a
/// records::RecordError must not end the summary: the faults are then reported unanalysed).
std::vector<Row> speed_errors(const std::string& path, double r) {
  std::vector<records::TraceRow> trace;
  try {
    trace = records::read_trace(path);
  } catch (const records::RecordError&) {
    return {};
  }
  std::vector<Row> rows;
  rows.reserve(trace.size());
  for (const auto& x : trace) {
    const double ref = x.ref_speed_mps(r);
    rows.push_back({x.t_s, ref > 0.0 ? 100.0 * std::fabs(x.v_x_mps - ref) / ref : 0.0});
  }
  return rows;
}

}  // namespace

void analyse_faults(nlohmann::json& failures, const std::vector<records::MembershipEvent>& events,
                    const std::string& trace_csv, double wheel_radius_m, double band_pct) {
  const std::vector<Row> rows = speed_errors(trace_csv, wheel_radius_m);
  const double t_end = rows.empty() ? 0.0 : rows.back().t;
  for (std::size_t i = 0; i < failures.size(); ++i) {
    auto& f = failures[i];
    if (f.contains("skipped")) continue;  // it did not happen: nothing to detect or recover from
    const double at = f.value("at_s", 0.0);
    const std::string target = f.value("target", "");
    // A restart, a resume or a heal is detected when the target answers again; a kill, a pause or
    // a partition when the plant drops it.
    const std::string action = f.value("action", "");
    const bool restart = action == "restart" || action == "resume" || action == "heal";
    // A host fault is detected by the first event of any process on that host.
    const nlohmann::json on_host = f.value("processes", nlohmann::json::array());
    auto concerns = [&](const std::string& name) {
      return name == target || std::find(on_host.begin(), on_host.end(), name) != on_host.end();
    };
    // Detection: the first membership event of the target at or after the fault. An agent's own
    // fault (action fault) is detected by its group: the plant recorded when.
    if (action != "fault") {
    f["detected_s"] = nullptr;
    f["detect_wall_ms"] = nullptr;
    for (const auto& e : events) {
      if (!concerns(e.name) || e.t_s < at - 1e-9) continue;
      if ((e.event == "rejoined") != restart) continue;
      f["detected_s"] = e.t_s;
      if (f.contains("wall_ms")) f["detect_wall_ms"] = e.wall_ms - f.value("wall_ms", 0.0);
      break;
    }
    }
    // Recovery window: until the next fault (or the end of the run).
    double until = t_end + 1.0;
    for (std::size_t k = 0; k < failures.size(); ++k)
      if (k != i && !failures[k].contains("skipped") && failures[k].value("at_s", 0.0) > at)
        until = std::min(until, failures[k].value("at_s", 0.0));
    double max_err = 0.0, last_out = -1.0, last_in = -1.0;
    for (const auto& r : rows) {
      if (r.t < at || r.t >= until) continue;
      last_in = r.t;
      max_err = std::max(max_err, r.err_pct);
      if (r.err_pct > band_pct) last_out = r.t;
    }
    const double step = rows.size() > 1 ? rows[1].t - rows[0].t : 0.0;
    f["max_speed_error_pct"] = max_err;
    if (last_in < 0.0 || (last_out >= 0.0 && last_out >= last_in))
      f["recovered_s"] = nullptr;  // no data, or still outside the band when the window closed
    else
      f["recovered_s"] = last_out < 0.0 ? at : last_out + step;  // at: it never left the band
  }
}

}  // namespace maptr::deploy
