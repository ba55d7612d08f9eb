// maptr_central: the central controller (trajectory -> wheel references, count relay).
#include "central/central_node.hpp"

int main(int argc, char** argv) {
  std::vector<std::string> store{"--name", "central"};
  std::vector<char*> args(argv, argv + argc);
  bool named = false;
  for (int i = 0; i < argc; ++i)
    if (std::string(argv[i]) == "--name") named = true;
  if (!named)
    for (auto& s : store) args.push_back(s.data());
  auto pa = maptr::comm::parse_process_args(static_cast<int>(args.size()), args.data(), "MAPTR central controller");
  auto log = maptr::comm::make_logger(pa);
  try {
    return maptr::central::CentralNode(pa, log).run();
  } catch (const std::exception& e) {
    log->critical("{}", e.what());
    return 1;
  }
}
