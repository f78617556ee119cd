// The protocol specification (runtime/spec/cases/*.yaml) replayed by the C++ runtime,
// without DDS (GoogleTest): each case drives a CommandManager on the seed's generated
// tables through a collecting outbox and scripted handlers (runtime/spec/README.md).
// tests/runtime/test_spec_cases.py is the reference driver: same steps, same comparisons.
//
// The cases come as the JSON `python -m rapidgen.protocol_cases json OUT.json` writes
// (arguments already typed), from the file named by RAPID_SPEC_CASES; one test per case,
// named Spec/Case.Replays/<file>_<case name>. Without the variable there are no cases and
// SpecCases.Loaded fails (tests/cpp_runtime/test_cpp_runtime.py sets it). A case with a
// `restart` step or a `journal` runs on the restart journal (in a temporary folder); a restart
// is the process dying: its manager's later writes unseen, a new manager restored from the journal.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fnmatch.h>
#include <sys/syscall.h>
#include <unistd.h>
#include <sys/stat.h>

#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <rapid_runtime/handlers.hpp>
#include <rapid_runtime/intake.hpp>
#include <rapid_runtime/journal.hpp>
#include <rapid_runtime/manager.hpp>
#include <rapid_runtime/serials.hpp>
#include <rapid_runtime/tables.hpp>
#include <rapid_runtime/value.hpp>

// The seeds' generated tables (bridge/tables.cpp of each generated package). Declared here
// rather than through each bridge/handlers.hpp: the two headers share a file name.
namespace rapid_k10red::bridge {
const ::rapid_runtime::Tables& tables();
}
namespace rapid_chariot::bridge {
const ::rapid_runtime::Tables& tables();
}
namespace rapid_robonaut2::bridge {
const ::rapid_runtime::Tables& tables();
}
namespace rapid_oddity::bridge {
const ::rapid_runtime::Tables& tables();
}

// A case's `disk: failing` makes the journal's fdatasync fail (EIO), `disk: full` its writes to
// a journal file (ENOSPC), until `disk: ok`: these definitions stand in for libc's in this
// program (the runtime is linked in statically).
namespace {
std::atomic<bool> disk_failing{false};
std::atomic<bool> disk_full{false};

bool journal_fd(int fd) {
    char link[64];
    char target[4096];
    std::snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    const ssize_t n = ::readlink(link, target, sizeof target);
    return n > 0 && std::string(target, static_cast<std::size_t>(n)).find(".journal") != std::string::npos;
}
}  // namespace

extern "C" int fdatasync(int fd) {
    if (disk_failing.load()) {
        errno = EIO;
        return -1;
    }
    return static_cast<int>(::syscall(SYS_fdatasync, fd));
}

extern "C" ssize_t write(int fd, const void* data, size_t size) {
    if (disk_full.load() && journal_fd(fd)) {
        errno = ENOSPC;
        return -1;
    }
    return ::syscall(SYS_write, fd, data, size);
}

using namespace rapid_runtime;
using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

