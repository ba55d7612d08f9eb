// Linked into the hooked plant: MAPTR_TEST_PLANT_BLIND_TO (hooks.hpp).
#include <cstdlib>

#include "plant/plant_loop.hpp"
#include "tests/hooks/hooks.hpp"

namespace {

const bool installed = [] {
  const char* name = std::getenv(maptr::test_hooks::kPlantBlindEnv);
  if (name != nullptr) maptr::plant::hide_first_answer_writer_of(name);
  return true;
}();

}  // namespace
