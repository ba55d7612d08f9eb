#pragma once
// What every MAPTR process shares at start-up: its command line (scenario, run folder, name,
// DDS options), its spdlog logger (one file per process in the run folder), and a stop flag
// set by SIGTERM/SIGINT.
#include <spdlog/logger.h>

#include <atomic>
#include <memory>
#include <string>

#include "comm/dds.hpp"
#include "deploy/scenario.hpp"

namespace maptr::comm {

struct ProcessArgs {
  std::string config;     ///< resolved scenario file
  std::string run_dir;    ///< results folder
  std::string name;       ///< process name (L3, group-L, central, plant)
  DdsOptions dds;
  config::Scenario scenario;
};

/// Parses `--config FILE --run-dir DIR --name NAME [--domain D] [--discovery-server H:P]`
/// (DDS options default to the environment the launcher sets). Exits 2 with a message on
/// bad input.
ProcessArgs parse_process_args(int argc, char** argv, const std::string& what);

/// A logger named after the process writing to RUN_DIR/logs/NAME.log (and stderr for errors).
std::shared_ptr<spdlog::logger> make_logger(const ProcessArgs& a);

/// Installs SIGTERM/SIGINT handlers that set the returned flag.
std::atomic<bool>& stop_flag();

}  // namespace maptr::comm
