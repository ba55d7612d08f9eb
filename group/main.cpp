// maptr_group: a group controller (Levels 2 and 3). Usage: maptr_group --side L|R --config ... --run-dir ...
#include <iostream>

#include "group/group_node.hpp"

int main(int argc, char** argv) {
  // --side L|R also names the process group-L / group-R.
  std::vector<std::string> store;
  std::vector<char*> args;
  std::string side;
  for (int i = 0; i < argc; ++i) {
    if (std::string(argv[i]) == "--side" && i + 1 < argc) {
      side = argv[++i];
      continue;
    }
    args.push_back(argv[i]);
  }
  if (side != "L" && side != "R") {
    std::cerr << "maptr_group: --side = " << side << ": must be L or R\n";
    return 2;
  }
  store = {"--name", "group-" + side};
  for (auto& s : store) args.push_back(s.data());
  auto pa =
      maptr::comm::parse_process_args(static_cast<int>(args.size()), args.data(), "MAPTR group controller");
  auto log = maptr::comm::make_logger(pa);
  try {
    return maptr::group::GroupNode(pa, side == "L" ? 0 : 1, log).run();
  } catch (const std::exception& e) {
    log->critical("{}", e.what());
    return 1;
  }
}
