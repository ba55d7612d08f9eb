#include "records/trace.hpp"

#include "model/kinematics.hpp"

namespace maptr::records {

namespace {
const char* const kFile = "trace.csv";
const char* const kCount = "%.0f";  // whole numbers held as double
const char* const kSix = "%.6g";
const char* const kNine = "%.9g";

std::vector<TraceRow> rows_of(const CsvFile& f) {
  return numeric_rows<TraceRow>(f, trace_columns(),
                                [](TraceRow& r, const TraceColumn& c, double v) { r.*c.value = v; });
}
}  // namespace

double TraceRow::ref_speed_mps(double wheel_radius_m) const {
  return model::speed_from_rates({ref_L_radps, ref_R_radps}, wheel_radius_m);
}

const std::vector<TraceColumn>& trace_columns() {
  static const std::vector<TraceColumn> cols = {
      {{"tick", "", kCount}, &TraceRow::tick},
      {{"t_s", "s", "%.6f"}, &TraceRow::t_s},
      {{"x_m", "m", kNine}, &TraceRow::x_m},
      {{"y_m", "m", kNine}, &TraceRow::y_m},
      {{"theta_rad", "rad", kNine}, &TraceRow::theta_rad},
      {{"v_x_mps", "m/s", kNine}, &TraceRow::v_x_mps},
      {{"w_radps", "rad/s", kNine}, &TraceRow::w_radps},
      {{"phidot_L_radps", "rad/s", kNine}, &TraceRow::phidot_L_radps},
      {{"phidot_R_radps", "rad/s", kNine}, &TraceRow::phidot_R_radps},
      {{"ref_L_radps", "rad/s", kNine}, &TraceRow::ref_L_radps},
      {{"ref_R_radps", "rad/s", kNine}, &TraceRow::ref_R_radps},
      {{"V_L_mean_V", "V", kNine}, &TraceRow::V_L_mean_V},
      {{"V_R_mean_V", "V", kNine}, &TraceRow::V_R_mean_V},
      {{"I_L_A", "A", kNine}, &TraceRow::I_L_A},
      {{"I_R_A", "A", kNine}, &TraceRow::I_R_A},
      {{"eff_L", "", kSix}, &TraceRow::eff_L},
      {{"eff_R", "", kSix}, &TraceRow::eff_R},
      {{"battery_V_L", "V", kNine}, &TraceRow::battery_V_L},
      {{"battery_V_R", "V", kNine}, &TraceRow::battery_V_R},
      {{"discharge_L_mAh", "mAh", kNine}, &TraceRow::discharge_L_mAh},
      {{"discharge_R_mAh", "mAh", kNine}, &TraceRow::discharge_R_mAh},
      {{"n_active_L", "", kCount}, &TraceRow::n_active_L},
      {{"n_active_R", "", kCount}, &TraceRow::n_active_R},
      {{"n_live_L", "", kCount}, &TraceRow::n_live_L},
      {{"n_live_R", "", kCount}, &TraceRow::n_live_R},
      {{"energy_J", "J", kNine}, &TraceRow::energy_J},
      {{"distance_m", "m", kNine}, &TraceRow::distance_m},
      {{"ref_x_m", "m", kNine}, &TraceRow::ref_x_m},
      {{"ref_y_m", "m", kNine}, &TraceRow::ref_y_m},
      {{"ref_theta_rad", "rad", kNine}, &TraceRow::ref_theta_rad},
      {{"cross_track_m", "m", kNine}, &TraceRow::cross_track_m}};
  return cols;
}

std::string trace_header() {
  std::vector<ColumnSpec> specs;
  for (const auto& c : trace_columns()) specs.push_back(c.spec);
  return header_line(specs);
}

std::string format_trace_row(const TraceRow& r) {
  std::string out;
  bool first = true;
  for (const auto& c : trace_columns()) {
    if (!first) out += ',';
    out += format_value(c.spec, r.*c.value);
    first = false;
  }
  return out + "\n";
}

TraceWriter::TraceWriter(const std::string& path) : RowWriter(path, trace_header(), CsvLines::Mode::kNew) {}

std::vector<TraceRow> read_trace(const std::string& path) { return rows_of(CsvFile::read(path, kFile)); }

std::vector<TraceRow> parse_trace(const std::string& text) { return rows_of(CsvFile::parse(text, kFile)); }

}  // namespace maptr::records
