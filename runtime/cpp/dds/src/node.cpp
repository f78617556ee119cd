#include "rapid_runtime/dds/node.hpp"
#include "rapid_runtime/dds/security.hpp"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <iterator>

#include <rapid_runtime/ports.hpp>

#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/topic/Topic.hpp>

namespace rapid_runtime {
namespace dds {

using namespace eprosima::fastdds::dds;

void quiet_nack_suppression(DataWriterQos& qos) {
    auto& d = qos.reliable_writer_qos().times.nackSupressionDuration;
    if (d.seconds == 0 && d.nanosec == 0) d = eprosima::fastrtps::Duration_t(0, NACK_SUPPRESSION_NS);
}

namespace {

// Fast DDS 2.9 keeps a profile's <data_writer>/<data_reader> <partition> as the endpoint
// property "partitions", which overrides the publisher's and subscriber's: every endpoint
// then stayed in the partition the profiles were generated for (K10's rapid_cmd with
// `--asset Restarter` or `--partition Foo` still matched only K10Red). The node's
// partition is the asset's (NodeOptions::partition), so the endpoint's copy goes.
void drop_endpoint_partitions(eprosima::fastrtps::rtps::PropertyPolicy& properties) {
    auto& all = properties.properties();
    all.erase(std::remove_if(all.begin(), all.end(), [](const auto& p) { return p.name() == "partitions"; }),
              all.end());
}

// Once per process: a domain whose ports the kernel may give out as ephemeral ones (ports.hpp).
void warn_of_ephemeral_ports(int domain) {
    static std::atomic<bool> warned{false};
    std::ifstream in("/proc/sys/net/ipv4/ip_local_port_range");
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const std::string clash = ephemeral_clash(domain, parse_port_range(text));
    if (clash.empty() || warned.exchange(true)) return;
    std::cerr << "rapid_runtime: warning: " << clash << std::endl;
}

}  // namespace

Node::Node(const NodeOptions& options) : partition_(options.partition) {
    auto* factory = DomainParticipantFactory::get_instance();
    const char* env = std::getenv("FASTDDS_DEFAULT_PROFILES_FILE");
    if (env == nullptr) env = std::getenv("FASTRTPS_DEFAULT_PROFILES_FILE");
    if (options.profiles_file.empty() && options.profiles_xml.empty() && (env == nullptr || *env == '\0'))
        throw DdsError("no QoS profiles: give the generated qos/fastdds/rapid_qos_profiles.xml or set "
                       "FASTDDS_DEFAULT_PROFILES_FILE (Fast DDS's defaults would leave loopback)");
    factory->load_profiles();  // FASTDDS_DEFAULT_PROFILES_FILE, when set
    if (!options.profiles_file.empty()) {
        if (factory->load_XML_profiles_file(options.profiles_file) != ReturnCode_t::RETCODE_OK)
            throw DdsError("cannot load QoS profiles " + options.profiles_file);
    } else if (!options.profiles_xml.empty() &&
               factory->load_XML_profiles_string(options.profiles_xml.data(), options.profiles_xml.size()) !=
                   ReturnCode_t::RETCODE_OK) {
        throw DdsError("cannot load the built-in QoS profiles");
    }
    DomainParticipantQos pqos;
    if (factory->get_participant_qos_from_profile("rapid_" + options.transport, pqos) != ReturnCode_t::RETCODE_OK)
        throw DdsError("no participant profile rapid_" + options.transport + " in the loaded QoS profiles");
    // A transport with rtt (docs/qos.md "Slow links") names the copies of the endpoint
    // profiles that carry its reliability timers: Fast DDS sets those per writer and reader.
    for (const auto& property : pqos.properties().properties())
        if (property.name() == "rapid.link") link_ = property.value();
    const std::string enclave = security_enclave(partition_);  // DDS Security hook (security.hpp)
    if (!enclave.empty()) apply_security(pqos, enclave);
    warn_of_ephemeral_ports(options.domain);
    participant_ = factory->create_participant(options.domain, pqos);
    if (participant_ == nullptr)
        throw DdsError(!enclave.empty() ? security_refusal(enclave)
                                        : "no participant from profile rapid_" + options.transport + " on domain " +
                                              std::to_string(options.domain));
    // One publisher and one subscriber in the asset's partition: the partition is theirs in
    // DDS, and every RAPID endpoint of the asset shares it.
    PublisherQos pq = participant_->get_default_publisher_qos();
    pq.partition().clear();
    pq.partition().push_back(partition_.c_str());
    publisher_ = participant_->create_publisher(pq);
    SubscriberQos sq = participant_->get_default_subscriber_qos();
    sq.partition().clear();
    sq.partition().push_back(partition_.c_str());
    subscriber_ = participant_->create_subscriber(sq);
    if (publisher_ == nullptr || subscriber_ == nullptr) throw DdsError("cannot create publisher or subscriber");
}

Node::~Node() {
    if (participant_ == nullptr) return;
    participant_->delete_contained_entities();
    DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

Topic* Node::topic_of(const std::string& name, const std::string& type) {
    auto found = topics_.find(name);
    if (found != topics_.end()) return found->second;
    Topic* t = participant_->create_topic(name, type, TOPIC_QOS_DEFAULT);
    if (t == nullptr) throw DdsError("cannot create topic " + name + " of " + type);
    topics_[name] = t;
    return t;
}

DataWriter* Node::make_writer(Topic* topic, const std::string& profile, const WriterTweak& tweak) {
    DataWriterQos qos;
    if ((link_.empty() || publisher_->get_datawriter_qos_from_profile(profile + "@" + link_, qos) !=
                              ReturnCode_t::RETCODE_OK) &&
        publisher_->get_datawriter_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK)
        throw DdsError("no writer profile " + profile + " in the loaded QoS profiles");
    drop_endpoint_partitions(qos.properties());
    if (tweak) tweak(qos);
    DataWriter* w = publisher_->create_datawriter(topic, qos);
    if (w == nullptr) throw DdsError("cannot create writer of " + topic->get_name() + " (" + profile + ")");
    return w;
}

void Node::delete_writer(DataWriter* writer) {
    if (publisher_->delete_datawriter(writer) != ReturnCode_t::RETCODE_OK)
        throw DdsError("cannot delete a writer of " + writer->get_topic()->get_name());
}

DataReader* Node::make_reader(Topic* topic, const std::string& profile, const ReaderTweak& tweak,
                              DataReaderListener* listener) {
    DataReaderQos qos;
    if ((link_.empty() || subscriber_->get_datareader_qos_from_profile(profile + "@" + link_, qos) !=
                              ReturnCode_t::RETCODE_OK) &&
        subscriber_->get_datareader_qos_from_profile(profile, qos) != ReturnCode_t::RETCODE_OK)
        throw DdsError("no reader profile " + profile + " in the loaded QoS profiles");
    drop_endpoint_partitions(qos.properties());
    if (tweak) tweak(qos);
    DataReader* r = listener == nullptr
                        ? subscriber_->create_datareader(topic, qos)
                        : subscriber_->create_datareader(topic, qos, listener, StatusMask::data_available());
    if (r == nullptr) throw DdsError("cannot create reader of " + topic->get_name() + " (" + profile + ")");
    return r;
}

}  // namespace dds
}  // namespace rapid_runtime
