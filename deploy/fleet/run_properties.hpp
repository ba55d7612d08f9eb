#pragma once
// Properties of a finished run, checked over its history (`maptr check`): the summary, the
// trace and whether the recording is there, free of files, DDS and processes. Each property
// gives a verdict, the first tick where it broke and a one-line reason. The table of
// properties (name, argument, definition) is the one reference: `maptr check --list
// --markdown` writes docs/PROPERTIES.md from it.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "records/trace.hpp"

namespace maptr::deploy::properties {

/// What a run left that the properties read (loaded by the caller).
struct History {
  nlohmann::json summary;               ///< summary.json
  std::vector<records::TraceRow> trace;  ///< trace.csv
  bool recording_file = false;          ///< run.mcap exists
  std::string record = "all";           ///< what the scenario asked run.mcap to hold (all, plant, none)
  double path_tolerance_m = 0.5;        ///< the scenario's control.path_tolerance_m
};

/// One property of the table.
struct Property {
  std::string name;
  std::string arg;  ///< "" when it takes none, else its meaning with its unit
  std::optional<double> default_arg;  ///< the argument when none is given (nullopt: from the run)
  double arg_min = 0, arg_max = 0;    ///< the argument's range
  std::string definition;
};

/// Every property, in the order they are checked.
const std::vector<Property>& table();

/// A property to check: its name and argument.
struct Spec {
  std::string name;
  std::optional<double> arg;
  /// NAME or NAME:ARG as given.
  std::string text() const;
};

/// Parses NAME or NAME:ARG. Throws std::invalid_argument naming the value and the rule (an
/// unknown name lists the known ones; an argument out of range gives the range).
Spec parse_spec(const std::string& text);

/// Every property of the table with its default argument.
std::vector<Spec> all_specs();

/// A property's verdict over one run.
struct Verdict {
  std::string property;  ///< Spec::text()
  bool holds = true;
  long long tick = -1;  ///< first tick where it broke (-1: holds, or broke at no tick)
  double t_s = -1;      ///< simulated time of that tick, s
  std::string reason;   ///< why it broke, or what was checked when it holds
};

/// Checks one property over a history.
Verdict evaluate(const Spec& spec, const History& h);

/// The table as text or as the markdown of docs/PROPERTIES.md.
std::string reference(bool markdown);

}  // namespace maptr::deploy::properties
