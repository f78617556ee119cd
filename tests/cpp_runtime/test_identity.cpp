// identity.hpp: whose certificate a writer's GUID prefix comes from (cmdSrc bound to the
// certificate, docs/secure.md). The digest below is the SHA-256 of the DER subject
// "CN=RapidWorkbench" (what `rapidgen secure` writes for that source); the prefix is what
// PKI-DH makes from it: bit 1, then the digest's first 47 bits (8f 6d 69 3e de 53), the
// other 6 bytes from the participant's own candidate GUID.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include <rapid_runtime/identity.hpp>

using namespace rapid_runtime;

namespace {

const std::string RW = "1edad27dbca6b7a03715b7aa7dbcc9d3b38755c4b523b55fc7d0437a59a4607a";
const std::string SB = "8186328593d401747be513fdd4270cb999e926bbd29e01e6cd7f9a10e9c4a884";
const GuidPrefix RW_WRITER{0x8f, 0x6d, 0x69, 0x3e, 0xde, 0x53, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06};

Identities both() {
    return Identities::parse("# comment\n\nRapidWorkbench " + RW + " CN=RapidWorkbench\nScienceBackroom " + SB +
                                 " CN=ScienceBackroom\n",
                             "identities.txt");
}

}  // namespace

TEST(Identity, PrefixComesFromTheSubjectDigest) {
    const Identities ids = both();
    ASSERT_EQ(ids.sources().size(), 2u);
    EXPECT_TRUE(comes_from(RW_WRITER, ids.sources()[0].digest));
    EXPECT_FALSE(comes_from(RW_WRITER, ids.sources()[1].digest));
    EXPECT_EQ(ids.owner(RW_WRITER), "RapidWorkbench");
    GuidPrefix other = RW_WRITER;
    for (int i = 6; i < 12; ++i) other[i] = 0xff;  // the participant's own half does not matter
    EXPECT_EQ(ids.owner(other), "RapidWorkbench");
}

TEST(Identity, EveryOneOfThe47BitsCounts) {
    const Identities ids = both();
    for (int bit = 1; bit < 48; ++bit) {  // prefix bits 1..47 (bit 0 is the flag)
        GuidPrefix flipped = RW_WRITER;
        flipped[bit / 8] ^= static_cast<std::uint8_t>(0x80 >> (bit % 8));
        EXPECT_EQ(ids.owner(flipped), "") << "bit " << bit;
    }
    GuidPrefix unflagged = RW_WRITER;
    unflagged[0] &= 0x7f;  // a GUID PKI-DH never made
    EXPECT_EQ(ids.owner(unflagged), "");
}

TEST(Identity, RefusalNamesBoth) {
    const Identities ids = both();
    EXPECT_FALSE(ids.refusal("RapidWorkbench", RW_WRITER).has_value());
    EXPECT_EQ(ids.refusal("ScienceBackroom", RW_WRITER).value(),
              "cmdSrc 'ScienceBackroom' is not the writer's identity 'RapidWorkbench'");
    GuidPrefix stranger{};
    stranger[0] = 0x80;
    EXPECT_EQ(ids.refusal("RapidWorkbench", stranger).value(),
              "cmdSrc 'RapidWorkbench' is not the writer's identity (its certificate is none of this keystore's "
              "ground sources)");
    EXPECT_EQ(ids.refusal("", RW_WRITER).value(), "cmdSrc '' is not the writer's identity 'RapidWorkbench'");
    // a cmdSrc from the wire is escaped before it reaches a log or an ack
    EXPECT_EQ(ids.refusal("x\x1b[2J", RW_WRITER).value().find('\x1b'), std::string::npos);
}

TEST(Identity, MalformedFilesAreRefusedWithTheirLine) {
    const auto error = [](const std::string& text) {
        try {
            Identities::parse(text, "ids");
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_EQ(error("RapidWorkbench\n").rfind("ids:1: expected", 0), 0u);
    EXPECT_EQ(error("# c\nRapidWorkbench " + RW.substr(2) + "\n").rfind("ids:2: expected", 0), 0u);
    EXPECT_EQ(error("RapidWorkbench " + RW.substr(0, 63) + "g\n").rfind("ids:1: expected", 0), 0u);
    EXPECT_EQ(error("A " + RW + "\nA " + SB + "\n"), "ids:2: source 'A' listed twice");
    EXPECT_TRUE(Identities::parse("", "ids").sources().empty());
    EXPECT_THROW(Identities::load("/nonexistent/identities.txt"), std::runtime_error);
}
