// Deliberately broken protocol behaviour, for the conformance tests only: a bridge built
// with RAPID_RUNTIME_TEST_BREAKS takes `--break KIND` (BridgeOptions::breaks) and breaks one
// rule the way tests/conformance/broken/ breaks the Python runtime, so that `rapidgen
// conform` can be shown to catch a C++ bridge doing it (tests/cpp_client/test_broken.py).
// A bridge built without the flag refuses any break. Where each kind is injected: the
// Bridge's intake, acks and state topics, config publishing (Bridge::publish_config), the
// telemetry helpers and the simulated robot (telemetry.cpp, simulate.cpp), and the
// manager's own decisions (ManagerBreaks, manager.hpp: compiled into test builds only).
#ifndef RAPID_RUNTIME_DDS_BREAKS_HPP
#define RAPID_RUNTIME_DDS_BREAKS_HPP

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include <rapid_runtime/command.hpp>
#include <rapid_runtime/manager.hpp>
#include <rapid_runtime/tables.hpp>
#include <rapid_runtime/texts.hpp>

#include "bridge.hpp"
#include "messages.hpp"

namespace rapid_runtime {
namespace dds {

class Breaks {
public:
    static constexpr double DRIFT_PERIOD = 3.0;  // s (serial-drift, as the Python kind)

    // kind -> the conformance check it fails (tests/conformance/broken/ has the same names)
    static const std::vector<std::pair<std::string, std::string>>& kinds() {
        static const std::vector<std::pair<std::string, std::string>> all = {
            // intake, acks and state topics (bridge.cpp)
            {"ack-topic-suffixed", "CMD-01"},  {"noop-unimplemented", "CMD-02"}, {"wrong-ack-order", "CMD-03"},
            {"ack-after-final", "CMD-04"},     {"any-subsystem", "CMD-05"},      {"unknown-command-ok", "CMD-06"},
            {"extra-args-ignored", "CMD-07"},  {"args-converted", "CMD-08"},     {"other-asset-accepted", "CMD-09"},
            {"long-ack-message", "CMD-11"},    {"ack-names-commander", "CMD-12"}, {"ack-ids-truncated", "CMD-12"},
            {"volatile-acks", "CMD-13"},       {"crash-on-bad-input", "CMD-14"}, {"ranges-unchecked", "CMD-15"},
            {"queue-status-code", "QUE-01"},   {"queue-record-status", "QUE-05"}, {"access-state-unwritten", "ACC-01"},
            {"zero-serial", "CFG-05"},
            // the manager's decisions (ManagerBreaks)
            {"no-dedup", "CMD-10"},            {"request-unpublished", "ACC-02"}, {"no-control-gate", "ACC-03"},
            {"grab-refused", "ACC-04"},        {"grab-unpublished", "ACC-04"},   {"release-by-anyone", "ACC-05"},
            {"stop-needs-control", "ACC-06"},  {"request-steals-control", "ACC-07"}, {"queue-lifo", "QUE-02"},
            {"queue-parallel", "QUE-02"},      {"append-target-ignored", "QUE-03"}, {"delete-wrong-command", "QUE-04"},
            // configs (Bridge::publish_config)
            {"position-config-unpublished", "CFG-01"}, {"volatile-config", "CFG-02"}, {"wrong-config", "CFG-03"},
            {"config-without-source", "CFG-04"}, {"serial-drift", "CFG-05"},
            // telemetry (telemetry.cpp) and the simulated robot (simulate.cpp)
            {"position-silent", "TEL-01"},     {"wrong-serial", "TEL-02"},       {"misaligned-values", "TEL-03"},
            {"millisecond-stamps", "TEL-04"},  {"frozen-stamps", "TEL-04"},      {"sample-without-source", "TEL-05"},
            {"slow-rate", "TEL-06"},           {"millivolts", "TEL-07"},         {"gps-silent", "TEL-08"},
        };
        return all;
    }

    Breaks(const std::vector<std::string>& names, const Tables& tables) : tables_(tables), start_us_(now_us()) {
#ifndef RAPID_RUNTIME_TEST_BREAKS
        if (!names.empty())
            throw std::invalid_argument("--break is for test builds only (RAPID_RUNTIME_TEST_BREAKS)");
#endif
        for (const auto& n : names) {
            bool known = false;
            for (const auto& [kind, check] : kinds()) known = known || kind == n;
            if (!known) throw std::invalid_argument("unknown break " + n);
            on_.insert(n);
        }
        if (on("ranges-unchecked"))
            for (auto& t : tables_.types)
                for (auto& c : t.commands)
                    for (auto& p : c.params) p.min = p.max = std::nullopt;
        // the first position entry's config (CFG-01), as the Python kind
        for (const auto& e : tables_.telemetry)
            if (e.kind == "position" && e.topic("config") != nullptr) {
                position_config_ = e.topic("config")->topic;
                break;
            }
    }
    ~Breaks() { stop(); }
    Breaks(const Breaks&) = delete;
    Breaks& operator=(const Breaks&) = delete;

