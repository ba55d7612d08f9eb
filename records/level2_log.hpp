#pragma once
// level2-L.csv / level2-R.csv: every Level-2 decision of one group controller (appended: a
// restarted controller continues its file). Status codes are control::Level2Status values.
#include <fstream>
#include <string>
#include <vector>

#include "control/level2/status.hpp"
#include "records/csv.hpp"

namespace maptr::records {

/// One Level-2 decision.
struct Level2Record {
  double t_s = 0;               ///< simulated time of the decision, s
  double n_live = 0;            ///< live agents of the side
  double n_other = 0;           ///< active agents of the other side
  double status = 0;            ///< a control::Level2Status code
  double relaxed = 0;           ///< Ipopt's relaxed (continuous) optimum
  double ipopt_n_active = -1;   ///< the integer Ipopt's optimum led to
  double oracle_n_active = -1;  ///< the exhaustive search's choice, -1 when not checked
  double n_target = 0;          ///< the N_a the side runs
  double solve_ms = 0;          ///< Ipopt's solve time, ms
};

/// A column of the Level-2 log and where its value lives in a Level2Record.
struct Level2Column {
  ColumnSpec spec;
  double Level2Record::*value;
};

/// The columns of level2-<side>.csv, in file order.
const std::vector<Level2Column>& level2_columns();

/// The file of one side in a run folder: RUN_DIR/level2-L.csv or level2-R.csv.
std::string level2_log_path(const std::string& run_dir, int side);

/// One decision as a line of the log (with its newline).
std::string format_level2_record(const Level2Record& r);

/// Appends decisions to a side's log; writes the header when the file is new.
class Level2LogWriter {
 public:
  explicit Level2LogWriter(const std::string& path);
  /// False when the file could not be opened (the controller runs on without its log).
  explicit operator bool() const { return static_cast<bool>(out_); }
  void write(const Level2Record& r);

 private:
  std::ofstream out_;
};

/// Reads a side's log by column name; throws RecordError naming a missing column or a
/// malformed number.
std::vector<Level2Record> read_level2_log(const std::string& path);
std::vector<Level2Record> parse_level2_log(const std::string& text);

}  // namespace maptr::records
