#pragma once
// summary.json's keys, documented once: every key a run writes (the plant's plant.json under
// `plant`), with its type, unit and meaning. `maptr fields --summary` and docs/SUMMARY.md show them.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace maptr::records {

/// One key of summary.json. `path` is dotted; a list's entries are `[]`; a key that stands for a
/// name chosen at run time is written in angle brackets: `rejected_samples.<process>`,
/// `plant.tick_timing_us.<part>.median`, `level2.<side>.decisions`.
struct SummaryField {
  std::string path;
  std::string type;         ///< number, integer, text, bool, object, list, "number|null" ...
  std::string unit;         ///< SI unit ("s", "J", "m", "m/J", "mAh", "V", "%", "ms", "µs", "kB", "rad", "m/s"), "1" for counts/pure numbers, "" for text/bool
  std::string description;  ///< one line, what it means for a user reading a run's results
};

/// Every key, in the order summary.json is documented (top-level first, then nested groups).
const std::vector<SummaryField>& summary_fields();

/// True when a concrete key path (e.g. "rejected_samples.L3", "failures[].at_s",
/// "plant.tick_timing_us.barrier.p90") matches a table path: segments separated by '.', a
/// segment "<...>" matches any one segment (any name), "[]" suffixes must match exactly.
bool summary_path_matches(const std::string& pattern, const std::string& path);

/// The key paths of a summary.json that no table entry matches (the tests' check that every key
/// a run writes is documented). An object or list that is a table entry itself (`recording`
/// when null, `discovery_rematched[]`) is not looked into further.
std::vector<std::string> undocumented_summary_keys(const nlohmann::json& summary);

namespace detail {
/// The keys of the plant's results (records/summary_plant_fields.cpp).
std::vector<SummaryField> plant_keys_run();
std::vector<SummaryField> plant_keys_faults();
}  // namespace detail

}  // namespace maptr::records