namespace {

constexpr auto WAIT = std::chrono::seconds(10);
constexpr auto SLICE = std::chrono::milliseconds(50);  // re-checks of what the outbox is not told of

const Tables& seed_tables(const std::string& seed) {
    if (seed == "k10") return rapid_k10red::bridge::tables();
    if (seed == "chariot") return rapid_chariot::bridge::tables();
    if (seed == "robonaut2") return rapid_robonaut2::bridge::tables();
    if (seed == "oddity") return rapid_oddity::bridge::tables();
    throw std::invalid_argument("no tables for seed '" + seed + "' in this driver (add them to CMakeLists.txt)");
}

// ---- the cases ------------------------------------------------------------------------------------

struct Loaded {
    std::vector<json> cases;
    std::string error;  // why there are none
};

const Loaded& loaded() {
    static const Loaded all = [] {
        Loaded out;
        const char* path = std::getenv("RAPID_SPEC_CASES");
        if (path == nullptr || !*path) {
            out.error = "RAPID_SPEC_CASES is not set (python -m rapidgen.protocol_cases json OUT.json writes the file)";
            return out;
        }
        std::ifstream in(path);
        if (!in) {
            out.error = std::string("cannot read ") + path;
            return out;
        }
        try {
            json doc = json::parse(in);
            for (auto& c : doc.at("cases")) out.cases.push_back(std::move(c));
        } catch (const json::exception& e) {
            out.error = std::string(path) + ": " + e.what();
            out.cases.clear();
        }
        if (out.error.empty() && out.cases.empty()) out.error = std::string(path) + " holds no case";
        return out;
    }();
    return all;
}

// A case, as GoogleTest's parameter: its index in loaded().cases.
struct CaseRef {
    std::size_t index;
    const json& get() const { return loaded().cases.at(index); }
};

std::string where(const json& c) {
    return c.at("file").get<std::string>() + ":" + std::to_string(c.at("line").get<int>()) + " '" +
           c.at("name").get<std::string>() + "'";
}

void PrintTo(const CaseRef& ref, std::ostream* os) { *os << where(ref.get()); }

std::vector<CaseRef> case_refs() {
    std::vector<CaseRef> out;
    for (std::size_t i = 0; i < loaded().cases.size(); ++i) out.push_back({i});
    return out;
}

// <file stem>_<case name>, letters, digits and single underscores (GoogleTest's rule).
std::string sanitized(const json& c) {
    std::string file = c.at("file").get<std::string>();
    file = file.substr(0, file.rfind('.'));
    std::string raw = file + "_" + c.at("name").get<std::string>(), name;
    for (char ch : raw) {
        bool word = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9');
        if (word)
            name += ch;
        else if (!name.empty() && name.back() != '_')
            name += '_';
    }
    while (!name.empty() && name.back() == '_') name.pop_back();
    return name;
}

// The test's name: sanitized, numbered when an earlier case sanitizes alike.
std::string test_name(const ::testing::TestParamInfo<CaseRef>& info) {
    const std::string name = sanitized(info.param.get());
    for (std::size_t i = 0; i < info.param.index; ++i)
        if (sanitized(loaded().cases[i]) == name) return name + "_" + std::to_string(info.param.index);
    return name;
}

// ---- values ---------------------------------------------------------------------------------------

Value value_of(const json& arg) {
    const std::string type = arg.at("type").get<std::string>();
    const json& v = arg.at("value");
    if (type == "RAPID_BOOL") return Value(v.get<bool>());
    if (type == "RAPID_DOUBLE") return Value(v.get<double>());
    if (type == "RAPID_FLOAT") return Value(v.get<float>());
    if (type == "RAPID_INT") return Value(v.get<std::int32_t>());
    if (type == "RAPID_LONGLONG") return Value(v.get<std::int64_t>());
    if (type == "RAPID_STRING") return Value(v.get<std::string>());
    if (type == "RAPID_VEC3d") return Value(v.get<Vec3d>());
    if (type == "RAPID_MAT33f") return Value(v.get<Mat33f>());
    throw std::invalid_argument("unknown argument type " + type);
}

// A handler's argument as the case writes it (a vector as a list).
json plain(const Value& v) {
    return std::visit([](const auto& x) -> json { return json(x); }, v);
}

// As the Python driver's _same: a float on either side compares within a relative 1e-6
// (RAPID_FLOAT is 32 bits here), lists element by element, the rest exactly.
bool same(const json& seen, const json& want) {
    if (seen.is_number_float() || want.is_number_float()) {
        if (!seen.is_number() || !want.is_number()) return false;
        double a = seen.get<double>(), b = want.get<double>();
        return std::fabs(a - b) <= std::max(1e-6 * std::max(std::fabs(a), std::fabs(b)), 1e-9);
    }
    if (want.is_array()) {
        if (!seen.is_array() || seen.size() != want.size()) return false;
        for (std::size_t i = 0; i < want.size(); ++i)
            if (!same(seen[i], want[i])) return false;
        return true;
    }
    return seen == want;
}

QueueAction action_of(const std::string& name) {
    static const std::map<std::string, QueueAction> actions{
        {"QUEUE_BYPASS", QueueAction::Bypass}, {"QUEUE_APPEND", QueueAction::Append},
        {"QUEUE_DELETE", QueueAction::Delete}, {"QUEUE_INSERT", QueueAction::Insert},
        {"QUEUE_REPLACE", QueueAction::Replace}};
    auto it = actions.find(name);
    // a name the IDL does not have: a value outside the enum, as it would come off the wire
    return it != actions.end() ? it->second : static_cast<QueueAction>(99);
}

// ---- what the manager writes -------------------------------------------------------------------------

struct Ack {
    std::string status;  // QUEUED, EXECUTING, REQUEUED, COMPLETED
    std::string completion;  // NOT, OK, BAD_SYNTAX, EXEC_FAILED, CANCELED
    std::string message;
};

// Everything a case looks at, under one lock: the outbox's writes and the handler calls,
// each waking the expectations (Python's Outbox and Scripted share one condition too).
struct Seen {
    std::mutex mutex;
    std::condition_variable changed;
    std::uint64_t generation = 0;  // counts changes (a waiter misses none)
    std::map<std::string, std::vector<Ack>> acks;
    std::vector<std::string> first;  // cmdIds in the order of their first ack
    int stopped = 0;  // the asset's shutdown callback's calls (Admin/shutdown)
    std::optional<std::tuple<int, std::vector<std::string>, std::vector<std::string>>> queue;
    std::map<std::string, std::string> statuses;  // the last QueueState's pending and active records'
    std::vector<std::string> completed;  // the last QueueState's completed records' cmdIds
    std::optional<std::pair<std::string, std::vector<std::string>>> access;
    std::vector<std::string> retired;
    std::vector<std::string> logs;
    std::vector<std::pair<std::string, json>> calls;
    // the scripted handlers' state: each send's behaviour by its number (the Cmd's stamp: a
    // repeat of a running cmdId must not change what the running one does)
    std::map<std::int64_t, json> behaviour;
    std::set<std::string> released;
    bool all_released = false;

