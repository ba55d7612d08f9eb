#pragma once
// The launcher's control FIFO, RUN_DIR/control: another terminal writes lines
// "kill NAME", "restart NAME", "pause NAME" or "resume NAME" (`maptr kill|restart|pause|resume
// NAME`), or "kill-host|partition|heal hN" (`maptr kill-host|partition|heal hN`); the launcher
// applies them at once.
#include <string>
#include <string_view>
#include <vector>

namespace maptr::deploy::fleet {

struct Command {
  std::string action, target;
  bool valid = false;  ///< the action is kill, restart, pause, resume, kill-host, partition or heal
};

/// Splits a byte stream into commands, one per complete line; a partial line waits for the
/// rest. Pure.
class CommandLines {
 public:
  std::vector<Command> feed(std::string_view bytes);

 private:
  std::string buf_;
};

/// The reading end: created (and any older FIFO replaced) on construction, removed on
/// destruction. Without a FIFO (mkfifo failed) it reads nothing.
class ControlFifo {
 public:
  explicit ControlFifo(const std::string& run_dir);
  ~ControlFifo();
  ControlFifo(const ControlFifo&) = delete;
  ControlFifo& operator=(const ControlFifo&) = delete;

  /// Commands written since the last call (never blocks).
  std::vector<Command> read();

 private:
  std::string path_;
  int fd_ = -1;
  CommandLines lines_;
};

/// Path of the control FIFO of the fleet running in run_dir.
std::string control_fifo_path(const std::string& run_dir);

}  // namespace maptr::deploy::fleet

namespace maptr::deploy {
/// Sends "kill NAME" or "restart NAME" to the launcher running in run_dir (through its
/// control FIFO). Throws std::runtime_error when no fleet runs there.
void send_command(const std::string& run_dir, const std::string& action, const std::string& target);
}  // namespace maptr::deploy