    bool on(const std::string& kind) const { return on_.count(kind) != 0; }
    bool any() const { return !on_.empty(); }
    // What the manager validates against (ranges-unchecked: no ranges).
    const Tables& tables() const { return tables_; }

#ifdef RAPID_RUNTIME_TEST_BREAKS
    // The manager's decisions broken (manager.cpp, under the same flag).
    ManagerBreaks manager() const {
        ManagerBreaks m;
        m.no_dedup = on("no-dedup");
        m.request_unpublished = on("request-unpublished");
        m.no_control_gate = on("no-control-gate");
        m.grab_refused = on("grab-refused");
        m.grab_unpublished = on("grab-unpublished");
        m.release_by_anyone = on("release-by-anyone");
        m.stop_needs_control = on("stop-needs-control");
        m.request_steals_control = on("request-steals-control");
        m.queue_lifo = on("queue-lifo");
        m.queue_parallel = on("queue-parallel");
        m.append_target_ignored = on("append-target-ignored");
        m.delete_wrong_command = on("delete-wrong-command");
        return m;
    }
#endif

    // A received command as the broken bridge sees it; nothing: answered here (or crashed).
    std::optional<Cmd> intake(Cmd cmd, Outbox& out) const {
        if (on("crash-on-bad-input"))
            for (const auto& v : cmd.args) {
                const double* d = std::get_if<double>(&v);
                const float* f = std::get_if<float>(&v);
                if ((d != nullptr && std::isnan(*d)) || (f != nullptr && std::isnan(*f)))
                    ::_exit(70);  // what an unchecked float conversion in a robot's bridge does
            }
        if (on("other-asset-accepted")) cmd.asset_name = tables_.name;
        const std::string* type = tables_.type_of(cmd.subsystem);
        if (on("any-subsystem") && type == nullptr)  // dispatched by command name alone
            for (const auto& s : tables_.subsystems)
                if (tables_.command(s.name, cmd.name)) {
                    cmd.subsystem = s.name;
                    break;
                }
        CommandRef ref = tables_.command(cmd.subsystem, cmd.name);
        if (on("unknown-command-ok") && type != nullptr && !ref) {  // a dispatcher's default case
            out.ack(cmd, AckStatus::Executing, Completion::Not, "");
            out.ack(cmd, AckStatus::Completed, Completion::Ok, "");
            return std::nullopt;
        }
        if (ref && on("extra-args-ignored") && cmd.args.size() > ref.spec->params.size())
            cmd.args.resize(ref.spec->params.size());
        if (ref && on("args-converted") && cmd.args.size() == ref.spec->params.size())
            for (std::size_t i = 0; i < cmd.args.size(); ++i) cmd.args[i] = converted(ref.spec->params[i].type, cmd.args[i]);
        return cmd;
    }

    // An ack as the broken bridge writes it: write(cmd, status, completed, message) 0..2 times.
    template <class Write>
    void ack(const Cmd& cmd, AckStatus status, Completion completed, std::string message, Write write) const {
        if (on("noop-unimplemented") && cmd.subsystem == "Admin" && cmd.name == "noOp" && completed == Completion::Ok) {
            completed = Completion::ExecFailed;
            message = texts::NOT_IMPLEMENTED;
        }
        if (on("long-ack-message") && !message.empty())
            message = (message + " " + std::string(128, 'x')).substr(0, 128);  // Astrobee's 128 bytes
        Cmd as = cmd;
        if (on("ack-names-commander")) as.asset_name = cmd.src_name;
        if (on("ack-ids-truncated")) as.cmd_id = cmd.cmd_id.substr(0, 12);
        write(as, status, completed, message);
        if (on("wrong-ack-order") && status == AckStatus::Executing)
            write(as, AckStatus::Queued, Completion::Not, "");
        // once per cmdId: the stored final ack written again for a resent cmdId (issue 42,
        // CMD-10 accepts it) goes out as it was
        if (on("ack-after-final") && status == AckStatus::Completed && after_final_.insert(cmd.cmd_id).second)
            write(as, AckStatus::Executing, Completion::Not, "");
    }

    int queue_code(int code) const { return on("queue-status-code") ? 2 : code; }

    std::vector<Record> pending(const std::vector<Record>& in) const {
        std::vector<Record> out = in;
        if (on("queue-record-status"))
            for (auto& r : out) r.status = RecordStatus::Succeeded;
        return out;
    }

    // ---- configs --------------------------------------------------------------------------

