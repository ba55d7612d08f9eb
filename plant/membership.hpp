#pragma once
// Who the plant waits for: every agent, both groups and central, each live or not, with its
// answer to the current tick, its DDS writer (learnt from its first sample) and whether it is
// rejoining after a restart or a pause. Three sources change it: the launcher's events (a
// process died; a restarted process is matched and ready; a process was paused (SIGSTOP) or
// resumed (SIGCONT) at a fault gate), DDS liveliness (a writer's lease expired: only
// the member's current writer counts) and the barrier's wall-clock deadline. A member declared
// dead is re-admitted as soon as it answers the current tick. Each change is logged with the
// simulated time and the wall clock (ms since the epoch).
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "records/plant_results.hpp"

namespace maptr::plant {

enum class Role { kAgent, kGroup, kCentral };

struct MemberId {
  Role role = Role::kAgent;
  int side = 0;   ///< agents and groups: 0 = left, 1 = right
  int index = 0;  ///< agents: index within the side
  bool operator==(const MemberId& o) const { return role == o.role && side == o.side && index == o.index; }
};

/// The process name of a member ("L3", "group-R", "central").
std::string member_name(const MemberId& id);

/// Identity of a DDS writer (its instance handle's bytes and whether it was ever set).
struct WriterId {
  std::array<uint8_t, 16> bytes{};
  bool set = false;
  bool operator==(const WriterId& o) const { return set == o.set && bytes == o.bytes; }
};

struct Member {
  bool live = true;       ///< waited for at each tick
  bool answered = false;  ///< answered the current tick
  WriterId writer{};      ///< DDS writer, learnt from its first sample
  bool writer_known = false;
  int participant = -1;    ///< DDS participant id the launcher gave its latest start (-1: not said)
  bool rejoining = false;  ///< restarted or resumed (launcher): expected from the next tick, not yet heard
  bool paused = false;     ///< paused by the launcher: not waited for, its lease loss expected
  bool excused = false;    ///< an idle agent not due to answer the current tick (comm/lockstep/lockstep.hpp)
};

/// One membership change: who, what, simulated time (s) and wall clock (ms since the epoch).
/// A process joining or leaving, as plant.json keeps it.
using MembershipRecord = records::MembershipEvent;

/// What a launcher event says (kOther: any other kind, only counted).
enum class LauncherEvent { kDied, kStarted, kPaused, kResumed, kOther };

class Membership {
 public:
  /// wall_ms: the wall clock, ms since the epoch (stamps each record).
  Membership(int per_side, std::function<double()> wall_ms);

  int per_side() const { return per_side_; }
  /// Every member: agents L0.., R0.., then group-L, group-R, central.
  const std::vector<MemberId>& all() const { return all_; }
  Member& at(const MemberId& id);
  const Member& at(const MemberId& id) const;
  /// The member of a process name, if any.
  std::optional<MemberId> find(const std::string& name) const;

  /// Simulated time stamped on the records from now on, s.
  void set_time(double t_s) { t_s_ = t_s; }
  /// A new tick: nobody has answered it yet. excused(side, index): the agent need not answer it
  /// (idle and not due); a rejoining agent is always waited for.
  void begin_tick(const std::function<bool(int, int)>& excused = nullptr);

  /// Launcher event number seq about process `name`: a death ends the wait for it; a started
  /// (restarted) process is waited for from now on, and its old writer no longer counts; a
  /// paused process is out from now on (its ticks say so, and the loss of its lease is no
  /// news); a resumed one is waited for again from now on, on the same writer. The caller has
  /// checked the event (plant/validation.hpp); `name` is a member or the plant. False (nothing
  /// applied, the sequence unchanged) for seq not above launcher_seq() or kind kOther.
  /// `participant`: for kStarted, the participant id of the new start (0 or -1: not said).
  bool on_launcher(uint64_t seq, LauncherEvent kind, const std::string& name, int participant = -1);
  /// Highest launcher event number applied so far.
  uint64_t launcher_seq() const { return launcher_seq_; }
  /// A writer of `role`'s topic lost its liveliness: the member whose current writer it is dies
  /// (unless the launcher paused it or it is rejoining: a lease that ran out during a pause).
  void on_liveliness_lost(Role role, const WriterId& writer);
  /// Whether an answer of `id` on `writer` (of participant `writer_participant`, -1 unknown) is
  /// its own: from the participant the launcher gave its latest start when it said which (on a
  /// plain domain); else the writer of its first answer since that start.
  bool takes(const MemberId& id, const WriterId& writer, int writer_participant = -1) const {
    const Member& m = at(id);
    if (m.participant >= 0 && writer_participant >= 0) return writer_participant == m.participant;
    return !m.writer_known || m.writer == writer;
  }
  /// member answered the current tick on `writer`: live again (a rejoin is recorded once).
  void on_answer(const MemberId& id, const WriterId& writer);
  /// The barrier's deadline passed: every live member that has not answered is dead; returns
  /// how many agents were declared dead.
  int on_deadline();

  /// 1 per live agent of a side.
  std::vector<uint8_t> live_mask(int side) const;
  /// 1 per member paused by the launcher, in the order of all().
  std::vector<uint8_t> paused_mask() const;
  int live_count(int side) const;
  const std::vector<MembershipRecord>& records() const { return records_; }

 private:
  void mark_dead(const MemberId& id, const char* why);
  void record(const MemberId& id, const char* what);

  int per_side_;
  std::function<double()> wall_ms_;
  std::vector<Member> agents_[2];
  Member groups_[2];
  Member central_;
  std::vector<MemberId> all_;
  double t_s_ = 0.0;
  uint64_t launcher_seq_ = 0;
  std::vector<MembershipRecord> records_;
};

}  // namespace maptr::plant
