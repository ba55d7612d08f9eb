// A stand-in for maptr_agent in the zygote tests (test_fleet_zygote.cpp): `zygote_probe --zygote
// FD` serves as a zygote; a copy, or the probe started with exec, prints what it runs with (one
// KEY=VALUE per line) and exits with the number of its first argument.
#include <sys/prctl.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "comm/posix/zygote.hpp"

namespace {

int probe_main(int argc, char** argv) {
  int pdeathsig = 0;
  prctl(PR_GET_PDEATHSIG, &pdeathsig);
  char comm[17] = {};
  prctl(PR_GET_NAME, comm);
  std::ifstream f("/proc/self/cmdline");
  std::stringstream cmdline;
  cmdline << f.rdbuf();
  const char* probe = std::getenv("MAPTR_PROBE");
  std::printf("pid=%d\nppid=%d\npgrp=%d\npdeathsig=%d\ncomm=%s\nforked=%d\nprobe=%s\nhome=%s\nargc=%d\n", getpid(),
              getppid(), getpgrp(), pdeathsig, comm, cmdline.str().find("--zygote") != std::string::npos,
              probe ? probe : "", std::getenv("HOME") ? "set" : "unset", argc);
  for (int i = 0; i < argc; ++i) std::printf("argv%d=%s\n", i, argv[i]);
  std::fflush(stdout);
  return argc > 1 ? std::atoi(argv[1]) : 0;
}

}  // namespace

int main(int argc, char** argv) {
  const int fd = maptr::comm::zygote_fd(argc, argv);
  if (fd >= 0) return maptr::comm::serve_zygote(fd, probe_main);
  return probe_main(argc, argv);
}