    void bump() {
        ++generation;
        changed.notify_all();
    }
    bool is_released(const std::string& id) const { return all_released || released.count(id) > 0; }
};

std::vector<std::string> ids_of(const std::vector<Record>& records) {
    std::vector<std::string> out;
    for (const auto& r : records) out.push_back(r.cmd->cmd_id);
    return out;
}

// One life of the asset's outbox: once its process "dies" (a restart step), what its manager
// still writes is not seen.
class CollectingOutbox : public Outbox {
public:
    explicit CollectingOutbox(Seen& seen) : seen_(seen) {}
    void ack(const Cmd& cmd, AckStatus status, Completion completed, const std::string& message) override {
        std::lock_guard<std::mutex> lock(seen_.mutex);
        if (dead_) return;
        if (seen_.acks.count(cmd.cmd_id) == 0) seen_.first.push_back(cmd.cmd_id);
        seen_.acks[cmd.cmd_id].push_back({std::string(name_of(status)).substr(4),  // ACK_
                                          std::string(name_of(completed)).substr(14),  // ACK_COMPLETED_
                                          message});
        seen_.bump();
    }
    void queue_state(int code, const std::vector<Record>& pending, const std::vector<Record>& active,
                     const std::vector<Record>& completed) override {
        std::lock_guard<std::mutex> lock(seen_.mutex);
        if (dead_) return;
        seen_.queue.emplace(code, ids_of(pending), ids_of(active));
        seen_.completed = ids_of(completed);
        seen_.statuses.clear();
        for (const auto* records : {&pending, &active})
            for (const auto& r : *records) seen_.statuses[r.cmd->cmd_id] = std::string(name_of(r.status));
        seen_.bump();
    }
    void access_state(const std::string& controller, const std::vector<std::string>& requestors) override {
        std::lock_guard<std::mutex> lock(seen_.mutex);
        if (dead_) return;
        seen_.access.emplace(controller, requestors);
        seen_.bump();
    }
    void retire(const Cmd& cmd) override {
        std::lock_guard<std::mutex> lock(seen_.mutex);
        if (dead_) return;
        seen_.retired.push_back(cmd.cmd_id);
        seen_.bump();
    }
    void log(const std::string& text) override {
        std::lock_guard<std::mutex> lock(seen_.mutex);
        if (dead_) return;
        seen_.logs.push_back(text);
        seen_.bump();
    }
    void die() {
        std::lock_guard<std::mutex> lock(seen_.mutex);
        dead_ = true;
    }

private:
    Seen& seen_;
    bool dead_ = false;  // (under seen_.mutex)
};

// Every handler method: behaves as the case's `handler:` for the cmdId says.
class Scripted : public Handlers {
public:
    explicit Scripted(Seen& seen) : seen_(seen) {}

