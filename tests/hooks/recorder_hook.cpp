// Linked into the hooked launcher: MAPTR_TEST_RECORDER_DEAF_TO (hooks.hpp).
#include <cstdlib>

#include "recorder/recorder.hpp"
#include "tests/hooks/hooks.hpp"

namespace {

const bool installed = [] {
  const char* name = std::getenv(maptr::test_hooks::kRecorderDeafEnv);
  if (name != nullptr) maptr::recorder::hide_first_answer_writer_of(name);
  return true;
}();

}  // namespace
