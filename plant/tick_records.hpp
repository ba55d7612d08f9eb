#pragma once
// Where the plant writes its per-tick records: the trace (one row per traced tick) and the
// assignments (one row per change of a side's set of driving agents). One small interface,
// so that the CSV files below can be swapped for another writer without touching the node.
#include <memory>
#include <string>

#include "plant_core/plant_core.hpp"

namespace maptr::plant {

class RunFiles {
 public:
  virtual ~RunFiles() = default;
  /// Writes everything one tick produced (flushed, so an aborted run keeps what it produced).
  virtual void write(const plant_core::TickRecord& rec) = 0;
};

/// The trace (records/trace.hpp) at trace_path and, when assignments_path is not empty, the
/// assignment rows (records/assignments.hpp) at assignments_path. Throws records::RecordError
/// (a std::runtime_error) when a file cannot be opened.
std::unique_ptr<RunFiles> open_csv_run_files(const std::string& trace_path,
                                             const std::string& assignments_path);

}  // namespace maptr::plant
