// Robonaut 2's RAPID bridge, hand-written on Fast DDS 2.9 without rapidgen's runtime: it
// uses only the generated types, topic types and computed configs (asset.hpp), and the
// generated Fast DDS QoS profiles. What it does is RAPID's (rapid-protocol.md 5):
//   - publishes each config once, durable, with one serial (start time in seconds);
//   - answers each command once per cmdId: EXECUTING -> COMPLETED/OK, or COMPLETED/BAD_SYNTAX
//     when the subsystem, command, argument count or an argument's type does not match the
//     CommandConfig; ignores commands addressed to another asset and repeated cmdIds;
//   - publishes agent, joint and position telemetry at Robonaut 2's rates (10, 50, 10 Hz).
// Deliberately missing: parameter ranges (the CommandConfig does not carry them), so
// conformance check CMD-15 (recommended) fails.
//
//   r2_asset PROFILES_XML DOMAIN SECONDS    prints "bridge ready" once its endpoints exist
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <iostream>
#include <set>
#include <string>
#include <thread>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <rapid_robonaut2/asset.hpp>
#include <rapid_robonaut2/topics.hpp>

using namespace eprosima::fastdds::dds;
using Clock = std::chrono::steady_clock;
namespace r2 = rapid_robonaut2;

static const std::string SOURCE = "R2CppBridge";
static const std::string ASSET(r2::ASSET_NAME);
// Acks are keyed by cmdId: one instance per command. The generated profile sets no instance
// limit (Fast DDS's default of 10 would refuse the 11th command's acks), so memory is
// bounded here: the final acks of this many recent commands stay for late joiners, the
// oldest is unregistered (its history freed once every reader acknowledged).
static constexpr std::size_t ACK_INSTANCES = 1024;

static std::int64_t micros_now() {
    return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

class Node {
public:
    Node(DomainParticipant* p) : p_(p) {}

    template <class T>
    DataWriter* writer(std::string_view topic, std::string_view profile) {
        DataWriter* w = p_->create_publisher_with_profile(std::string(profile))
                            ->create_datawriter_with_profile(make_topic<T>(topic), std::string(profile));
        if (w == nullptr) throw std::runtime_error("cannot create writer of " + std::string(topic));
        return w;
    }
    template <class T>
    DataReader* reader(std::string_view topic, std::string_view profile) {
        return p_->create_subscriber_with_profile(std::string(profile))
            ->create_datareader_with_profile(make_topic<T>(topic), std::string(profile));
    }

private:
    template <class T>
    Topic* make_topic(std::string_view name) {
        const char* type = rapidgen::dds::Traits<T>::name;
        if (p_->find_type(type).empty()) TypeSupport(new rapidgen::dds::TopicType<T>()).register_type(p_);
        Topic* t = p_->create_topic(std::string(name), type, TOPIC_QOS_DEFAULT);
        if (t == nullptr) throw std::runtime_error("cannot create topic " + std::string(name));
        return t;
    }
    DomainParticipant* p_;
};

// One telemetry stream: a sample type, its topic and period, refreshed header on each write.
template <class T>
struct Stream {
    DataWriter* w;
    T sample;
    Clock::duration period;
    Clock::time_point next;
    void tick(Clock::time_point now) {
        if (now < next) return;
        next += period;
        if (next < now) next = now + period;  // fell behind: do not burst
        sample.hdr.timeStamp = micros_now();
        w->write(&sample);
    }
};

class Commands {
public:
    Commands(const rapid::CommandConfig& cfg, DataWriter* acks, rapid::Header hdr) : cfg_(cfg), acks_(acks), hdr_(hdr) {}

    void handle(const rapid::Command& c) {
        if (c.hdr.assetName != ASSET) return;  // another asset's command (rapid-protocol.md 5)
        if (!seen_.insert(c.cmdId).second) return;  // a repeated cmdId
        order_.push_back(c.cmdId);
        if (order_.size() > 4096) {
            seen_.erase(order_.front());
            order_.pop_front();
        }
        std::string why = check(c);
        if (!why.empty()) {
            ack(c.cmdId, rapid::AckStatus::ACK_COMPLETED, rapid::AckCompletedStatus::ACK_COMPLETED_BAD_SYNTAX, why);
            return;
        }
        ack(c.cmdId, rapid::AckStatus::ACK_EXECUTING, rapid::AckCompletedStatus::ACK_COMPLETED_NOT, "");
        ack(c.cmdId, rapid::AckStatus::ACK_COMPLETED, rapid::AckCompletedStatus::ACK_COMPLETED_OK, "");
    }

    void forget_oldest_ack() {
        rapid::Ack a;
        a.hdr = hdr_;
        a.cmdId = acked_.front();
        acked_.pop_front();
        acks_->unregister_instance(&a, HANDLE_NIL);
    }

private:
    // Why the command does not match the dictionary, or "" (messages never echo input:
    // Ack.message is a String128).
    std::string check(const rapid::Command& c) const {
        const rapid::Subsystem* sub = nullptr;
        for (const auto& s : cfg_.availableSubsystems)
            if (s.name == c.subsysName) sub = &s;
        if (sub == nullptr) return "unknown subsystem";
        for (const auto& t : cfg_.availableSubsystemTypes) {
            if (t.name != sub->subsystemTypeName) continue;
            for (const auto& def : t.commands) {
                if (def.name != c.cmdName) continue;
                if (def.parameters.size() != c.arguments.size())
                    return "expected " + std::to_string(def.parameters.size()) + " arguments, got " +
                           std::to_string(c.arguments.size());
                for (std::size_t i = 0; i < def.parameters.size(); ++i)
                    if (def.parameters[i].type != c.arguments[i]._d())
                        return "argument " + std::to_string(i + 1) + " has the wrong type";
                return "";
            }
        }
        return "unknown command for this subsystem";
    }

    void ack(const std::string& id, rapid::AckStatus status, rapid::AckCompletedStatus done, const std::string& msg) {
        rapid::Ack a;
        a.hdr = hdr_;
        a.hdr.timeStamp = micros_now();
        a.cmdId = id;
        a.status = status;
        a.completedStatus = done;
        a.message = msg;
        if (status == rapid::AckStatus::ACK_COMPLETED) {
            acked_.push_back(id);
            if (acked_.size() >= ACK_INSTANCES) forget_oldest_ack();
        }
        if (!acks_->write(&a)) std::cerr << "ack for " << id << " not written" << std::endl;
    }

    const rapid::CommandConfig& cfg_;
    DataWriter* acks_;
    rapid::Header hdr_;
    std::set<std::string> seen_;
    std::deque<std::string> order_;
    std::deque<std::string> acked_;  // cmdIds whose acks the writer still holds, oldest first
};

static Clock::duration period(double hz) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / hz));
}

