#include "comm/dds/security.hpp"

#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/x509.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "comm/dds/fleet_ids.hpp"

namespace maptr::comm {

namespace {

constexpr const char* kCertSuffix = ".cert.pem";

std::string file_uri(const std::string& path) { return "file://" + path; }

struct Registry {
  std::mutex m;
  std::map<SubjectKey, std::string> names;
  int agents = -1;  ///< the fleet size base_ids was built for
  std::map<SubjectKey, int> base_ids;
};

SubjectKey key_of(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) {
  SubjectKey k;
  std::copy(prefix.value, prefix.value + k.size(), k.begin());
  return k;
}

Registry& registry() {
  static Registry r;
  return r;
}

}  // namespace

void add_security_properties(eprosima::fastdds::dds::PropertyPolicyQos& p, const SecureFiles& f,
                             const std::string& id) {
  const std::string auth = "dds.sec.auth.builtin.PKI-DH.";
  const std::string access = "dds.sec.access.builtin.Access-Permissions.";
  auto& props = p.properties();
  props.emplace_back("dds.sec.auth.plugin", "builtin.PKI-DH");
  props.emplace_back(auth + "identity_ca", file_uri(f.ca_cert()));
  props.emplace_back(auth + "identity_certificate", file_uri(f.cert(id)));
  props.emplace_back(auth + "private_key", file_uri(f.key(id)));
  props.emplace_back("dds.sec.access.plugin", "builtin.Access-Permissions");
  props.emplace_back(access + "permissions_ca", file_uri(f.ca_cert()));
  props.emplace_back(access + "governance", file_uri(f.governance()));
  props.emplace_back(access + "permissions", file_uri(f.permissions(id)));
  props.emplace_back("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

SubjectKey subject_key(const std::string& cert_pem) {
  std::unique_ptr<FILE, int (*)(FILE*)> in(std::fopen(cert_pem.c_str(), "r"), &std::fclose);
  if (!in) throw std::runtime_error("cannot read certificate " + cert_pem);
  std::unique_ptr<X509, void (*)(X509*)> cert(PEM_read_X509(in.get(), nullptr, nullptr, nullptr), &X509_free);
  unsigned char md[EVP_MAX_MD_SIZE];
  unsigned int len = 0;
  if (!cert || !X509_NAME_digest(X509_get_subject_name(cert.get()), EVP_sha256(), md, &len) || len < 6)
    throw std::runtime_error("cannot hash the subject name of certificate " + cert_pem);
  // The DDS Security derivation: the digest shifted right by one bit, top bit set.
  SubjectKey k;
  k[0] = static_cast<uint8_t>(0x80 | (md[0] >> 1));
  for (std::size_t i = 1; i < k.size(); ++i) k[i] = static_cast<uint8_t>((md[i - 1] << 7) | (md[i] >> 1));
  return k;
}

void learn_secure_identities(const SecureFiles& f) {
  std::map<SubjectKey, std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(f.dir)) {
    const std::string file = e.path().filename().string();
    const std::string suffix = kCertSuffix;
    if (file.size() <= suffix.size() || file.compare(file.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string id = file.substr(0, file.size() - suffix.size());
    if (id == "ca") continue;
    names[subject_key(e.path().string())] = id;
  }
  auto& r = registry();
  std::lock_guard<std::mutex> g(r.m);
  r.names = std::move(names);
  r.agents = -1;
}

std::optional<std::string> secure_identity(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix) {
  if (!is_secure_prefix(prefix)) return std::nullopt;
  auto& r = registry();
  std::lock_guard<std::mutex> g(r.m);
  const auto it = r.names.find(key_of(prefix));
  if (it == r.names.end()) return std::nullopt;
  return it->second;
}

std::optional<int> secure_base_id(const eprosima::fastrtps::rtps::GuidPrefix_t& prefix, int agents) {
  if (!is_secure_prefix(prefix)) return std::nullopt;
  auto& r = registry();
  std::lock_guard<std::mutex> g(r.m);
  if (r.agents != agents) {
    r.base_ids.clear();
    for (const auto& [k, name] : r.names)
      if (const int id = name == "launcher" ? kLauncherParticipantId : base_participant_id(name, agents);
          id >= 0)
        r.base_ids[k] = id;
    r.agents = agents;
  }
  const auto it = r.base_ids.find(key_of(prefix));
  if (it == r.base_ids.end()) return std::nullopt;
  return it->second;
}

}  // namespace maptr::comm
