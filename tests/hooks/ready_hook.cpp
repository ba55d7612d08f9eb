// Linked into every hooked process: MAPTR_TEST_SILENT_ONCE and MAPTR_TEST_ABORT_ONCE (hooks.hpp).
#include <cstdlib>
#include <fstream>
#include <string>

#include "comm/dds/process.hpp"
#include "tests/hooks/hooks.hpp"

namespace {

/// True when the hook `env` names this process and its file is not there yet (it is then created).
bool hooked_once(const char* env, const std::string& name) {
  const char* hook = std::getenv(env);
  if (hook == nullptr) return false;
  const std::string h = hook;
  const auto colon = h.find(':');
  if (colon == std::string::npos || h.substr(0, colon) != name) return false;
  const std::string path = h.substr(colon + 1);
  if (std::ifstream(path).good()) return false;
  std::ofstream(path) << name << "\n";
  return true;
}

bool gate(const std::string& name) {
  if (hooked_once(maptr::test_hooks::kAbortOnceEnv, name)) std::abort();
  return !hooked_once(maptr::test_hooks::kSilentOnceEnv, name);
}

const bool installed = [] {
  maptr::comm::set_ready_gate(&gate);
  return true;
}();

}  // namespace
