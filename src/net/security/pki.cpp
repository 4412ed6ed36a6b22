#include "net/security/pki.hpp"

#include <openssl/asn1.h>
#include <openssl/bio.h>
#include <openssl/x509v3.h>

#include <ctime>
#include <memory>

namespace dsswarm::security {

namespace {

using Asn1IntegerPtr = std::unique_ptr<ASN1_INTEGER, OpensslDeleter<ASN1_INTEGER_free>>;
using Asn1TimePtr = std::unique_ptr<ASN1_TIME, OpensslDeleter<ASN1_TIME_free>>;
using ExtensionPtr = std::unique_ptr<X509_EXTENSION, OpensslDeleter<X509_EXTENSION_free>>;

void set_time(ASN1_TIME* field, TimePoint t) {
  check_openssl(ASN1_TIME_set(field, std::chrono::system_clock::to_time_t(t)) != nullptr, "ASN1_TIME_set");
}

Asn1TimePtr asn1_time(TimePoint t) {
  Asn1TimePtr time(ASN1_TIME_new());
  check_openssl(time != nullptr, "ASN1_TIME_new");
  set_time(time.get(), t);
  return time;
}

Asn1IntegerPtr asn1_integer(std::uint64_t v) {
  Asn1IntegerPtr n(ASN1_INTEGER_new());
  check_openssl(n != nullptr && ASN1_INTEGER_set_uint64(n.get(), v) == 1, "ASN1_INTEGER_set_uint64");
  return n;
}

void add_extension(X509* cert, X509* issuer, int nid, const char* value) {
  X509V3_CTX ctx;
  X509V3_set_ctx(&ctx, issuer, cert, nullptr, nullptr, 0);
  ExtensionPtr ext(X509V3_EXT_nconf_nid(nullptr, &ctx, nid, value));
  check_openssl(ext != nullptr && X509_add_ext(cert, ext.get(), -1) == 1, "X509_add_ext");
}

void set_subject(X509* cert, const CertificateSpec& spec) {
  X509_NAME* name = X509_get_subject_name(cert);
  auto add = [name](const char* field, const std::string& value) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(value.c_str());
    check_openssl(X509_NAME_add_entry_by_txt(name, field, MBSTRING_UTF8, bytes, -1, -1, 0) == 1, "X509_NAME_add_entry");
  };
  add("CN", spec.common_name);
  add("O", spec.organization);
}

}  // namespace

KeyPtr generate_ec_key() {
  KeyPtr key(EVP_EC_gen("P-256"));
  check_openssl(key != nullptr, "EVP_EC_gen(P-256)");
  return key;
}

CertPtr make_certificate(const CertificateSpec& spec, EVP_PKEY* subject_key, X509* issuer, EVP_PKEY* issuer_key) {
  CertPtr cert(X509_new());
  check_openssl(cert != nullptr, "X509_new");
  check_openssl(X509_set_version(cert.get(), X509_VERSION_3) == 1, "X509_set_version");
  check_openssl(X509_set_serialNumber(cert.get(), asn1_integer(spec.serial).get()) == 1, "X509_set_serialNumber");
  set_time(X509_getm_notBefore(cert.get()), spec.validity.not_before);
  set_time(X509_getm_notAfter(cert.get()), spec.validity.not_after);
  set_subject(cert.get(), spec);
  X509* signer = issuer != nullptr ? issuer : cert.get();
  check_openssl(X509_set_issuer_name(cert.get(), X509_get_subject_name(signer)) == 1, "X509_set_issuer_name");
  check_openssl(X509_set_pubkey(cert.get(), subject_key) == 1, "X509_set_pubkey");
  add_extension(cert.get(), signer, NID_subject_key_identifier, "hash");
  if (spec.is_ca) {
    // digitalSignature as well: the CA also signs the governance and
    // permissions documents, and S/MIME verification checks the key usage.
    add_extension(cert.get(), signer, NID_basic_constraints, "critical,CA:TRUE");
    add_extension(cert.get(), signer, NID_key_usage, "critical,keyCertSign,cRLSign,digitalSignature");
  } else {
    add_extension(cert.get(), signer, NID_authority_key_identifier, "keyid:always");
    add_extension(cert.get(), signer, NID_basic_constraints, "critical,CA:FALSE");
    add_extension(cert.get(), signer, NID_key_usage, "critical,digitalSignature");
  }
  check_openssl(X509_sign(cert.get(), issuer_key, EVP_sha256()) > 0, "X509_sign");
  return cert;
}

