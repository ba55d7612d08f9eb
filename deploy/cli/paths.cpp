#include "deploy/cli/paths.hpp"

#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "comm/posix/environment.hpp"
#include "config/scenario.hpp"

namespace maptr::deploy::cli {

namespace fs = std::filesystem;

std::string source_dir() { return MAPTR_SOURCE_DIR; }

std::string default_scenario() { return source_dir() + "/deploy/scenarios/default.yaml"; }

std::string bin_dir(const char* argv0) {
  std::error_code ec;
  fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) self = fs::absolute(argv0);
  return self.parent_path().string();
}

std::string unique_run_dir(const std::string& base, const std::string& name) {
  std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", std::localtime(&now));
  std::string dir = base + "/" + stamp + "-" + name;
  for (int i = 2; fs::exists(dir); ++i) dir = base + "/" + stamp + "-" + name + "-" + std::to_string(i);
  return dir;
}

int resolve_domain(int option) {
  if (option >= 0) return option;
  const char* env = std::getenv(comm::kEnvDomain);
  return env ? std::atoi(env) : 0;
}

bool input_read(const std::function<void()>& read) {
  try {
    read();
    return true;
  } catch (const config::ScenarioError& e) {
    std::cerr << "maptr: " << e.what() << "\n";
  } catch (const std::invalid_argument& e) {  // model::ParamError and the options' own
    std::cerr << "maptr: " << e.what() << "\n";
  }
  return false;
}

}  // namespace maptr::deploy::cli
