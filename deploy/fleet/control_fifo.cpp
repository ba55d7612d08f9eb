#include "deploy/fleet/control_fifo.hpp"

#include "config/scenario.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <sstream>
#include <stdexcept>

namespace maptr::deploy {

namespace fleet {

std::vector<Command> CommandLines::feed(std::string_view bytes) {
  buf_.append(bytes.data(), bytes.size());
  std::vector<Command> out;
  for (std::size_t nl; (nl = buf_.find('\n')) != std::string::npos;) {
    std::istringstream line(buf_.substr(0, nl));
    buf_.erase(0, nl + 1);
    Command c;
    line >> c.action >> c.target;
    c.valid = c.action == "kill" || c.action == "restart" || c.action == "pause" || c.action == "resume" ||
              config::is_host_action(c.action);
    out.push_back(c);
  }
  return out;
}

std::string control_fifo_path(const std::string& run_dir) { return run_dir + "/control"; }

ControlFifo::ControlFifo(const std::string& run_dir) : path_(control_fifo_path(run_dir)) {
  ::unlink(path_.c_str());
  if (mkfifo(path_.c_str(), 0600) == 0) fd_ = ::open(path_.c_str(), O_RDONLY | O_NONBLOCK);
}

ControlFifo::~ControlFifo() {
  if (fd_ >= 0) ::close(fd_);
  ::unlink(path_.c_str());
}

std::vector<Command> ControlFifo::read() {
  if (fd_ < 0) return {};
  std::string bytes;
  char buf[256];
  ssize_t n;
  while ((n = ::read(fd_, buf, sizeof(buf))) > 0) bytes.append(buf, static_cast<std::size_t>(n));
  return lines_.feed(bytes);
}

}  // namespace fleet

void send_command(const std::string& run_dir, const std::string& action, const std::string& target) {
  const std::string fifo = fleet::control_fifo_path(run_dir);
  const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
  if (fd < 0) throw std::runtime_error("no fleet is running in " + run_dir + " (no reader on " + fifo + ")");
  const std::string line = action + " " + target + "\n";
  const ssize_t n = ::write(fd, line.data(), line.size());
  ::close(fd);
  if (n != static_cast<ssize_t>(line.size())) throw std::runtime_error("could not write to " + fifo);
}

}  // namespace maptr::deploy
