// The ground side (soraCore's CommandAckPair role): send a command by name with typed
// arguments, checked against the asset's dictionary (its tables, or the CommandConfig it
// publishes), and follow its acks until the final COMPLETED, with a deadline.
//
//     Client client(options, &rapid_k10red::bridge::tables());   // or no tables: the live config
//     client.wait_for_asset(10);
//     auto granted = client.wait_final(client.request_control(), 10);
//     auto id = client.send("Mobility", "simpleMove", {{"frame", "SITE"}, {"xyt", Vec3d{1, 2, 0}}});
//     auto acks = client.wait_final(id, 30);   // QUEUED? EXECUTING ... COMPLETED/OK
//
// Acks are correlated by cmdId alone, read with KEEP_ALL so no intermediate one is lost;
// only the acks of followed commands (those sent, or follow()ed) are kept, at most
// ACKS_PER_COMMAND each; the others are counted (strangers()) and dropped, so an ack flood
// for cmdIds nobody sent does not grow the client (runtime/rapid_runtime/commander.py).
#ifndef RAPID_RUNTIME_DDS_CLIENT_HPP
#define RAPID_RUNTIME_DDS_CLIENT_HPP

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <rapid_runtime/args.hpp>
#include <rapid_runtime/command.hpp>
#include <rapid_runtime/tables.hpp>

#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>

#include "node.hpp"

namespace rapid_runtime {
namespace dds {

inline constexpr std::size_t ACKS_PER_COMMAND = 64;

struct AckEvent {
    AckStatus status = AckStatus::Completed;
    Completion completed = Completion::Not;
    std::string message;
    bool final() const { return status == AckStatus::Completed; }
    bool ok() const { return status == AckStatus::Completed && completed == Completion::Ok; }
};

// "QUEUED", "COMPLETED OK  text": as `rapidgen cmd` prints an ack (message made visible).
std::string describe(const AckEvent& ack);

// A command refused before it is sent (unknown subsystem or command, bad arguments).
class CommandError : public std::runtime_error {
public:
    explicit CommandError(const std::string& what) : std::runtime_error(what) {}
};

struct ClientOptions {
    std::string asset;  // hdr.assetName of the commands (default: the tables' name)
    std::string partition;  // default: the tables' partition, else the asset's name
    std::string source = "rapid_cmd";  // cmdSrc and hdr.srcName
    int domain = -1;  // -1: the tables' domain (else 0)
    std::string profiles_file;  // the asset's generated qos/fastdds/rapid_qos_profiles.xml
    std::string profiles_xml;  // or its text (a generated bridge's PROFILES_XML)
    std::string transport = "local";  // participant profile rapid_<transport>
    // A wait for acks spins (yielding) this long before it sleeps: an ack that comes
    // within it does not need this thread woken (0: sleep at once).
    unsigned spin_us = 300;
};

struct SendOptions {
    QueueAction action = QueueAction::Bypass;
    std::string target;  // INSERT, REPLACE, DELETE: the queued command acted on
    std::string cmd_id;  // empty: a fresh one (new_id())
    bool limits = true;  // false: ranges and allowed values unchecked (the asset answers)
};

class Client {
public:
    // `tables`, when given, is the dictionary until a live one is read (and keeps the
    // limits and defaults the CommandConfig does not carry); it must outlive the client.
    explicit Client(ClientOptions options, const Tables* tables = nullptr);
    ~Client();
    Client(const Client&) = delete;
    Client& operator=(const Client&) = delete;

    // True once an asset's command reader matched the command writer and its ack writer
    // the ack reader (Astrobee's ground side waits likewise).
    bool wait_for_asset(double seconds);
    // The same, now, without waiting.
    bool asset_matched() const;
    // The participants (GUID prefixes) that are the asset now: a command reader matched to
    // the command writer and an ack writer matched to the ack reader, in one participant
    // (a tool that only reads commands is not the asset). A restarted asset is a new one.
    std::set<std::string> asset_participants() const;
    // Reads the asset's CommandConfig (transient-local: published once) for up to
    // `seconds`: it becomes the dictionary, a parameter keeping the tables' unit, range,
    // allowed values and default when its name and type agree. False: none came.
    bool read_dictionary(double seconds);
    const Tables* dictionary() const { return dictionary_; }
    const std::string& asset() const { return options_.asset; }
    const std::string& partition() const { return options_.partition; }
    int domain() const { return options_.domain; }

