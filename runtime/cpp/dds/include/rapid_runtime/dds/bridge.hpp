// A running RAPID asset on Fast DDS: the manager behind the intake door, acks and state
// topics written, configs published with their serials, telemetry headers filled.
//
//     Bridge bridge(tables, handlers, options);
//     bridge.publish_config("rapid_command_config", rapid_k10red::config_rapid_command_config());
//     bridge.start();                 // states published, commands read
//     while (!bridge.wait(0.5)) ...   // until Admin/shutdown or stop()
//
// The generated glue (phase 2) only fills in the tables, the configs and the handlers.
#ifndef RAPID_RUNTIME_DDS_BRIDGE_HPP
#define RAPID_RUNTIME_DDS_BRIDGE_HPP

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include <rapid_runtime/identity.hpp>
#include <rapid_runtime/intake.hpp>
#include <rapid_runtime/journal.hpp>
#include <rapid_runtime/log.hpp>
#include <rapid_runtime/manager.hpp>
#include <rapid_runtime/serials.hpp>

#include "ack_writers.hpp"
#include "messages.hpp"
#include "node.hpp"

namespace rapid_runtime {
namespace dds {

inline constexpr const char* COMMAND_TOPIC = "rapid_command";
inline constexpr const char* ACK_TOPIC = "rapid_ack";
inline constexpr const char* QUEUE_STATE_TOPIC = "rapid_queue_state";
inline constexpr const char* ACCESS_STATE_TOPIC = "rapid_accesscontrol_state";
// Acks are transient-local, keyed by cmdId: a commander discovered late still gets the
// whole sequence (QUEUED, EXECUTING, REQUEUED, EXECUTING, COMPLETED, a few progress acks).
inline constexpr int ACK_HISTORY = 8;

struct BridgeOptions {
    int domain = -1;  // -1: the tables' domain
    std::string profiles_file;  // the asset's generated qos/fastdds/rapid_qos_profiles.xml
    std::string profiles_xml;  // or its content (a generated bridge's built-in copy)
    std::string transport = "local";
    std::size_t command_window = COMMAND_WINDOW;
    std::int64_t serial = -1;  // the configs' first serial (-1: start time in seconds)
    std::string journal;  // the restart journal's folder (journal.hpp); empty: no journal
    std::function<void(const std::string&)> log;  // default: stderr, "[asset] text"
    std::vector<std::string> breaks;  // test builds only: rules broken on purpose (breaks.hpp)
    int stop_timeout_ms = DEFAULT_STOP_TIMEOUT_MS;  // --stop-timeout (manager.hpp)
    int shutdown_timeout_ms = DEFAULT_SHUTDOWN_TIMEOUT_MS;  // --shutdown-timeout: stop()'s bound
};

class Breaks;
class StaleWatch;

// What a test build's --break does to one config's publication (breaks.hpp); a plain
// bridge publishes every config as it is.
struct ConfigBreak {
    bool write = true;  // false: never written (no writer either); its serial is still set
    bool durable = true;  // false: a volatile writer
    bool named = true;  // false: srcName left empty
    bool short_command_config = false;  // the CommandConfig's last subsystem left out
    std::string salt;  // added to the content compared for a new serial (serial-drift: always new)
};

class Bridge : public Outbox {
public:
    Bridge(const Tables& tables, Handlers& handlers, BridgeOptions options = {});
    ~Bridge() override;
    Bridge(const Bridge&) = delete;
    Bridge& operator=(const Bridge&) = delete;

    // Publish a config on its transient-local topic; a changed content gets a new, larger
    // serial (receivers ignore a config whose serial did not change). Returns the serial.
    template <class T>
    std::int32_t publish_config(const std::string& topic, T value, const std::string& profile = "RapidConfigQos") {
        if (breaking_configs_) return broken_config(topic, std::move(value), profile);
        std::lock_guard<std::mutex> lock(config_mutex_);
        value.hdr = ::rapid::Header{};
        auto bytes = rapidgen::cdr::serialize(value);
        auto [serial, changed] = serials_.update(topic, std::string(bytes.begin(), bytes.end()));
        if (changed) {
            value.hdr = header(tables_.name, tables_.name, serial);
            node_->writer<T>(topic, profile)->write(&value);
        }
        return serial;
    }

    // A sample or state paired with a config: its header copies the config's (srcName and
    // assetName the asset, serial the config's), timeStamp now in microseconds.
    template <class T>
    void publish(const std::string& topic, T& sample, const std::string& config_topic,
                 const std::string& profile = "RapidSampleQos") {
        sample.hdr = header(tables_.name, tables_.name, serial_of(config_topic));
        node_->writer<T>(topic, profile)->write(&sample);
    }

