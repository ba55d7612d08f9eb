#pragma once
// What every subcommand of the maptr CLI resolves the same way: the default scenario, the folder
// of the executables, a fresh run folder and the DDS domain.
#include <functional>
#include <string>

namespace maptr::deploy::cli {

/// The highest DDS domain id `--domain` accepts.
inline constexpr int kMaxDomain = 232;

/// deploy/scenarios/default.yaml of the source tree.
std::string default_scenario();

/// The project's source tree.
std::string source_dir();

/// The folder of the running executable (maptr_plant & co. are next to it).
std::string bin_dir(const char* argv0);

/// BASE/<date>-<time>-NAME, with -2, -3, ... when it exists.
std::string unique_run_dir(const std::string& base, const std::string& name);

/// The DDS domain: `option` when given (>= 0), else $MAPTR_DOMAIN, else 0.
int resolve_domain(int option);

/// Runs `read`, a command's reading of its input; a bad scenario, robot or option it throws
/// (config::ScenarioError, model::ParamError, std::invalid_argument) is printed as
/// "maptr: <what>" and gives false.
bool input_read(const std::function<void()>& read);

}  // namespace maptr::deploy::cli