    // serial-drift: republish is called every DRIFT_PERIOD s (the topic's first one kept).
    ConfigBreak config(const std::string& topic, std::function<void()> republish) {
        ConfigBreak c;
        c.write = !(on("position-config-unpublished") && topic == position_config_);
        c.durable = !on("volatile-config");
        c.named = !on("config-without-source");
        c.short_command_config = on("wrong-config") && topic == "rapid_command_config";
        if (on("serial-drift")) {
            c.salt = "#" + std::to_string(++drifts_);
            drift(topic, std::move(republish));
        }
        return c;
    }
    bool configs_broken() const {
        for (const char* k : {"position-config-unpublished", "volatile-config", "wrong-config", "config-without-source",
                              "serial-drift"})
            if (on(k)) return true;
        return false;
    }

    // Before the writers go (Bridge::stop); idempotent.
    void stop() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        if (thread_.joinable()) thread_.join();
    }

    // ---- telemetry ------------------------------------------------------------------------

    // A telemetry sample's header as the broken bridge fills it.
    void sample_header(::rapid::Header& h) const {
        if (on("wrong-serial")) h.serial += 1;
        if (on("millisecond-stamps")) h.timeStamp /= 1000;
        if (on("frozen-stamps")) h.timeStamp = start_us_;  // recent at first, never advancing
        if (on("sample-without-source")) h.srcName.clear();
    }
    bool samples_broken() const {
        return on("wrong-serial") || on("millisecond-stamps") || on("frozen-stamps") || on("sample-without-source");
    }
    // Telemetry values in the config's order, of the keys' types, as the broken bridge sends them.
    void values(const TelemetrySpec& e, std::vector<::rapid::ParameterUnion>& v) const {
        if (on("millivolts"))
            for (std::size_t i = 0; i < e.values.size() && i < v.size(); ++i)
                if (e.values[i].name == "batteryVoltage" && v[i]._d() == ::rapid::DataType::RAPID_FLOAT)
                    v[i].f(v[i].f() * 1000);
        if (on("misaligned-values")) {
            std::reverse(v.begin(), v.end());
            ::rapid::ParameterUnion extra;
            extra.b(true);
            v.push_back(extra);
        }
    }
    // The simulated robot: a telemetry entry (its kind, the index among entries of its
    // kind) left silent, its writer made all the same.
    bool silent(const std::string& kind, std::size_t index) const {
        return (on("position-silent") && kind == "position" && index == 0) ||
               (on("gps-silent") && kind == "custom" && index == 0);
    }
    double rate(double declared) const { return on("slow-rate") ? declared / 2 : declared; }

private:
    // republish called every DRIFT_PERIOD s on a thread of its own, until stop().
    void drift(const std::string& topic, std::function<void()> republish) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (stopping_) return;
        drifting_.emplace(topic, std::move(republish));
        if (thread_.joinable()) return;
        thread_ = std::thread([this] {
            std::unique_lock<std::mutex> lock(mutex_);
            while (!wake_.wait_for(lock, std::chrono::duration<double>(DRIFT_PERIOD), [this] { return stopping_; })) {
                auto all = drifting_;
                lock.unlock();
                for (auto& [t, republish] : all) republish();
                lock.lock();
            }
        });
    }

    // The value read as the parameter's type whatever the union said, as a bridge calling
    // the union's accessor for the declared type would (unchanged when it cannot be).
    static Value converted(DataType t, const Value& v) {
        double x = 0;
        bool number = true;
        if (auto* d = std::get_if<double>(&v)) x = *d;
        else if (auto* f = std::get_if<float>(&v)) x = *f;
        else if (auto* i = std::get_if<std::int32_t>(&v)) x = *i;
        else if (auto* l = std::get_if<std::int64_t>(&v)) x = static_cast<double>(*l);
        else number = false;
        if (t == DataType::String && !std::holds_alternative<std::string>(v)) return Value(repr(v));
        if (!number) return v;
        if (t == DataType::Double) return Value(x);
        if (t == DataType::Float) return Value(static_cast<float>(x));
        if (std::isfinite(x) && std::floor(x) == x && std::fabs(x) < 2e9) {
            if (t == DataType::Int) return Value(static_cast<std::int32_t>(x));
            if (t == DataType::LongLong) return Value(static_cast<std::int64_t>(x));
        }
        return v;
    }

    Tables tables_;
    std::set<std::string> on_;
    mutable std::set<std::string> after_final_;  // ack-after-final's cmdIds (under the Bridge's ack lock)
    std::int64_t start_us_;
    std::string position_config_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stopping_ = false;
    std::map<std::string, std::function<void()>> drifting_;  // topic -> its republication
    std::atomic<std::uint64_t> drifts_{0};
    std::thread thread_;
};

}  // namespace dds
}  // namespace rapid_runtime

#endif
