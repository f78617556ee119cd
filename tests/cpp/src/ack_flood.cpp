// RAPID's Ack topic on Fast DDS 2.9 with the generated QoS profiles, as an asset and a ground
// tool use it: one writer keyed by cmdId (an instance per command), readers that join late.
// Driven line by line on stdin, one answer line per command on stdout:
//   writer                          the ack writer (profile RapidReliableDurableQos)
//   reader NAME                     an ack reader (same profile) created now
//   write FIRST LAST                acks of cmdIds ack-FIRST .. ack-(LAST-1), EXECUTING then
//                                     COMPLETED/OK each -> "wrote N failed F" (writes)
//   matched N SECONDS               wait until the writer matched N readers -> "matched K"
//   expect NAME FIRST LAST SECONDS  wait until reader NAME took the COMPLETED ack of each
//                                     cmdId of the range -> "got NAME K of N"
//   quit
//
//   ack_flood PROFILES_XML DOMAIN
// Fast DDS's errors, and its warnings while it loads the XML, go to stderr. Exit 3 when the
// XML does not load or an entity cannot be created.
#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/log/Log.hpp>
#include <fastdds/dds/log/StdoutErrConsumer.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <rapid_k10red/topics.hpp>

using namespace eprosima::fastdds::dds;

static const std::string PROFILE = "RapidReliableDurableQos";  // Ack's (rapid-protocol.md 6)

struct Failure : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class Acks {
public:
    explicit Acks(DomainParticipant* p) : p_(p) {
        TypeSupport(new rapidgen::dds::TopicType<rapid::Ack>()).register_type(p_);
        topic_ = p_->create_topic("rapid_ack", rapidgen::dds::Traits<rapid::Ack>::name, TOPIC_QOS_DEFAULT);
        if (topic_ == nullptr) throw Failure("no topic");
    }

    void make_writer() {
        Publisher* pub = p_->create_publisher_with_profile(PROFILE);
        writer_ = pub == nullptr ? nullptr : pub->create_datawriter_with_profile(topic_, PROFILE);
        if (writer_ == nullptr) throw Failure("no writer");
    }

    void make_reader(const std::string& name) {
        Subscriber* sub = p_->create_subscriber_with_profile(PROFILE);
        DataReader* r = sub == nullptr ? nullptr : sub->create_datareader_with_profile(topic_, PROFILE);
        if (r == nullptr) throw Failure("no reader");
        readers_[name] = {r, {}};
    }

    // Acks for ack-first .. ack-(last-1); how many of the writes failed.
    int write(int first, int last) {
        if (writer_ == nullptr) throw Failure("no writer yet");
        int failed = 0;
        for (int i = first; i < last; ++i) {
            rapid::Ack a;
            a.hdr.srcName = "AckFlood";
            a.hdr.assetName = "K10Red";
            a.cmdId = "ack-" + std::to_string(i);
            a.status = rapid::AckStatus::ACK_EXECUTING;  // as an asset answers: EXECUTING, then COMPLETED
            if (!writer_->write(&a)) ++failed;
            a.status = rapid::AckStatus::ACK_COMPLETED;
            a.completedStatus = rapid::AckCompletedStatus::ACK_COMPLETED_OK;
            if (!writer_->write(&a)) ++failed;
        }
        return failed;
    }

    int matched(int want, double seconds) {
        auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        PublicationMatchedStatus st;
        do {
            writer_->get_publication_matched_status(st);
            if (st.current_count >= want) break;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        } while (std::chrono::steady_clock::now() < end);
        return st.current_count;
    }

    // Of ack-first .. ack-(last-1), how many COMPLETED acks reader `name` has taken (waits up
    // to `seconds` for all).
    int expect(const std::string& name, int first, int last, double seconds) {
        DataReader* reader = readers_.at(name).first;
        std::set<std::string>& got = readers_.at(name).second;
        auto count = [&] {
            int n = 0;
            for (int i = first; i < last; ++i) n += got.count("ack-" + std::to_string(i)) ? 1 : 0;
            return n;
        };
        auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        while (true) {
            rapid::Ack a;
            SampleInfo info;
            while (reader->take_next_sample(&a, &info) == ReturnCode_t::RETCODE_OK)
                if (info.valid_data && a.status == rapid::AckStatus::ACK_COMPLETED) got.insert(a.cmdId);
            if (count() == last - first || std::chrono::steady_clock::now() >= end) return count();
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
    }

private:
    DomainParticipant* p_;
    Topic* topic_ = nullptr;
    DataWriter* writer_ = nullptr;
    std::map<std::string, std::pair<DataReader*, std::set<std::string>>> readers_;
};

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: ack_flood PROFILES_XML DOMAIN\n";
        return 2;
    }
    Log::ClearConsumers();
    Log::RegisterConsumer(std::unique_ptr<LogConsumer>(new StdoutErrConsumer()));  // warnings and errors
    Log::SetVerbosity(Log::Kind::Warning);  // while loading the XML
    auto* factory = DomainParticipantFactory::get_instance();
    if (factory->load_XML_profiles_file(argv[1]) != ReturnCode_t::RETCODE_OK) return 3;
    Log::Flush();
    Log::SetVerbosity(Log::Kind::Error);  // running: errors only (unmatching at exit warns)
    DomainParticipant* p = factory->create_participant_with_profile(std::atoi(argv[2]), "rapid_local");
    if (p == nullptr) return 3;
    int status = 0;
    try {
        Acks acks(p);
        std::string line;
        while (std::getline(std::cin, line)) {
            std::istringstream in(line);
            std::string cmd, name;
            int a = 0, b = 0;
            double s = 0;
            in >> cmd;
            if (cmd == "quit") break;
            if (cmd == "writer") {
                acks.make_writer();
                std::cout << "writer" << std::endl;
            } else if (cmd == "reader" && in >> name) {
                acks.make_reader(name);
                std::cout << "reader " << name << std::endl;
            } else if (cmd == "write" && in >> a >> b) {
                std::cout << "wrote " << 2 * (b - a) << " failed " << acks.write(a, b) << std::endl;
            } else if (cmd == "matched" && in >> a >> s) {
                std::cout << "matched " << acks.matched(a, s) << std::endl;
            } else if (cmd == "expect" && in >> name >> a >> b >> s) {
                std::cout << "got " << name << " " << acks.expect(name, a, b, s) << " of " << b - a << std::endl;
            } else {
                std::cout << "bad command: " << line << std::endl;
            }
        }
    } catch (const std::exception& e) {  // Failure, or an unknown reader name (a test's mistake)
        std::cerr << "ack_flood: " << e.what() << std::endl;
        status = 3;
    }
    p->delete_contained_entities();
    factory->delete_participant(p);
    Log::Flush();
    return status;
}
