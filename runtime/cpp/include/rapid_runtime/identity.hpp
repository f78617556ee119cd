// cmdSrc bound to the certificate (docs/secure.md): in a secured deployment a command runs
// only when its cmdSrc names the participant that wrote it.
//
// DDS Security's PKI-DH makes a participant's GUID prefix from its identity certificate:
// the first bit 1, then the first 47 bits of the SHA-256 of the certificate's subject name
// (DER); Fast DDS 2.9 refuses a handshake whose participant GUID does not come from the
// certificate it authenticated with (PKIDH.cpp, "Bad participant_key's 47bits in c.pdata").
// `rapidgen secure` writes each asset's enclave an identities.txt: one line per ground
// source, "<source> <64 hex digits: the subject's SHA-256> [the subject, for people]".
// From it and the GUID prefix of the writer a command came from, the bridge knows whose
// certificate wrote it. No DDS and no crypto here: the digests come from the keystore.
#ifndef RAPID_RUNTIME_IDENTITY_HPP
#define RAPID_RUNTIME_IDENTITY_HPP

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rapid_runtime {

inline constexpr const char* IDENTITIES_FILE = "identities.txt";

using SubjectDigest = std::array<std::uint8_t, 32>;
using GuidPrefix = std::array<std::uint8_t, 12>;

// Whether a participant whose GUID prefix is `prefix` authenticated with a certificate
// whose subject name hashes to `digest` (the 47 bits PKI-DH derives, and the first bit).
bool comes_from(const GuidPrefix& prefix, const SubjectDigest& digest);

class Identities {
public:
    struct Source {
        std::string name;
        SubjectDigest digest{};
    };

    // An identities.txt's content; throws std::runtime_error naming `where` and the line.
    static Identities parse(const std::string& text, const std::string& where);
    // The file; throws std::runtime_error when it cannot be read or parsed.
    static Identities load(const std::string& path);

    // The source whose certificate the writer's GUID prefix comes from ("" when none).
    std::string owner(const GuidPrefix& writer) const;
    // Why a command from `writer` claiming `cmd_src` must not run (nothing when cmd_src is
    // the writer's identity): "cmdSrc 'A' is not the writer's identity 'B'".
    std::optional<std::string> refusal(const std::string& cmd_src, const GuidPrefix& writer) const;

    const std::vector<Source>& sources() const { return sources_; }

private:
    std::vector<Source> sources_;
};

}  // namespace rapid_runtime

#endif
