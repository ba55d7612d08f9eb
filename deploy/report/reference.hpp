#pragma once
// The references a user reads instead of the source: every scenario field (config's field
// table), every summary.json key (records' key table) and every environment variable
// (comm/posix/environment.hpp), as text for the terminal or as a markdown table. `maptr fields` prints
// them; docs/SCENARIO.md, docs/SUMMARY.md and docs/ENVIRONMENT.md are generated from them (a unit
// test fails when a committed file differs).
#include <string>
#include <vector>

#include "config/settings.hpp"

namespace maptr::deploy::report {

/// The scenario fields whose path starts with `prefix` ("" for all): path, type, default,
/// allowed values, unit and description. Markdown: the whole docs/SCENARIO.md.
std::string scenario_reference(const std::string& prefix, bool markdown);
/// The summary.json keys whose path starts with `prefix`. Markdown: the whole docs/SUMMARY.md.
std::string summary_reference(const std::string& prefix, bool markdown);
/// Every environment variable MAPTR reads. Markdown: the whole docs/ENVIRONMENT.md.
std::string environment_reference(bool markdown);
/// Every setting outside the scenario: the launcher's, the plant's, the cores'.
std::vector<config::Setting> all_settings();
/// The settings outside the scenario (config/settings.hpp). Markdown: the whole docs/SETTINGS.md.
std::string settings_reference(const std::vector<config::Setting>& settings, bool markdown);
/// How many scenario fields (or summary keys) start with `prefix`.
int scenario_field_count(const std::string& prefix);
int summary_key_count(const std::string& prefix);

}  // namespace maptr::deploy::report
