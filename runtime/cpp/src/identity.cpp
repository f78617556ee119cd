#include "rapid_runtime/identity.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rapid_runtime/text.hpp"

namespace rapid_runtime {

namespace {

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

bool parse_digest(const std::string& hex, SubjectDigest& out) {
    if (hex.size() != 2 * out.size()) return false;
    for (std::size_t i = 0; i < out.size(); ++i) {
        const int hi = hex_value(hex[2 * i]), lo = hex_value(hex[2 * i + 1]);
        if (hi < 0 || lo < 0) return false;
        out[i] = static_cast<std::uint8_t>(hi << 4 | lo);
    }
    return true;
}

}  // namespace

bool comes_from(const GuidPrefix& prefix, const SubjectDigest& digest) {
    // prefix bits 1..47 are the digest's bits 0..46 (bit 0 of the prefix is set).
    if ((prefix[0] & 0x80) == 0) return false;
    for (std::size_t i = 0; i < 6; ++i) {
        std::uint8_t bits = static_cast<std::uint8_t>(prefix[i] << 1);
        if (i < 5) bits = static_cast<std::uint8_t>(bits | prefix[i + 1] >> 7);
        const std::uint8_t want = i < 5 ? digest[i] : static_cast<std::uint8_t>(digest[i] & 0xfe);
        if (bits != want) return false;
    }
    return true;
}

Identities Identities::parse(const std::string& text, const std::string& where) {
    Identities out;
    std::istringstream in(text);
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::istringstream fields(line);
        std::string name, hex;
        if (!(fields >> name) || name[0] == '#') continue;
        Source s;
        s.name = name;
        if (!(fields >> hex) || !parse_digest(hex, s.digest))
            throw std::runtime_error(where + ":" + std::to_string(number) +
                                     ": expected '<source> <64 hex digits>' (run rapidgen secure)");
        for (const auto& known : out.sources_)
            if (known.name == name)
                throw std::runtime_error(where + ":" + std::to_string(number) + ": source '" + visible(name) +
                                         "' listed twice");
        out.sources_.push_back(std::move(s));
    }
    return out;
}

Identities Identities::load(const std::string& path) {
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error("cannot read " + path +
                                 ": a secured bridge binds cmdSrc to the writer's certificate with it "
                                 "(run rapidgen secure to write it; docs/secure.md)");
    std::ostringstream text;
    text << in.rdbuf();
    return parse(text.str(), path);
}

std::string Identities::owner(const GuidPrefix& writer) const {
    for (const auto& s : sources_)
        if (comes_from(writer, s.digest)) return s.name;
    return "";
}

std::optional<std::string> Identities::refusal(const std::string& cmd_src, const GuidPrefix& writer) const {
    const std::string who = owner(writer);
    if (!who.empty() && who == cmd_src) return std::nullopt;
    std::string text = "cmdSrc '" + visible(cmd_src, 64) + "' is not the writer's identity";
    if (!who.empty()) return text + " '" + who + "'";
    return text + " (its certificate is none of this keystore's ground sources)";
}

}  // namespace rapid_runtime
