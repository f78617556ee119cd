// ports.hpp: which domain ids put their RTPS ports into the host's ephemeral range (where
// a Cyclone participant of another domain can be given one of them as its send port).
#include <gtest/gtest.h>

#include <rapid_runtime/ports.hpp>

using namespace rapid_runtime;

TEST(Ports, WellKnownPortsOfADomain) {
    EXPECT_EQ(rtps_ports(0).first, 7400);
    EXPECT_EQ(rtps_ports(0).last, 7449);  // index 19's user unicast port, 7400 + 11 + 2 * 19
    EXPECT_EQ(rtps_ports(133).first, 40650);
}

TEST(Ports, RangeFromProc) {
    const PortRange r = parse_port_range("32768\t60999\n");
    EXPECT_EQ(r.first, 32768);
    EXPECT_EQ(r.last, 60999);
    EXPECT_TRUE(parse_port_range("").empty());
    EXPECT_TRUE(parse_port_range("32768").empty());
    EXPECT_TRUE(parse_port_range("x y").empty());
    EXPECT_TRUE(parse_port_range("0 70000").empty());
}

TEST(Ports, LinuxDefaultRangeClashesWithDomains102To214) {
    const PortRange linux_default = parse_port_range("32768 60999");
    for (int d = 0; d <= 232; ++d) {
        const bool clash = !ephemeral_clash(d, linux_default).empty();
        EXPECT_EQ(clash, d >= 102 && d <= 214) << "domain " << d;
    }
    const std::string text = ephemeral_clash(133, linux_default);
    EXPECT_NE(text.find("domain 133's RTPS ports (40650-40699)"), std::string::npos) << text;
    EXPECT_NE(text.find("(32768-60999"), std::string::npos) << text;
}

TEST(Ports, TheHostsRangeDecides) {
    EXPECT_EQ(ephemeral_clash(133, PortRange{}), "");
    EXPECT_EQ(ephemeral_clash(13, parse_port_range("1024 65535")).empty(), false);  // a wide range reaches 13 too
}