    Result execute(CommandContext& ctx) override {
        const std::string id = ctx.cmd().cmd_id;
        json h;
        {
            std::lock_guard<std::mutex> lock(seen_.mutex);
            json values = json::array();
            for (const auto& v : ctx.args()) values.push_back(plain(v));
            seen_.calls.emplace_back(id, std::move(values));
            seen_.bump();
            auto it = seen_.behaviour.find(ctx.cmd().stamp);
            h = it != seen_.behaviour.end() ? it->second : json{{"kind", "ok"}, {"text", ""}, {"texts", json::array()}};
        }
        const std::string kind = h.at("kind").get<std::string>();
        const std::string text = h.at("text").get<std::string>();
        if (kind == "ok") return Result::ok(text);
        if (kind == "fail") throw CommandFailed(text);
        if (kind == "error") throw std::runtime_error(text);
        if (kind == "odd_error") throw 42;  // (not a std::exception)
        if (kind == "not_implemented") return Result::not_implemented();
        if (kind == "progress") {
            for (const auto& t : h.at("texts")) ctx.progress(t.get<std::string>());
            return Result::ok();
        }
        if (kind == "block") {
            while (!released(id))
                if (!ctx.sleep(0.005)) return Result::ok();  // told to stop: returns (CANCELED, or REQUEUED)
            return Result::ok("released");
        }
        if (kind == "stubborn") {  // deaf to being told to stop
            std::unique_lock<std::mutex> lock(seen_.mutex);
            seen_.changed.wait_for(lock, std::chrono::seconds(60), [&] { return seen_.is_released(id); });
            lock.unlock();
            if (!text.empty()) ctx.progress(text);  // (once released: after its answer, it must go nowhere)
            return Result::ok("released");
        }
        throw std::logic_error("unknown handler behaviour " + kind);
    }

private:
    bool released(const std::string& id) {
        std::lock_guard<std::mutex> lock(seen_.mutex);
        return seen_.is_released(id);
    }
    Seen& seen_;
};

// ---- comparisons and how they print -----------------------------------------------------------------

bool ack_matches(const Ack& seen, const json& want) {
    if (seen.status != want.at("status").get<std::string>()) return false;
    if (!want.at("completion").is_null() && seen.completion != want.at("completion").get<std::string>()) return false;
    if (want.at("message").is_null()) return true;
    const std::string m = want.at("message").get<std::string>();
    return want.at("prefix").get<bool>() ? seen.message.compare(0, m.size(), m) == 0 : seen.message == m;
}

std::string show(const std::vector<Ack>& acks) {
    json out = json::array();
    for (const auto& a : acks) out.push_back(a.status + " " + a.completion + ": " + a.message);
    return out.dump();
}

std::string show(const std::vector<std::string>& ids) { return json(ids).dump(); }

std::string show_want(const json& acks) {
    json out = json::array();
    for (const auto& a : acks) {
        std::string s = a.at("status").get<std::string>();
        if (!a.at("completion").is_null()) s += " " + a.at("completion").get<std::string>();
        if (!a.at("message").is_null()) s += ": " + a.at("message").get<std::string>() + (a.at("prefix").get<bool>() ? "*" : "");
        out.push_back(s);
    }
    return out.dump();
}

// ---- the replay ------------------------------------------------------------------------------------

// Environment variables as they were before a case changed them: put back when destroyed.
class SavedEnv {
public:
    SavedEnv() = default;
    SavedEnv(const SavedEnv&) = delete;
    SavedEnv& operator=(const SavedEnv&) = delete;
    ~SavedEnv() {
        for (const auto& [var, value] : before_) {
            if (value) ::setenv(var.c_str(), value->c_str(), 1);
            else ::unsetenv(var.c_str());
        }
    }
    void set(const std::string& var, const char* value) {  // (nullptr: unset)
        if (!before_.count(var)) {
            const char* was = std::getenv(var.c_str());
            before_[var] = was ? std::optional<std::string>(was) : std::nullopt;
        }
        if (value) ::setenv(var.c_str(), value, 1);
        else ::unsetenv(var.c_str());
    }

private:
    std::map<std::string, std::optional<std::string>> before_;
};

class Replay {
public:
    explicit Replay(const json& c) : case_(c), tables_(seed_tables(c.at("asset").get<std::string>())), handlers_(seen_) {
        if (!c.at("asset_name").is_null()) tables_.name = c.at("asset_name").get<std::string>();  // (renamed)
        for (const auto& [key, v] : c.at("options").items()) {
            if (key == "window")
                options_.window = v.get<std::size_t>();
            else if (key == "queue_limit")
                options_.queue_limit = v.get<std::size_t>();
            else if (key == "bypass_limit")
                options_.bypass_limit = v.get<std::size_t>();
            else if (key == "stop_timeout_ms")
                options_.stop_timeout_ms = v.get<int>();
            else
                throw std::invalid_argument("option '" + key + "' is not known to this driver");
        }
        options_.on_shutdown = [this] {
            std::lock_guard<std::mutex> lock(seen_.mutex);
            ++seen_.stopped;
            seen_.bump();
        };
        // a case that restarts the asset, or starts on a journal, runs with the restart journal
        // as the bridge does, in a state folder not made yet (the runtime makes it) unless the
        // case's journal is written there first
        const json& found = c.at("journal");
        const json& state = c.at("state");
        bool journaled = !found.is_null() || !state.is_null();
        for (const auto& s : c.at("steps"))
            if (s.at("op") == "restart") journaled = true;
        if (journaled) {
            temp_ = temp_dir();
            journal_dir_ = temp_ + "/" + (state.is_null() ? "state/rapid_runtime" : state.at("dir").get<std::string>());
        }
        if (!state.is_null()) {  // (the journal's default folder named by these, in the case's folder)
            for (const auto& var : state.at("unset")) env_.set(var.get<std::string>(), nullptr);
            for (const auto& [var, rel] : state.at("set").items()) env_.set(var, (temp_ + "/" + rel.get<std::string>()).c_str());
        }
        if (!found.is_null()) {
            std::filesystem::create_directories(journal_dir_);
            std::ofstream file(journal_dir_ + "/" + found.at("file").get<std::string>(), std::ios::binary);
            file << found.at("text").get<std::string>();
            if (!file.flush()) throw std::runtime_error("cannot write the case's journal in " + journal_dir_);
            if (!found.at("new").is_null()) {  // (what a crash in the middle of a compaction left)
                std::ofstream left(journal_dir_ + "/" + found.at("file").get<std::string>() + ".new", std::ios::binary);
                left << found.at("new").get<std::string>();
                if (!left.flush()) throw std::runtime_error("cannot write the case's .new file in " + journal_dir_);
            }
        }
        start();
        // a case with a door offers commands there as the bridge's reader does; shut until `open`
        const json& door = c.at("door");
        if (!door.is_null()) {
            CollectingOutbox* out = outboxes_.back().get();
            intake_ = std::make_unique<Intake>(manager(), [out](const std::string& t) { out->log(t); },
                                               door.value("per_writer", PER_WRITER),
                                               door.value("shed_answers", SHED_ANSWERS));
        }
    }
    ~Replay() {  // the door closes, every handler returns, then the asset shuts down (Python's close())
        disk_failing.store(false);
        disk_full.store(false);
        intake_.reset();
        {
            std::lock_guard<std::mutex> lock(seen_.mutex);
            seen_.all_released = true;
            seen_.bump();
        }
        manager().shut_down(2000);
        managers_.clear();  // (each joins its handlers' threads)
        journals_.clear();
        if (!temp_.empty()) std::filesystem::remove_all(temp_);
    }
    Replay(const Replay&) = delete;
    Replay& operator=(const Replay&) = delete;

