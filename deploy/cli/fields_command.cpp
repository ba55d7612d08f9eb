#include "deploy/cli/fields_command.hpp"

#include <iostream>

#include "deploy/report/reference.hpp"

namespace maptr::deploy::cli {

CLI::App* add_fields_command(CLI::App& app, FieldsArgs& a) {
  auto* c = app.add_subcommand(
      "fields", "the scenario's fields (path, type, default, allowed values, unit, description); --summary: summary.json's keys");
  c->add_option("prefix", a.prefix, "only the fields whose path starts with this, e.g. control. or faults[]");
  c->add_flag("--markdown", a.markdown, "as a markdown table (docs/SCENARIO.md, docs/SUMMARY.md)");
  auto* summary = c->add_flag("--summary", a.summary,
                              "the keys of a run's summary.json instead of the scenario's fields");
  c->add_flag(
       "--environment", a.environment,
       "the environment variables MAPTR reads (who sets each, its values) instead of the scenario's fields")
      ->excludes(summary);
  c->add_flag(
       "--settings", a.settings,
       "the fixed settings of the processes that no scenario field sets (launcher, plant, group, Level 2)")
      ->excludes(summary)
      ->excludes("--environment");
  return c;
}

int cmd_fields(const FieldsArgs& a) {
  if (a.settings) {
    std::cout << report::settings_reference(report::all_settings(), a.markdown);
    return 0;
  }
  if (a.environment) {
    std::cout << report::environment_reference(a.markdown);
    return 0;
  }
  const int n = a.summary ? report::summary_key_count(a.prefix) : report::scenario_field_count(a.prefix);
  if (n == 0) {
    std::cerr << "maptr: fields " << a.prefix << ": no " << (a.summary ? "summary.json key" : "scenario field")
              << " starts with '" << a.prefix << "' (maptr fields" << (a.summary ? " --summary" : "")
              << " lists them all)\n";
    return 2;
  }
  std::cout << (a.summary ? report::summary_reference(a.prefix, a.markdown)
                          : report::scenario_reference(a.prefix, a.markdown));
  return 0;
}

}  // namespace maptr::deploy::cli
