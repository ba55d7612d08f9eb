#include "plant/ledger_keeper.hpp"

#include "comm/lockstep/side.hpp"
#include "comm/lockstep/wear_ledger.hpp"
#include "records/ledger_file.hpp"

namespace maptr::plant {

void LedgerKeeper::on_status(int side, const msg::GroupStatus& g) {
  Kept& k = kept_[side];
  k.heard = true;
  k.handing = false;
  k.entry.side(comm::to_msg_side(side));
  k.entry.assignment(g.active());
  k.entry.ledger(g.ledger());
}

void LedgerKeeper::on_started(int side, long participant) {
  Kept& k = kept_[side];
  k.handing = k.heard;  // a group never heard from left nothing to go on from
  k.entry.for_participant(participant > 0 ? static_cast<int32_t>(participant) : -1);
}

void LedgerKeeper::fill(msg::PlantTick& t) const {
  t.ledgers().clear();
  for (const Kept& k : kept_)
    if (k.handing) t.ledgers().push_back(k.entry);
}

void LedgerKeeper::save(const std::string& run_dir) const {
  for (int s = 0; s < 2; ++s)
    if (kept_[s].heard)
      records::save_ledger(records::ledger_path(run_dir, s),
                           comm::ledger_of(kept_[s].entry.ledger(), kept_[s].entry.assignment()));
}

}  // namespace maptr::plant
