#include "deploy/cli/fuzz_command.hpp"

#include "deploy/cli/paths.hpp"

namespace maptr::deploy::cli {

namespace {
/// `--seconds`: at most a day per target.
constexpr int kMaxFuzzSeconds = 86400;
}  // namespace

CLI::App* add_fuzz_command(CLI::App& app, FuzzArgs& a) {
  auto* c = app.add_subcommand("fuzz", "run the libFuzzer targets (scenario parser, DDS sample checks)");
  c->add_option("--target", a.o.target, "scenario, samples or all")
      ->check(CLI::IsMember({"scenario", "samples", "all"}));
  c->add_option("--seconds", a.o.seconds, "seconds per target")
      ->required()
      ->check(CLI::Range(1, kMaxFuzzSeconds));
  c->add_option("--out", a.o.out, "output folder (default runs/<date>-fuzz)");
  c->add_option("--fuzz-build", a.o.fuzz_build, "the clang build of tests/fuzz (default: build/fuzz)");
  return c;
}

int cmd_fuzz(FuzzArgs a, const std::string& bin_dir) {
  a.o.source_dir = source_dir();
  if (a.o.fuzz_build.empty()) a.o.fuzz_build = bin_dir + "/../fuzz";
  if (a.o.out.empty()) a.o.out = unique_run_dir("runs", "fuzz");
  return run_fuzz(a.o);
}

}  // namespace maptr::deploy::cli
