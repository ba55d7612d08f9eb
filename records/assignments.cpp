#include "records/assignments.hpp"

namespace maptr::records {

namespace {
const char* const kFile = "assignments.csv";

std::vector<AssignmentRecord> rows_of(const CsvFile& f) {
  const auto& cols = assignment_columns();
  const std::size_t c_t = f.column(cols[0].name), c_side = f.column(cols[1].name),
                    c_drv = f.column(cols[2].name);
  std::vector<AssignmentRecord> out(f.rows());
  for (std::size_t i = 0; i < f.rows(); ++i) {
    out[i].t_s = f.number(i, c_t);
    const std::string& side = f.text(i, c_side);
    if (side != "L" && side != "R")
      throw RecordError(std::string(kFile) + " line " + std::to_string(i + 2) + ", column 'side': '" + side +
                        "' is neither L nor R");
    out[i].side = side[0];
    out[i].driving = f.text(i, c_drv);
  }
  return out;
}
}  // namespace

const std::vector<ColumnSpec>& assignment_columns() {
  static const std::vector<ColumnSpec> cols = {
      {"t_s", "s", "%.6f"}, {"side", "", "%c"}, {"driving", "", "%s"}};
  return cols;
}

std::string format_assignment(const AssignmentRecord& r) {
  const auto& cols = assignment_columns();
  return format_value(cols[0], r.t_s) + "," + r.side + "," + r.driving + "\n";
}

AssignmentsWriter::AssignmentsWriter(const std::string& path)
    : RowWriter(path, header_line(assignment_columns()), CsvLines::Mode::kNew) {}

std::vector<AssignmentRecord> read_assignments(const std::string& path) {
  return rows_of(CsvFile::read(path, kFile));
}

std::vector<AssignmentRecord> parse_assignments(const std::string& text) {
  return rows_of(CsvFile::parse(text, kFile));
}

}  // namespace maptr::records