CrlPtr make_crl(X509* ca, EVP_PKEY* ca_key, const std::vector<RevokedCertificate>& revoked, const Validity& validity,
                std::uint64_t crl_number) {
  CrlPtr crl(X509_CRL_new());
  check_openssl(crl != nullptr, "X509_CRL_new");
  check_openssl(X509_CRL_set_version(crl.get(), 1) == 1, "X509_CRL_set_version");  // 1 = v2
  check_openssl(X509_CRL_set_issuer_name(crl.get(), X509_get_subject_name(ca)) == 1, "X509_CRL_set_issuer_name");
  check_openssl(X509_CRL_set1_lastUpdate(crl.get(), asn1_time(validity.not_before).get()) == 1, "CRL lastUpdate");
  check_openssl(X509_CRL_set1_nextUpdate(crl.get(), asn1_time(validity.not_after).get()) == 1, "CRL nextUpdate");
  for (const RevokedCertificate& r : revoked) {
    X509_REVOKED* entry = X509_REVOKED_new();
    check_openssl(entry != nullptr, "X509_REVOKED_new");
    const bool ok = X509_REVOKED_set_serialNumber(entry, asn1_integer(r.serial).get()) == 1 &&
                    X509_REVOKED_set_revocationDate(entry, asn1_time(r.revoked_at).get()) == 1 &&
                    X509_CRL_add0_revoked(crl.get(), entry) == 1;  // takes ownership on success
    if (!ok) X509_REVOKED_free(entry);
    check_openssl(ok, "CRL entry");
  }
  check_openssl(X509_CRL_sort(crl.get()) == 1, "X509_CRL_sort");
  check_openssl(X509_CRL_add1_ext_i2d(crl.get(), NID_crl_number, asn1_integer(crl_number).get(), 0, 0) == 1,
                "CRL number");
  check_openssl(X509_CRL_sign(crl.get(), ca_key, EVP_sha256()) > 0, "X509_CRL_sign");
  return crl;
}

std::string smime_sign_text(std::string_view document, X509* signer, EVP_PKEY* signer_key) {
  constexpr int kFlags = PKCS7_DETACHED | PKCS7_TEXT;
  BioPtr content = memory_bio(document);
  Pkcs7Ptr p7(PKCS7_sign(signer, signer_key, nullptr, content.get(), kFlags));
  check_openssl(p7 != nullptr, "PKCS7_sign");
  BioPtr out(BIO_new(BIO_s_mem()));
  check_openssl(out != nullptr, "BIO_new");
  BioPtr again = memory_bio(document);  // the detached part is written out again
  check_openssl(SMIME_write_PKCS7(out.get(), p7.get(), again.get(), kFlags) == 1, "SMIME_write_PKCS7");
  return bio_contents(out.get());
}

TimePoint certificate_not_after(X509* cert) {
  std::tm tm{};
  check_openssl(ASN1_TIME_to_tm(X509_get0_notAfter(cert), &tm) == 1, "ASN1_TIME_to_tm");
  return std::chrono::system_clock::from_time_t(timegm(&tm));
}

std::string certificate_subject(X509* cert) {
  BioPtr bio(BIO_new(BIO_s_mem()));
  check_openssl(bio != nullptr, "BIO_new");
  check_openssl(X509_NAME_print_ex(bio.get(), X509_get_subject_name(cert), 0, XN_FLAG_RFC2253) >= 0,
                "X509_NAME_print_ex");
  return bio_contents(bio.get());
}

}  // namespace dsswarm::security
