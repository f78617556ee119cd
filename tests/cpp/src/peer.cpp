// Live interop peer on Fast DDS 2.9 with the generated topic types and QoS profiles.
//   peer pub XML DOMAIN SECONDS   publish each sample of stdin every 200 ms for SECONDS
//   peer sub XML DOMAIN SECONDS   read until every topic of stdin delivered its sample
// stdin: "topic type profile le_hex" lines (the sample is the decoded vector). The sub
// prints "ok TOPIC" / "MISMATCH TOPIC" per topic and exits 0 when all are equal.
#include <chrono>
#include <iostream>
#include <map>
#include <memory>
#include <set>
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

#include "common.hpp"

using namespace eprosima::fastdds::dds;

struct Endpoint {
    virtual ~Endpoint() = default;
    virtual bool write() = 0;
    virtual int take() = 0;  // 0 nothing, 1 equal, 2 different
    std::string topic;
};

template <class T>
struct Impl : Endpoint {
    T expected;
    DataWriter* writer = nullptr;
    DataReader* reader = nullptr;

    Impl(DomainParticipant* p, const std::string& topic_name, const std::string& profile, const Bytes& bytes, bool pub) {
        topic = topic_name;
        expected = rapidgen::cdr::deserialize<T>(bytes);
        const char* type_name = rapidgen::dds::Traits<T>::name;
        if (p->find_type(type_name).empty()) TypeSupport(new rapidgen::dds::TopicType<T>()).register_type(p);
        Topic* t = p->create_topic(topic_name, type_name, TOPIC_QOS_DEFAULT);
        if (t == nullptr) throw std::runtime_error("no topic " + topic_name);
        if (pub) {
            writer = p->create_publisher_with_profile(profile)->create_datawriter_with_profile(t, profile);
        } else {
            reader = p->create_subscriber_with_profile(profile)->create_datareader_with_profile(t, profile);
        }
        if (writer == nullptr && reader == nullptr) throw std::runtime_error("no endpoint for profile " + profile);
    }
    bool write() override { return writer->write(&expected); }
    int take() override {
        T got;
        SampleInfo info;
        int result = 0;
        while (reader->take_next_sample(&got, &info) == ReturnCode_t::RETCODE_OK) {
            if (!info.valid_data) continue;
            result = got == expected ? 1 : 2;
            if (result == 2) break;
        }
        return result;
    }
};

using Factory = std::unique_ptr<Endpoint> (*)(DomainParticipant*, const std::string&, const std::string&, const Bytes&, bool);

template <class T>
std::unique_ptr<Endpoint> make(DomainParticipant* p, const std::string& t, const std::string& prof, const Bytes& b, bool pub) {
    return std::make_unique<Impl<T>>(p, t, prof, b, pub);
}

int main(int argc, char** argv) {
    if (argc != 5) return 2;
    std::string mode = argv[1];
    auto* factory = DomainParticipantFactory::get_instance();
    if (factory->load_XML_profiles_file(argv[2]) != ReturnCode_t::RETCODE_OK) return 3;
    DomainParticipant* p = factory->create_participant_with_profile(std::atoi(argv[3]), "rapid_local");
    if (p == nullptr) return 3;
    std::map<std::string, Factory> table;
#define RAPIDGEN_TYPE(T, NAME) table[NAME] = &make<T>;
#include "topics.inc"
#undef RAPIDGEN_TYPE
    std::vector<std::unique_ptr<Endpoint>> eps;
    std::string topic, type, profile, hex;
    while (std::cin >> topic >> type >> profile >> hex) eps.push_back(table.at(type)(p, topic, profile, unhex(hex), mode == "pub"));
    auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(std::atof(argv[4]));
    int status = 1;
    std::set<std::string> done;
    while (std::chrono::steady_clock::now() < end) {
        for (auto& e : eps) {
            if (mode == "pub") {
                e->write();
            } else if (!done.count(e->topic)) {
                int r = e->take();
                if (r == 2) std::cout << "MISMATCH " << e->topic << std::endl;
                if (r != 0) {
                    done.insert(e->topic);
                    if (r == 1) std::cout << "ok " << e->topic << std::endl;
                }
            }
        }
        if (mode == "sub" && done.size() == eps.size()) {
            status = 0;
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(mode == "pub" ? 200 : 20));
    }
    if (mode == "pub") status = 0;
    eps.clear();
    p->delete_contained_entities();
    factory->delete_participant(p);
    return status;
}
