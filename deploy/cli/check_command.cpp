#include "deploy/cli/check_command.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "deploy/fleet/run_history.hpp"
#include "records/junit.hpp"
#include "records/result_table.hpp"

namespace maptr::deploy::cli {

namespace {
constexpr int kExitOk = 0, kExitBroken = 1, kExitBadInput = 2;
namespace props = deploy::properties;

}  // namespace

CLI::App* add_check_command(CLI::App& app, CheckArgs& a) {
  auto* c = app.add_subcommand("check", "check properties of a finished run over its summary, trace and recording");
  c->add_option("run", a.run, "the run folder");
  c->add_option("--property", a.properties,
                "NAME or NAME:ARG (repeatable; default: every property with its default argument; --list names them)");
  c->add_option("--junit", a.junit, "also write a JUnit XML file, one test case per property");
  c->add_flag("--list", a.list, "list the properties and what each checks");
  c->add_flag("--markdown", a.markdown, "with --list: as the markdown of docs/PROPERTIES.md");
  return c;
}

std::vector<props::Spec> property_specs(const std::vector<std::string>& values) {
  std::vector<props::Spec> specs;
  for (const auto& p : values) {
    try {
      specs.push_back(props::parse_spec(p));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--property ") + e.what());
    }
  }
  return specs;
}

std::vector<props::Verdict> check_run(const std::string& run_dir, const std::vector<props::Spec>& specs,
                                      std::vector<records::JunitCase>* cases) {
  const auto h = props::load_history(run_dir);
  std::vector<props::Verdict> out;
  for (const auto& s : specs) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto v = props::evaluate(s, h);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::string where = v.holds || v.tick < 0 ? "" : "tick " + std::to_string(v.tick);
    std::printf("%-24s %-6s %-12s %s\n", v.property.c_str(), v.holds ? "holds" : "BROKE", where.c_str(),
                v.reason.c_str());
    if (cases) cases->push_back({v.property, "maptr.check", dt, v.holds ? "" : (where.empty() ? "" : where + ": ") + v.reason});
    out.push_back(v);
  }
  std::fflush(stdout);
  return out;
}

std::string write_repro(const std::string& run_dir, const std::vector<std::string>& what_broke,
                        const std::string& trace_sha256, const std::string& fallback_scenario) {
  namespace fs = std::filesystem;
  std::string scenario = run_dir + "/scenario.yaml";
  if (!fs::exists(scenario)) scenario = fallback_scenario;
  std::ifstream in(scenario);
  if (scenario.empty() || !in) return "";
  std::stringstream text;
  text << in.rdbuf();
  fs::create_directories(run_dir);
  const std::string path = run_dir + "/repro.yaml";
  records::write_text_file(path, props::repro_yaml(text.str(), what_broke, trace_sha256));
  return path;
}

int cmd_check(const CheckArgs& a) {
  if (a.list) {
    std::cout << props::reference(a.markdown);
    return kExitOk;
  }
  if (a.run.empty()) {
    std::fprintf(stderr, "maptr check: RUN: a run folder is needed (or --list)\n");
    return kExitBadInput;
  }
  std::vector<props::Spec> specs;
  try {
    specs = property_specs(a.properties);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "maptr check: %s\n", e.what());
    return kExitBadInput;
  }
  if (specs.empty()) specs = props::all_specs();
  std::vector<records::JunitCase> cases;
  std::vector<props::Verdict> verdicts;
  try {
    verdicts = check_run(a.run, specs, &cases);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "maptr check: %s\n", e.what());
    return kExitBadInput;
  }
  int broken = 0;
  for (const auto& v : verdicts) broken += !v.holds;
  std::printf("%zu properties, %d broke (%s)\n", specs.size(), broken, a.run.c_str());
  if (!a.junit.empty()) {
    try {
      records::write_text_file(a.junit, records::junit_xml("maptr check " + a.run, cases));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "maptr check: --junit %s: %s\n", a.junit.c_str(), e.what());
      return kExitBadInput;
    }
  }
  return broken ? kExitBroken : kExitOk;
}

}  // namespace maptr::deploy::cli
