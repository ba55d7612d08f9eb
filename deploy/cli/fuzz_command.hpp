#pragma once
// `maptr fuzz [--target scenario|samples|all] --seconds N`: long runs of the fuzz targets.
#include <CLI/CLI.hpp>
#include <string>

#include "deploy/studies/fuzz/fuzz.hpp"

namespace maptr::deploy::cli {

struct FuzzArgs {
  FuzzOptions o;
};

CLI::App* add_fuzz_command(CLI::App& app, FuzzArgs& a);
int cmd_fuzz(FuzzArgs a, const std::string& bin_dir);

}  // namespace maptr::deploy::cli
