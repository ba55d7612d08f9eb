#include "deploy/fleet/secure_domain.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace maptr::deploy::fleet {

namespace {

/// Certificates and permissions outlive any run: ten years.
constexpr int kValidDays = 3650;
/// Permissions start a day early: a clock a little behind still accepts them.
constexpr int kValidBeforeDays = 1;
constexpr const char* kCurve = "ec_paramgen_curve:prime256v1";
constexpr const char* kLog = "openssl.log";

// The extensions of the CA and of the identities' certificates.
constexpr const char* kOpensslConfig = R"([req]
distinguished_name = dn
prompt = no
[dn]
[ca_ext]
basicConstraints = critical, CA:true
keyUsage = critical, digitalSignature, keyCertSign, cRLSign
subjectKeyIdentifier = hash
[identity_ext]
basicConstraints = critical, CA:false
keyUsage = critical, digitalSignature, keyAgreement
subjectKeyIdentifier = hash
authorityKeyIdentifier = keyid
)";

constexpr const char* kXmlHead =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\">\n";

std::string utc(std::chrono::system_clock::time_point t) {
  const std::time_t tt = std::chrono::system_clock::to_time_t(t);
  std::tm tm{};
  gmtime_r(&tt, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%S", &tm);
  return buf;
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace

std::string governance_xml(int domain) {
  std::ostringstream x;
  x << kXmlHead << "  <domain_access_rules>\n    <domain_rule>\n"
    << "      <domains><id>" << domain << "</id></domains>\n"
    << "      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>\n"
    << "      <enable_join_access_control>true</enable_join_access_control>\n"
    << "      <discovery_protection_kind>ENCRYPT</discovery_protection_kind>\n"
    << "      <liveliness_protection_kind>ENCRYPT</liveliness_protection_kind>\n"
    << "      <rtps_protection_kind>NONE</rtps_protection_kind>\n"
    << "      <topic_access_rules>\n        <topic_rule>\n"
    << "          <topic_expression>*</topic_expression>\n"
    << "          <enable_discovery_protection>true</enable_discovery_protection>\n"
    << "          <enable_liveliness_protection>true</enable_liveliness_protection>\n"
    << "          <enable_read_access_control>true</enable_read_access_control>\n"
    << "          <enable_write_access_control>true</enable_write_access_control>\n"
    << "          <metadata_protection_kind>ENCRYPT</metadata_protection_kind>\n"
    << "          <data_protection_kind>ENCRYPT</data_protection_kind>\n"
    << "        </topic_rule>\n      </topic_access_rules>\n"
    << "    </domain_rule>\n  </domain_access_rules>\n</dds>\n";
  return x.str();
}

std::string permissions_xml(const Grant& g, int domain, const std::string& not_before,
                            const std::string& not_after) {
  std::ostringstream x;
  x << kXmlHead << "  <permissions>\n    <grant name=\"" << g.identity << "\">\n"
    << "      <subject_name>CN=" << g.identity << "</subject_name>\n"
    << "      <validity><not_before>" << not_before << "</not_before><not_after>" << not_after
    << "</not_after></validity>\n"
    << "      <allow_rule>\n        <domains><id>" << domain << "</id></domains>\n";
  if (!g.publish.empty()) {
    x << "        <publish><topics>";
    for (const auto& t : g.publish) x << "<topic>" << t << "</topic>";
    x << "</topics></publish>\n";
  }
  x << "        <subscribe><topics><topic>*</topic></topics></subscribe>\n"
    << "      </allow_rule>\n      <default>DENY</default>\n    </grant>\n  </permissions>\n</dds>\n";
  return x.str();
}

SecureDomain::SecureDomain(const std::string& dir, int domain)
    : f_{std::filesystem::absolute(dir).lexically_normal().string()}, domain_(domain) {}

SecureDomain SecureDomain::create(const std::string& dir, int domain) {
  std::filesystem::create_directories(dir);
  std::filesystem::permissions(dir, std::filesystem::perms::owner_all,
                               std::filesystem::perm_options::replace);
  SecureDomain d(dir, domain);
  write_text(d.config_file(), kOpensslConfig);
  d.openssl({"req", "-x509", "-config", d.config_file(), "-extensions", "ca_ext", "-newkey", "ec", "-pkeyopt",
             kCurve, "-nodes", "-keyout", d.f_.ca_key(), "-out", d.f_.ca_cert(), "-days",
             std::to_string(kValidDays), "-subj", "/CN=MAPTR fleet CA"});
  chmod(d.f_.ca_key().c_str(), S_IRUSR | S_IWUSR);
  d.sign(governance_xml(domain), d.f_.governance());
  return d;
}

void SecureDomain::add_identity(const Grant& g) const {
  const std::string& id = g.identity;
  openssl({"req",         "-x509",       "-config",
           config_file(), "-extensions", "identity_ext",
           "-newkey",     "ec",          "-pkeyopt",
           kCurve,        "-nodes",      "-keyout",
           f_.key(id),    "-out",        f_.cert(id),
           "-CA",         f_.ca_cert(),  "-CAkey",
           f_.ca_key(),   "-days",       std::to_string(kValidDays),
           "-subj",       "/CN=" + id});
  chmod(f_.key(id).c_str(), S_IRUSR | S_IWUSR);
  const auto now = std::chrono::system_clock::now();
  const auto day = std::chrono::hours(24);
  sign(permissions_xml(g, domain_, utc(now - kValidBeforeDays * day), utc(now + kValidDays * day)),
       f_.permissions(id));
}

void SecureDomain::sign(const std::string& xml, const std::string& out) const {
  const std::string in = out + ".xml";
  write_text(in, xml);
  openssl(
      {"smime", "-sign", "-text", "-in", in, "-out", out, "-signer", f_.ca_cert(), "-inkey", f_.ca_key()});
}

void SecureDomain::openssl(const std::vector<std::string>& args) const {
  // posix_spawn: safe in a process that already runs DDS threads.
  const std::string log = f_.dir + "/" + kLog;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0600);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  std::vector<std::string> store = {"openssl"};
  store.insert(store.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : store) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int err = posix_spawnp(&pid, "openssl", &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  int st = 0;
  if (err == 0) waitpid(pid, &st, 0);
  if (err != 0 || !WIFEXITED(st) || WEXITSTATUS(st) != 0)
    throw std::runtime_error("openssl " + args.front() + " failed for the secure domain (see " + log + ")");
}

}  // namespace maptr::deploy::fleet
