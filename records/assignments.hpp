#pragma once
// assignments.csv: which agents of a side drive, one row each time the set changes. `driving`
// is a mask over the side's agents in index order ('1': drives over [t_s, next change)).
#include <cstdio>
#include <string>
#include <vector>

#include "records/csv.hpp"

namespace maptr::records {

struct AssignmentRecord {
  double t_s = 0;       ///< simulated time of the change, s
  char side = 'L';      ///< 'L' or 'R'
  std::string driving;  ///< '0'/'1' per agent of the side
};

/// The columns of assignments.csv, in file order.
const std::vector<ColumnSpec>& assignment_columns();

/// One change as a line of assignments.csv (with its newline).
std::string format_assignment(const AssignmentRecord& r);

/// Writes assignments.csv: the header at construction, then one flushed line per change.
/// Throws RecordError when `path` cannot be written.
struct AssignmentsWriter : RowWriter<AssignmentRecord, format_assignment> {
  explicit AssignmentsWriter(const std::string& path);
};

/// Reads assignments.csv by column name; throws RecordError naming a missing column, a
/// malformed time or a side that is neither L nor R.
std::vector<AssignmentRecord> read_assignments(const std::string& path);
std::vector<AssignmentRecord> parse_assignments(const std::string& text);

}  // namespace maptr::records
