#include "plant/run_files.hpp"

#include <cstdio>
#include <stdexcept>

namespace maptr::plant {

namespace {

class CsvRunFiles : public RunFiles {
 public:
  CsvRunFiles(const std::string& trace_path, const std::string& assignments_path) {
    if (!assignments_path.empty()) {
      assignments_ = std::fopen(assignments_path.c_str(), "w");
      if (!assignments_) throw std::runtime_error("cannot write " + assignments_path);
      std::fprintf(assignments_, "t_s,side,driving\n");
    }
    trace_ = std::fopen(trace_path.c_str(), "w");
    if (!trace_) {
      if (assignments_) std::fclose(assignments_);
      throw std::runtime_error("cannot write the trace " + trace_path);
    }
    std::fprintf(
        trace_,
        "tick,t_s,x_m,y_m,theta_rad,v_x_mps,w_radps,phidot_L_radps,phidot_R_radps,ref_L_radps,ref_R_radps,"
        "V_L_mean_V,V_R_mean_V,I_L_A,I_R_A,eff_L,eff_R,battery_V_L,battery_V_R,discharge_L_mAh,"
        "discharge_R_mAh,n_active_L,n_active_R,n_live_L,n_live_R,energy_J,distance_m\n");
    std::fflush(trace_);
  }
  ~CsvRunFiles() override {
    std::fclose(trace_);
    if (assignments_) std::fclose(assignments_);
  }
  CsvRunFiles(const CsvRunFiles&) = delete;
  CsvRunFiles& operator=(const CsvRunFiles&) = delete;

  void write(const sim::TickRecord& rec) override {
    if (rec.row) write_row(*rec.row);
    if (assignments_)
      for (const auto& a : rec.assignments) write_assignment(a);
  }

 private:
  void write_row(const sim::TraceRow& r) {
    const model::State& x = r.x;
    std::fprintf(
        trace_,
        "%lld,%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6g,%.6g,%.9g,%.9g,"
        "%.9g,%.9g,%d,%d,%d,%d,%.9g,%.9g\n",
        r.tick, r.t_s, x[model::kX], x[model::kY], x[model::kTheta], x[model::kVx], x[model::kW],
        r.phidot_radps[0], r.phidot_radps[1], r.ref_radps[0], r.ref_radps[1], r.voltage_mean_V[0],
        r.voltage_mean_V[1], r.current_A[0], r.current_A[1], r.efficiency_mean[0], r.efficiency_mean[1],
        r.battery_V[0], r.battery_V[1], x[model::kChargeL], x[model::kChargeR], r.n_active[0], r.n_active[1],
        r.n_live[0], r.n_live[1], x[model::kEnergyL] + x[model::kEnergyR], x[model::kDistance]);
    std::fflush(trace_);
  }
  void write_assignment(const sim::AssignmentChange& a) {
    std::string mask(a.driving.size(), '0');
    for (std::size_t j = 0; j < a.driving.size(); ++j)
      if (a.driving[j]) mask[j] = '1';
    std::fprintf(assignments_, "%.6f,%c,%s\n", a.t_s, a.side == 0 ? 'L' : 'R', mask.c_str());
    std::fflush(assignments_);
  }

  std::FILE* trace_ = nullptr;
  std::FILE* assignments_ = nullptr;
};

}  // namespace

std::unique_ptr<RunFiles> open_csv_run_files(const std::string& trace_path,
                                             const std::string& assignments_path) {
  return std::make_unique<CsvRunFiles>(trace_path, assignments_path);
}

}  // namespace maptr::plant
