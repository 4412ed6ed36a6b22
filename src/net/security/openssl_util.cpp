#include "net/security/openssl_util.hpp"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/pem.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/errors.hpp"

namespace dsswarm::security {

namespace {

std::string drain_error_queue() {
  std::string out;
  char buf[256];
  while (const unsigned long e = ERR_get_error()) {
    ERR_error_string_n(e, buf, sizeof buf);
    if (!out.empty()) out += "; ";
    out += buf;
  }
  return out.empty() ? "no details" : out;
}

template <typename Write>
std::string pem_with(Write write) {
  BioPtr bio(BIO_new(BIO_s_mem()));
  check_openssl(bio != nullptr, "BIO_new");
  check_openssl(write(bio.get()) == 1, "PEM write");
  return bio_contents(bio.get());
}

template <typename T, typename Read>
T parse_pem(std::string_view pem, const std::string& source, const char* kind, Read read) {
  BioPtr bio = memory_bio(pem);
  T object(read(bio.get()));
  if (!object) {
    const std::string details = drain_error_queue();
    throw InputError(source + ": not a PEM " + kind + " (" + details + ")");
  }
  return object;
}

}  // namespace

void check_openssl(bool ok, std::string_view what) {
  if (!ok) throw std::runtime_error("openssl: " + std::string(what) + ": " + drain_error_queue());
}

BioPtr memory_bio(std::string_view data) {
  BioPtr bio(BIO_new_mem_buf(data.data(), static_cast<int>(data.size())));
  check_openssl(bio != nullptr, "BIO_new_mem_buf");
  return bio;
}

std::string bio_contents(BIO* bio) {
  char* data = nullptr;
  const long n = BIO_get_mem_data(bio, &data);
  return n > 0 ? std::string(data, static_cast<std::size_t>(n)) : std::string();
}

std::string pem_of(X509* cert) {
  return pem_with([cert](BIO* b) { return PEM_write_bio_X509(b, cert); });
}

std::string pem_of(X509_CRL* crl) {
  return pem_with([crl](BIO* b) { return PEM_write_bio_X509_CRL(b, crl); });
}

std::string pem_of(EVP_PKEY* key) {
  // OpenSSL 3 writes PKCS#8 through PEM_write_bio_PrivateKey; no passphrase:
  // a robot starts unattended, the file's mode (0600) protects it.
  return pem_with([key](BIO* b) { return PEM_write_bio_PrivateKey(b, key, nullptr, nullptr, 0, nullptr, nullptr); });
}

CertPtr parse_certificate(std::string_view pem, const std::string& source) {
  return parse_pem<CertPtr>(pem, source, "certificate",
                            [](BIO* b) { return PEM_read_bio_X509(b, nullptr, nullptr, nullptr); });
}

KeyPtr parse_private_key(std::string_view pem, const std::string& source) {
  return parse_pem<KeyPtr>(pem, source, "private key",
                           [](BIO* b) { return PEM_read_bio_PrivateKey(b, nullptr, nullptr, nullptr); });
}

CrlPtr parse_crl(std::string_view pem, const std::string& source) {
  return parse_pem<CrlPtr>(pem, source, "CRL",
                           [](BIO* b) { return PEM_read_bio_X509_CRL(b, nullptr, nullptr, nullptr); });
}

std::string read_text_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError("error while reading " + path.string());
  return text.str();
}

}  // namespace dsswarm::security
