#pragma once
// Every environment variable MAPTR reads, declared once: its name, who sets it and what it does.
// The launcher hands the fleet's settings to its processes this way (comm::options_from_env reads
// them); a user sets the others. `maptr fields --environment` prints this table.
namespace maptr::comm {

inline constexpr const char* kEnvDomain = "MAPTR_DOMAIN";
inline constexpr const char* kEnvFleetId = "MAPTR_FLEET_ID";
inline constexpr const char* kEnvParticipantId = "MAPTR_PARTICIPANT_ID";
inline constexpr const char* kEnvTransport = "MAPTR_TRANSPORT";
inline constexpr const char* kEnvLease = "MAPTR_LEASE_S";
inline constexpr const char* kEnvShmPortQueue = "MAPTR_SHM_PORT_QUEUE";
inline constexpr const char* kEnvShmSegmentBytes = "MAPTR_SHM_SEGMENT_BYTES";
inline constexpr const char* kEnvDiscoveryServer = "MAPTR_DISCOVERY_SERVER";
inline constexpr const char* kEnvDiscoveryOwn = "MAPTR_DISCOVERY_OWN";
inline constexpr const char* kEnvInterface = "MAPTR_INTERFACE";
inline constexpr const char* kEnvPlantLoss = "MAPTR_PLANT_LOSS_S";
inline constexpr const char* kEnvSecurityDir = "MAPTR_SECURITY_DIR";
inline constexpr const char* kEnvDdsLog = "MAPTR_DDS_LOG";
inline constexpr const char* kEnvAgentStart = "MAPTR_AGENT_START";
inline constexpr const char* kEnvQosProfiles = "FASTRTPS_DEFAULT_PROFILES_FILE";
inline constexpr const char* kEnvRuntimeDir = "XDG_RUNTIME_DIR";

struct EnvironmentVariable {
  const char* name;
  const char* set_by;  ///< "user" (optional; its value is checked before a fleet starts) or "launcher"
  const char* values;  ///< what it holds
  const char* meaning;
};

inline constexpr EnvironmentVariable kEnvironment[] = {
    {kEnvDomain, "user, launcher", "0 to 232", "the DDS domain (`maptr run --domain` wins; default 0)"},
    {kEnvDdsLog, "user", "error, warning or info",
     "Fast DDS's log level in every process (default Fast DDS's)"},
    {kEnvAgentStart, "user", "zygote or exec",
     "how the launcher starts the agents of this machine (default zygote: forked from a loaded copy)"},
    {kEnvShmSegmentBytes, "user", "bytes",
     "each participant's shared-memory segment size (default Fast DDS's)"},
    {kEnvQosProfiles, "user", "an XML file",
     "Fast DDS's profiles file, loaded instead of the QoS profiles shipped beside the binaries "
     "(maptr_qos.xml)"},
    {kEnvRuntimeDir, "user", "a folder",
     "where running fleets register for `maptr ps` and the commands that find a fleet (default /run or "
     "/tmp)"},
    {kEnvFleetId, "launcher", "a 32-bit number", "the fleet's id, in every participant's GUID prefix"},
    {kEnvParticipantId, "launcher", "a participant id", "the process's participant id for this start"},
    {kEnvTransport, "launcher", "shm, shm+udp or udp", "the data transport"},
    {kEnvLease, "launcher", "s", "the participants' lease duration"},
    {kEnvShmPortQueue, "launcher", "samples", "the shared-memory port queue's length"},
    {kEnvDiscoveryServer, "launcher", "HOST:PORT[,HOST:PORT...]", "the discovery server(s), one per host"},
    {kEnvDiscoveryOwn, "launcher", "a host index", "on several hosts: the server of the process's own host"},
    {kEnvInterface, "launcher", "an IPv4 address", "the interface UDP uses (default 127.0.0.1)"},
    {kEnvPlantLoss, "launcher", "s",
     "on several hosts: how long the plant may be silent before it counts as lost"},
    {kEnvSecurityDir, "launcher", "a folder", "on a secure domain: the fleet's certificates and permissions"},
};

}  // namespace maptr::comm
