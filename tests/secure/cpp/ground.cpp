// A ground tool for the DDS Security tests (tests/secure): a Fast DDS participant secured
// by the runtime's own hook (security.hpp: RAPID_SECURITY_KEYSTORE/_ENCLAVE) that either
// sends commands to an asset or watches its acks. Built against K10's generated types.
//
//   secure_ground command PROFILES DOMAIN PARTITION SOURCE PREFIX COUNT WAIT_S
//     takes control (AccessControl/grabControl, cmdId PREFIX-control), then sends COUNT
//     Admin/echo commands (cmdId PREFIX-i, text "plaintext PREFIX-i") whether or not the
//     asset was discovered, then waits up to WAIT_S for their COMPLETED acks.
//     Prints "participant: ok|refused: why", "writer: ok|refused", "matched: N",
//     "failed CMDID: ack message" for each command (control too) completed not OK,
//     "completed: K of COUNT". Exit 0 when every command completed OK, 4 when not, 1 when
//     the participant or the writer could not be made.
//   secure_ground watch PROFILES DOMAIN PARTITION WAIT_S PREFIX...
//     reads the asset's acks (transient-local: the history too) for WAIT_S seconds and
//     prints "matched: 0|1" and "acked PREFIX: N" (distinct cmdIds starting with PREFIX-,
//     the control command included) for each prefix.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <rapid_k10red/topics.hpp>
#include <rapid_k10red/types.hpp>

#include "rapid_runtime/dds/security.hpp"

using namespace eprosima::fastdds::dds;
using Clock = std::chrono::steady_clock;

