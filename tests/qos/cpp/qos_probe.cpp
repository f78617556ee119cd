// Test probe for the generated Fast DDS XML (tests/qos): built by the tests with g++
// against Fast DDS 2.9, never shipped.
//
//   qos_probe qos  XML DOMAIN PARTICIPANT_PROFILE PROFILE...   print each profile's QoS (JSON lines)
//   qos_probe pqos XML - PROFILE...                            print participant profiles' QoS (creates nothing)
//   qos_probe echo XML DOMAIN PARTICIPANT_PROFILE PROFILE SECONDS COUNT
//                  read rapidtest_ping, write every sample back on rapidtest_pong
//   qos_probe ping XML DOMAIN PARTICIPANT_PROFILE PROFILE SECONDS COUNT
//                  write pings until COUNT distinct pongs came back (exit 0) or SECONDS passed (exit 1)
//
// Any Fast DDS error or warning logged while loading the XML fails the run (exit 3).
#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/log/Log.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/transport/TCPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

using namespace eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::SerializedPayload_t;
using eprosima::fastrtps::rtps::InstanceHandle_t;

namespace {

std::atomic<int> g_problems{0};
std::atomic<bool> g_loading{true};  // problems count while the XML loads; later only errors print

class CountingConsumer : public LogConsumer {
public:
    void Consume(const Log::Entry& entry) override {
        if (entry.kind == Log::Kind::Error || entry.kind == Log::Kind::Warning) {
            if (g_loading) ++g_problems;
            std::cerr << "fastdds log [" << entry.context.category << "] " << entry.message << std::endl;
        }
    }
};

// rapidtest::Ping { long seq; string text; } (@final, XCDR1), as in the Python side.
struct Ping {
    int32_t seq = 0;
    std::string text;
};

class PingType : public TopicDataType {
public:
    PingType() {
        setName("rapidtest::Ping");
        m_typeSize = 4 + 4 + 4 + 260;  // encapsulation + seq + string length + text
        m_isGetKeyDefined = false;
        auto_fill_type_information(false);
        auto_fill_type_object(false);
    }
    bool serialize(void* data, SerializedPayload_t* payload) override {
        auto* p = static_cast<Ping*>(data);
        eprosima::fastcdr::FastBuffer buf(reinterpret_cast<char*>(payload->data), payload->max_size);
        eprosima::fastcdr::Cdr ser(buf, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
        payload->encapsulation = ser.endianness() == eprosima::fastcdr::Cdr::BIG_ENDIANNESS ? CDR_BE : CDR_LE;
        try {
            ser.serialize_encapsulation();
            ser << p->seq << p->text;
        } catch (...) {
            return false;
        }
        payload->length = static_cast<uint32_t>(ser.getSerializedDataLength());
        return true;
    }
    bool deserialize(SerializedPayload_t* payload, void* data) override {
        auto* p = static_cast<Ping*>(data);
        eprosima::fastcdr::FastBuffer buf(reinterpret_cast<char*>(payload->data), payload->length);
        eprosima::fastcdr::Cdr deser(buf, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
        try {
            deser.read_encapsulation();
            payload->encapsulation = deser.endianness() == eprosima::fastcdr::Cdr::BIG_ENDIANNESS ? CDR_BE : CDR_LE;
            deser >> p->seq >> p->text;
        } catch (...) {
            return false;
        }
        return true;
    }
    std::function<uint32_t()> getSerializedSizeProvider(void* data) override {
        auto* p = static_cast<Ping*>(data);
        return [p]() { return static_cast<uint32_t>(4 + 4 + 4 + p->text.size() + 1 + 3); };
    }
    void* createData() override { return new Ping(); }
    void deleteData(void* data) override { delete static_cast<Ping*>(data); }
    bool getKey(void*, InstanceHandle_t*, bool) override { return false; }
};

const char* name_of(ReliabilityQosPolicyKind k) { return k == RELIABLE_RELIABILITY_QOS ? "reliable" : "best_effort"; }
const char* name_of(DurabilityQosPolicyKind k) {
    switch (k) {
        case VOLATILE_DURABILITY_QOS: return "volatile";
        case TRANSIENT_LOCAL_DURABILITY_QOS: return "transient_local";
        case TRANSIENT_DURABILITY_QOS: return "transient";
        default: return "persistent";
    }
}
const char* name_of(HistoryQosPolicyKind k) { return k == KEEP_LAST_HISTORY_QOS ? "keep_last" : "keep_all"; }

std::string partitions(const PartitionQosPolicy& p) {
    std::string out = "[";
    bool first = true;
    for (const auto& n : p.names()) {
        out += (first ? "\"" : ",\"") + n + "\"";
        first = false;
    }
    return out + "]";
}

int fail(const std::string& msg) {
    Log::Flush();
    std::cerr << "qos_probe: " << msg << std::endl;
    return 2;
}

struct Session {
    DomainParticipant* participant = nullptr;
    Topic* ping = nullptr;
    Topic* pong = nullptr;
};

int open_session(const std::string& xml, int domain, const std::string& profile, Session& s) {
    auto* factory = DomainParticipantFactory::get_instance();
    if (factory->load_XML_profiles_file(xml) != ReturnCode_t::RETCODE_OK) return fail("cannot load " + xml);
    Log::Flush();
    if (g_problems) return 3;
    g_loading = false;
    Log::SetVerbosity(Log::Kind::Error);
    s.participant = factory->create_participant_with_profile(domain, profile);
    if (s.participant == nullptr) return fail("cannot create participant with profile " + profile);
    TypeSupport type(new PingType());
    type.register_type(s.participant);
    s.ping = s.participant->create_topic("rapidtest_ping", "rapidtest::Ping", TOPIC_QOS_DEFAULT);
    s.pong = s.participant->create_topic("rapidtest_pong", "rapidtest::Ping", TOPIC_QOS_DEFAULT);
    return (s.ping && s.pong) ? 0 : fail("cannot create topics");
}

double seconds(const eprosima::fastrtps::Duration_t& d) { return d.seconds + d.nanosec * 1e-9; }

std::string link_of(const DomainParticipantQos& q) {
    for (const auto& p : q.properties().properties())
        if (p.name() == "rapid.link") return p.value();
    return "";
}

void print_participant(const std::string& profile) {
    DomainParticipantQos q;
    DomainParticipantFactory::get_instance()->get_participant_qos_from_profile(profile, q);
    const auto& port = q.wire_protocol().port;
    uint32_t max_size = 0;
    for (const auto& t : q.transport().user_transports) {
        if (auto udp = std::dynamic_pointer_cast<eprosima::fastdds::rtps::UDPv4TransportDescriptor>(t)) {
            max_size = udp->maxMessageSize;
        }
    }
    std::cout << "{\"participant\":\"" << profile << "\",\"port_base\":" << port.portBase
              << ",\"domain_gain\":" << port.domainIDGain << ",\"participant_gain\":" << port.participantIDGain
              << ",\"d0\":" << port.offsetd0 << ",\"d1\":" << port.offsetd1 << ",\"d2\":" << port.offsetd2
              << ",\"d3\":" << port.offsetd3 << ",\"max_message_size\":" << max_size
              << ",\"builtin_transports\":" << (q.transport().use_builtin_transports ? "true" : "false")
              << ",\"discovery\":" << static_cast<int>(q.wire_protocol().builtin.discovery_config.discoveryProtocol)
              << ",\"multicast_locators\":" << q.wire_protocol().builtin.metatrafficMulticastLocatorList.size()
              << ",\"initial_peers\":" << q.wire_protocol().builtin.initialPeersList.size()
              << ",\"transports\":" << q.transport().user_transports.size()
              << ",\"lease\":" << seconds(q.wire_protocol().builtin.discovery_config.leaseDuration)
              << ",\"announcement\":"
              << seconds(q.wire_protocol().builtin.discovery_config.leaseDuration_announcementperiod)
              << ",\"link\":\"" << link_of(q) << "\"}" << std::endl;
}

std::string limits(const ResourceLimitsQosPolicy& l) {
    return "\"max_samples\":" + std::to_string(l.max_samples) + ",\"max_instances\":" +
           std::to_string(l.max_instances) + ",\"max_samples_per_instance\":" +
           std::to_string(l.max_samples_per_instance);
}

int run_qos(Session& s, const std::vector<std::string>& profiles) {
    for (const auto& name : profiles) {
        Publisher* pub = s.participant->create_publisher_with_profile(name);
        Subscriber* sub = s.participant->create_subscriber_with_profile(name);
        if (!pub || !sub) return fail("no publisher/subscriber profile " + name);
        DataWriter* w = pub->create_datawriter_with_profile(s.ping, name);
        DataReader* r = sub->create_datareader_with_profile(s.ping, name);
        if (!w || !r) return fail("no data_writer/data_reader profile " + name);
        DataWriterQos wq = w->get_qos();
        DataReaderQos rq = r->get_qos();
        std::cout << "{\"profile\":\"" << name << "\",\"side\":\"writer\",\"reliability\":\""
                  << name_of(wq.reliability().kind) << "\",\"durability\":\"" << name_of(wq.durability().kind)
                  << "\",\"history\":\"" << name_of(wq.history().kind) << "\",\"depth\":" << wq.history().depth
                  << ",\"publish_mode\":\""
                  << (wq.publish_mode().kind == ASYNCHRONOUS_PUBLISH_MODE ? "asynchronous" : "synchronous")
                  << "\"," << limits(wq.resource_limits())
                  << ",\"heartbeat\":" << seconds(wq.reliable_writer_qos().times.heartbeatPeriod)
                  << ",\"nack_suppression\":" << seconds(wq.reliable_writer_qos().times.nackSupressionDuration)
                  << ",\"max_blocking\":" << seconds(wq.reliability().max_blocking_time)
                  << ",\"partition\":" << partitions(pub->get_qos().partition()) << "}" << std::endl;
        std::cout << "{\"profile\":\"" << name << "\",\"side\":\"reader\",\"reliability\":\""
                  << name_of(rq.reliability().kind) << "\",\"durability\":\"" << name_of(rq.durability().kind)
                  << "\",\"history\":\"" << name_of(rq.history().kind) << "\",\"depth\":" << rq.history().depth
                  << "," << limits(rq.resource_limits())
                  << ",\"partition\":" << partitions(sub->get_qos().partition()) << "}" << std::endl;
    }
    return 0;
}

int run_exchange(Session& s, const std::string& profile, bool echo, double seconds, int count) {
    Publisher* pub = s.participant->create_publisher_with_profile(profile);
    Subscriber* sub = s.participant->create_subscriber_with_profile(profile);
    if (!pub || !sub) return fail("no publisher/subscriber profile " + profile);
    DataWriter* w = pub->create_datawriter_with_profile(echo ? s.pong : s.ping, profile);
    DataReader* r = sub->create_datareader_with_profile(echo ? s.ping : s.pong, profile);
    if (!w || !r) return fail("no data_writer/data_reader profile " + profile);
    auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    auto next_ping = std::chrono::steady_clock::now();
    std::set<int32_t> seen;
    int32_t seq = 0;
    std::cout << "ready" << std::endl;
    while (std::chrono::steady_clock::now() < deadline && static_cast<int>(seen.size()) < count) {
        if (!echo && std::chrono::steady_clock::now() >= next_ping) {
            Ping p;
            p.seq = ++seq;
            p.text = "fastdds ping " + std::to_string(p.seq);
            w->write(&p);
            next_ping += std::chrono::milliseconds(100);
        }
        Ping got;
        SampleInfo info;
        while (r->take_next_sample(&got, &info) == ReturnCode_t::RETCODE_OK) {
            if (!info.valid_data) continue;
            if (echo) {
                got.text = "echo: " + got.text;
                w->write(&got);
            }
            if (seen.insert(got.seq).second) std::cout << "got " << got.seq << " " << got.text << std::endl;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (echo) std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let the last echoes go out
    std::cout << "received " << seen.size() << std::endl;
    return static_cast<int>(seen.size()) >= count ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 5) {
        std::cerr << "usage: qos_probe qos|echo|ping XML DOMAIN PARTICIPANT_PROFILE PROFILE..." << std::endl;
        return 2;
    }
    Log::ClearConsumers();
    Log::RegisterConsumer(std::unique_ptr<LogConsumer>(new CountingConsumer()));
    Log::SetVerbosity(Log::Kind::Warning);
    std::string mode = argv[1], xml = argv[2], participant_profile = argv[4];
    int domain = std::atoi(argv[3]);
    if (mode == "pqos") {
        if (DomainParticipantFactory::get_instance()->load_XML_profiles_file(xml) != ReturnCode_t::RETCODE_OK) {
            return fail("cannot load " + xml);
        }
        Log::Flush();
        if (g_problems) return 3;
        for (int i = 4; i < argc; ++i) print_participant(argv[i]);
        Log::Flush();
        return g_problems ? 3 : 0;
    }
    Session s;
    int rc = open_session(xml, domain, participant_profile, s);
    if (rc != 0) return rc;
    if (mode == "qos") {
        print_participant(participant_profile);
        rc = run_qos(s, std::vector<std::string>(argv + 5, argv + argc));
    } else if ((mode == "echo" || mode == "ping") && argc == 8) {
        rc = run_exchange(s, argv[5], mode == "echo", std::atof(argv[6]), std::atoi(argv[7]));
    } else {
        rc = fail("bad arguments");
    }
    s.participant->delete_contained_entities();
    DomainParticipantFactory::get_instance()->delete_participant(s.participant);
    Log::Flush();
    return rc;
}
