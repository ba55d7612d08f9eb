#include "deploy/report/reference.hpp"

#include <charconv>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "comm/posix/environment.hpp"
#include "config/scenario.hpp"
#include "records/summary_fields.hpp"

namespace maptr::deploy::report {

namespace {

std::string type_name(config::FieldType t) {
  switch (t) {
    case config::FieldType::kReal: return "real";
    case config::FieldType::kInteger: return "integer";
    case config::FieldType::kBool: return "bool";
    case config::FieldType::kText: return "text";
  }
  return "?";
}

/// The values a field takes, in words: a range, a set of choices, a rule.
std::string allowed(const config::FieldInfo& f) {
  std::string out;
  if (f.type == config::FieldType::kReal || f.type == config::FieldType::kInteger) out = f.range.describe();
  if (f.type == config::FieldType::kBool) out = "true, false";
  for (std::size_t i = 0; i < f.choices.size(); ++i) out += (i ? ", " : "") + f.choices[i];
  if (!f.rule.empty()) out += (out.empty() ? "" : "; ") + f.rule;
  return out;
}

/// A default as a person reads it: a number in its shortest exact form (0.2, not the
/// 0.20000000000000001 that to_yaml() writes to read back bit for bit), text as it is.
std::string shown(const std::string& yaml) {
  if (yaml.empty()) return yaml;
  char* end = nullptr;
  const double v = std::strtod(yaml.c_str(), &end);
  if (end != yaml.c_str() + yaml.size() || yaml.find_first_of("0123456789") == std::string::npos) return yaml;
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, r.ptr);
}

/// A markdown cell: '|' escaped, never empty.
std::string cell(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out.empty() ? "–" : out;
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

std::vector<config::FieldInfo> scenario_fields(const std::string& prefix) {
  std::vector<config::FieldInfo> out;
  for (const auto& f : config::reference_field_table())
    if (starts_with(f.path, prefix)) out.push_back(f);
  return out;
}

std::vector<records::SummaryField> summary_keys(const std::string& prefix) {
  std::vector<records::SummaryField> out;
  for (const auto& f : records::summary_fields())
    if (starts_with(f.path, prefix)) out.push_back(f);
  return out;
}

constexpr const char* kScenarioHead =
    "# Scenario fields\n\n"
    "Every field a scenario file (YAML) may hold, generated from the field table in\n"
    "`config/scenario_fields.cpp` by `maptr fields --markdown` (do not edit by hand: a unit test\n"
    "fails when this file differs from the table). A field left out takes its default; a value\n"
    "outside its allowed range is refused before anything starts, naming the file, the field, the\n"
    "value and the rule (exit 2). `trajectory.segments[]` and `faults[]` are lists: each entry is a\n"
    "mapping of the fields shown under them. `maptr run` options that set fields: `--agents`,\n"
    "`--gross-kg`, `--motor`, `--driver`, `--mode`, `--duration`, `--tick-hz`, `--trace-every`,\n"
    "`--record`, `--record-compression`, `--tick-filter`, `--plant-priority`, `--speed` (every moving segment), and\n"
    "`--kill`/`--restart`/`--pause`/`--resume`/`--fault`/`--clear`/`--kill-host`/`--partition`/`--heal`\n"
    "(entries of `faults`). Example scenarios: `deploy/scenarios/`. What a run writes:\n"
    "[SUMMARY.md](SUMMARY.md).\n\n"
    "Input only: read from files, not written back into the run folder's scenario.yaml\n"
    "(e.g. an arc's `radius_m` becomes its `yaw_rate_rad_s`).\n\n";

constexpr const char* kSummaryHead =
    "# summary.json\n\n"
    "Every key of a run's `summary.json` (the launcher's record of the run, with the plant's\n"
    "`plant.json` under `plant`), generated from the key table in `records/summary_fields.cpp` by\n"
    "`maptr fields --summary --markdown` (do not edit by hand: a unit test fails when this file\n"
    "differs from the table, and a fleet test fails when a run writes a key the table lacks).\n"
    "`[]` marks the entries of a list; `<name>` a key named at run time (a process, a side L/R, a\n"
    "topic). `scenario` is the scenario's name; the scenario as run is the run folder's\n"
    "`scenario.yaml`, whose fields are in [SCENARIO.md](SCENARIO.md).\n\n";

constexpr const char* kEnvironmentHead =
    "# Environment variables\n\n"
    "Every environment variable MAPTR reads, generated from the table in `comm/posix/environment.hpp` by\n"
    "`maptr fields --environment --markdown` (do not edit by hand: a unit test fails when this file\n"
    "differs from the table, and another when the product names a `MAPTR_*` variable the table\n"
    "lacks). A user may set those marked `user` (`maptr run` refuses a `MAPTR_DDS_LOG` or\n"
    "`MAPTR_AGENT_START` outside its set before anything starts, exit 2). The launcher sets the\n"
    "others for the processes it starts: they are how a fleet's settings reach each process.\n\n";

constexpr const char* kSettingsHead =
    "# Settings\n\n"
    "The fixed settings of the processes, which no scenario field sets: the launcher's waits, waves\n"
    "and leases, the plant's bounds and deadlines, central's path follower, the group core's cruise\n"
    "band and the Level-2 solver's tolerances, with the values a run uses. Generated by `maptr fields "
    "--settings\n"
    "--markdown` from one table (`deploy/report/settings_table.cpp`); a unit test fails when this\n"
    "file differs, or when a struct holds a setting the table lacks. Wall-clock waits only bound how\n"
    "long a process waits; none of them changes what the simulation computes. The scenario's fields:\n"
    "[SCENARIO.md](SCENARIO.md); the environment: [ENVIRONMENT.md](ENVIRONMENT.md).\n\n";

}  // namespace

std::string settings_reference(const std::vector<config::Setting>& settings, bool markdown) {
  std::ostringstream os;
  if (markdown) os << kSettingsHead << "| setting | value | unit | meaning |\n|---|---|---|---|\n";
  for (const auto& s : settings) {
    if (markdown)
      os << "| `" << s.name << "` | " << cell(s.value) << " | " << cell(s.unit) << " | " << cell(s.meaning)
         << " |\n";
    else
      os << s.name << "  " << s.value << (s.unit.empty() || s.unit == "1" ? "" : " " + s.unit) << "\n    "
         << s.meaning << "\n";
  }
  return os.str();
}

std::string environment_reference(bool markdown) {
  std::ostringstream os;
  if (markdown) os << kEnvironmentHead << "| variable | set by | values | meaning |\n|---|---|---|---|\n";
  for (const auto& v : comm::kEnvironment) {
    if (markdown)
      os << "| `" << v.name << "` | " << v.set_by << " | " << cell(v.values) << " | " << cell(v.meaning)
         << " |\n";
    else
      os << v.name << "  set by " << v.set_by << "  values " << v.values << "\n    " << v.meaning << "\n";
  }
  return os.str();
}

std::string scenario_reference(const std::string& prefix, bool markdown) {
  std::ostringstream os;
  if (markdown) {
    os << kScenarioHead << "| field | type | default | allowed | unit | description |\n|---|---|---|---|---|---|\n";
    for (const auto& f : scenario_fields(prefix))
      os << "| `" << f.path << "` | " << type_name(f.type) << " | "
         << (f.input_only ? std::string("(input only)") : cell(shown(f.default_value))) << " | " << cell(allowed(f)) << " | "
         << cell(f.unit) << " | " << cell(f.description) << " |\n";
    return os.str();
  }
  for (const auto& f : scenario_fields(prefix)) {
    os << f.path << "  " << type_name(f.type);
    if (!f.unit.empty() && f.unit != "1") os << " [" << f.unit << "]";
    os << "  default " << (f.input_only ? std::string("(input only)") : f.default_value.empty() ? "(none)" : shown(f.default_value));
    if (const std::string a = allowed(f); !a.empty()) os << "  allowed " << a;
    os << "\n    " << f.description << "\n";
  }
  return os.str();
}

std::string summary_reference(const std::string& prefix, bool markdown) {
  std::ostringstream os;
  if (markdown) {
    os << kSummaryHead << "| key | type | unit | description |\n|---|---|---|---|\n";
    for (const auto& f : summary_keys(prefix))
      os << "| `" << f.path << "` | " << cell(f.type) << " | " << cell(f.unit) << " | " << cell(f.description) << " |\n";
    return os.str();
  }
  for (const auto& f : summary_keys(prefix)) {
    os << f.path << "  " << f.type;
    if (!f.unit.empty() && f.unit != "1") os << " [" << f.unit << "]";
    os << "\n    " << f.description << "\n";
  }
  return os.str();
}

int scenario_field_count(const std::string& prefix) { return static_cast<int>(scenario_fields(prefix).size()); }
int summary_key_count(const std::string& prefix) { return static_cast<int>(summary_keys(prefix).size()); }

}  // namespace maptr::deploy::report