    std::int32_t serial_of(const std::string& config_topic) const;
    // The test build's breaks (breaks.hpp; none in a plain bridge), for the telemetry helpers.
    const Breaks& breaks() const { return *breaks_; }
    // Stale telemetry's watch (telemetry.hpp), shared by the telemetry helpers; stop() joins it.
    StaleWatch& stale() { return *stale_; }
    void start();  // publishes the states, opens the command path; prints nothing
    // idempotent: no command read any more, the pending and running ones answered (running
    // handlers told to stop and waited for up to shutdown_timeout_ms), the last acks
    // delivered (up to 2 s), the journal closed clean, threads joined. Handler calls that
    // did not return are left running (handlers_running()): the caller ends the process.
    void stop();
    std::size_t handlers_running() const { return handlers_running_; }
    void request_stop();  // from any thread (Admin/shutdown, a signal handler's flag)
    bool wait(double seconds);  // true once stopping was requested
    bool stopping() const { return stop_requested_.load(); }

    Node& node() { return *node_; }
    const Tables& tables() const { return tables_; }
    CommandManager& manager() { return *manager_; }
    void log(const std::string& text) override { (*log_)(text); }

    // ---- Outbox (manager.hpp) ------------------------------------------------------------
    void ack(const Cmd& cmd, AckStatus status, Completion completed, const std::string& message) override;
    void queue_state(int code, const std::vector<Record>& pending, const std::vector<Record>& active,
                     const std::vector<Record>& completed) override;
    void access_state(const std::string& controller, const std::vector<std::string>& requestors) override;
    void retire(const Cmd& cmd) override;

private:
    class CommandListener;
    // Fast DDS's receive thread, when commands came: each is offered to the intake (which
    // never blocks: its own thread runs the manager, the handlers run on theirs).
    void read_commands(eprosima::fastdds::dds::DataReader* reader);
    // Secured: a command whose cmdSrc is not the identity of the writer's certificate is
    // answered COMPLETED/EXEC_FAILED and logged here, never offered (identity.hpp).
    bool refused_source(const ::rapid::Command& sample, const eprosima::fastdds::dds::InstanceHandle_t& writer);
    // A test build's config breaks: what publish_config does instead (breaks.hpp).
    ConfigBreak config_break(const std::string& topic, std::function<void()> republish);
    template <class T>
    std::int32_t broken_config(const std::string& topic, T value, const std::string& profile) {
        const ConfigBreak how = config_break(topic, [this, topic, value, profile] { broken_config(topic, value, profile); });
        std::lock_guard<std::mutex> lock(config_mutex_);
        value.hdr = ::rapid::Header{};
        if constexpr (std::is_same_v<T, ::rapid::CommandConfig>)
            if (how.short_command_config && !value.availableSubsystems.empty()) value.availableSubsystems.pop_back();
        auto bytes = rapidgen::cdr::serialize(value);
        auto [serial, changed] = serials_.update(topic, std::string(bytes.begin(), bytes.end()) + how.salt);
        if (changed && how.write) {
            value.hdr = header(tables_.name, tables_.name, serial);
            if (!how.named) value.hdr.srcName.clear();
            const bool durable = how.durable;
            node_->writer<T>(topic, profile, [durable](eprosima::fastdds::dds::DataWriterQos& q) {
                     if (!durable) q.durability().kind = eprosima::fastdds::dds::VOLATILE_DURABILITY_QOS;
                 })->write(&value);
        }
        return serial;
    }

    const Tables& tables_;
    std::unique_ptr<Breaks> breaks_;  // (before the manager: it may hold the manager's tables)
    bool breaking_configs_ = false;  // (a test build's config breaks)
    std::unique_ptr<Log> log_;
    std::unique_ptr<StaleWatch> stale_;
    JournalRecovered recovered_;  // what the journal held after a crash (answered at start())
    std::unique_ptr<Journal> journal_;  // before the manager, which writes to it
    Serials serials_;
    mutable std::mutex config_mutex_;
    std::unique_ptr<Node> node_;  // before the manager: written to until the manager is gone
    // The ack writers' generations (ack_writers.hpp), made at start(); null once stopped.
    std::unique_ptr<AckWriters<eprosima::fastdds::dds::DataWriter*>> acks_;
    std::size_t ack_generation_ = ACK_GENERATION_MIN;  // commands per ack writer
    std::mutex ack_mutex_;
    ::rapid::Ack ack_;  // one sample, reused for every ack
    std::unique_ptr<CommandManager> manager_;
    std::unique_ptr<Intake> intake_;
    std::unique_ptr<Identities> identities_;  // secured only: the ground sources' subject digests
    std::unique_ptr<CommandListener> listener_;  // (outlives the reader: node_ goes first in stop())
    eprosima::fastdds::dds::DataReader* commands_ = nullptr;
    std::mutex reading_mutex_;  // a callback under way; stop() waits for it
    ::rapid::Command command_;  // one sample, reused (under reading_mutex_)
    std::atomic<bool> stop_requested_{false};
    std::atomic<bool> reading_{false};
    bool stopped_ = false;
    std::size_t handlers_running_ = 0;  // after stop(): handler calls that never returned
    std::mutex wait_mutex_;
    std::condition_variable wake_;
};

}  // namespace dds
}  // namespace rapid_runtime

#endif
