// What the recorder's verdict costs: every message of a run.mcap judged again
// (recorder::judge_sample, as the recorder's file thread judges each sample it writes),
// REPEAT times over the whole file; prints the median time per sample and per tick.
//
//   maptr_verdict_cost RUN/run.mcap [--repeat N]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <set>
#include <vector>

#include "comm/dds/dds.hpp"
#include "recorder/recorder.hpp"
#include "recorder/sample_verdict.hpp"
#include "records/mcap.hpp"

namespace mcap = maptr::records::mcap;
namespace rec = maptr::recorder;

int main(int argc, char** argv) {
  CLI::App app{"Times the recorder's verdict on every message of a run.mcap"};
  std::string path;
  int repeat = 11;
  app.add_option("file", path, "a run's run.mcap")->required()->check(CLI::ExistingFile);
  app.add_option("--repeat", repeat, "passes over the file; the median is printed")->check(CLI::Range(1, 1000));
  CLI11_PARSE(app, argc, argv);
  const mcap::File f = mcap::read_file(path);
  // The fleet's size: the agents that wrote replies the recorder took.
  std::set<std::string> agents;
  std::size_t ticks = 0;
  for (const auto& [id, c] : f.channels) {
    const auto process = c.metadata.find(rec::kProcessKey);
    if (c.topic == maptr::comm::topic::kAgentReply && process != c.metadata.end() && !process->second.empty())
      agents.insert(process->second);
  }
  for (const auto& m : f.messages)
    ticks += f.channels.at(m.channel_id).topic == maptr::comm::topic::kTick;
  if (f.messages.empty() || agents.empty()) {
    std::fprintf(stderr, "verdict_cost: %s holds no agent replies\n", path.c_str());
    return 2;
  }
  std::vector<double> pass_ns;
  std::size_t taken = 0;
  for (int r = 0; r < repeat; ++r) {
    taken = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto& m : f.messages) {
      const auto& c = f.channels.at(m.channel_id);
      taken += rec::judge_sample(c.topic, m.data, c.metadata.at(rec::kProcessKey), static_cast<int>(agents.size())) ==
               rec::Verdict::kTaken;
    }
    pass_ns.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count());
  }
  std::nth_element(pass_ns.begin(), pass_ns.begin() + repeat / 2, pass_ns.end());
  const double median = pass_ns[repeat / 2];
  std::printf("%zu messages (%zu taken) of %zu ticks, %zu agents; judged %d times: median %.0f ns per sample, %.2f "
              "us per tick\n",
              f.messages.size(), taken, ticks, agents.size(), repeat, median / f.messages.size(),
              ticks ? median / ticks / 1000.0 : 0.0);
  return 0;
}