    // One step; false (with a failure reported) when an expectation was not met.
    bool step(const json& s) {
        const std::string op = s.at("op").get<std::string>();
        if (op == "send" || op == "offer") {
            Cmd c = cmd(s);
            {
                std::lock_guard<std::mutex> lock(seen_.mutex);
                seen_.behaviour[c.stamp] = s.at("handler");
            }
            if (op == "send")
                manager().receive(c);
            else
                intake_->offer(std::move(c), s.at("writer").get<std::string>());
        } else if (op == "open") {
            intake_->start();
        } else if (op == "refuse") {
            manager().refuse(cmd(s), s.at("why").get<std::string>());
        } else if (op == "release") {
            std::lock_guard<std::mutex> lock(seen_.mutex);
            seen_.released.insert(s.at("id").get<std::string>());
            seen_.bump();
        } else if (op == "restart") {
            if (s.at("clean").get<bool>())
                stop_and_start();
            else
                crash();
        } else if (op == "idle") {
            if (!manager().wait_idle(10.0)) return fail("the manager to become idle", "it did not within 10 s");
        } else if (op == "shutdown") {
            manager().shut_down(s.at("timeout_ms").get<int>());
        } else if (op == "acks") {
            return expect_acks(s);
        } else if (op == "queue") {
            return expect_queue(s);
        } else if (op == "control") {
            return expect_control(s);
        } else if (op == "calls") {
            return expect_calls(s);
        } else if (op == "retired") {
            const auto want = s.at("ids").get<std::vector<std::string>>();
            return until("retired " + show(want), [&] { return seen_.retired == want; },
                         [&] { return show(seen_.retired); });
        } else if (op == "pending") {
            // the manager's own view: read without the outbox's lock (the manager writes to the
            // outbox under its own lock; taking them the other way round could deadlock)
            const auto want = s.at("ids").get<std::vector<std::string>>();
            std::vector<std::string> got;
            return until_unlocked("pending " + show(want), [&] { return (got = manager().pending_ids()) == want; },
                                  [&] { return show(got); });
        } else if (op == "no_log") {  // (at this step: what came before it has been waited for)
            const std::string text = s.at("text").get<std::string>();
            std::lock_guard<std::mutex> lock(seen_.mutex);
            for (const auto& line : seen_.logs)
                if (line.find(text) != std::string::npos) return fail("no log line with '" + text + "'", line);
        } else if (op == "log_count") {  // (waits for that many, then no more)
            const std::string text = s.at("text").get<std::string>();
            const std::size_t want = s.at("count").get<std::size_t>();
            auto count = [&] {
                return static_cast<std::size_t>(std::count_if(seen_.logs.begin(), seen_.logs.end(),
                                                              [&](const std::string& line) { return line.find(text) != std::string::npos; }));
            };
            auto last = [&] {
                auto from = seen_.logs.size() > 10 ? seen_.logs.end() - 10 : seen_.logs.begin();
                return show(std::vector<std::string>(from, seen_.logs.end()));
            };
            if (!until(std::to_string(want) + " log lines with '" + text + "'", [&] { return count() >= want; }, last)) return false;
            std::string shown;
            {
                std::lock_guard<std::mutex> lock(seen_.mutex);
                if (count() == want) return true;
                shown = last();
            }
            return fail(std::to_string(want) + " log lines with '" + text + "'", shown);
        } else if (op == "disk") {
            disk_failing.store(s.at("failing").get<bool>());
            disk_full.store(s.at("full").get<bool>());
            return true;
        } else if (op == "log") {
            const std::string text = s.at("text").get<std::string>();
            return until("a log line with '" + text + "'", [&] {
                return std::any_of(seen_.logs.begin(), seen_.logs.end(),
                                   [&](const std::string& line) { return line.find(text) != std::string::npos; });
            }, [&] {
                auto from = seen_.logs.size() > 10 ? seen_.logs.end() - 10 : seen_.logs.begin();
                return show(std::vector<std::string>(from, seen_.logs.end()));
            });
        } else if (op == "order") {
            return expect_order(s.at("ids").get<std::vector<std::string>>());
        } else if (op == "stopped") {
            const int want = s.at("count").get<int>();
            int got = 0;
            if (!until("the shutdown callback called " + std::to_string(want) + " times",
                       [&] { return (got = seen_.stopped) >= want; }, [&] { return std::to_string(seen_.stopped); }))
                return false;
            return got == want || fail("the shutdown callback called " + std::to_string(want) + " times",
                                       std::to_string(got) + " calls");
        } else if (op == "serial") {
            const bool clock = s.at("clock").get<bool>();
            const std::int64_t want = s.at("value").get<std::int64_t>();
            if (clock ? std::llabs(serial_ - started_) <= 2 : serial_ == want) return true;
            return fail(clock ? "the configs' serial at the clock" : "the configs' serial " + std::to_string(want),
                        std::to_string(serial_));
        } else if (op == "files") {
            return expect_files(s.at("names").get<std::vector<std::string>>());
        } else if (op == "journal_file") {
            return expect_journal_file(s);
        } else {
            return fail("a step this driver knows", "step '" + op + "'");
        }
        return true;
    }

private:
    CommandManager& manager() { return *managers_.back(); }

