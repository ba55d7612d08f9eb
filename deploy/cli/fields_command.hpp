#pragma once
// `maptr fields [PREFIX]`: the scenario's fields (with --summary summary.json's keys, with
// --environment the environment variables), as text or as the markdown of docs/SCENARIO.md,
// docs/SUMMARY.md and docs/ENVIRONMENT.md.
#include <CLI/CLI.hpp>
#include <string>

namespace maptr::deploy::cli {

struct FieldsArgs {
  std::string prefix;
  bool markdown = false;
  bool summary = false;
  bool environment = false;
  bool settings = false;
};

CLI::App* add_fields_command(CLI::App& app, FieldsArgs& a);
int cmd_fields(const FieldsArgs& a);

}  // namespace maptr::deploy::cli
