// A domain id whose RTPS ports lie in the host's ephemeral port range lets other domains in.
//
// Fast DDS 2.9 announces its participants without their domain id, and Cyclone DDS also reads
// the socket it sends from, whose port the kernel picks from the ephemeral range. When one of
// a Fast DDS participant's discovery ports (where it sends its announcements) is such a port
// of a Cyclone participant on ANOTHER domain, the two discover each other across domains:
// seen here, a conformance runner on domain 75 judged a C++ bridge on domain 133. Linux's
// default range (32768-60999) holds the ports of domains 102-214; ROS 2 gives the same advice
// (0-101) for the same reason. Node warns at start-up (docs/qos.md, "Domain ids on one host").
#ifndef RAPID_RUNTIME_PORTS_HPP
#define RAPID_RUNTIME_PORTS_HPP

#include <sstream>
#include <string>

namespace rapid_runtime {

struct PortRange {
    long first = 0, last = -1;  // inclusive; empty when last < first
    bool empty() const { return last < first; }
    bool overlaps(const PortRange& o) const { return !empty() && !o.empty() && first <= o.last && o.first <= last; }
};

// The well-known ports of a domain's first 20 participant indices (the generated
// configurations' MaxAutoParticipantIndex 19): port base 7400, domain gain 250, participant
// gain 2, offsets 0, 1, 10 and 11.
inline PortRange rtps_ports(int domain) {
    const long base = 7400L + 250L * domain;
    return {base, base + 11 + 2 * 19};
}

// The text of /proc/sys/net/ipv4/ip_local_port_range ("32768\t60999"); empty when unreadable.
inline PortRange parse_port_range(const std::string& text) {
    std::istringstream in(text);
    PortRange r;
    if (!(in >> r.first >> r.last) || r.first < 1 || r.last > 65535) return {};
    return r;
}

// The warning to print, or "" when the domain's ports are clear of `ephemeral`.
inline std::string ephemeral_clash(int domain, const PortRange& ephemeral) {
    const PortRange ports = rtps_ports(domain);
    if (!ports.overlaps(ephemeral)) return "";
    std::ostringstream out;
    out << "domain " << domain << "'s RTPS ports (" << ports.first << "-" << ports.last
        << ") lie in this host's ephemeral port range (" << ephemeral.first << "-" << ephemeral.last
        << ", net.ipv4.ip_local_port_range): a Cyclone DDS participant on another domain can discover this one "
           "(Fast DDS announces no domain id); choose a domain id whose ports lie outside it (0-101 with "
           "Linux's default range)";
    return out.str();
}

}  // namespace rapid_runtime

#endif
