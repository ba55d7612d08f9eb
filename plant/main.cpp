// maptr_plant: the plant simulator; owns simulated time and runs the lock-step barrier.
#include "plant/plant_node.hpp"

int main(int argc, char** argv) {
  std::vector<std::string> store{"--name", "plant"};
  std::vector<char*> args(argv, argv + argc);
  bool named = false;
  for (int i = 0; i < argc; ++i)
    if (std::string(argv[i]) == "--name") named = true;
  if (!named)
    for (auto& s : store) args.push_back(s.data());
  auto pa = maptr::comm::parse_process_args(static_cast<int>(args.size()), args.data(), "MAPTR plant simulator");
  auto log = maptr::comm::make_logger(pa);
  try {
    return maptr::plant::PlantNode(pa, log).run();
  } catch (const std::exception& e) {
    log->critical("{}", e.what());
    return 1;
  }
}
