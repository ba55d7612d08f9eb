#pragma once
// DDS Security of a fleet run with `maptr run --secure`: the files every participant loads and
// who wrote a sample on an authenticated domain.
//
// One folder (RUN_DIR/security) holds the run's CA certificate, the signed governance and, per
// identity NAME (a process name: plant, central, group-L, L3, launcher), NAME.cert.pem,
// NAME.key.pem (mode 0600) and NAME.permissions.p7s. A participant with a security folder
// enables PKI-DH authentication, AES-GCM-GMAC cryptography and Access-Permissions access
// control with file:// URIs to them (deploy/fleet/secure_domain.hpp writes the folder).
//
// Under DDS Security the first 6 bytes of a participant's GUID prefix are derived from its
// certificate's subject name (SHA-256 of the DER name, shifted right by one bit, top bit set),
// and authentication checks that derivation: they say which certificate, and so which process,
// wrote a sample. The other 6 bytes are a hash of the prefix the process asked for.
#include <array>
#include <cstdint>
#include <fastdds/dds/core/policy/QosPolicies.hpp>
#include <fastdds/rtps/common/GuidPrefix_t.hpp>
#include <optional>
#include <string>

namespace maptr::comm {

/// The file names of a secure domain's folder.
struct SecureFiles {
  std::string dir;  ///< absolute path of the folder
  std::string ca_cert() const { return dir + "/ca.cert.pem"; }
  std::string ca_key() const { return dir + "/ca.key.pem"; }
  std::string governance() const { return dir + "/governance.p7s"; }
  std::string cert(const std::string& id) const { return dir + "/" + id + ".cert.pem"; }
  std::string key(const std::string& id) const { return dir + "/" + id + ".key.pem"; }
  std::string permissions(const std::string& id) const { return dir + "/" + id + ".permissions.p7s"; }
};

/// Adds the dds.sec.* properties of identity `id` (authentication, access control and
/// cryptography, every file from `f`) to a participant's property policy.
void add_security_properties(eprosima::fastdds::dds::PropertyPolicyQos& p, const SecureFiles& f,
                             const std::string& id);

/// The 6 leading GUID-prefix bytes DDS Security derives from the certificate in `cert_pem`
/// (throws std::runtime_error if it cannot be read).
using SubjectKey = std::array<uint8_t, 6>;
SubjectKey subject_key(const std::string& cert_pem);

/// Learns every identity of the folder (each NAME.cert.pem) for secure_identity(); called once
/// per process by the first participant with security. Throws on an unreadable certificate.
void learn_secure_identities(const SecureFiles& f);

/// The identity (process name) whose certificate a participant's GUID prefix was derived from,
/// if it is one of the learnt identities.
std::optional<std::string> secure_identity(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix);

/// The first participant id (comm/dds/fleet_ids.hpp) of the process whose certificate the prefix
/// was derived from, in a fleet of `agents` agents; no strings: cheap enough for every sample.
std::optional<int> secure_base_id(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix, int agents);

/// True when the prefix is one DDS Security derived from a certificate (its top bit is set).
inline bool is_secure_prefix(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) {
  return (prefix.value[0] & 0x80) != 0;
}

}  // namespace maptr::comm