    // The journal folder holds as many files as `patterns`, each matched by one of them and
    // each of them matching one (`*`: any run of characters).
    bool expect_files(const std::vector<std::string>& patterns) {
        std::vector<std::string> names;
        if (std::filesystem::exists(journal_dir_))
            for (const auto& e : std::filesystem::directory_iterator(journal_dir_)) names.push_back(e.path().filename());
        std::sort(names.begin(), names.end());
        auto match = [](const std::string& p, const std::string& n) { return ::fnmatch(p.c_str(), n.c_str(), 0) == 0; };
        bool ok = names.size() == patterns.size();
        for (const auto& n : names)
            ok = ok && std::any_of(patterns.begin(), patterns.end(), [&](const std::string& p) { return match(p, n); });
        for (const auto& p : patterns)
            ok = ok && std::any_of(names.begin(), names.end(), [&](const std::string& n) { return match(p, n); });
        return ok || fail("the journal folder holding " + show(patterns), show(names));
    }

    // The journal file's mode, and its lines: each a sound record (its newline, its CRC) holding
    // the fields given, spelled as the runtimes write them, between `{` or `,` and `,` or `}`
    // (checked at once: the steps before it waited for what they describe).
    bool expect_journal_file(const json& s) {
        const std::string path = journal_dir_ + "/" + s.at("file").get<std::string>();
        if (!s.at("mode").is_null()) {
            struct stat st {};
            char mode[8] = "none";
            if (::stat(path.c_str(), &st) == 0) std::snprintf(mode, sizeof mode, "0%03o", static_cast<unsigned>(st.st_mode & 0777));
            if (s.at("mode").get<std::string>() != mode) return fail("the journal's mode " + s.at("mode").get<std::string>(), mode);
        }
        if (s.at("lines").is_null()) return true;
        std::ifstream in(path, std::ios::binary);
        std::string raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::vector<std::string> lines;
        for (std::size_t pos = 0; pos < raw.size();) {
            std::size_t nl = raw.find('\n', pos);
            std::size_t end = nl == std::string::npos ? raw.size() : nl + 1;
            lines.push_back(raw.substr(pos, end - pos));
            pos = end;
        }
        const auto& want = s.at("lines");
        if (s.at("tail").get<bool>() && lines.size() > want.size())  // (the file's last lines only)
            lines.erase(lines.begin(), lines.end() - static_cast<std::ptrdiff_t>(want.size()));
        bool ok = lines.size() == want.size();
        for (std::size_t i = 0; ok && i < lines.size(); ++i) {
            const std::string& line = lines[i];
            ok = line.size() >= 11 && line.back() == '\n' && line[8] == ' ';
            if (!ok) break;
            const std::string body = line.substr(9, line.size() - 10);
            char crc[16];
            std::snprintf(crc, sizeof crc, "%08x", static_cast<unsigned>(crc32_of(body)));
            ok = line.compare(0, 8, crc) == 0;
            for (const auto& f : want[i]) {
                const std::string field = f.get<std::string>();
                bool found = false;
                for (const char* a : {"{", ","})
                    for (const char* b : {",", "}"}) found = found || body.find(a + field + b) != std::string::npos;
                ok = ok && found;
            }
        }
        return ok || fail("the journal's lines holding " + want.dump(),
                          json(lines).dump(-1, ' ', false, json::error_handler_t::replace));
    }

    // zlib's CRC-32 (the journal's), computed here rather than by the runtime under test
    static std::uint32_t crc32_of(const std::string& data) {
        std::uint32_t c = 0xFFFFFFFFu;
        for (unsigned char b : data) {
            c ^= b;
            for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        }
        return c ^ 0xFFFFFFFFu;
    }

    static std::string temp_dir() {
        std::string pattern = ::testing::TempDir() + "spec-journal-XXXXXX";
        std::vector<char> buf(pattern.begin(), pattern.end());
        buf.push_back('\0');
        if (::mkdtemp(buf.data()) == nullptr) throw std::runtime_error("cannot make a journal folder");
        return buf.data();
    }

