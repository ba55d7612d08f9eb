#pragma once
// Sample validation: pure checks of the samples the plant takes, on the IDL types, free of
// the node. A sample is malformed when it breaks the rule of its type (idl/rules.hpp: a field
// out of its range, not finite, a mask of the wrong length, a count above a side's agents) or
// is physically impossible now (a voltage above the side's battery + tolerance); a well-formed
// sample still counts only for the tick it answers, and only once per sender and tick
// (OncePerTick).
#include "idl/maptr.h"
#include "plant/membership.hpp"

namespace maptr::plant {

/// Ranges a sample must respect (the node sets the battery voltages at each tick).
struct SampleLimits {
  int per_side = 0;                   ///< agents per side
  double battery_V[2] = {0.0, 0.0};   ///< each side's battery voltage at t_k, V
  double voltage_tolerance_V = 1e-9;  ///< allowed excess of an applied voltage over it, V
  double ref_bound_radps = 1e4;       ///< largest |wheel speed reference|, rad/s
  bool bidirectional = false;         ///< the driver applies [-V_B, V_B] (else [0, V_B])
  double v_bound_mps = 1e2;           ///< largest |body speed reference|, m/s
  double w_bound_radps = 1e2;         ///< largest |yaw rate reference|, rad/s
};

/// The rule of the sample's type, and for an agent reply a voltage its side's driver can apply
/// with the side's battery now (the battery at the current tick).
bool valid(const msg::AgentReply& r, const SampleLimits& l);
bool valid(const msg::GroupStatus& g, const SampleLimits& l);
bool valid(const msg::CentralCommand& c, const SampleLimits& l);
/// The rule of the sample's type alone: what any answer must meet, whichever tick it answers.
bool well_formed(const msg::AgentReply& r, const SampleLimits& l);
inline bool well_formed(const msg::GroupStatus& g, const SampleLimits& l) { return valid(g, l); }
inline bool well_formed(const msg::CentralCommand& c, const SampleLimits& l) { return valid(c, l); }
/// A membership event: the rule of its type, and its node kind, side and index are those of
/// the process it names (an agent's from its name, a group's side, central, the plant).
bool valid(const msg::MembershipEvent& e, const SampleLimits& l);

/// What a MembershipEvent says, for the DDS-free membership (kOther: a value this build does
/// not know).
LauncherEvent launcher_event(msg::MemberEvent kind);

/// True when the agent's state drives its motor over the tick (active, holding or stopping).
bool drives(const msg::AgentReply& r);

/// kForged: well-formed, but its writer is not the process the sample speaks for.
enum class Verdict { kAccepted, kMalformed, kOtherTick, kForged };

/// Whether a sample counts for tick k: well-formed, answering k, and possible at k. What is
/// physically possible is judged at the tick the sample answers: the limits are those of tick
/// k, so an answer to another tick (a copy of the previous tick's answer, whose full-duty
/// voltage was the battery's a tick ago) meets the rule of its type only.
template <class Sample>
Verdict check(const Sample& s, const SampleLimits& l, long long k) {
  if (!well_formed(s, l)) return Verdict::kMalformed;
  if (static_cast<long long>(s.tick()) != k) return Verdict::kOtherTick;
  if (!valid(s, l)) return Verdict::kMalformed;
  return Verdict::kAccepted;
}

/// At most one answer per sender and tick (one OncePerTick per agent, group and central): the
/// first admitted one is used; a copy (a follower answers a resent tick again with the same
/// sample; its count of rejected samples may have grown) is ignored; a different one for the
/// same tick is a conflict: not used, and counted. A participant that forged the sender's prefix
/// is the sender here: keyed on the process, not on the writer.
enum class Once { kFirst, kCopy, kConflict };

template <class Sample>
class OncePerTick {
 public:
  Once see(const Sample& s, long long k) {
    if (k != tick_) {
      tick_ = k;
      first_ = s;
      return Once::kFirst;
    }
    Sample same = s;
    same.rejected(first_.rejected());
    return same == first_ ? Once::kCopy : Once::kConflict;
  }

 private:
  long long tick_ = -1;
  Sample first_;
};

/// True for a copy of the answer to the previous tick (k - 1) from its own sender: a follower
/// answers a repeated tick again, and that copy may arrive once tick k is out. Not a reject.
inline bool repeated(Verdict v, unsigned long long sample_tick, long long k) {
  return v == Verdict::kOtherTick && static_cast<long long>(sample_tick) + 1 == k;
}

/// True for an answer to an earlier tick than k - 1 from its own sender: it came after the plant
/// gave up waiting for it (a missed deadline, a slow process). Not used, and counted as late,
/// apart from the malformed and forged samples.
inline bool late(Verdict v, unsigned long long sample_tick, long long k) {
  return v == Verdict::kOtherTick && static_cast<long long>(sample_tick) + 1 < k;
}

}  // namespace maptr::plant
