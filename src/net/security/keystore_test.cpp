// The keys directory without DDS: what init/add/revoke write, checked with
// libcrypto the way Cyclone's plugins check it, and every refusal.
#include "net/security/keystore.hpp"

#include <gtest/gtest.h>
#include <openssl/pem.h>
#include <openssl/x509_vfy.h>

#include <filesystem>

#include "common/errors.hpp"
#include "common/test_files.hpp"
#include "net/security/openssl_util.hpp"
#include "net/security/security_config.hpp"

namespace dsswarm::security {
namespace {

namespace fs = std::filesystem;
using StorePtr = std::unique_ptr<X509_STORE, OpensslDeleter<X509_STORE_free>>;
using StoreCtxPtr = std::unique_ptr<X509_STORE_CTX, OpensslDeleter<X509_STORE_CTX_free>>;

CertPtr load_cert(const fs::path& p) { return parse_certificate(read_text_file(p), p.string()); }
CrlPtr load_crl(const fs::path& p) { return parse_crl(read_text_file(p), p.string()); }

// X509_verify_cert of `cert` against `ca` (and `crl`, when given): the
// verification error code, X509_V_OK when valid. As Cyclone's auth plugin does.
int verify(X509* cert, X509* ca, X509_CRL* crl = nullptr) {
  StorePtr store(X509_STORE_new());
  X509_STORE_add_cert(store.get(), ca);
  if (crl != nullptr) X509_STORE_add_crl(store.get(), crl);
  StoreCtxPtr ctx(X509_STORE_CTX_new());
  X509_STORE_CTX_init(ctx.get(), store.get(), cert, nullptr);
  if (crl != nullptr) X509_STORE_CTX_set_flags(ctx.get(), X509_V_FLAG_CRL_CHECK);
  return X509_verify_cert(ctx.get()) == 1 ? X509_V_OK : X509_STORE_CTX_get_error(ctx.get());
}

// The signed document's content if its S/MIME signature verifies against
// `ca` (as Cyclone's access-control plugin reads it), else "". The signed
// text is in canonical form (CRLF line ends); they are turned back into LF.
std::string verified_content(const fs::path& p7s, X509* ca) {
  const std::string text = read_text_file(p7s);
  BioPtr in = memory_bio(text);
  BIO* content = nullptr;
  Pkcs7Ptr p7(SMIME_read_PKCS7(in.get(), &content));
  BioPtr content_owner(content);
  if (!p7) return "";
  StorePtr store(X509_STORE_new());
  X509_STORE_add_cert(store.get(), ca);
  BioPtr out(BIO_new(BIO_s_mem()));
  if (PKCS7_verify(p7.get(), nullptr, store.get(), content, out.get(), PKCS7_TEXT) != 1) return "";
  std::string content_text = bio_contents(out.get());
  std::erase(content_text, '\r');
  return content_text;
}

int revoked_count(X509_CRL* crl) {
  const STACK_OF(X509_REVOKED)* entries = X509_CRL_get_REVOKED(crl);
  return entries == nullptr ? 0 : sk_X509_REVOKED_num(entries);
}

fs::perms mode_of(const fs::path& p) { return fs::status(p).permissions() & fs::perms::all; }

class KeystoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = test::fresh_dir(std::string("keystore_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    dir_ = root_ / "keys";
  }
  void TearDown() override { fs::remove_all(root_); }
  KeysLayout layout() const { return KeysLayout{dir_}; }

  fs::path root_, dir_;
};

TEST_F(KeystoreTest, InitMakesSelfSignedCaSignedGovernanceAndEmptyCrl) {
  KeysInitOptions options;
  options.swarm_id = 7;
  options.days = 30;
  init_keys(dir_, options);
  const CertPtr ca = load_cert(layout().ca_certificate());
  EXPECT_EQ(verify(ca.get(), ca.get()), X509_V_OK);
  EXPECT_EQ(certificate_subject(ca.get()), "O=dsswarm-7,CN=dsswarm-7 CA");
  const auto days_left = std::chrono::duration_cast<std::chrono::hours>(certificate_not_after(ca.get()) -
                                                                        std::chrono::system_clock::now());
  EXPECT_NEAR(static_cast<double>(days_left.count()) / 24.0, 30.0, 0.05);
  EXPECT_EQ(mode_of(layout().ca_key()), fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_NE(read_text_file(layout().ca_key()).find("-----BEGIN PRIVATE KEY-----"), std::string::npos);  // PKCS#8

  const std::string governance = verified_content(layout().governance(), ca.get());
  EXPECT_EQ(governance, read_text_file(layout().governance_source()));
  EXPECT_NE(governance.find("<domains><id>7</id></domains>"), std::string::npos);
  EXPECT_NE(governance.find("<allow_unauthenticated_participants>false<"), std::string::npos);
  EXPECT_NE(governance.find("<topic_expression>dsswarm*</topic_expression>"), std::string::npos);

  const CrlPtr crl = load_crl(layout().crl());
  KeyPtr ca_public(X509_get_pubkey(ca.get()));
  EXPECT_EQ(X509_CRL_verify(crl.get(), ca_public.get()), 1);
  EXPECT_EQ(revoked_count(crl.get()), 0);
  // The empty CRL is current: with CRL checking on, a robot still verifies.
  add_robot(dir_, "r");
  EXPECT_EQ(verify(load_cert(layout().robot("r").certificate()).get(), ca.get(), crl.get()), X509_V_OK);
  EXPECT_EQ(load_swarm_keys(dir_).domain_id, 7);
  EXPECT_TRUE(fs::is_directory(layout().robots()));
}

TEST_F(KeystoreTest, AddIssuesCertificateKeyAndPermissionsSignedByTheCa) {
  init_keys(dir_, {});
  const RobotRecord r = add_robot(dir_, "robot1");
  const RobotFiles files = layout().robot("robot1");
  const CertPtr ca = load_cert(layout().ca_certificate());
  const CertPtr cert = load_cert(files.certificate());
  EXPECT_EQ(verify(cert.get(), ca.get()), X509_V_OK);
  EXPECT_EQ(certificate_subject(cert.get()), "O=dsswarm-1,CN=robot1");
  EXPECT_EQ(r.subject, "CN=robot1,O=dsswarm-1");
  EXPECT_EQ(ASN1_INTEGER_get(X509_get0_serialNumber(cert.get())), static_cast<long>(r.serial));
  const KeyPtr key = parse_private_key(read_text_file(files.key()), "key");
  EXPECT_EQ(X509_check_private_key(cert.get(), key.get()), 1);
  EXPECT_EQ(mode_of(files.key()), fs::perms::owner_read | fs::perms::owner_write);

  const std::string permissions = verified_content(files.permissions(), ca.get());
  EXPECT_EQ(permissions, read_text_file(files.permissions_source()));
  EXPECT_NE(permissions.find("<subject_name>CN=robot1,O=dsswarm-1</subject_name>"), std::string::npos);
  EXPECT_NE(permissions.find("<not_after>" + utc_text(r.validity.not_after) + "</not_after>"), std::string::npos);
  // A certificate from another CA does not verify against this one.
  const fs::path other = root_ / "other";
  init_keys(other, {});
  EXPECT_NE(verify(cert.get(), load_cert(KeysLayout{other}.ca_certificate()).get()), X509_V_OK);
}

TEST_F(KeystoreTest, SerialsAreNeverReused) {
  init_keys(dir_, {});
  const auto a = add_robot(dir_, "a").serial, b = add_robot(dir_, "b").serial;
  revoke_robot(dir_, "b");
  const auto c = add_robot(dir_, "c").serial;
  EXPECT_EQ(a, 2u);
  EXPECT_EQ(b, 3u);
  EXPECT_EQ(c, 4u);
  EXPECT_EQ(load_swarm_keys(dir_).next_serial, 5u);
}

TEST_F(KeystoreTest, RevokeListsTheRobotInTheCrlAndOthersStayValid) {
  init_keys(dir_, {});
  add_robot(dir_, "keep");
  const RobotRecord gone = add_robot(dir_, "gone");
  const RobotRecord revoked = revoke_robot(dir_, "gone");
  ASSERT_TRUE(revoked.revoked_at.has_value());
  const CertPtr ca = load_cert(layout().ca_certificate());
  const CrlPtr crl = load_crl(layout().crl());
  EXPECT_EQ(revoked_count(crl.get()), 1);
  EXPECT_EQ(verify(load_cert(layout().robot("gone").certificate()).get(), ca.get(), crl.get()), X509_V_ERR_CERT_REVOKED);
  EXPECT_EQ(verify(load_cert(layout().robot("keep").certificate()).get(), ca.get(), crl.get()), X509_V_OK);
  EXPECT_EQ(load_swarm_keys(dir_).crl_number, 2u);
  EXPECT_EQ(gone.serial, revoked.serial);
}

TEST_F(KeystoreTest, ExplicitValidityPeriodsGoIntoCertificateAndPermissions) {
  init_keys(dir_, {});
  const auto now = std::chrono::system_clock::now();
  RobotKeyOptions o;
  o.permissions_validity = Validity{now - std::chrono::hours(48), now - std::chrono::hours(24)};
  add_robot(dir_, "late", o);
  const std::string text = read_text_file(layout().robot("late").permissions_source());
  EXPECT_NE(text.find("<not_after>" + utc_text(now - std::chrono::hours(24)) + "</not_after>"), std::string::npos);
  // The certificate keeps its default period (until the CA expires).
  const CertPtr cert = load_cert(layout().robot("late").certificate());
  EXPECT_EQ(certificate_not_after(cert.get()), certificate_not_after(load_cert(layout().ca_certificate()).get()));
}

TEST_F(KeystoreTest, SecurityConfigNamesEveryFileAsAbsoluteFileUri) {
  init_keys(dir_, {});
  add_robot(dir_, "r1");
  const std::string xml = security_config_xml(dir_, "r1");
  const std::string abs = fs::absolute(dir_).lexically_normal().string();
  for (const std::string& element : std::vector<std::string>{"<IdentityCA>file:" + abs + "/ca.pem</IdentityCA>",
                                    "<IdentityCertificate>file:" + abs + "/robots/r1/cert.pem<",
                                    "<PrivateKey>file:" + abs + "/robots/r1/key.pem<", "<CRL>file:" + abs + "/crl.pem<",
                                    "<PermissionsCA>file:" + abs + "/ca.pem<", "<Governance>file:" + abs + "/governance.p7s<",
                                    "<Permissions>file:" + abs + "/robots/r1/permissions.p7s<", "<Cryptographic/>"}) {
    EXPECT_NE(xml.find(element), std::string::npos) << element;
  }
  EXPECT_EQ(xml.rfind("<Security>", 0), 0u);
  EXPECT_EQ(secured_domain_id(dir_), 1);
}

}  // namespace
}  // namespace dsswarm::security