namespace {

struct Dds {
    DomainParticipant* participant = nullptr;
    Publisher* publisher = nullptr;
    Subscriber* subscriber = nullptr;
    ~Dds() {
        if (participant == nullptr) return;
        participant->delete_contained_entities();
        DomainParticipantFactory::get_instance()->delete_participant(participant);
    }
};

// One line of the answer the tests read, written in one piece: Fast DDS's logging thread
// writes to the same stdout, and a line written part by part could be split by its output
// (a refused participant's line once was, by the log of that refusal).
template <class... Parts>
void say(const Parts&... parts) {
    std::ostringstream line;
    (line << ... << parts);
    line << '\n';
    std::cout << line.str() << std::flush;
}

// The participant from the profiles' rapid_local (loopback), secured when the environment
// says so; publisher and subscriber in `partition`. False (and why, printed) when refused.
bool open(Dds& d, const std::string& profiles, int domain, const std::string& partition, const std::string& who) {
    auto* factory = DomainParticipantFactory::get_instance();
    DomainParticipantQos qos;
    if (factory->load_XML_profiles_file(profiles) != ReturnCode_t::RETCODE_OK ||
        factory->get_participant_qos_from_profile("rapid_local", qos) != ReturnCode_t::RETCODE_OK) {
        say("participant: refused: cannot load ", profiles);
        return false;
    }
    qos.name(who);
    std::string enclave;
    try {
        enclave = rapid_runtime::dds::security_enclave(who);
        if (!enclave.empty()) rapid_runtime::dds::apply_security(qos, enclave);
    } catch (const std::exception& e) {
        say("participant: refused: ", e.what());
        return false;
    }
    d.participant = factory->create_participant(domain, qos);
    if (d.participant == nullptr) {
        say("participant: refused: ",
            enclave.empty() ? std::string("no participant") : rapid_runtime::dds::security_refusal(enclave));
        return false;
    }
    say("participant: ok", enclave.empty() ? " (unsecured)" : " (secured)");
    PublisherQos pq = d.participant->get_default_publisher_qos();
    pq.partition().push_back(partition.c_str());
    d.publisher = d.participant->create_publisher(pq);
    SubscriberQos sq = d.participant->get_default_subscriber_qos();
    sq.partition().push_back(partition.c_str());
    d.subscriber = d.participant->create_subscriber(sq);
    return d.publisher != nullptr && d.subscriber != nullptr;
}

template <class PubSub>
Topic* topic(Dds& d, const char* name) {
    TypeSupport type(new PubSub());
    type.register_type(d.participant);
    return d.participant->create_topic(name, type.get_type_name(), TOPIC_QOS_DEFAULT);
}

DataReader* ack_reader(Dds& d) {
    DataReaderQos q;
    d.subscriber->get_datareader_qos_from_profile("RapidReliableDurableQos", q);
    Topic* t = topic<rapid::AckPubSubType>(d, "rapid_ack");
    return t == nullptr ? nullptr : d.subscriber->create_datareader(t, q);
}

// Takes every ack waiting; calls f(ack) for each valid one.
template <class F>
void take_acks(DataReader* r, F f) {
    rapid::Ack ack;
    SampleInfo info;
    while (r->take_next_sample(&ack, &info) == ReturnCode_t::RETCODE_OK)
        if (info.valid_data) f(ack);
}

int command(int argc, char** argv) {
    if (argc != 9) return 2;
    const std::string profiles = argv[2], partition = argv[4], source = argv[5], prefix = argv[6];
    const int domain = std::atoi(argv[3]), count = std::atoi(argv[7]);
    const double wait_s = std::atof(argv[8]);
    Dds d;
    if (!open(d, profiles, domain, partition, source)) return 1;
    DataWriterQos wq;
    d.publisher->get_datawriter_qos_from_profile("RapidReliableQos", wq);
    Topic* ct = topic<rapid::CommandPubSubType>(d, "rapid_command");
    DataWriter* w = ct == nullptr ? nullptr : d.publisher->create_datawriter(ct, wq);
    DataReader* acks = ack_reader(d);
    if (w == nullptr) {
        say("writer: refused (its permissions do not grant rapid_command in partition ", partition, ")");
        return 1;
    }
    say("writer: ok");
    const auto deadline = Clock::now() + std::chrono::milliseconds(static_cast<long>(wait_s * 1000));
    PublicationMatchedStatus m{};
    // Wait for the asset, but send whether or not it was found: what arrives is the test.
    while (Clock::now() < deadline - std::chrono::milliseconds(static_cast<long>(wait_s * 500))) {
        w->get_publication_matched_status(m);
        if (m.current_count > 0) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    say("matched: ", m.current_count);
    // Take control first (K10's access control runs other commands only for the controller).
    rapid::Command ctl;
    ctl.hdr.srcName = source;
    ctl.hdr.assetName = "K10Red";
    ctl.cmdId = prefix + "-control";
    ctl.cmdSrc = source;
    ctl.subsysName = "AccessControl";
    ctl.cmdName = "grabControl";
    w->write(&ctl);
    std::set<std::string> done, failed;
    int ok = 0;
    for (int i = 0; i < count; ++i) {
        rapid::Command c;
        c.hdr.srcName = source;
        c.hdr.assetName = "K10Red";
        c.cmdId = prefix + "-" + std::to_string(i);
        c.cmdSrc = source;
        c.subsysName = "Admin";
        c.cmdName = "echo";
        rapid::ParameterUnion text;
        text.s("plaintext " + prefix + "-" + std::to_string(i));
        c.arguments.push_back(text);
        w->write(&c);
    }
    while (Clock::now() < deadline && static_cast<int>(done.size()) < count) {
        if (acks != nullptr)
            take_acks(acks, [&](const rapid::Ack& a) {
                if (a.cmdId.rfind(prefix + "-", 0) != 0 || a.status != rapid::AckStatus::ACK_COMPLETED) return;
                if (a.completedStatus != rapid::AckCompletedStatus::ACK_COMPLETED_OK && failed.insert(a.cmdId).second)
                    say("failed ", a.cmdId, ": ", a.message);
                if (a.cmdId == ctl.cmdId) return;
                if (done.insert(a.cmdId).second && a.completedStatus == rapid::AckCompletedStatus::ACK_COMPLETED_OK)
                    ++ok;
            });
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    say("completed: ", ok, " of ", count);
    return ok == count ? 0 : 4;
}

int watch(int argc, char** argv) {
    if (argc < 7) return 2;
    const std::string profiles = argv[2], partition = argv[4];
    const int domain = std::atoi(argv[3]);
    const double wait_s = std::atof(argv[5]);
    Dds d;
    if (!open(d, profiles, domain, partition, "watcher")) return 1;
    DataReader* r = ack_reader(d);
    if (r == nullptr) {
        say("reader: refused");
        return 1;
    }
    std::map<std::string, std::set<std::string>> seen;
    // Read until WAIT_S, or 2 s after the asset's ack writer was matched (its history comes then).
    auto deadline = Clock::now() + std::chrono::milliseconds(static_cast<long>(wait_s * 1000));
    bool matched = false;
    while (Clock::now() < deadline) {
        SubscriptionMatchedStatus m{};
        r->get_subscription_matched_status(m);
        if (!matched && m.current_count > 0) {
            matched = true;
            deadline = std::min(deadline, Clock::now() + std::chrono::seconds(2));
        }
        take_acks(r, [&](const rapid::Ack& a) {
            for (int i = 6; i < argc; ++i)
                if (a.cmdId.rfind(std::string(argv[i]) + "-", 0) == 0) seen[argv[i]].insert(a.cmdId);
        });
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    say("matched: ", matched ? 1 : 0);
    for (int i = 6; i < argc; ++i) say("acked ", argv[i], ": ", seen[argv[i]].size());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string mode = argc > 1 ? argv[1] : "";
    int rc = mode == "command" ? command(argc, argv) : mode == "watch" ? watch(argc, argv) : 2;
    if (rc == 2) std::cerr << "usage: see the comment at the top of ground.cpp" << std::endl;
    return rc;
}