    // The asset starts: a new outbox and manager, on the journal (recovering what the last
    // life left) when the case restarts.
    void start() {
        outboxes_.push_back(std::make_unique<CollectingOutbox>(seen_));
        CollectingOutbox& out = *outboxes_.back();
        ManagerOptions o = options_;
        JournalRecovered recovered;
        if (!journal_dir_.empty()) {
            // (a case with `state:` starts the asset without a folder: the runtime's default one)
            const std::string folder = case_.at("state").is_null() ? journal_dir_ : Journal::default_dir();
            journals_.push_back(Journal::open(folder, tables_.name, 0,
                                              o.window, [&out](const std::string& t) { out.log(t); }, recovered));
            if (!journals_.back()) throw std::runtime_error("the restart journal cannot be opened in " + journal_dir_);
            o.journal = journals_.back().get();
        }
        // the configs' serial as the bridge chooses it (start_serials, as dds/src/bridge.cpp): the one asked for,
        // else past the journal's last, else the clock's
        started_ = std::time(nullptr);
        const std::int64_t asked = case_.at("serial").is_null() ? -1 : case_.at("serial").get<std::int64_t>();
        serial_ = start_serials(asked, recovered, o.journal, started_).start();
        managers_.push_back(
            std::make_unique<CommandManager>(tables_, handlers_, out, o));
        if (recovered.crashed) managers_.back()->restore(recovered);
    }

    // The process dies (kill -9): what its manager writes from now on is not seen, its journal
    // stays as the disk has it (no stop record), nothing more starts in it; then it starts again.
    void crash() {
        CommandManager& old = manager();
        old.begin_batch();  // (the manager's lock: no step of it half seen)
        outboxes_.back()->die();
        Journal* journal = old.release_journal();
        old.end_batch();
        if (journal != nullptr) journal->close(false);
        old.shut_down(0);  // (its handlers told to stop, unseen; a stubborn one runs on until released)
        start();
    }

    // A clean stop as the bridge's (every command answered, the journal closed with its stop
    // record), then a start on that journal.
    void stop_and_start() {
        CommandManager& old = manager();
        old.shut_down(5000);
        old.begin_batch();
        Journal* journal = old.release_journal();
        old.end_batch();
        if (journal != nullptr) journal->close(true);
        start();
    }

    Cmd cmd(const json& s) {
        Cmd c;
        c.stamp = ++sends_;  // (hdr.timeStamp: the manager only passes it on)
        c.cmd_id = s.at("id").get<std::string>();
        c.cmd_src = s.at("src").get<std::string>();
        c.subsystem = s.at("subsystem").get<std::string>();
        c.name = s.at("name").get<std::string>();
        for (const auto& a : s.at("args")) c.args.push_back(value_of(a));
        c.action = action_of(s.at("action").get<std::string>());
        c.target = s.at("target").get<std::string>();
        c.src_name = s.at("src_name").get<std::string>();
        c.asset_name = s.at("asset").get<std::string>();
        return c;
    }

    bool fail(const std::string& what, const std::string& seen) {
        ADD_FAILURE() << where(case_) << ": expected " << what << "; seen " << seen;
        return false;
    }

    // Waits (up to WAIT) until ok() holds, checked under the lock of what was seen and again
    // at every change; then fails with seen().
    template <class Ok, class Show>
    bool until(const std::string& what, Ok ok, Show seen) {
        std::unique_lock<std::mutex> lock(seen_.mutex);
        if (seen_.changed.wait_for(lock, WAIT, ok)) return true;
        std::string shown = seen();
        lock.unlock();
        return fail(what, shown);
    }

    // The same for a condition read outside that lock: re-checked at every change and every SLICE.
    template <class Ok, class Show>
    bool until_unlocked(const std::string& what, Ok ok, Show seen) {
        const auto end = Clock::now() + WAIT;
        for (;;) {
            std::uint64_t generation;
            {
                std::lock_guard<std::mutex> lock(seen_.mutex);
                generation = seen_.generation;
            }
            if (ok()) return true;
            if (Clock::now() >= end) return fail(what, seen());
            std::unique_lock<std::mutex> lock(seen_.mutex);
            seen_.changed.wait_until(lock, std::min(end, Clock::now() + SLICE),
                                     [&] { return seen_.generation != generation; });
        }
    }

    // The cmdIds' first acks in this order (waiting until each has one).
    bool expect_order(const std::vector<std::string>& want) {
        std::vector<std::string> got;
        auto firsts = [&] {
            got.clear();
            for (const auto& id : seen_.first)
                if (std::find(want.begin(), want.end(), id) != want.end()) got.push_back(id);
            return got.size() == want.size();
        };
        if (!until("first acks in the order " + show(want), firsts, [&] { return show(got); })) return false;
        return got == want || fail("first acks in the order " + show(want), show(got));
    }

