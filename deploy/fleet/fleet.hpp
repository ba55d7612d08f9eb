#pragma once
// One fleet run, the DDS side of the launcher: the launcher's participant (a client of the
// fleet's discovery server), the children, the launch waves, the run loop (the plant's clock,
// the control FIFO, the fault gates, deaths), the end of every process and the summary.
// launch() drives it step by step.
#include <spdlog/logger.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "comm/dds/dds.hpp"
#include "deploy/fleet/children.hpp"
#include "deploy/fleet/config.hpp"
#include "deploy/fleet/control_fifo.hpp"
#include "deploy/fleet/discovery.hpp"
#include "deploy/fleet/fault_execution.hpp"
#include "deploy/fleet/fleet_recorder.hpp"
#include "deploy/fleet/host_placement.hpp"
#include "deploy/fleet/launcher.hpp"
#include "deploy/fleet/launcher_participant.hpp"
#include "deploy/fleet/plant_clock.hpp"
#include "deploy/fleet/ready_check.hpp"
#include "deploy/fleet/registry.hpp"
#include "deploy/fleet/stall_watch.hpp"
#include "deploy/fleet/summary_build.hpp"
#include "deploy/fleet/waves.hpp"
#include "deploy/fleet/zygote_client.hpp"
#include "idl/maptrPubSubTypes.h"

namespace maptr::deploy::fleet {

/// The GUID prefix of the participant of the writer behind a DDS instance handle.
GuidPrefix writer_prefix(const eprosima::fastrtps::rtps::InstanceHandle_t& h);

class Fleet : private FaultTargets {
 public:
  /// Sets up the run directory, the discovery server and the launcher's participant.
  Fleet(const LaunchOptions& o, spdlog::logger& log, const FleetConfig& cfg = {});
  ~Fleet();

  /// Starts the first wave and opens the control FIFO.
  void start_processes();
  /// Waits until every process is ready (starting the next waves); false if the run aborted.
  bool discover();
  /// Sends CONTROL_START.
  void start_run();
  /// Runs until the plant ends (or the run is interrupted).
  void run();
  /// Ends every process, then the discovery server; removes the fleet's shared-memory ports.
  void end();
  /// Builds summary.json and writes it to the run directory.
  nlohmann::json summary();

 private:
  using Clock = std::chrono::steady_clock;
  /// The discovery server of this machine, or one per host (not on a secure domain).
  void make_discovery_servers();
  /// The transport the fleet's participants use and the environment that tells them.
  void choose_transport();
  void make_children();
  void start_recorder();
  void await_recorder();
  /// Starts again every agent whose answer writer run.mcap's recorder has not matched, and waits
  /// (up to the rematch interval) until they are ready again; false when there was none.
  bool rematch_unrecorded();
  void make_secure_domain();
  void rematch_unready();
  /// A process that ended during discovery is started again (fleet_ready.cpp), up to
  /// discovery_death_restarts times; false when it may not be.
  bool restart_dead(Child& c);
  /// Ends `c` (SIGTERM, then SIGKILL) and starts it again with its next participant id; writes
  /// fleet.json. Returns the pid it had.
  pid_t start_again(Child& c);
  void learn_secure_plant(const eprosima::fastrtps::rtps::InstanceHandle_t& writer);
  bool secure() const { return o_.secure; }
  void write_fleet() const;
  void spawn_child(Child& c);
  /// Starts the agents' zygote, unless MAPTR_AGENT_START=exec or the fleet runs on hosts.
  void start_zygote();
  /// Follows the ticks and gates of the plant participant with this id (plant_clock.hpp).
  void follow_plant(int participant_id);
  void spawn_wave(LaunchWaves::Range r);
  void print_external_commands() const;
  // Readiness (fleet_ready.cpp): only from the participant expected for each process.
  void take_ready();
  void announce_restarted();
  /// The processes whose NodeReady samples since the last call are believed (ready() true);
  /// the others are rejected, counted in rec_.ready_rejected and logged (the first 20).
  std::vector<Child*> believed_ready();
  ReadyClaim claim_of(const msg::NodeReady& r, const eprosima::fastrtps::rtps::InstanceHandle_t& writer,
                      Child*& c);
  void reap(bool expected);
  void on_exit(const Exit& e, bool expected);
  void publish_member(const Child& c, msg::MemberEvent kind);
  void apply_fault(const config::FaultSpec& f, double at_s, const std::string& origin);
  // The fleet's processes as targets of faults (fault_execution.hpp).
  TargetState state_of(const std::string& target) override;
  pid_t pid_of(const std::string& target) override;
  void kill_target(const std::string& target) override;
  void restart_target(const std::string& target) override;
  void pause_target(const std::string& target, bool pause) override;
  void pause_or_resume(Child* c, pid_t pid, bool pause);
  void open_gate(const msg::FaultGate& g);
  bool restart_unready(const std::vector<std::string>& restarted);
  void take_ticks();
  void take_commands();
  void print_progress();
  std::string not_ready() const;
  Child* find(const std::string& name);
  // A fleet on several hosts (fleet_hosts.cpp).
  void setup_hosts();
  std::vector<std::string> apply_host_fault(const config::FaultSpec& f, double at_s);
  /// Starts again on a surviving host each controller of a lost host once it is reaped
  /// (hosts.failover); returns their names.
  std::vector<std::string> fail_over();
  /// partition: the host's controllers (central, groups) are left to run on there (stranded) and
  /// fail over to a surviving host.
  void strand_controllers(int h, double at_s);
  /// heal of host h (-1: every host, at the run's end): SIGKILL to its stranded copies.
  void end_stranded(int h);
  /// A stranded copy's local process was reaped: its pid is not to be signalled any more.
  void forget_stranded(pid_t pid);
  /// A failed-over controller `c` is ready again: its failover ends at the plant's time.
  void failed_over(const Child& c);
  bool on_hosts() const { return hosts_ != nullptr; }
  double since(Clock::time_point t0) const;

