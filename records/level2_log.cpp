#include "records/level2_log.hpp"

namespace maptr::records {

namespace {
const char* const kFile = "level2 log";
const char* const kCount = "%.0f";
const char* const kReal = "%g";  // the default text form of a double in a C++ stream

std::vector<Level2Record> rows_of(const CsvFile& f) {
  return numeric_rows<Level2Record>(f, level2_columns(),
                                    [](Level2Record& r, const Level2Column& c, double v) { c.set(r, v); });
}

/// The column of member m, whatever its number type.
template <typename T>
Level2Column column(ColumnSpec spec, T Level2Record::*m) {
  return {std::move(spec), [m](const Level2Record& r) { return static_cast<double>(r.*m); },
          [m](Level2Record& r, double v) { r.*m = static_cast<T>(v); }};
}

std::vector<ColumnSpec> specs() {
  std::vector<ColumnSpec> s;
  for (const auto& c : level2_columns()) s.push_back(c.spec);
  return s;
}
}  // namespace

const std::vector<Level2Column>& level2_columns() {
  static const std::vector<Level2Column> cols = {
      column({"t_s", "s", kReal}, &Level2Record::t_s),
      column({"n_live", "", kCount}, &Level2Record::n_live),
      column({"n_other", "", kCount}, &Level2Record::n_other),
      column({"status", "", kCount}, &Level2Record::status),
      column({"relaxed", "", kReal}, &Level2Record::relaxed),
      column({"ipopt_n_active", "", kCount}, &Level2Record::ipopt_n_active),
      column({"oracle_n_active", "", kCount}, &Level2Record::oracle_n_active),
      column({"n_target", "", kCount}, &Level2Record::n_target),
      column({"solve_ms", "ms", kReal}, &Level2Record::solve_ms)};
  return cols;
}

std::string level2_log_path(const std::string& run_dir, int side) {
  return run_dir + "/level2-" + (side == 0 ? "L" : "R") + ".csv";
}

std::string format_level2_record(const Level2Record& r) {
  std::string out;
  for (const auto& c : level2_columns()) out += (out.empty() ? "" : ",") + format_value(c.spec, c.get(r));
  return out + "\n";
}

Level2LogWriter::Level2LogWriter(const std::string& path)
    : RowWriter(path, header_line(specs()), CsvLines::Mode::kAppend) {}

std::vector<Level2Record> read_level2_log(const std::string& path) {
  return rows_of(CsvFile::read(path, path.substr(path.find_last_of('/') + 1)));
}

std::vector<Level2Record> parse_level2_log(const std::string& text) {
  return rows_of(CsvFile::parse(text, kFile));
}

}  // namespace maptr::records
