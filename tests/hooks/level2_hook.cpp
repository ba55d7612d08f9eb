// Linked into the hooked group controller: MAPTR_TEST_LEVEL2_DELAY_MS (hooks.hpp). A value that
// is not an integer from 0 to kMaxLevel2DelayMs ends the process with exit code 2 before main.
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <string>

#include "group/group_node.hpp"
#include "tests/hooks/hooks.hpp"

namespace {

const bool installed = [] {
  using maptr::test_hooks::kLevel2DelayEnv;
  using maptr::test_hooks::kMaxLevel2DelayMs;
  const char* v = std::getenv(kLevel2DelayEnv);
  if (v == nullptr || *v == '\0') return true;
  const std::string text(v);
  std::size_t used = 0;
  long ms = -1;
  try {
    ms = std::stol(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || ms < 0 || ms > kMaxLevel2DelayMs) {
    std::cerr << kLevel2DelayEnv << " = " << text.substr(0, 80) << ": must be an integer from 0 to "
              << kMaxLevel2DelayMs << " (ms)\n";
    std::exit(2);
  }
  maptr::group::set_level2_pause(std::chrono::milliseconds(ms));
  return true;
}();

}  // namespace