  const LaunchOptions& o_;
  const config::Scenario& sc_;
  spdlog::logger& log_;
  FleetConfig cfg_;
  std::string cfg_path_;
  comm::DdsOptions dds_;
  RunRecord rec_;
  Environment env_;
  ParticipantIds ids_;
  std::vector<std::unique_ptr<DiscoveryServer>> ds_;  ///< one, one per host, or none (a secure domain)
  std::unique_ptr<HostPlacement> hosts_;              ///< none: every process on this machine
  std::vector<Failover> failovers_;                   ///< controllers of lost hosts started elsewhere
  struct Stranded {
    int host;
    pid_t pid;
    std::string name;
    pid_t remote_pid;    ///< over ssh: its pid on its host (-1: unknown)
    std::string binary;  ///< what it runs (checked before its end)
  };
  std::vector<Stranded> stranded_;  ///< the old copies of controllers failed over from a cut-off host
  std::unique_ptr<LauncherParticipant> domain_;       ///< the launcher's participant
  std::unique_ptr<FleetRecorder> recorder_;  ///< run.mcap (records nothing when the scenario says none)
  std::vector<Child> kids_;
  std::unique_ptr<LaunchWaves> waves_;
  std::unique_ptr<Zygote> zygote_;  ///< forks the agents on this machine (none: exec)
  std::unique_ptr<ControlFifo> fifo_;
  std::unique_ptr<FleetRegistration> registration_;  ///< `maptr ps` finds the fleet while it runs
  FaultExecution faults_;  ///< the schedule, applied through this fleet's FaultTargets
  PlantClock clock_;
  StallWatch stall_;
  long gates_seen_ = 0;
  std::set<std::string> ready_names_;
  std::vector<std::string> plant_unmatched_;  ///< the plant's latest report: the members it has not matched
  Clock::time_point t_launch_, t_run_, last_wave_, last_print_, last_progress_;
  bool plant_done_ = false;
  bool discovered_ = false;  ///< discover() has returned: deaths are announced from now on
  bool ds_paused_ = false;   ///< the discovery server is stopped by a pause fault
  long reported_rejected_ = 0;
  long host_pids_written_ = 0;  ///< processes whose pid on their host fleet.json holds
};

/// Set by SIGINT/SIGTERM: the run ends.
std::atomic<bool>& interrupted();

}  // namespace maptr::deploy::fleet
