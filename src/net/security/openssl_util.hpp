#pragma once
// Owning handles for libcrypto objects and PEM conversions, so the key tooling
// never leaks on an error path. Failures of libcrypto itself throw
// std::runtime_error carrying OpenSSL's error queue.
#include <openssl/evp.h>
#include <openssl/pkcs7.h>
#include <openssl/x509.h>

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace dsswarm::security {

template <auto Free>
struct OpensslDeleter {
  template <typename T>
  void operator()(T* p) const { Free(p); }
};

using KeyPtr = std::unique_ptr<EVP_PKEY, OpensslDeleter<EVP_PKEY_free>>;
using CertPtr = std::unique_ptr<X509, OpensslDeleter<X509_free>>;
using CrlPtr = std::unique_ptr<X509_CRL, OpensslDeleter<X509_CRL_free>>;
using Pkcs7Ptr = std::unique_ptr<PKCS7, OpensslDeleter<PKCS7_free>>;
using BioPtr = std::unique_ptr<BIO, OpensslDeleter<BIO_free_all>>;

// Throws std::runtime_error("openssl: <what>: <queued errors>") when !ok.
void check_openssl(bool ok, std::string_view what);

// A read-only memory BIO over `data` (which must outlive it).
BioPtr memory_bio(std::string_view data);
// Everything written so far into a memory BIO.
std::string bio_contents(BIO* bio);

std::string pem_of(X509* cert);
std::string pem_of(X509_CRL* crl);
// The private key as unencrypted PKCS#8 PEM ("BEGIN PRIVATE KEY").
std::string pem_of(EVP_PKEY* key);

// Parse PEM text; `source` names the file in the InputError thrown on failure.
CertPtr parse_certificate(std::string_view pem, const std::string& source);
KeyPtr parse_private_key(std::string_view pem, const std::string& source);
CrlPtr parse_crl(std::string_view pem, const std::string& source);

// Whole file as a string; InputError naming the file if it cannot be read.
std::string read_text_file(const std::filesystem::path& path);

}  // namespace dsswarm::security
