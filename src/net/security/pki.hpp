#pragma once
// The swarm's public-key infrastructure on libcrypto: ECDSA P-256 keys,
// X.509 certificates (the self-signed CA and the robots'), the CA's
// revocation list, and S/MIME signing of the governance and permissions
// documents exactly as `openssl smime -sign -text` does (the form Cyclone
// DDS's access-control plugin reads).
#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "net/security/openssl_util.hpp"

namespace dsswarm::security {

using TimePoint = std::chrono::system_clock::time_point;

struct Validity {
  TimePoint not_before;
  TimePoint not_after;
};

// What goes into a certificate; the subject is CN=common_name,O=organization.
struct CertificateSpec {
  std::string common_name;
  std::string organization;
  std::uint64_t serial = 0;
  Validity validity;
  bool is_ca = false;
};

struct RevokedCertificate {
  std::uint64_t serial = 0;
  TimePoint revoked_at;
};

// A fresh ECDSA key on P-256 (the curve Cyclone's PKI-DH plugin accepts).
KeyPtr generate_ec_key();

// A certificate for `subject_key`, signed by `issuer_key`. With no issuer
// certificate it is self-signed (issuer name = subject name): the CA.
CertPtr make_certificate(const CertificateSpec& spec, EVP_PKEY* subject_key, X509* issuer, EVP_PKEY* issuer_key);

// A version-2 CRL from `ca` listing `revoked`, valid over `validity`
// (thisUpdate .. nextUpdate), carrying `crl_number`.
CrlPtr make_crl(X509* ca, EVP_PKEY* ca_key, const std::vector<RevokedCertificate>& revoked, const Validity& validity,
                std::uint64_t crl_number);

// `document` signed by `signer` as a detached S/MIME text message
// (multipart/signed, content-type text/plain).
std::string smime_sign_text(std::string_view document, X509* signer, EVP_PKEY* signer_key);

// The certificate's validity end, and its subject in RFC 2253 form
// ("O=dsswarm-1,CN=robot1": most specific first).
TimePoint certificate_not_after(X509* cert);
std::string certificate_subject(X509* cert);

}  // namespace dsswarm::security
