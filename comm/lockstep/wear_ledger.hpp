#pragma once
// A group's wear ledger on the wire: the group sends it with every status, the plant keeps the
// last one of each side and gives it back, in a tick, to the group's next start (and writes it
// to RUN_DIR/ledger-<side>.json at the end). One map between control::Ledger and msg::WearLedger.
#include <vector>

#include "control/level3/ledger.hpp"
#include "idl/maptr.h"

namespace maptr::comm {

/// The ledger's message (its assignment travels beside it).
inline msg::WearLedger to_msg(const control::Ledger& l) {
  msg::WearLedger m;
  m.wear_m(l.wear_m);
  m.active_time_s(l.active_time_s);
  m.last_t(l.last_t);
  m.last_alloc_t(l.last_alloc_t);
  m.n_target(static_cast<uint16_t>(l.n_target));
  m.decisions(l.decisions);
  m.reallocations(l.reallocations);
  return m;
}

/// The ledger a message and its `assignment` describe.
inline control::Ledger ledger_of(const msg::WearLedger& m, const std::vector<uint8_t>& assignment) {
  control::Ledger l;
  l.wear_m = m.wear_m();
  l.active_time_s = m.active_time_s();
  l.last_t = m.last_t();
  l.last_alloc_t = m.last_alloc_t();
  l.n_target = m.n_target();
  l.assignment = assignment;
  l.decisions = m.decisions();
  l.reallocations = m.reallocations();
  return l;
}

}  // namespace maptr::comm
