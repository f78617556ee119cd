#include "rapid_runtime/dds/security.hpp"

#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace rapid_runtime {
namespace dds {

namespace {

const char* env(const char* name) {
    const char* v = std::getenv(name);
    return (v != nullptr && *v != '\0') ? v : nullptr;
}

bool readable(const std::string& path) { return std::ifstream(path).good(); }

}  // namespace

std::string security_enclave(const std::string& identity) {
    const char* keystore = env("RAPID_SECURITY_KEYSTORE");
    if (keystore == nullptr) return "";
    const char* chosen = env("RAPID_SECURITY_ENCLAVE");
    std::string name = chosen != nullptr ? chosen : identity;
    if (name.find('/') != std::string::npos) return name;
    return std::string(keystore) + "/enclaves/" + name;
}

void apply_security(eprosima::fastdds::dds::DomainParticipantQos& qos, const std::string& enclave) {
    // The keystore's files, as the builtin plugins name them (file:// URIs).
    const std::vector<std::pair<const char*, const char*>> files = {
        {"dds.sec.auth.builtin.PKI-DH.identity_ca", "identity_ca.cert.pem"},
        {"dds.sec.auth.builtin.PKI-DH.identity_certificate", "cert.pem"},
        {"dds.sec.auth.builtin.PKI-DH.private_key", "key.pem"},
        {"dds.sec.access.builtin.Access-Permissions.permissions_ca", "permissions_ca.cert.pem"},
        {"dds.sec.access.builtin.Access-Permissions.governance", "governance.p7s"},
        {"dds.sec.access.builtin.Access-Permissions.permissions", "permissions.p7s"},
    };
    std::string missing;
    for (const auto& f : files)
        if (!readable(enclave + "/" + f.second)) missing += std::string(missing.empty() ? "" : ", ") + f.second;
    if (!missing.empty())
        throw std::runtime_error("DDS Security keystore " + enclave + ": cannot read " + missing +
                       " (make it with `rapidgen secure`; RAPID_SECURITY_ENCLAVE names another enclave)");
    auto& props = qos.properties().properties();
    props.emplace_back("dds.sec.auth.plugin", "builtin.PKI-DH");
    props.emplace_back("dds.sec.access.plugin", "builtin.Access-Permissions");
    props.emplace_back("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
    for (const auto& f : files) props.emplace_back(f.first, "file://" + enclave + "/" + f.second);
}

std::string security_refusal(const std::string& enclave) {
    return "DDS Security refused this participant's keystore " + enclave +
           ": a certificate not from the identity CA, expired, a key that is not the certificate's, "
           "or governance/permissions whose signature does not verify with the permissions CA "
           "(Fast DDS's log above says which; `rapidgen secure --check` reports expiry)";
}

}  // namespace dds
}  // namespace rapid_runtime
