// maptr_discovery: the fleet's Fast DDS discovery server, a process of its own.
//
// The launcher starts it before any other process and ends it after the last one; if it dies
// during a run, the launcher starts it again on the same address and the clients re-register
// (their participants ping a server they lost until it answers). It carries metatraffic only.
// It talks to its clients over UDP only, whatever the fleet's data transport
// (comm/dds/participant_qos.cpp says why). A UDP-only server of an earlier build aborted once
// on Fast DDS 2.9.1's send-statistics assertion (`OutputTrafficManager.hpp:87`, a list its
// comment calls not thread-safe); a server that dies is started again by the launcher, and
// the matches made stay.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <thread>

#include "comm/dds/dds.hpp"
#include "comm/dds/process.hpp"
#include "comm/posix/environment.hpp"

int main(int argc, char** argv) {
  CLI::App app{"MAPTR discovery server (started and stopped by `maptr run`)"};
  maptr::comm::DdsOptions o = maptr::comm::options_from_env();
  app.add_option(
      "--address", o.discovery_server,
      std::string("HOST:PORT to listen on, or the fleet's list HOST:PORT,HOST:PORT,... (default: ") +
          maptr::comm::kEnvDiscoveryServer + ")");
  app.add_option("--index", o.server_index,
                 "which entry of the list this server is (its GUID prefix; it connects to the others)");
  app.add_option("--domain", o.domain, std::string("DDS domain (default: ") + maptr::comm::kEnvDomain + ")");
  CLI11_PARSE(app, argc, argv);
  if (o.discovery_server.empty()) {
    std::fprintf(stderr, "maptr_discovery: no address: give --address HOST:PORT or set %s\n",
                 maptr::comm::kEnvDiscoveryServer);
    return 2;
  }
  o.is_server = true;
  auto& stop = maptr::comm::stop_flag();
  try {
    const auto servers = maptr::comm::split_servers(o.discovery_server);
    const std::string own =
        o.server_index >= 0 && o.server_index < static_cast<int>(servers.size()) ? servers[o.server_index] : "?";
    maptr::comm::Participant p("discovery", o);
    std::fprintf(stderr, "maptr_discovery: serving domain %d on %s\n", o.domain, own.c_str());
    while (!stop.load()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "maptr_discovery: %s\n", e.what());
    return 1;
  }
  return 0;
}
