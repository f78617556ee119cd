#include "rapid_runtime/dds/bridge.hpp"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <iostream>

#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include <rapid_runtime/text.hpp>

#include "rapid_runtime/dds/breaks.hpp"
#include "rapid_runtime/dds/security.hpp"
#include "rapid_runtime/dds/telemetry.hpp"

namespace rapid_runtime {
namespace dds {

using namespace eprosima::fastdds::dds;

namespace {

// The DDS writer a command came from, for the intake's per-writer FIFOs and logs.
std::string writer_id(const InstanceHandle_t& handle) {
    std::string out;
    char buf[4];
    for (std::size_t i = 0; i < 16; ++i) {
        std::snprintf(buf, sizeof buf, "%02x", static_cast<unsigned>(handle.value[i]));
        out += buf;
    }
    return out;
}

}  // namespace

class Bridge::CommandListener : public DataReaderListener {
public:
    explicit CommandListener(Bridge& bridge) : bridge_(bridge) {}
    void on_data_available(DataReader* reader) override { bridge_.read_commands(reader); }

private:
    Bridge& bridge_;
};

Bridge::Bridge(const Tables& tables, Handlers& handlers, BridgeOptions options)
    : tables_(tables), breaks_(std::make_unique<Breaks>(options.breaks, tables)) {
    auto write = options.log;
    if (!write) {
        std::string prefix = "[" + visible(tables.name) + "] ";
        write = [prefix](const std::string& text) { std::cerr << prefix << text << std::endl; };
    }
    log_ = std::make_unique<Log>(write);
    stale_ = std::make_unique<StaleWatch>(tables);
    const int domain = options.domain < 0 ? tables.domain : options.domain;
    if (!options.journal.empty())
        journal_ = Journal::open(options.journal, tables.name, domain, options.command_window,
                                 [this](const std::string& text) { log(text); }, recovered_);
    // configs come back with a serial above any used before the crash
    serials_ = start_serials(breaks_->on("zero-serial") ? 0 : options.serial, recovered_, journal_.get(),
                             std::time(nullptr));
    NodeOptions node;
    node.domain = domain;
    node.profiles_file = options.profiles_file;
    node.profiles_xml = options.profiles_xml;
    node.transport = options.transport;
    node.partition = tables.partition.empty() ? tables.name : tables.partition;
    node_ = std::make_unique<Node>(node);
    // Secured (the node's enclave): cmdSrc is bound to the writer's certificate; the
    // enclave's identities.txt (rapidgen secure) says whose certificate a GUID comes from.
    const std::string enclave = security_enclave(node.partition);
    if (!enclave.empty()) {
        identities_ = std::make_unique<Identities>(Identities::load(enclave + "/" + IDENTITIES_FILE));
        log("DDS Security: cmdSrc bound to the writer's certificate (" + std::to_string(identities_->sources().size()) +
            " ground source(s) in " + enclave + "/" + IDENTITIES_FILE + ")");
    }
    ManagerOptions m;
    m.window = options.command_window;
    ack_generation_ = ack_generation_size(options.command_window);
    m.stop_timeout_ms = options.stop_timeout_ms;
    m.shutdown_timeout_ms = options.shutdown_timeout_ms;
    m.on_shutdown = [this] { request_stop(); };
#ifdef RAPID_RUNTIME_TEST_BREAKS
    m.breaks = breaks_->manager();
#endif
    breaking_configs_ = breaks_->configs_broken();
    m.journal = journal_.get();
    manager_ = std::make_unique<CommandManager>(breaks_->any() ? breaks_->tables() : tables, handlers, *this, m);
    intake_ = std::make_unique<Intake>(*manager_, [this](const std::string& text) { log(text); });
}

Bridge::~Bridge() { stop(); }

ConfigBreak Bridge::config_break(const std::string& topic, std::function<void()> republish) {
    return breaks_->config(topic, std::move(republish));
}

std::int32_t Bridge::serial_of(const std::string& config_topic) const {
    std::lock_guard<std::mutex> lock(config_mutex_);
    return serials_.of(config_topic);
}

void Bridge::start() {
    if (!tables_.subsystems.empty()) {
        // The ack writer exists before the command reader: commanders wait to match both.
        // One writer per generation of commands (ack_writers.hpp), each with this QoS.
        const std::string topic = breaks_->on("ack-topic-suffixed") ? "rapid_ack-" + tables_.name : ACK_TOPIC;
        const bool durable = !breaks_->on("volatile-acks");
        // Off a slow link, a heartbeat every 5 ms (node.hpp): a commander that joins late gets the
        // kept acks, and in order its own after them, once the heartbeat has brought its first
        // ACKNACK: a new rapid_cmd's first ack took 22-108 ms with 100 ms, 11-33 ms with 5 ms
        // (bench/README.md). Heartbeats go out only while acks are unacknowledged.
        const std::uint32_t heartbeat_ns = node_->on_link() ? 100'000'000 : COMMAND_HEARTBEAT_NS;
        auto make = [this, topic, durable, heartbeat_ns] {
            return node_->new_writer<::rapid::Ack>(topic, "RapidReliableDurableQos", [durable, heartbeat_ns](DataWriterQos& q) {
                if (!durable) q.durability().kind = VOLATILE_DURABILITY_QOS;
                // an ack a commander missed is sent again within the heartbeat (Fast DDS's: 3 s)
                q.reliable_writer_qos().times.heartbeatPeriod = eprosima::fastrtps::Duration_t(0, heartbeat_ns);
                quiet_nack_suppression(q);
                q.history().kind = KEEP_LAST_HISTORY_QOS;
                q.history().depth = ACK_HISTORY;
                q.resource_limits().max_samples_per_instance = ACK_HISTORY;
            });
        };
        auto destroy = [this](DataWriter* w) {
            try {
                node_->delete_writer(w);
            } catch (const std::exception& e) {  // a writer kept is memory, not a failure
                log(std::string("an old ack writer not deleted: ") + e.what());
            }
        };
        std::lock_guard<std::mutex> lock(ack_mutex_);
        acks_ = std::make_unique<AckWriters<DataWriter*>>(make, ack_generation_, destroy);
    }
    manager_->publish_states();
    if (tables_.subsystems.empty()) return;
    if (recovered_.crashed) {  // before any new command: a retried cmdId is known
        auto [answered, again] = manager_->restore(recovered_);
        log("journal: restarted after a crash; " + std::to_string(answered) + " unfinished command(s) answered, " +
            std::to_string(again) + " final ack(s) written again");
        recovered_ = JournalRecovered{};
    }
    // The profile's resource limits stay: Fast DDS refuses a bounded max_samples while
    // instances are unbounded (one instance per commander, never bounded safely), so the
    // bound is the intake door's (PER_WRITER waiting, then "bridge busy"), which takes
    // every sample as it comes.
    // Read by a listener on Fast DDS's receive thread, not a thread of ours waiting on the
    // reader: one thread handoff less per command (bench/README.md, the C++ bridge).
    intake_->start();
    reading_ = true;
    listener_ = std::make_unique<CommandListener>(*this);
    commands_ = node_->reader<::rapid::Command>(COMMAND_TOPIC, "RapidReliableQos", {}, listener_.get());
}

void Bridge::read_commands(DataReader* reader) {
    std::lock_guard<std::mutex> lock(reading_mutex_);
    ::rapid::Command& sample = command_;  // reused: taking a command allocates only what it holds
    SampleInfo info;
    while (reading_ && reader->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
        if (!info.valid_data) continue;  // (samples that do not decode are dropped by the topic type)
        try {
            if (identities_ && refused_source(sample, info.publication_handle)) continue;
            if (!breaks_->any()) {
                intake_->offer(command_in(sample), writer_id(info.publication_handle));
            } else if (auto cmd = breaks_->intake(command_in(sample), *this)) {
                intake_->offer(std::move(*cmd), writer_id(info.publication_handle));
            }
        } catch (const std::exception& e) {  // a bad sample must not stop command intake
            log("command '" + sample.cmdId + "' not read: " + e.what());
        }
    }
}

bool Bridge::refused_source(const ::rapid::Command& sample, const InstanceHandle_t& writer) {
    GuidPrefix prefix{};
    for (std::size_t i = 0; i < prefix.size(); ++i) prefix[i] = writer.value[i];  // (the handle is the writer's GUID)
    auto why = identities_->refusal(sample.cmdSrc, prefix);
    if (!why) return false;
    log("refused '" + visible(sample.cmdId) + "' from writer " + writer_id(writer) + ": " + *why);
    manager_->refuse(command_in(sample), *why);  // COMPLETED/EXEC_FAILED, its cmdId not remembered
    return true;
}

void Bridge::request_stop() {
    {
        std::lock_guard<std::mutex> lock(wait_mutex_);
        stop_requested_ = true;
    }
    wake_.notify_all();
}

bool Bridge::wait(double seconds) {
    std::unique_lock<std::mutex> lock(wait_mutex_);
    return wake_.wait_for(lock, std::chrono::duration<double>(seconds), [this] { return stop_requested_.load(); });
}

void Bridge::stop() {
    if (stopped_) return;
    stopped_ = true;
    request_stop();
    stale_->stop();  // (the stale-telemetry watcher: it writes through the node)
    breaks_->stop();  // (serial-drift's republications)
    {
        std::lock_guard<std::mutex> lock(reading_mutex_);  // (a callback under way ends first)
        reading_ = false;
    }
    if (intake_) intake_->stop();
    if (manager_) {
        std::size_t abandoned = manager_->abandon();
        if (abandoned) log("stopping: " + std::to_string(abandoned) + " unfinished command(s) answered");
    }
    // the last acks (shutdown's own, the unfinished ones') reach their readers: 2 s in all
    std::vector<DataWriter*> ack_writers;
    {
        std::lock_guard<std::mutex> lock(ack_mutex_);
        if (acks_ != nullptr) ack_writers = acks_->writers();
    }
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    for (DataWriter* w : ack_writers) {
        const auto left = std::chrono::duration_cast<std::chrono::nanoseconds>(until - std::chrono::steady_clock::now());
        if (left.count() <= 0) break;
        w->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(static_cast<std::int32_t>(left.count() / 1'000'000'000),
                                                                   static_cast<std::uint32_t>(left.count() % 1'000'000'000)));
    }
    if (manager_ && manager_->release_journal() != nullptr)
        journal_->close(true);  // every command answered: the next start begins afresh
    handlers_running_ = manager_ ? manager_->handlers_running() : 0;
    if (handlers_running_ > 0) {  // threads still in a handler use the manager: never freed under them
        log("stopping: " + std::to_string(handlers_running_) + " handler(s) still running after the shutdown bound");
        (void)manager_.release();  // (shut down: it writes nothing more)
    }
    manager_.reset();  // cancels what runs, joins the handlers
    intake_.reset();
    {
        std::lock_guard<std::mutex> lock(ack_mutex_);
        acks_.reset();  // (its thread joined; the live writers go with the node)
    }
    node_.reset();
}

// ---- Outbox -------------------------------------------------------------------------------------

void Bridge::ack(const Cmd& cmd, AckStatus status, Completion completed, const std::string& message) {
    std::lock_guard<std::mutex> lock(ack_mutex_);
    if (acks_ == nullptr) return;
    // the generation is the command's (a test build's broken acks go through it too)
    DataWriter* writer = acks_->writer_for(ack_key(cmd.src_name, cmd.asset_name, cmd.cmd_id));
    auto write = [this, writer](const Cmd& c, AckStatus s, Completion done, const std::string& text) {
        fill_ack(ack_, c, s, done, text);
        if (!writer->write(&ack_)) log("ack of '" + c.cmd_id + "' not written");
    };
    if (breaks_->any()) breaks_->ack(cmd, status, completed, message, write);
    else write(cmd, status, completed, message);
}

void Bridge::retire(const Cmd& cmd) {
    // Its instance is not unregistered (Fast DDS would free its acks on the receive thread,
    // one linear search of the writer's history each): its generation's writer is deleted,
    // history and all, once every command it took is retired (ack_writers.hpp).
    std::lock_guard<std::mutex> lock(ack_mutex_);
    if (acks_ == nullptr) return;
    acks_->retire(ack_key(cmd.src_name, cmd.asset_name, cmd.cmd_id));
}

void Bridge::queue_state(int code, const std::vector<Record>& pending, const std::vector<Record>& active,
                         const std::vector<Record>& completed) {
    auto q = breaks_->any() ? dds::queue_state(header(tables_.name, tables_.name, serials_.start(),
                                                      breaks_->queue_code(code)),
                                               breaks_->pending(pending), active, completed)
                            : dds::queue_state(header(tables_.name, tables_.name, serials_.start(), code), pending,
                                               active, completed);
    node_->writer<::rapid::QueueState>(QUEUE_STATE_TOPIC, "RapidStateQos")->write(&q);
}

void Bridge::access_state(const std::string& controller, const std::vector<std::string>& requestors) {
    auto* writer = node_->writer<::rapid::AccessControlState>(ACCESS_STATE_TOPIC, "RapidStateQos");
    if (breaks_->on("access-state-unwritten")) return;  // (the writer exists)
    ::rapid::AccessControlState s;
    s.hdr = header(tables_.name, tables_.name, serials_.start());
    s.controller = controller;
    s.requestors = requestors;
    writer->write(&s);
}

}  // namespace dds
}  // namespace rapid_runtime
