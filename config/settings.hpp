#pragma once
// The settings outside the scenario: fixed thresholds of the processes (the launcher's waits and
// waves, the plant's bounds and deadlines, central's path follower, the group core's cruise band,
// the Level-2 solver's tolerances). Each struct that holds them keeps its values; one table,
// deploy/report/settings_table.cpp, lists them all as Settings, so that `maptr fields --settings`
// shows what a run runs with (docs/SETTINGS.md).
#include <chrono>
#include <string>
#include <vector>

namespace maptr::config {

struct Setting {
  std::string name;   ///< "<owner>.<field>", e.g. "plant.resend_s"
  std::string value;  ///< the value a run uses, as text
  std::string unit;   ///< "" for none
  std::string meaning;
};

/// A value as a person reads it: a number in its shortest exact form, a duration in ms.
std::string setting_value(double v);
std::string setting_value(int v);
std::string setting_value(bool v);
std::string setting_value(std::chrono::milliseconds v);

}  // namespace maptr::config
