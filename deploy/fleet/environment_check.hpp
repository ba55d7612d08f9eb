#pragma once
// The MAPTR_* environment variables that choose how a fleet runs, checked before anything
// starts: a value outside its set is bad input (exit 2, the variable and the value named), as
// a bad option is. Pure: the caller passes the lookup (std::getenv in the program).
#include <functional>
#include <optional>
#include <string>

#include "comm/posix/environment.hpp"

namespace maptr::deploy::fleet {

/// MAPTR_DDS_LOG: Fast DDS's log level in every process (comm/dds/dds.hpp, DdsOptions::dds_log).
inline constexpr const char* kDdsLogEnv = comm::kEnvDdsLog;

/// The first variable with a value outside its set, as "NAME=VALUE: expected ...", or nothing.
std::optional<std::string> environment_error(const std::function<const char*(const char*)>& getenv);

}  // namespace maptr::deploy::fleet