int main(int argc, char** argv) {
    if (argc != 4) {
        std::cerr << "usage: r2_asset PROFILES_XML DOMAIN SECONDS\n";
        return 2;
    }
    auto* factory = DomainParticipantFactory::get_instance();
    if (factory->load_XML_profiles_file(argv[1]) != ReturnCode_t::RETCODE_OK) return 3;
    DomainParticipant* p = factory->create_participant_with_profile(std::atoi(argv[2]), "rapid_local");
    if (p == nullptr) return 3;
    Node node(p);

    rapid::Header hdr;  // every message's header: this bridge, the asset, one serial
    hdr.srcName = SOURCE;
    hdr.assetName = ASSET;
    hdr.serial = static_cast<std::int32_t>(micros_now() / 1000000);
    auto with_hdr = [&](auto cfg) {
        cfg.hdr = hdr;
        cfg.hdr.timeStamp = micros_now();
        return cfg;
    };
    const auto command_cfg = with_hdr(r2::config_rapid_command_config());
    const auto agent_cfg = with_hdr(r2::config_rapid_agent_config());
    const auto joint_cfg = with_hdr(r2::config_rapid_joint_config());
    const auto left_cfg = with_hdr(r2::config_rapid_position_config_leftArm());
    const auto right_cfg = with_hdr(r2::config_rapid_position_config_rightArm());

    DataWriter* acks = node.writer<rapid::Ack>("rapid_ack", "RapidReliableDurableQos");
    DataReader* commands = node.reader<rapid::Command>("rapid_command", "RapidReliableQos");
    node.writer<rapid::CommandConfig>("rapid_command_config", "RapidConfigQos")->write(const_cast<rapid::CommandConfig*>(&command_cfg));
    node.writer<rapid::AgentConfig>("rapid_agent_config", "RapidConfigQos")->write(const_cast<rapid::AgentConfig*>(&agent_cfg));
    node.writer<rapid::JointConfig>("rapid_joint_config", "RapidConfigQos")->write(const_cast<rapid::JointConfig*>(&joint_cfg));
    node.writer<rapid::PositionConfig>("rapid_position_config-leftArm", "RapidConfigQos")
        ->write(const_cast<rapid::PositionConfig*>(&left_cfg));
    node.writer<rapid::PositionConfig>("rapid_position_config-rightArm", "RapidConfigQos")
        ->write(const_cast<rapid::PositionConfig*>(&right_cfg));

    // Samples: values in the config's order with its types (its default values), one
    // entry per joint in each field Robonaut 2 reports, identity poses.
    auto now = Clock::now();
    Stream<rapid::AgentState> agent{node.writer<rapid::AgentState>("rapid_agent_state", "RapidSampleQos"), {}, period(10), now};
    agent.sample.hdr = hdr;
    for (const auto& k : agent_cfg.valueKeys) agent.sample.values.push_back(k.value);
    Stream<rapid::JointSample> joints{node.writer<rapid::JointSample>("rapid_joint_sample", "RapidSampleQos"), {}, period(50), now};
    joints.sample.hdr = hdr;
    const std::size_t n = joint_cfg.jointDefinitions.size();
    joints.sample.anglePos.assign(n, 0.0f);
    joints.sample.angleVel.assign(n, 0.0f);
    joints.sample.torque.assign(n, 0.0f);
    joints.sample.status.assign(n, rapid::JOINT_ENABLED);
    rapid::PositionSample pose;
    pose.hdr = hdr;
    pose.pose.rot = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    Stream<rapid::PositionSample> left{node.writer<rapid::PositionSample>("rapid_position_sample-leftArm", "RapidSampleQos"), pose, period(10), now};
    Stream<rapid::PositionSample> right{node.writer<rapid::PositionSample>("rapid_position_sample-rightArm", "RapidSampleQos"), pose, period(10), now};
    for (const auto& k : left_cfg.valueKeys) left.sample.values.push_back(k.value);
    for (const auto& k : right_cfg.valueKeys) right.sample.values.push_back(k.value);

    Commands handler(command_cfg, acks, hdr);
    std::cout << "bridge ready: hand-written C++ asset " << ASSET << ", domain " << argv[2] << std::endl;

    const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(std::atof(argv[3])));
    rapid::Command cmd;
    SampleInfo info;
    while (Clock::now() < end) {
        // samples that fail to decode are dropped by the topic type (never reach here)
        while (commands->take_next_sample(&cmd, &info) == ReturnCode_t::RETCODE_OK)
            if (info.valid_data) handler.handle(cmd);
        now = Clock::now();
        agent.tick(now);
        joints.tick(now);
        left.tick(now);
        right.tick(now);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    p->delete_contained_entities();
    factory->delete_participant(p);
    return 0;
}
