#include "rapid_runtime/dds/client.hpp"

#include <chrono>
#include <sstream>
#include <unistd.h>

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/core/status/SubscriptionMatchedStatus.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/rtps/common/InstanceHandle.h>

#include <rapid_runtime/text.hpp>

#include "rapid_runtime/dds/messages.hpp"

namespace rapid_runtime {
namespace dds {

using namespace eprosima::fastdds::dds;
using Clock = std::chrono::steady_clock;

namespace {

inline constexpr const char* COMMAND_TOPIC = "rapid_command";
inline constexpr const char* ACK_TOPIC = "rapid_ack";
inline constexpr const char* COMMAND_CONFIG_TOPIC = "rapid_command_config";

Clock::time_point deadline(double seconds) {
    return Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

bool has_final(const std::vector<AckEvent>& acks) {
    for (const auto& a : acks)
        if (a.final()) return true;
    return false;
}

// The live CommandConfig as tables; a parameter keeps the given tables' limits, unit and
// default when its name and type agree (rapidgen cmd's merged_tables).
Tables merged(const ::rapid::CommandConfig& config, const Tables* given, const ClientOptions& o) {
    Tables t;
    if (given != nullptr) t = *given;
    t.name = o.asset;
    t.partition = o.partition;
    t.subsystems.clear();
    t.types.clear();
    for (const auto& s : config.availableSubsystems) t.subsystems.push_back({s.name, s.subsystemTypeName});
    for (const auto& st : config.availableSubsystemTypes) {
        SubsystemType type{st.name, {}};
        const SubsystemType* mine = given != nullptr ? given->subsystem_type(st.name) : nullptr;
        for (const auto& c : st.commands) {
            const CommandSpec* known = nullptr;
            if (mine != nullptr)
                for (const auto& k : mine->commands)
                    if (k.name == c.name) known = &k;
            CommandSpec spec;
            spec.name = c.name;
            spec.abortable = c.abortable;
            spec.suspendable = c.suspendable;
            spec.standard = known != nullptr && known->standard;
            for (const auto& p : c.parameters) {
                auto dtype = static_cast<DataType>(static_cast<std::int32_t>(p.type));
                const Param* same = nullptr;
                if (known != nullptr)
                    for (const auto& k : known->params)
                        if (k.name == p.key && k.type == dtype) same = &k;
                if (same != nullptr) {
                    spec.params.push_back(*same);
                } else {
                    Param q;
                    q.name = p.key;
                    q.type = dtype;
                    spec.params.push_back(q);
                }
            }
            type.commands.push_back(std::move(spec));
        }
        t.types.push_back(std::move(type));
    }
    return t;
}

}  // namespace

std::string describe(const AckEvent& ack) {
    std::string text(name_of(ack.status).substr(4));  // "ACK_" off
    if (ack.status == AckStatus::Completed || ack.completed != Completion::Not)
        text += " " + std::string(name_of(ack.completed).substr(14));  // "ACK_COMPLETED_" off
    if (!ack.message.empty()) text += "  " + visible(ack.message, 200);
    return text;
}

Client::Client(ClientOptions options, const Tables* tables) : options_(std::move(options)), given_(tables) {
    if (options_.asset.empty() && tables != nullptr) options_.asset = tables->name;
    if (options_.asset.empty()) throw DdsError("no asset to command: give its name or its tables");
    if (options_.partition.empty())
        options_.partition = tables != nullptr && !tables->partition.empty() && tables->name == options_.asset
                                 ? tables->partition
                                 : options_.asset;
    if (options_.domain < 0) options_.domain = tables != nullptr ? tables->domain : 0;
    dictionary_ = tables;
    NodeOptions n;
    n.domain = options_.domain;
    n.profiles_file = options_.profiles_file;
    n.profiles_xml = options_.profiles_xml;
    n.transport = options_.transport;
    n.partition = options_.partition;
    node_ = std::make_unique<Node>(n);
    acks_reader_ = node_->reader<::rapid::Ack>(ACK_TOPIC, "RapidReliableDurableQos", [](DataReaderQos& q) {
        q.history().kind = KEEP_ALL_HISTORY_QOS;  // every intermediate ack
        // room for a command's acks before they are taken: with the profile's 1 per
        // instance, a COMPLETED right behind its EXECUTING was refused and came again
        // only on the writer's next heartbeat (a third of round trips took 100-200 ms)
        q.resource_limits().max_samples_per_instance = static_cast<std::int32_t>(ACKS_PER_COMMAND);
    }, &ack_listener_);
    // A command written while the asset's reader has not yet matched this writer is dropped
    // there and sent again on the next heartbeat: every 5 ms off a slow link (node.hpp,
    // COMMAND_HEARTBEAT_NS: the history emptied before a burst fills it, no write waits for a
    // heartbeat), 100 ms on one; not Fast DDS's 3 s.
    const std::uint32_t heartbeat_ns = node_->on_link() ? 100'000'000 : COMMAND_HEARTBEAT_NS;
    commands_ = node_->writer<::rapid::Command>(COMMAND_TOPIC, "RapidReliableQos", [heartbeat_ns](DataWriterQos& q) {
        q.reliable_writer_qos().times.heartbeatPeriod = eprosima::fastrtps::Duration_t(0, heartbeat_ns);
        q.reliability().max_blocking_time = eprosima::fastrtps::Duration_t(10, 0);  // a flood waits for room
        quiet_nack_suppression(q);  // (node.hpp: Fast DDS's event thread not woken per command)
    });
    commands_->set_listener(&matches_, StatusMask::publication_matched());
    acks_reader_->set_listener(&ack_listener_, StatusMask::subscription_matched() << StatusMask::data_available());
}

namespace {

std::string participant_of(const eprosima::fastrtps::rtps::InstanceHandle_t& handle) {
    eprosima::fastrtps::rtps::GUID_t guid;
    eprosima::fastrtps::rtps::iHandle2GUID(guid, handle);
    std::ostringstream out;
    out << guid.guidPrefix;
    return out.str();
}

void count(std::mutex& mutex, std::map<std::string, int>& table, const std::string& key, int change) {
    std::lock_guard<std::mutex> lock(mutex);
    if ((table[key] += change) <= 0) table.erase(key);
}

}  // namespace

void Client::Matches::on_publication_matched(DataWriter*, const PublicationMatchedStatus& info) {
    count(mutex_, readers_, participant_of(info.last_subscription_handle), info.current_count_change);
}

void Client::Matches::on_subscription_matched(DataReader*, const SubscriptionMatchedStatus& info) {
    count(mutex_, writers_, participant_of(info.last_publication_handle), info.current_count_change);
}

std::set<std::string> Client::Matches::both() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::set<std::string> out;
    for (const auto& [key, n] : readers_)
        if (writers_.count(key) != 0) out.insert(key);
    return out;
}

std::set<std::string> Client::asset_participants() const { return matches_.both(); }

Client::~Client() {
    {
        std::lock_guard<std::mutex> lock(mutex_);  // (a callback under way ends first)
        reading_ = false;
    }
    node_.reset();
}

void Client::read_acks(DataReader* reader) {
    std::lock_guard<std::mutex> lock(mutex_);
    ::rapid::Ack& sample = ack_;
    SampleInfo info;
    bool added = false;
    while (reading_ && reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
        if (!info.valid_data) continue;
        auto found = acks_.find(sample.cmdId);
        if (found == acks_.end()) {
            ++strangers_;
            continue;
        }
        if (found->second.size() < ACKS_PER_COMMAND) {
            found->second.push_back({static_cast<AckStatus>(static_cast<std::int32_t>(sample.status)),
                                     static_cast<Completion>(static_cast<std::int32_t>(sample.completedStatus)),
                                     sample.message});
            added = true;
        }
    }
    if (added) {
        arrived_.fetch_add(1, std::memory_order_release);
        changed_.notify_all();
    }
}

template <class Done>
void Client::await(std::unique_lock<std::mutex>& lock, Clock::time_point end, Done done) const {
    if (done()) return;
    // Spin first (yielding the CPU each turn), then sleep: an answer that comes within
    // options_.spin_us is seen without waking this thread, which on a VM costs about as
    // much as the round trip itself (bench/README.md, the C++ bridge).
    const auto spin_end = std::min(end, Clock::now() + std::chrono::microseconds(options_.spin_us));
    std::uint64_t seen = arrived_.load(std::memory_order_acquire);
    lock.unlock();
    while (Clock::now() < spin_end) {
        std::this_thread::yield();
        const std::uint64_t now = arrived_.load(std::memory_order_acquire);
        if (now == seen) continue;
        seen = now;
        lock.lock();
        if (done()) return;
        lock.unlock();
    }
    lock.lock();
    changed_.wait_until(lock, end, done);
}

bool Client::asset_matched() const {
    PublicationMatchedStatus pub;
    SubscriptionMatchedStatus sub;
    commands_->get_publication_matched_status(pub);
    acks_reader_->get_subscription_matched_status(sub);
    return pub.current_count > 0 && sub.current_count > 0;
}

bool Client::wait_for_asset(double seconds) {
    const auto end = deadline(seconds);
    while (true) {
        if (asset_matched()) return true;
        if (Clock::now() >= end) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

bool Client::read_dictionary(double seconds) {
    auto* reader = node_->reader<::rapid::CommandConfig>(COMMAND_CONFIG_TOPIC, "RapidConfigQos");
    ::rapid::CommandConfig config;
    SampleInfo info;
    bool found = false;
    const auto end = deadline(seconds);
    while (!found && Clock::now() < end) {
        if (!reader->wait_for_unread_message(eprosima::fastrtps::Duration_t(0, 50'000'000))) continue;
        while (reader->take_next_sample(&config, &info) == ReturnCode_t::RETCODE_OK)
            if (info.valid_data && config.hdr.assetName == options_.asset) {
                found = true;
                break;
            }
    }
    if (!found) return false;
    live_ = merged(config, given_, options_);
    dictionary_ = &live_;
    return true;
}

std::string Client::new_id() {
    // Unique: counter, source, process and time (rapid-protocol.md 5), as the Python commander.
    auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                  std::chrono::system_clock::now().time_since_epoch()).count();
    std::lock_guard<std::mutex> lock(write_mutex_);
    return std::to_string(++counter_) + "-" + options_.source + "-" + std::to_string(::getpid()) + "-" +
           std::to_string(ms);
}

const CommandSpec& Client::entry(const std::string& subsystem, const std::string& command) const {
    if (dictionary_ == nullptr)
        throw CommandError("no command dictionary for " + visible(options_.asset, 64) +
                           " (give its tables, or read its CommandConfig first)");
    if (dictionary_->type_of(subsystem) == nullptr) {
        std::string names;
        for (const auto& s : dictionary_->subsystems) names += (names.empty() ? "" : ", ") + s.name;
        throw CommandError("asset " + visible(options_.asset, 64) + " has no subsystem '" + visible(subsystem, 64) +
                           "' (known: " + names + ")");
    }
    CommandRef ref = dictionary_->command(subsystem, command);
    if (!ref) {
        std::string names;
        if (const auto* t = dictionary_->subsystem_type(*dictionary_->type_of(subsystem)))
            for (const auto& c : t->commands) names += (names.empty() ? "" : ", ") + c.name;
        throw CommandError("subsystem " + visible(subsystem, 64) + " has no command '" + visible(command, 64) +
                           "' (known: " + names + ")");
    }
    return *ref.spec;
}

namespace {

void check_action(const SendOptions& how, const Tables* tables) {
    bool targeted = how.action == QueueAction::Insert || how.action == QueueAction::Replace ||
                    how.action == QueueAction::Delete;
    if (targeted == how.target.empty())
        throw CommandError(std::string(name_of(how.action)) +
                           (targeted ? " needs a target cmdId" : " takes no target cmdId"));
    if (how.action != QueueAction::Bypass && tables != nullptr && !tables->has_type("Queue"))
        throw CommandError(std::string(name_of(how.action)) + ": asset " + visible(tables->name, 64) +
                           " has no command queue");
}

}  // namespace

std::string Client::send(const std::string& subsystem, const std::string& command, const std::vector<NamedValue>& args,
                         const SendOptions& how) {
    const CommandSpec& spec = entry(subsystem, command);
    check_action(how, dictionary_);
    Arguments values = complete(spec, args, how.limits);
    if (!values) throw CommandError(values.errors.front());
    Cmd cmd;
    cmd.cmd_id = how.cmd_id;
    cmd.subsystem = subsystem;
    cmd.name = command;
    cmd.args = std::move(values.values);
    cmd.action = how.action;
    cmd.target = how.target;
    return write(cmd);
}

std::string Client::send_text(const std::string& subsystem, const std::string& command,
                              const std::vector<std::string>& words, const SendOptions& how) {
    return send_raw(prepare_text(subsystem, command, words, how));
}

Cmd Client::prepare_text(const std::string& subsystem, const std::string& command, const std::vector<std::string>& words,
                         const SendOptions& how) const {
    const CommandSpec& spec = entry(subsystem, command);
    check_action(how, dictionary_);
    Arguments values = complete_text(spec, words, how.limits);
    if (!values) {
        std::string all;
        for (const auto& e : values.errors) all += (all.empty() ? "" : "; ") + e;
        throw CommandError(all);
    }
    Cmd cmd;
    cmd.cmd_id = how.cmd_id;
    cmd.subsystem = subsystem;
    cmd.name = command;
    cmd.args = std::move(values.values);
    cmd.action = how.action;
    cmd.target = how.target;
    return cmd;
}

std::string Client::send_raw(Cmd cmd) { return write(cmd); }

std::string Client::request_control(bool grab) {
    Cmd cmd;
    cmd.subsystem = "AccessControl";
    cmd.name = grab ? "grabControl" : "requestControl";
    return write(cmd);
}

std::string Client::write(Cmd& cmd) {
    if (cmd.cmd_id.empty()) cmd.cmd_id = new_id();
    if (cmd.cmd_src.empty()) cmd.cmd_src = options_.source;
    if (cmd.src_name.empty()) cmd.src_name = options_.source;
    if (cmd.asset_name.empty()) cmd.asset_name = options_.asset;
    if (cmd.stamp == 0) cmd.stamp = now_us();
    follow(cmd.cmd_id);
    ::rapid::Command out = command_out(cmd);
    std::lock_guard<std::mutex> lock(write_mutex_);
    if (!commands_->write(&out)) throw DdsError("command " + visible(cmd.cmd_id, 64) + " not written");
    return cmd.cmd_id;
}

void Client::follow(const std::string& cmd_id) {
    std::lock_guard<std::mutex> lock(mutex_);
    acks_.emplace(cmd_id, std::vector<AckEvent>{});
}

void Client::forget(const std::string& cmd_id) {
    std::lock_guard<std::mutex> lock(mutex_);
    acks_.erase(cmd_id);
}

std::vector<AckEvent> Client::acks(const std::string& cmd_id) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto found = acks_.find(cmd_id);
    return found == acks_.end() ? std::vector<AckEvent>{} : found->second;
}

std::vector<AckEvent> Client::wait_final(const std::string& cmd_id, double seconds) const {
    std::unique_lock<std::mutex> lock(mutex_);
    auto done = [&] {
        auto found = acks_.find(cmd_id);
        return found != acks_.end() && has_final(found->second);
    };
    await(lock, deadline(seconds), done);
    auto found = acks_.find(cmd_id);
    return found == acks_.end() ? std::vector<AckEvent>{} : found->second;
}

std::vector<AckEvent> Client::wait_count(const std::string& cmd_id, std::size_t count, double seconds) const {
    std::unique_lock<std::mutex> lock(mutex_);
    auto done = [&] {
        auto found = acks_.find(cmd_id);
        return found != acks_.end() && found->second.size() >= count;
    };
    await(lock, deadline(seconds), done);
    auto found = acks_.find(cmd_id);
    return found == acks_.end() ? std::vector<AckEvent>{} : found->second;
}

std::size_t Client::wait_all_final(const std::vector<std::string>& cmd_ids, double seconds) const {
    std::unique_lock<std::mutex> lock(mutex_);
    std::size_t done = 0;  // the first `done` ids have their final ack
    auto all = [&] {
        while (done < cmd_ids.size()) {
            auto found = acks_.find(cmd_ids[done]);
            if (found == acks_.end() || !has_final(found->second)) return false;
            ++done;
        }
        return true;
    };
    await(lock, deadline(seconds), all);
    std::size_t n = 0;
    for (const auto& id : cmd_ids) {
        auto found = acks_.find(id);
        n += found != acks_.end() && has_final(found->second);
    }
    return n;
}

}  // namespace dds
}  // namespace rapid_runtime
