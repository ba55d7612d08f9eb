#pragma once
// level2-L.csv / level2-R.csv: every Level-2 decision of one group controller (appended: a
// restarted controller continues its file): one row per control::Level2Decision, status codes
// control::Level2Status values.
#include <functional>
#include <string>
#include <vector>

#include "control/level2/status.hpp"
#include "records/csv.hpp"

namespace maptr::records {

/// One Level-2 decision, a row of the log: the group core's own record.
using Level2Record = control::Level2Decision;

/// A column of the Level-2 log and how a Level2Record gives and takes its value.
struct Level2Column {
  ColumnSpec spec;
  std::function<double(const Level2Record&)> get;
  std::function<void(Level2Record&, double)> set;
};

/// The columns of level2-<side>.csv, in file order.
const std::vector<Level2Column>& level2_columns();

/// The file of one side in a run folder: RUN_DIR/level2-L.csv or level2-R.csv.
std::string level2_log_path(const std::string& run_dir, int side);

/// One decision as a line of the log (with its newline).
std::string format_level2_record(const Level2Record& r);

/// Appends decisions to a side's log; writes the header when the file is new. Throws
/// RecordError when `path` cannot be written.
struct Level2LogWriter : RowWriter<Level2Record, format_level2_record> {
  explicit Level2LogWriter(const std::string& path);
};

/// Reads a side's log by column name; throws RecordError naming a missing column or a
/// malformed number.
std::vector<Level2Record> read_level2_log(const std::string& path);
std::vector<Level2Record> parse_level2_log(const std::string& text);

}  // namespace maptr::records
