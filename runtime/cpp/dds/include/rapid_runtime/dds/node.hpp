// One Fast DDS participant of the asset, from the generated QoS profiles: writers and
// readers per topic with their RAPID profile, in the asset's partition.
//
// DDS traffic stays where the profiles say: the participant is created from a profile of
// the generated Fast DDS XML ("rapid_local": loopback only), loaded from `profiles_file`,
// else from `profiles_xml` (the XML itself: a generated bridge carries its asset's), and
// from FASTDDS_DEFAULT_PROFILES_FILE (load_profiles()). Without any of them it refuses to
// start rather than fall back to Fast DDS's defaults (multicast on every interface).
#ifndef RAPID_RUNTIME_DDS_NODE_HPP
#define RAPID_RUNTIME_DDS_NODE_HPP

#include <cstdint>
#include <functional>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include "rapid_runtime_dds_types.hpp"

namespace rapid_runtime {
namespace dds {

class DdsError : public std::runtime_error {
public:
    explicit DdsError(const std::string& what) : std::runtime_error(what) {}
};

struct NodeOptions {
    int domain = 0;
    std::string profiles_file;  // the generated qos/fastdds/rapid_qos_profiles.xml
    std::string profiles_xml;  // or its content (used when profiles_file is empty)
    std::string transport = "local";  // participant profile "rapid_<transport>"
    std::string partition;  // the asset's; overrides the profiles' partition
};

// A reliable writer's NACK suppression, when its profile leaves Fast DDS's 0: 5 ms. With 0,
// each sample sent restarts the reader proxy's suppression timer, which wakes Fast DDS's
// event thread at once to take the writer's lock (against the next write) for every
// sample; with 5 ms it wakes once per 5 ms of writes. A NACK inside those 5 ms is for a
// sample still on its way (it comes only with a heartbeat: 5 ms apart here); a link's
// profile (docs/qos.md "Slow links") sets its own (0.8 x rtt) and keeps it.
inline constexpr std::uint32_t NACK_SUPPRESSION_NS = 5'000'000;
// The heartbeat period of rapid_cmd's command writer and the bridge's ack writer off a slow
// link. The command writer's KEEP_ALL history (400 samples) is emptied only by the reader's
// ACKNACK, which answers a heartbeat: with 100 ms, a client sending 4000+ commands a second
// filled it and its next write blocked until the heartbeat (20-70 ms maxima in the benches);
// with 5 ms it holds ~20 at that rate. A late-joining ack reader gets the kept acks, and its
// own after them, once a heartbeat has brought its first ACKNACK. A heartbeat goes out only
// while samples are unacknowledged; a link keeps 100 ms (a NACK there costs a resend).
inline constexpr std::uint32_t COMMAND_HEARTBEAT_NS = 5'000'000;
void quiet_nack_suppression(eprosima::fastdds::dds::DataWriterQos& qos);

class Node {
public:
    using WriterTweak = std::function<void(eprosima::fastdds::dds::DataWriterQos&)>;
    using ReaderTweak = std::function<void(eprosima::fastdds::dds::DataReaderQos&)>;

    explicit Node(const NodeOptions& options);
    ~Node();
    Node(const Node&) = delete;
    Node& operator=(const Node&) = delete;
    // The participant's transport is a slow link (a profile with rtt: docs/qos.md "Slow links").
    bool on_link() const { return !link_.empty(); }

    // The topic's writer (created once, with `profile`, then tweak(qos) applied).
    template <class T>
    eprosima::fastdds::dds::DataWriter* writer(const std::string& topic, const std::string& profile,
                                               const WriterTweak& tweak = {}) {
        std::lock_guard<std::recursive_mutex> lock(mutex_);
        auto found = writers_.find(topic);
        if (found != writers_.end()) return found->second;
        auto* w = make_writer(make_topic<T>(topic), profile, tweak);
        writers_[topic] = w;
        return w;
    }

    // A writer of the topic of its own (not the topic's shared one: the ack writers'
    // generations, ack_writers.hpp), deleted with delete_writer() or with the node. Both
    // leave the node's lock free while Fast DDS makes or deletes the writer (writer()'s
    // lookups on the command path do not wait for them).
    template <class T>
    eprosima::fastdds::dds::DataWriter* new_writer(const std::string& topic, const std::string& profile,
                                                   const WriterTweak& tweak = {}) {
        eprosima::fastdds::dds::Topic* t = nullptr;
        {
            std::lock_guard<std::recursive_mutex> lock(mutex_);
            t = make_topic<T>(topic);
        }
        return make_writer(t, profile, tweak);
    }
    void delete_writer(eprosima::fastdds::dds::DataWriter* writer);

    // A new reader of the topic; with a listener, it hears data_available only (on Fast
    // DDS's receive thread, from the reader's creation: no sample comes before it).
    template <class T>
    eprosima::fastdds::dds::DataReader* reader(const std::string& topic, const std::string& profile,
                                               const ReaderTweak& tweak = {},
                                               eprosima::fastdds::dds::DataReaderListener* listener = nullptr) {
        std::lock_guard<std::recursive_mutex> lock(mutex_);
        return make_reader(make_topic<T>(topic), profile, tweak, listener);
    }

    eprosima::fastdds::dds::DomainParticipant* participant() { return participant_; }
    const std::string& partition() const { return partition_; }

private:
    template <class T>
    eprosima::fastdds::dds::Topic* make_topic(const std::string& name) {
        const char* type = rapidgen::dds::Traits<T>::name;
        if (participant_->find_type(type).empty())
            eprosima::fastdds::dds::TypeSupport(new rapidgen::dds::TopicType<T>()).register_type(participant_);
        return topic_of(name, type);
    }
    eprosima::fastdds::dds::Topic* topic_of(const std::string& name, const std::string& type);
    eprosima::fastdds::dds::DataWriter* make_writer(eprosima::fastdds::dds::Topic* topic, const std::string& profile,
                                                    const WriterTweak& tweak);
    eprosima::fastdds::dds::DataReader* make_reader(eprosima::fastdds::dds::Topic* topic, const std::string& profile,
                                                    const ReaderTweak& tweak,
                                                    eprosima::fastdds::dds::DataReaderListener* listener);

    std::recursive_mutex mutex_;
    std::string partition_;
    std::string link_;  // the participant profile's rapid.link: endpoint profiles <profile>@<link> first
    eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
    eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
    eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
    std::map<std::string, eprosima::fastdds::dds::Topic*> topics_;
    std::map<std::string, eprosima::fastdds::dds::DataWriter*> writers_;
};

}  // namespace dds
}  // namespace rapid_runtime

#endif
