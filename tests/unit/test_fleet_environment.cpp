#include <gtest/gtest.h>

#include <map>
#include <string>

#include "deploy/fleet/environment_check.hpp"

using maptr::deploy::fleet::environment_error;

namespace {
auto lookup(const std::map<std::string, std::string>& env) {
  return [env](const char* name) -> const char* {
    const auto it = env.find(name);
    return it == env.end() ? nullptr : it->second.c_str();
  };
}
}  // namespace

TEST(Environment, UnsetAndKnownValuesAreAccepted) {
  EXPECT_FALSE(environment_error(lookup({})));
  EXPECT_FALSE(environment_error(lookup({{"MAPTR_AGENT_START", "exec"}, {"MAPTR_DDS_LOG", "warning"}})));
  EXPECT_FALSE(environment_error(lookup({{"MAPTR_AGENT_START", "zygote"}, {"MAPTR_DDS_LOG", "info"}})));
}

TEST(Environment, AValueOutsideItsSetNamesTheVariableTheValueAndTheChoices) {
  EXPECT_EQ(environment_error(lookup({{"MAPTR_AGENT_START", "fork"}})).value_or(""),
            "MAPTR_AGENT_START=fork: expected zygote or exec");
  EXPECT_EQ(environment_error(lookup({{"MAPTR_DDS_LOG", "WARNING"}})).value_or(""),
            "MAPTR_DDS_LOG=WARNING: expected error, warning or info");
  EXPECT_EQ(environment_error(lookup({{"MAPTR_DDS_LOG", ""}})).value_or(""),
            "MAPTR_DDS_LOG=: expected error, warning or info");
}
