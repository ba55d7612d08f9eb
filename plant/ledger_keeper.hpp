#pragma once
// The groups' wear ledgers as their last taken statuses carried them. A group's process keeps
// no state on a disk: when the launcher starts a group again (a restart, or a failover to another
// host), every tick carries the kept ledger of its side, addressed to the new start's DDS
// participant, until that start answers; it goes on from there (group/group_node.cpp). At the
// end the kept ledgers are the run's RUN_DIR/ledger-<side>.json (records/ledger_file.hpp).
#include <string>

#include "idl/maptr.h"

namespace maptr::plant {

class LedgerKeeper {
 public:
  /// A status of `side`'s group that the plant took: its ledger is kept, and a hand-over to a
  /// new start ends (only the new start's statuses are taken once it is announced).
  void on_status(int side, const msg::GroupStatus& g);
  /// The launcher started `side`'s group again as DDS participant `participant` (< 0: not said).
  void on_started(int side, long participant);
  /// Puts the hand-overs under way into tick `t` (none: its list is emptied).
  void fill(msg::PlantTick& t) const;
  /// Writes RUN_DIR/ledger-<side>.json for each side whose group was heard from; throws
  /// std::runtime_error when a file cannot be written.
  void save(const std::string& run_dir) const;

 private:
  struct Kept {
    bool heard = false;     ///< a status of the side was taken
    bool handing = false;   ///< a new start waits for it
    msg::KeptLedger entry;  ///< side, for_participant, assignment and ledger
  };
  Kept kept_[2];
};

}  // namespace maptr::plant
