#include "plant/tick_records.hpp"

#include <optional>

#include "records/assignments.hpp"
#include "records/trace.hpp"

namespace maptr::plant {

namespace {

/// The trace record of the core's row k (counts become whole doubles; energy is both sides').
records::TraceRow to_record(const plant_core::TraceRow& r) {
  const model::State& x = r.x;
  records::TraceRow o;
  o.tick = static_cast<double>(r.tick);
  o.t_s = r.t_s;
  o.x_m = x[model::kX];
  o.y_m = x[model::kY];
  o.theta_rad = x[model::kTheta];
  o.v_x_mps = x[model::kVx];
  o.w_radps = x[model::kW];
  o.phidot_L_radps = r.phidot_radps[0];
  o.phidot_R_radps = r.phidot_radps[1];
  o.ref_L_radps = r.ref_radps[0];
  o.ref_R_radps = r.ref_radps[1];
  o.V_L_mean_V = r.voltage_mean_V[0];
  o.V_R_mean_V = r.voltage_mean_V[1];
  o.I_L_A = r.current_A[0];
  o.I_R_A = r.current_A[1];
  o.eff_L = r.efficiency_mean[0];
  o.eff_R = r.efficiency_mean[1];
  o.battery_V_L = r.battery_V[0];
  o.battery_V_R = r.battery_V[1];
  o.discharge_L_mAh = x[model::kChargeL];
  o.discharge_R_mAh = x[model::kChargeR];
  o.n_active_L = r.n_active[0];
  o.n_active_R = r.n_active[1];
  o.n_live_L = r.n_live[0];
  o.n_live_R = r.n_live[1];
  o.energy_J = x[model::kEnergyL] + x[model::kEnergyR];
  o.distance_m = x[model::kDistance];
  o.ref_x_m = r.reference.x;
  o.ref_y_m = r.reference.y;
  o.ref_theta_rad = r.reference.theta;
  o.cross_track_m = r.cross_track_m;
  return o;
}

/// The assignment record of a change: side 'L'/'R', the driving flags as a '0'/'1' mask.
records::AssignmentRecord to_record(const plant_core::AssignmentChange& a) {
  records::AssignmentRecord o;
  o.t_s = a.t_s;
  o.side = a.side == 0 ? 'L' : 'R';
  o.driving.assign(a.driving.size(), '0');
  for (std::size_t j = 0; j < a.driving.size(); ++j)
    if (a.driving[j]) o.driving[j] = '1';
  return o;
}

class CsvRunFiles : public RunFiles {
 public:
  CsvRunFiles(const std::string& trace_path, const std::string& assignments_path) {
    if (!assignments_path.empty()) assignments_.emplace(assignments_path);
    trace_.emplace(trace_path);
  }

  void write(const plant_core::TickRecord& rec) override {
    if (rec.row) trace_->write(to_record(*rec.row));
    if (assignments_)
      for (const auto& a : rec.assignments) assignments_->write(to_record(a));
  }

 private:
  std::optional<records::AssignmentsWriter> assignments_;
  std::optional<records::TraceWriter> trace_;
};

}  // namespace

std::unique_ptr<RunFiles> open_csv_run_files(const std::string& trace_path,
                                             const std::string& assignments_path) {
  return std::make_unique<CsvRunFiles>(trace_path, assignments_path);
}

}  // namespace maptr::plant
