#include "comm/posix/zygote.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <thread>

namespace maptr::comm {

namespace {

constexpr std::size_t kMaxRequest = 1 << 20;  // argv and environment of one copy
constexpr auto kReparentWait = std::chrono::seconds(5);

std::vector<std::string> split_nul(const std::string& s) {
  std::vector<std::string> out;
  std::size_t from = 0;
  while (from < s.size()) {
    const std::size_t end = s.find('\0', from);
    if (end == std::string::npos) return {};  // every field ends with a NUL
    out.push_back(s.substr(from, end - from));
    from = end + 1;
  }
  return out;
}

/// In the copy: becomes the requester's child, sets itself up as exec would have left it, and
/// runs main. Never returns.
[[noreturn]] void run_copy(int fd, ZygoteRequest& r, const std::function<int(int, char**)>& main_fn) {
  close(fd);
  // The middle process exits at once; the kernel then hands this process to the nearest child
  // subreaper among its ancestors, the requester. The parent-death signal is armed only then:
  // armed before, the middle process's exit would fire it.
  const auto until = std::chrono::steady_clock::now() + kReparentWait;
  while (getppid() != r.parent && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::microseconds(50));
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != r.parent) _exit(1);  // the requester is gone, or is no subreaper
  setpgid(0, 0);  // a Ctrl-C in the terminal reaches the launcher only; it ends the children
  const int out = open(r.out_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (out >= 0) {
    dup2(out, 1);
    dup2(out, 2);
    close(out);
  }
  clearenv();
  for (auto& e : r.env) putenv(e.data());  // r lives until exit
  const std::string& prog = r.argv.front();
  const std::string base = prog.substr(prog.rfind('/') + 1);
  prctl(PR_SET_NAME, base.substr(0, 15).c_str());
  std::vector<char*> argv;
  for (auto& a : r.argv) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::exit(main_fn(static_cast<int>(r.argv.size()), argv.data()));
}

/// Forks a copy for r; its pid once it is the requester's child, or -errno.
int32_t fork_copy(int fd, ZygoteRequest& r, const std::function<int(int, char**)>& main_fn) {
  int p[2];
  if (pipe2(p, O_CLOEXEC) != 0) return -errno;
  const pid_t middle = fork();
  if (middle < 0) {
    const int e = errno;
    close(p[0]);
    close(p[1]);
    return -e;
  }
  if (middle == 0) {
    close(p[0]);
    const pid_t copy = fork();
    if (copy == 0) {
      close(p[1]);
      run_copy(fd, r, main_fn);
    }
    const int32_t v = copy < 0 ? -errno : copy;
    (void)!write(p[1], &v, sizeof v);
    _exit(0);
  }
  close(p[1]);
  int32_t v = -EIO;
  if (read(p[0], &v, sizeof v) != static_cast<ssize_t>(sizeof v)) v = -EIO;
  close(p[0]);
  while (waitpid(middle, nullptr, 0) < 0 && errno == EINTR) {
  }
  return v;
}

}  // namespace

std::string encode_zygote_request(const ZygoteRequest& r) {
  std::string m;
  const auto put = [&m](const std::string& s) {
    m += s;
    m += '\0';
  };
  put(std::to_string(r.parent));
  put(r.out_path);
  put(std::to_string(r.argv.size()));
  for (const auto& a : r.argv) put(a);
  for (const auto& e : r.env) put(e);
  return m;
}

std::optional<ZygoteRequest> decode_zygote_request(const std::string& message) {
  const auto f = split_nul(message);
  if (f.size() < 4) return std::nullopt;
  const auto number = [](const std::string& s, long& out) {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return false;
    out = std::stol(s);
    return true;
  };
  long parent = 0, argc = 0;
  if (!number(f[0], parent) || parent <= 1 || !number(f[2], argc) || argc < 1 ||
      static_cast<std::size_t>(argc) > f.size() - 3 || f[1].empty() || f[3].empty())
    return std::nullopt;
  ZygoteRequest r;
  r.parent = static_cast<pid_t>(parent);
  r.out_path = f[1];
  r.argv.assign(f.begin() + 3, f.begin() + 3 + argc);
  r.env.assign(f.begin() + 3 + argc, f.end());
  for (const auto& e : r.env)
    if (e.find('=') == std::string::npos || e.front() == '=') return std::nullopt;
  return r;
}

int serve_zygote(int fd, const std::function<int(int, char**)>& main_fn) {
  prctl(PR_SET_NAME, "maptr_zygote");  // not counted as an agent by the bench's /proc readings
  std::string buf(kMaxRequest, '\0');
  for (;;) {
    const ssize_t n = recv(fd, buf.data(), buf.size(), 0);
    if (n == 0) return 0;
    if (n < 0) {
      if (errno == EINTR) continue;
      return 1;
    }
    auto r = decode_zygote_request(buf.substr(0, static_cast<std::size_t>(n)));
    const int32_t v = r ? fork_copy(fd, *r, main_fn) : -EINVAL;
    if (send(fd, &v, sizeof v, MSG_NOSIGNAL) != static_cast<ssize_t>(sizeof v)) return 1;
  }
}

int zygote_fd(int argc, char** argv) {
  if (argc != 3 || std::strcmp(argv[1], kZygoteFlag) != 0) return -1;
  const std::string s = argv[2];
  if (s.empty() || s.size() > 4 || s.find_first_not_of("0123456789") != std::string::npos) return -2;
  return std::stoi(s);
}

}  // namespace maptr::comm
