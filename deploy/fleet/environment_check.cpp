#include "deploy/fleet/environment_check.hpp"

#include <vector>

#include "deploy/fleet/zygote_client.hpp"

namespace maptr::deploy::fleet {

std::optional<std::string> environment_error(const std::function<const char*(const char*)>& getenv) {
  struct Choice {
    const char* name;
    std::vector<std::string> values;
  };
  const Choice choices[] = {{kAgentStartEnv, {"zygote", "exec"}}, {kDdsLogEnv, {"error", "warning", "info"}}};
  for (const auto& c : choices) {
    const char* v = getenv(c.name);
    if (!v) continue;
    bool ok = false;
    std::string expected;
    for (std::size_t i = 0; i < c.values.size(); ++i) {
      ok = ok || c.values[i] == v;
      expected += (i == 0 ? "" : i + 1 == c.values.size() ? " or " : ", ") + c.values[i];
    }
    if (!ok) return std::string(c.name) + "=" + v + ": expected " + expected;
  }
  return std::nullopt;
}

}  // namespace maptr::deploy::fleet
