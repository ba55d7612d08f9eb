// maptr_agent: one wheel-motor agent (Level 1). Usage: maptr_agent --id L3 --config ... --run-dir ...
// `maptr_agent --zygote FD` serves the launcher as a zygote (comm/posix/zygote.hpp): it forks loaded
// copies of itself, each of which runs as `maptr_agent --id ...` would.
#include <iostream>

#include "agent/agent_node.hpp"
#include "comm/posix/zygote.hpp"

namespace {

int agent_main(int argc, char** argv) {
  // --id is the agent's name (also its process name); rewrite it as --name for the shared parser.
  std::vector<char*> args(argv, argv + argc);
  std::string name_flag = "--name";
  for (auto& a : args)
    if (std::string(a) == "--id") a = name_flag.data();
  auto pa = maptr::comm::parse_process_args(static_cast<int>(args.size()), args.data(), "MAPTR wheel agent");
  int side = 0, index = 0;
  if (!maptr::config::parse_agent_name(pa.name, side, index) || index >= pa.scenario.robot.per_side()) {
    std::cerr << "maptr_agent: --id = " << pa.name << ": must be L<i> or R<i> with i < "
              << pa.scenario.robot.per_side() << "\n";
    return 2;
  }
  auto log = maptr::comm::make_logger(pa);
  try {
    return maptr::agent::AgentNode(pa, side, index, log).run();
  } catch (const std::exception& e) {
    log->critical("{}", e.what());
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int fd = maptr::comm::zygote_fd(argc, argv);
  if (fd == -2) {
    std::cerr << "maptr_agent: --zygote = " << argv[2] << ": expected a file descriptor number\n";
    return 2;
  }
  if (fd >= 0) return maptr::comm::serve_zygote(fd, agent_main);
  return agent_main(argc, argv);
}