    bool expect_acks(const json& s) {
        const std::string id = s.at("id").get<std::string>();
        const json& want = s.at("acks");
        return until("acks of " + id + ": " + show_want(want), [&] {
            auto it = seen_.acks.find(id);
            const std::vector<Ack> none;
            const auto& got = it != seen_.acks.end() ? it->second : none;
            if (got.size() != want.size()) return false;
            for (std::size_t i = 0; i < got.size(); ++i)
                if (!ack_matches(got[i], want[i])) return false;
            return true;
        }, [&] {
            auto it = seen_.acks.find(id);
            return it != seen_.acks.end() ? show(it->second) : std::string("[]");
        });
    }

    bool expect_queue(const json& s) {
        return until("QueueState " + s.dump(), [&] {
            if (!seen_.queue) return false;
            const auto& [code, pending, active] = *seen_.queue;
            return (!s.contains("code") || s["code"].get<int>() == code) &&
                   (!s.contains("pending") || s["pending"].get<std::vector<std::string>>() == pending) &&
                   (!s.contains("active") || s["active"].get<std::vector<std::string>>() == active) &&
                   (!s.contains("completed") || s["completed"].get<std::vector<std::string>>() == seen_.completed) &&
                   statuses_match(s);
        }, [&] {
            if (!seen_.queue) return std::string("none");
            const auto& [code, pending, active] = *seen_.queue;
            return "code " + std::to_string(code) + ", pending " + show(pending) + ", active " + show(active) +
                   ", completed " + show(seen_.completed) + ", statuses " + json(seen_.statuses).dump();
        });
    }

    // The records' statuses the step names, in the last QueueState (under seen_.mutex).
    bool statuses_match(const json& s) const {
        if (!s.contains("statuses")) return true;
        for (const auto& [id, want] : s.at("statuses").items()) {
            auto it = seen_.statuses.find(id);
            if (it == seen_.statuses.end() || it->second != want.get<std::string>()) return false;
        }
        return true;
    }

    bool expect_control(const json& s) {
        return until("AccessControlState " + s.dump(), [&] {
            if (!seen_.access) return false;
            return (!s.contains("controller") || s["controller"].get<std::string>() == seen_.access->first) &&
                   (!s.contains("requestors") || s["requestors"].get<std::vector<std::string>>() == seen_.access->second);
        }, [&] {
            return seen_.access ? "controller " + seen_.access->first + ", requestors " + show(seen_.access->second)
                                : std::string("none");
        });
    }

    bool expect_calls(const json& s) {
        const json& want = s.at("calls");
        return until("handler calls " + want.dump(), [&] {
            if (seen_.calls.size() != want.size()) return false;
            for (std::size_t i = 0; i < want.size(); ++i)
                if (seen_.calls[i].first != want[i].at("id").get<std::string>() ||
                    !same(seen_.calls[i].second, want[i].at("values")))
                    return false;
            return true;
        }, [&] {
            json out = json::array();
            for (const auto& [id, values] : seen_.calls) out.push_back({{"id", id}, {"values", values}});
            return out.dump();
        });
    }

    const json& case_;
    Tables tables_;  // the seed's, under the case's asset_name if it has one
    ManagerOptions options_;
    std::string temp_;  // the case's temporary folder ("": none)
    std::string journal_dir_;  // the restart journal's folder in it ("": none)
    std::int64_t serial_ = 0;  // the configs' serial at the latest start
    std::int64_t started_ = 0;  // and when (seconds)
    SavedEnv env_;  // what a case's `state:` changed, put back when the replay ends (also if it fails to start)
    Seen seen_;
    std::vector<std::unique_ptr<CollectingOutbox>> outboxes_;  // one per life of the asset, the last live
    Scripted handlers_;
    std::vector<std::unique_ptr<Journal>> journals_;
    std::vector<std::unique_ptr<CommandManager>> managers_;  // the last is the running asset
    std::int64_t sends_ = 0;
    std::unique_ptr<Intake> intake_;  // the door, when the case has one (before the managers it serves end)
};

class Case : public ::testing::TestWithParam<CaseRef> {};

}  // namespace

TEST_P(Case, Replays) {
    const json& c = GetParam().get();
    const json& first = c.at("steps").at(0);
    if (first.at("op") == "refused") {  // (its only step: the manager refuses the case's options)
        const std::string text = first.at("text").get<std::string>();
        try {
            Replay replay(c);
            ADD_FAILURE() << where(c) << ": expected the options refused (" << text << "); the asset started";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << where(c) << ": refused with " << e.what();
        }
        return;
    }
    try {
        Replay replay(c);
        for (const auto& s : c.at("steps"))
            if (!replay.step(s)) return;  // (its failure says which and what was seen)
    } catch (const std::exception& e) {  // a case this driver cannot run: located, not a crash
        ADD_FAILURE() << where(c) << ": " << e.what();
    }
}

INSTANTIATE_TEST_SUITE_P(Spec, Case, ::testing::ValuesIn(case_refs()), test_name);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(Case);

TEST(SpecCases, Loaded) {
    EXPECT_TRUE(loaded().error.empty()) << loaded().error;
    EXPECT_FALSE(loaded().cases.empty());
}
