#pragma once
// The files of a secure domain (`maptr run --secure`, comm/dds/security.hpp), made with the openssl
// command-line tool in one folder (mode 0700): a private CA (EC P-256 key, self-signed
// certificate), the governance document signed by the CA, and per identity a private key
// (mode 0600), a certificate the CA signed (subject CN=NAME) and a permissions document the CA
// signed. The governance admits authenticated participants only and encrypts discovery,
// liveliness and every topic's data and metadata; a permissions document lets its identity
// subscribe to every topic and publish only the topics of its grant.
#include <string>
#include <vector>

#include "comm/dds/security.hpp"

namespace maptr::deploy::fleet {

/// What one identity may publish; it may subscribe to every topic.
struct Grant {
  std::string identity;              ///< process name: plant, central, group-L, L3, launcher
  std::vector<std::string> publish;  ///< topic names (comm::topic)
};

/// The governance document of DDS domain `domain`.
std::string governance_xml(int domain);
/// The permissions document of grant `g` on DDS domain `domain`, valid from `not_before` to
/// `not_after` (UTC, "YYYY-MM-DDThh:mm:ss").
std::string permissions_xml(const Grant& g, int domain, const std::string& not_before,
                            const std::string& not_after);

class SecureDomain {
 public:
  /// Creates the folder, the CA and the signed governance of DDS domain `domain`; throws
  /// std::runtime_error (naming openssl's log) when a step fails.
  static SecureDomain create(const std::string& dir, int domain);
  /// The secure domain whose CA is already in `dir`.
  SecureDomain(const std::string& dir, int domain);

  /// A key, a certificate and signed permissions for `g.identity`.
  void add_identity(const Grant& g) const;
  const comm::SecureFiles& files() const { return f_; }

 private:
  void openssl(const std::vector<std::string>& args) const;
  void sign(const std::string& xml, const std::string& out) const;
  std::string config_file() const { return f_.dir + "/openssl.cnf"; }

  comm::SecureFiles f_;
  int domain_;
};

}  // namespace maptr::deploy::fleet
