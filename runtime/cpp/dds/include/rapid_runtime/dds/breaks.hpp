// Deliberately broken protocol behaviour, for the conformance tests only: a bridge built
// with RAPID_RUNTIME_TEST_BREAKS takes `--break KIND` (BridgeOptions::breaks) and breaks one
// rule the way tests/conformance/broken/ breaks the Python runtime, so that `rapidgen
// conform` can be shown to catch a C++ bridge doing it (tests/cpp_client/test_broken.py).
// A bridge built without the flag refuses any break. Included by bridge.cpp only.
#ifndef RAPID_RUNTIME_DDS_BREAKS_HPP
#define RAPID_RUNTIME_DDS_BREAKS_HPP

#include <cmath>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <rapid_runtime/command.hpp>
#include <rapid_runtime/manager.hpp>
#include <rapid_runtime/tables.hpp>

namespace rapid_runtime {
namespace dds {

class Breaks {
public:
    // kind -> the conformance check it fails (tests/conformance/broken/ has the same names)
    static const std::vector<std::pair<std::string, std::string>>& kinds() {
        static const std::vector<std::pair<std::string, std::string>> all = {
            {"ack-topic-suffixed", "CMD-01"},  {"noop-unimplemented", "CMD-02"}, {"wrong-ack-order", "CMD-03"},
            {"ack-after-final", "CMD-04"},     {"any-subsystem", "CMD-05"},      {"unknown-command-ok", "CMD-06"},
            {"extra-args-ignored", "CMD-07"},  {"args-converted", "CMD-08"},     {"other-asset-accepted", "CMD-09"},
            {"long-ack-message", "CMD-11"},    {"ack-names-commander", "CMD-12"}, {"ack-ids-truncated", "CMD-12"},
            {"volatile-acks", "CMD-13"},       {"crash-on-bad-input", "CMD-14"}, {"ranges-unchecked", "CMD-15"},
            {"queue-status-code", "QUE-01"},   {"queue-record-status", "QUE-05"}, {"access-state-unwritten", "ACC-01"},
            {"zero-serial", "CFG-05"},
        };
        return all;
    }

    Breaks(const std::vector<std::string>& names, const Tables& tables) : tables_(tables) {
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
    }

    bool on(const std::string& kind) const { return on_.count(kind) != 0; }
    bool any() const { return !on_.empty(); }
    // What the manager validates against (ranges-unchecked: no ranges).
    const Tables& tables() const { return tables_; }

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
            message = "not implemented";
        }
        if (on("long-ack-message") && !message.empty())
            message = (message + " " + std::string(128, 'x')).substr(0, 128);  // Astrobee's 128 bytes
        Cmd as = cmd;
        if (on("ack-names-commander")) as.asset_name = cmd.src_name;
        if (on("ack-ids-truncated")) as.cmd_id = cmd.cmd_id.substr(0, 12);
        write(as, status, completed, message);
        if (on("wrong-ack-order") && status == AckStatus::Executing)
            write(as, AckStatus::Queued, Completion::Not, "");
        if (on("ack-after-final") && status == AckStatus::Completed)
            write(as, AckStatus::Executing, Completion::Not, "");
    }

    int queue_code(int code) const { return on("queue-status-code") ? 2 : code; }

    std::vector<Record> pending(const std::vector<Record>& in) const {
        std::vector<Record> out = in;
        if (on("queue-record-status"))
            for (auto& r : out) r.status = RecordStatus::Succeeded;
        return out;
    }

private:
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
};

}  // namespace dds
}  // namespace rapid_runtime

#endif
