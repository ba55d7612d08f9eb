// libFuzzer target: the scenario parser on arbitrary bytes. The only accepted outcomes are a
// scenario or a ScenarioError; any other exception escapes and crashes the run (a finding),
// as do the sanitizers' reports.
#include <cstddef>
#include <cstdint>
#include <string>

#include "config/scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  maptr::config::Scenario s;
  try {
    s = maptr::config::parse_scenario(text, "fuzz.yaml");
  } catch (const maptr::config::ScenarioError&) {
    return 0;
  }
  // What parses must write out and read back identical (a refusal here is a finding too).
  const std::string y = maptr::config::to_yaml(s);
  if (maptr::config::to_yaml(maptr::config::parse_scenario(y, "fuzz-resolved.yaml")) != y) __builtin_trap();
  return 0;
}
