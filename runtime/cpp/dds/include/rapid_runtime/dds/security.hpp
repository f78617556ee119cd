// DDS Security for a participant (docs/security.md, docs/secure.md): when the environment
// names a keystore made by `rapidgen secure`, the participant gets Fast DDS's builtin
// plugins (PKI-DH authentication, Access-Permissions, AES-GCM-GMAC) with its enclave's
// certificate, key, governance and permissions.
//
//   RAPID_SECURITY_KEYSTORE=DIR    the keystore (its enclaves/<name>/ folders)
//   RAPID_SECURITY_ENCLAVE=NAME    the participant's enclave (default: the identity the
//                                  caller gives; a bridge gives its partition, by default
//                                  the asset's name); a path with '/' is used as it is
//
// Without RAPID_SECURITY_KEYSTORE nothing changes. With it, a participant never starts
// unsecured: a missing file is an error naming it.
#ifndef RAPID_RUNTIME_DDS_SECURITY_HPP
#define RAPID_RUNTIME_DDS_SECURITY_HPP

#include <string>

#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>

namespace rapid_runtime {
namespace dds {

// The enclave folder the environment asks `identity` to use ("" when security is off).
std::string security_enclave(const std::string& identity);

// Adds the plugins' properties to `qos` for `enclave` (a folder of `rapidgen secure`'s
// layout); throws std::runtime_error listing the files that are missing (no Fast DDS
// header beyond the QoS: a ground program without the runtime's Node uses it too).
void apply_security(eprosima::fastdds::dds::DomainParticipantQos& qos, const std::string& enclave);

// What to tell the operator when a secured participant could not be created (Fast DDS
// refused the certificate, the key, or a signature: its log says which).
std::string security_refusal(const std::string& enclave);

}  // namespace dds
}  // namespace rapid_runtime

#endif
