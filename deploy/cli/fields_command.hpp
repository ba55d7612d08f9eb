#pragma once
// `maptr fields [PREFIX]`: the scenario's fields (or, with --summary, summary.json's keys), as
// text or as the markdown of docs/SCENARIO.md and docs/SUMMARY.md.
#include <CLI/CLI.hpp>
#include <string>

namespace maptr::deploy::cli {

struct FieldsArgs {
  std::string prefix;
  bool markdown = false;
  bool summary = false;
};

CLI::App* add_fields_command(CLI::App& app, FieldsArgs& a);
int cmd_fields(const FieldsArgs& a);

}  // namespace maptr::deploy::cli
