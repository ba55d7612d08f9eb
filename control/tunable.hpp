#pragma once
// A core's tunable parameter, declared beside the member it sets: its path in the scenario
// file, how to reach it in the core's tuning struct, the values allowed, the unit and one line
// of description. Each core lists its tunables next to its tuning struct (AgentTuning,
// GroupTuning, DiagnosisTuning, CentralTuning); the scenario's field table
// (config/scenario_fields.cpp) takes those lists as they are, so a field a core uses is added
// in the core's header (the member and its row) and nowhere else. Pure: no YAML, no files.
#include <variant>
#include <vector>

namespace maptr::control {

/// The values a number may take: from min to max, each end open or closed.
struct Bounds {
  double min = 0.0;
  double max = 0.0;
  bool min_open = false;
  bool max_open = false;
  static Bounds closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Bounds above(double lo, double hi) { return {lo, hi, true, false}; }  ///< (lo, hi]
};

template <class T>
struct Tunable {
  using Ref = std::variant<double& (*)(T&), int& (*)(T&), bool& (*)(T&)>;
  const char* path = "";  ///< "control.kp"
  Ref ref;                ///< the member in T
  Bounds bounds;          ///< numbers only
  const char* unit = "";  ///< SI; "1" for a count, "" for a flag
  const char* description = "";
};

template <class T>
Tunable<T> real_tunable(const char* path, double& (*ref)(T&), Bounds b, const char* unit, const char* desc) {
  return {path, ref, b, unit, desc};
}

template <class T>
Tunable<T> count_tunable(const char* path, int& (*ref)(T&), Bounds b, const char* desc) {
  return {path, ref, b, "1", desc};
}

template <class T>
Tunable<T> flag_tunable(const char* path, bool& (*ref)(T&), const char* desc) {
  return {path, ref, {}, "", desc};
}

}  // namespace maptr::control