    // Checked against the dictionary, sent; returns the cmdId. Throws CommandError.
    std::string send(const std::string& subsystem, const std::string& command, const std::vector<NamedValue>& args = {},
                     const SendOptions& how = {});
    // The same with key=value words (rapid_cmd's command line).
    std::string send_text(const std::string& subsystem, const std::string& command,
                          const std::vector<std::string>& words, const SendOptions& how = {});
    // The command send_text() would send, checked, not sent (send_raw() sends it).
    Cmd prepare_text(const std::string& subsystem, const std::string& command, const std::vector<std::string>& words,
                     const SendOptions& how = {}) const;
    // A command as given, unchecked (a test's malformed command); cmd_id and the header's
    // names are filled when empty. Returns the cmdId.
    std::string send_raw(Cmd cmd);
    // AccessControl/requestControl (grab: grabControl): the cmdId.
    std::string request_control(bool grab = false);

    void follow(const std::string& cmd_id);
    std::vector<AckEvent> acks(const std::string& cmd_id) const;
    // The acks of cmd_id up to its final COMPLETED, or what came within `seconds`.
    std::vector<AckEvent> wait_final(const std::string& cmd_id, double seconds) const;
    // Blocks until `count` acks of cmd_id are in, or `seconds` passed; returns them.
    std::vector<AckEvent> wait_count(const std::string& cmd_id, std::size_t count, double seconds) const;
    // Until every one of cmd_ids has its final ack, or `seconds`: how many have.
    std::size_t wait_all_final(const std::vector<std::string>& cmd_ids, double seconds) const;
    // Forget a command's acks (a long run keeps its memory flat).
    void forget(const std::string& cmd_id);
    std::uint64_t strangers() const { return strangers_.load(); }

    std::string new_id();

private:
    // Which remote participants' endpoints are matched (Fast DDS 2.9 does not list them:
    // get_matched_subscriptions is unsupported), from the matched-status callbacks.
    class Matches : public eprosima::fastdds::dds::DataWriterListener,
                    public eprosima::fastdds::dds::DataReaderListener {
    public:
        void on_publication_matched(eprosima::fastdds::dds::DataWriter*,
                                    const eprosima::fastdds::dds::PublicationMatchedStatus& info) override;
        void on_subscription_matched(eprosima::fastdds::dds::DataReader*,
                                     const eprosima::fastdds::dds::SubscriptionMatchedStatus& info) override;
        std::set<std::string> both() const;

    private:
        mutable std::mutex mutex_;
        std::map<std::string, int> readers_, writers_;  // participant -> endpoints matched
    };

    // The ack reader's listener: acks are taken on Fast DDS's receive thread, which wakes
    // the thread waiting for them (no reader thread of ours between the two); its matches
    // go to matches_.
    class AckListener : public eprosima::fastdds::dds::DataReaderListener {
    public:
        explicit AckListener(Client& client) : client_(client) {}
        void on_data_available(eprosima::fastdds::dds::DataReader* reader) override { client_.read_acks(reader); }
        void on_subscription_matched(eprosima::fastdds::dds::DataReader* reader,
                                     const eprosima::fastdds::dds::SubscriptionMatchedStatus& info) override {
            client_.matches_.on_subscription_matched(reader, info);
        }

    private:
        Client& client_;
    };

    const CommandSpec& entry(const std::string& subsystem, const std::string& command) const;
    std::string write(Cmd& cmd);
    void read_acks(eprosima::fastdds::dds::DataReader* reader);
    // Until done() (under lock) or `end`: spins up to options_.spin_us, then sleeps.
    template <class Done>
    void await(std::unique_lock<std::mutex>& lock, std::chrono::steady_clock::time_point end, Done done) const;

    ClientOptions options_;
    const Tables* given_ = nullptr;
    Tables live_;
    const Tables* dictionary_ = nullptr;
    Matches matches_;  // before node_: its entities call it until they are deleted
    AckListener ack_listener_{*this};  // (likewise)
    std::unique_ptr<Node> node_;
    eprosima::fastdds::dds::DataWriter* commands_ = nullptr;
    eprosima::fastdds::dds::DataReader* acks_reader_ = nullptr;
    std::mutex write_mutex_;
    mutable std::mutex mutex_;
    mutable std::condition_variable changed_;
    std::map<std::string, std::vector<AckEvent>> acks_;
    std::atomic<std::uint64_t> strangers_{0};
    std::atomic<std::uint64_t> arrived_{0};  // acks kept so far (a spinning wait looks here)
    ::rapid::Ack ack_;  // one sample, reused (under mutex_)
    bool reading_ = true;  // (under mutex_)
    std::uint64_t counter_ = 0;
};

}  // namespace dds
}  // namespace rapid_runtime

#endif
