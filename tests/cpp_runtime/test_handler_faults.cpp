// Handlers on a bad day (issue 42; runtime/cpp/README.md "The handler contract"): one
// fault-injecting handler per case, on K10's tables, no DDS. Built and run again under
// ASan/UBSan (tests/cpp_runtime/test_cpp_runtime.py, RAPID_RUNTIME_SANITIZE): a context used
// after its handler returned, or after the manager went, must be no use after free.
// Conditions, not sleeps, order the steps; the stop bounds are short (100-200 ms) so that a
// test waits for them, never measures them.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <rapid_runtime/manager.hpp>
#include <rapid_runtime/text.hpp>

#include "k10_tables.hpp"

using namespace rapid_runtime;
using namespace std::chrono_literals;

namespace {

constexpr auto WAIT = 20s;
const std::string OP = "RapidWorkbench";
const std::string FFFD = "\xef\xbf\xbd";

struct Sent {
    std::string status;  // QUEUED, EXECUTING, REQUEUED, COMPLETED
    std::string completed;  // NOT, OK, BAD_SYNTAX, EXEC_FAILED, CANCELED
    std::string message;
    bool operator==(const Sent& o) const {
        return std::tie(status, completed, message) == std::tie(o.status, o.completed, o.message);
    }
};

std::ostream& operator<<(std::ostream& os, const Sent& s) {
    return os << "{" << s.status << " " << s.completed << " '" << visible(s.message) << "'}";
}

class Recorder : public Outbox {
public:
    void ack(const Cmd& cmd, AckStatus status, Completion completed, const std::string& message) override {
        std::lock_guard<std::mutex> lock(mutex);
        acks[cmd.cmd_id].push_back(
            {std::string(name_of(status)).substr(4), std::string(name_of(completed)).substr(14), message});
        changed.notify_all();
    }
    void queue_state(int code, const std::vector<Record>& pending, const std::vector<Record>& active,
                     const std::vector<Record>&) override {
        std::lock_guard<std::mutex> lock(mutex);
        std::vector<std::string> p, a;
        for (const auto& r : pending) p.push_back(r.cmd->cmd_id);
        for (const auto& r : active) a.push_back(r.cmd->cmd_id);
        queue.emplace_back(code, p, a);
        changed.notify_all();
    }
    void access_state(const std::string&, const std::vector<std::string>&) override {}
    void retire(const Cmd&) override {}
    void log(const std::string& text) override {
        std::lock_guard<std::mutex> lock(mutex);
        logs.push_back(text);
    }

    std::vector<Sent> all(const std::string& id) {
        std::lock_guard<std::mutex> lock(mutex);
        return acks[id];
    }
    std::size_t finals(const std::string& id) {
        std::size_t n = 0;
        for (const auto& a : acks[id]) n += a.status == "COMPLETED";
        return n;
    }
    // The command's final ack, once it came (or WAIT passed: a failure).
    Sent final_(const std::string& id) {
        std::unique_lock<std::mutex> lock(mutex);
        EXPECT_TRUE(changed.wait_for(lock, WAIT, [&] { return finals(id) > 0; })) << id << ": no final ack";
        for (const auto& a : acks[id])
            if (a.status == "COMPLETED") return a;
        return {};
    }
    void until(const std::string& id, const std::string& status) {
        std::unique_lock<std::mutex> lock(mutex);
        ASSERT_TRUE(changed.wait_for(lock, WAIT, [&] {
            for (const auto& a : acks[id])
                if (a.status == status) return true;
            return false;
        })) << id << " never " << status;
    }
    std::vector<std::string> logs_naming(const std::string& what) {
        std::lock_guard<std::mutex> lock(mutex);
        std::vector<std::string> out;
        for (const auto& l : logs)
            if (l.find(what) != std::string::npos) out.push_back(l);
        return out;
    }

    std::mutex mutex;
    std::condition_variable changed;
    std::map<std::string, std::vector<Sent>> acks;
    std::vector<std::tuple<int, std::vector<std::string>, std::vector<std::string>>> queue;
    std::vector<std::string> logs;
};

// The faults, by command:
//   PanCam/pointCamera       ignores cancel: runs until released
//   Mobility/simpleMove      ignores cancel too (a drive that will not stop)
//   PanCam/takePicture       mode "left": OK at once; "right": fails
//   K10Native/nativeCommand  text: "helper" hands its context to two threads of its own (one
//                            by reference, one shared) and returns; "bad-text" answers with
//                            invalid UTF-8 and a NUL; "boom" throws; "progress-bad" reports
//                            progress with invalid UTF-8 and a NUL, then returns
class Faulty : public Handlers {
public:
    ~Faulty() override { join_helpers(); }

    Result execute(CommandContext& ctx) override {
        const std::string& c = ctx.command();
        if (c == "pointCamera" || c == "simpleMove") {
            {
                std::lock_guard<std::mutex> lock(mutex);
                stuck.push_back(&ctx);
            }
            while (!release.load()) std::this_thread::sleep_for(2ms);  // never looks at cancelled()
            ctx.progress("late progress, after the bound");  // a no-op once it was answered
            returned.fetch_add(1);
            return Result::ok("finished at last");
        }
        if (c == "takePicture") {
            if (ctx.arg<std::string>(0) == "right") throw CommandFailed("right camera offline");
            return Result::ok("picture");
        }
        if (c != "nativeCommand") return Handlers::execute(ctx);  // the stubs (stopAllMotion's)
        const std::string& what = ctx.arg<std::string>(0);
        if (what == "helper") {
            std::shared_ptr<CommandContext> shared = ctx.share();
            CommandContext* raw = &ctx;
            std::lock_guard<std::mutex> lock(mutex);
            helpers.emplace_back([this, raw] {  // a driver callback that kept a reference
                wait_go();
                raw->progress("from a helper, after return (by reference)");
                seen_done.fetch_add(raw->done() ? 1 : 0);
                reported.fetch_add(1);
            });
            helpers.emplace_back([this, shared] {  // one that shares the context
                wait_go();
                shared->progress("from a helper, after return (shared)");
                seen_done.fetch_add(shared->done() ? 1 : 0);
                reported.fetch_add(1);
                wait_late();  // and once more after the manager is gone
                shared->progress("from a helper, after the manager went");
                (void)shared->cancelled();
            });
            return Result::ok("helpers started");
        }
        if (what == "bad-text") return Result::ok(std::string("ok \xff\xfe end \xe2\x82 nul[") + '\0' + "]");
        if (what == "progress-bad") {
            ctx.progress(std::string("p\0q", 3));
            ctx.progress("r\xc0\xafs");
            return Result::ok("done");
        }
        if (what == "boom") throw std::runtime_error("boom");
        return Handlers::execute(ctx);
    }

    void go() {
        {
            std::lock_guard<std::mutex> lock(mutex);
            go_ = true;
        }
        wake.notify_all();
    }
    void late() {
        {
            std::lock_guard<std::mutex> lock(mutex);
            late_ = true;
        }
        wake.notify_all();
    }
    void join_helpers() {
        go();
        late();
        std::vector<std::thread> taken;
        {
            std::lock_guard<std::mutex> lock(mutex);
            taken.swap(helpers);
        }
        for (auto& t : taken) t.join();
    }
    // Wait until the helpers ran their first part (each adds to seen_done or not: counted by calls).
    std::size_t stuck_count() {
        std::lock_guard<std::mutex> lock(mutex);
        return stuck.size();
    }

    std::atomic<bool> release{false};
    std::atomic<int> returned{0};
    std::atomic<int> seen_done{0};
    std::atomic<int> reported{0};  // helpers past their first report
    std::mutex mutex;
    std::condition_variable wake;
    std::vector<std::thread> helpers;
    std::vector<CommandContext*> stuck;

private:
    void wait_go() {
        std::unique_lock<std::mutex> lock(mutex);
        wake.wait(lock, [this] { return go_; });
    }
    void wait_late() {
        std::unique_lock<std::mutex> lock(mutex);
        wake.wait(lock, [this] { return late_; });
    }
    bool go_ = false;
    bool late_ = false;
};

Cmd make(const std::string& id, const std::string& sub, const std::string& name, std::vector<Value> args,
         QueueAction action, const std::string& target = "", const std::string& src = OP) {
    Cmd c;
    c.cmd_id = id;
    c.cmd_src = src;
    c.subsystem = sub;
    c.name = name;
    c.args = std::move(args);
    c.action = action;
    c.target = target;
    c.src_name = "ground";
    c.asset_name = "K10Red";
    return c;
}

const std::vector<Value> POINT{Value(0.1f), Value(0.0f)};
const std::vector<Value> MOVE{Value(std::string("site")), Value(Vec3d{1.0, 0.0, 0.0})};
std::vector<Value> native(const std::string& what) { return {Value(what)}; }
std::vector<Value> picture(const std::string& mode) { return {Value(mode), Value(0.0f)}; }

// K10's tables with pointCamera's stop bound declared (150 ms), the default bound of the
// others set by the options.
class Faults : public ::testing::Test {
protected:
    void SetUp() override {
        tables = k10_tables();
        for (auto& type : tables.types)
            for (auto& c : type.commands)
                if (c.name == "pointCamera") c.stop_timeout_ms = POINT_BOUND_MS;
        ManagerOptions m;
        m.stop_timeout_ms = DEFAULT_BOUND_MS;
        manager = std::make_unique<CommandManager>(tables, handlers, out, m);
        send("AccessControl", "requestControl", {}, QueueAction::Bypass, "ctl");
        ASSERT_EQ(out.final_("ctl").completed, "OK");
    }
    void TearDown() override {
        handlers.release = true;
        handlers.join_helpers();
        manager.reset();
    }
    std::string send(const std::string& sub, const std::string& name, std::vector<Value> args = {},
                     QueueAction action = QueueAction::Bypass, std::string id = "", const std::string& target = "",
                     const std::string& src = OP) {
        if (id.empty()) id = "f" + std::to_string(++n_);
        manager->receive(make(id, sub, name, std::move(args), action, target, src));
        return id;
    }

    static constexpr int POINT_BOUND_MS = 150;
    static constexpr int DEFAULT_BOUND_MS = 100;
    Tables tables;
    Faulty handlers;
    Recorder out;
    std::unique_ptr<CommandManager> manager;
    int n_ = 0;
};

TEST_F(Faults, ProgressFromAHelperAfterABypassHandlerReturnedIsANoOpAndNoUseAfterFree) {
    auto h = send("K10Native", "nativeCommand", native("helper"));
    EXPECT_EQ(out.final_(h), (Sent{"COMPLETED", "OK", "helpers started"}));
    // the handler's thread is gone and the run answered; now the helpers report
    ASSERT_TRUE(manager->wait_idle(20));
    const auto before = out.all(h);
    handlers.go();
    // (a context held by reference stays valid while the runtime keeps it: the last 1024
    // finished commands' contexts, while the manager lives)
    for (auto end = std::chrono::steady_clock::now() + WAIT;
         handlers.reported.load() < 2 && std::chrono::steady_clock::now() < end;)
        std::this_thread::sleep_for(1ms);
    ASSERT_EQ(handlers.reported.load(), 2);
    // the manager goes while a helper still holds the shared context; then that helper calls it
    manager.reset();
    handlers.join_helpers();
    EXPECT_EQ(out.all(h), before);  // nothing after the COMPLETED
    EXPECT_EQ(handlers.seen_done.load(), 2);  // each saw the command done
}

TEST_F(Faults, ADeleteOfAHandlerThatIgnoresItIsHonestThenTheBoundFreesTheQueue) {
    auto a = send("PanCam", "pointCamera", POINT, QueueAction::Append);
    out.until(a, "EXECUTING");
    auto d = send("Admin", "noOp", {}, QueueAction::Delete, "", a);
    EXPECT_EQ(out.final_(d), (Sent{"COMPLETED", "OK", a + " cancel requested; handler has not stopped yet"}));
    auto next = send("PanCam", "takePicture", picture("left"), QueueAction::Append);
    out.until(next, "QUEUED");
    // at pointCamera's declared bound: its final ack, and the queue goes on
    EXPECT_EQ(out.final_(a), (Sent{"COMPLETED", "EXEC_FAILED", DID_NOT_STOP}));
    EXPECT_EQ(out.final_(next), (Sent{"COMPLETED", "OK", "picture"}));
    EXPECT_FALSE(manager->suspended());  // a command told to stop suspends nothing
    auto said = out.logs_naming(a);
    ASSERT_EQ(said.size(), 1u);
    EXPECT_NE(said[0].find("PanCam/pointCamera"), std::string::npos) << said[0];
    EXPECT_NE(said[0].find("150 ms"), std::string::npos) << said[0];
    EXPECT_NE(said[0].find("must stop it in hardware"), std::string::npos) << said[0];
    {
        std::lock_guard<std::mutex> lock(out.mutex);
        auto [code, pending, active] = out.queue.back();
        EXPECT_EQ(code, 0);
        EXPECT_TRUE(pending.empty() && active.empty());
    }
    // the handler returns at last: ignored (no second COMPLETED, its late progress a no-op)
    const auto before = out.all(a);
    handlers.release = true;
    for (auto end = std::chrono::steady_clock::now() + WAIT;
         handlers.returned.load() < 1 && std::chrono::steady_clock::now() < end;)
        std::this_thread::sleep_for(1ms);
    ASSERT_EQ(handlers.returned.load(), 1);
    ASSERT_TRUE(manager->wait_idle(20));
    EXPECT_EQ(manager->handlers_running(), 0u);
    EXPECT_EQ(out.all(a), before);
}

TEST_F(Faults, AReplaceOfAHandlerThatIgnoresItRunsOnceTheBoundAnsweredIt) {
    auto a = send("PanCam", "pointCamera", POINT, QueueAction::Append);
    out.until(a, "EXECUTING");
    auto r = send("PanCam", "takePicture", picture("left"), QueueAction::Replace, "", a);
    out.until(r, "QUEUED");
    EXPECT_EQ(out.final_(a), (Sent{"COMPLETED", "EXEC_FAILED", DID_NOT_STOP}));
    EXPECT_EQ(out.final_(r), (Sent{"COMPLETED", "OK", "picture"}));
    EXPECT_FALSE(manager->suspended());
    // QueueState showed the replacement as the active command once the old one's slot was freed
    std::lock_guard<std::mutex> lock(out.mutex);
    bool shown = false;
    for (const auto& [code, pending, active] : out.queue) shown = shown || active == std::vector<std::string>{r};
    EXPECT_TRUE(shown);
}

TEST_F(Faults, CancelAllOfAHandlerThatIgnoresItSaysSoAndTheDefaultBoundAnswersIt) {
    auto m = send("Mobility", "simpleMove", MOVE, QueueAction::Append);
    out.until(m, "EXECUTING");
    auto c = send("Queue", "cancelAll");
    EXPECT_EQ(out.final_(c), (Sent{"COMPLETED", "OK", "1 handler(s) asked to stop, not stopped yet"}));
    EXPECT_EQ(out.final_(m), (Sent{"COMPLETED", "EXEC_FAILED", DID_NOT_STOP}));  // the options' 100 ms
    auto said = out.logs_naming(m);
    ASSERT_EQ(said.size(), 1u);
    EXPECT_NE(said[0].find("Mobility/simpleMove"), std::string::npos) << said[0];
    EXPECT_NE(said[0].find("100 ms"), std::string::npos) << said[0];
}

TEST_F(Faults, CancelAllOfASuspendedQueueRepublishesQueueState) {
    auto bad = send("PanCam", "takePicture", picture("right"), QueueAction::Append);
    EXPECT_EQ(out.final_(bad).completed, "EXEC_FAILED");
    ASSERT_TRUE(manager->suspended());
    auto waiting = send("PanCam", "takePicture", picture("left"), QueueAction::Append);
    out.until(waiting, "QUEUED");
    std::size_t states = 0;
    {
        std::lock_guard<std::mutex> lock(out.mutex);
        states = out.queue.size();
        EXPECT_EQ(std::get<0>(out.queue.back()), -1);
        EXPECT_EQ(std::get<1>(out.queue.back()), std::vector<std::string>{waiting});
    }
    auto c = send("Queue", "cancelAll");
    EXPECT_EQ(out.final_(c), (Sent{"COMPLETED", "OK", ""}));
    EXPECT_EQ(out.final_(waiting), (Sent{"COMPLETED", "CANCELED", "cancelAll"}));
    std::lock_guard<std::mutex> lock(out.mutex);
    ASSERT_GT(out.queue.size(), states);
    EXPECT_EQ(std::get<0>(out.queue.back()), 0);  // idle: resumed, nothing pending
    EXPECT_TRUE(std::get<1>(out.queue.back()).empty());
}

TEST_F(Faults, StopAllMotionWithTheStubHandlerIsOkAndCountsMotionHandlersStillRunning) {
    auto m = send("Mobility", "simpleMove", MOVE);  // beside the queue
    out.until(m, "EXECUTING");
    auto s = send("Mobility", "stopAllMotion", {}, QueueAction::Bypass, "", "", "Intruder");  // always allowed
    EXPECT_EQ(out.final_(s), (Sent{"COMPLETED", "OK", std::string(NO_STOP_HANDLER) + "; 1 motion handler(s) not stopped yet"}));
    EXPECT_EQ(out.final_(m), (Sent{"COMPLETED", "EXEC_FAILED", DID_NOT_STOP}));
}

TEST_F(Faults, ShutdownAnswersEveryCommandWithinItsBoundWhateverTheHandlersDo) {
    auto a = send("PanCam", "pointCamera", POINT, QueueAction::Append);
    out.until(a, "EXECUTING");
    auto waiting = send("PanCam", "takePicture", picture("left"), QueueAction::Append);
    out.until(waiting, "QUEUED");
    auto down = manager->shut_down(200);
    EXPECT_EQ(down.answered, 2u);
    EXPECT_EQ(down.running, 1u);  // the handler still runs: the bridge ends the process
    EXPECT_EQ(out.final_(a), (Sent{"COMPLETED", "EXEC_FAILED", DID_NOT_STOP}));
    EXPECT_EQ(out.final_(waiting), (Sent{"COMPLETED", "CANCELED", SHUTTING_DOWN}));
    // shut down: nothing more is written, not for a new command nor for the late handler
    const auto before = out.all(a);
    send("Admin", "noOp", {}, QueueAction::Bypass, "after");
    handlers.release = true;
    for (auto end = std::chrono::steady_clock::now() + WAIT;
         manager->handlers_running() > 0 && std::chrono::steady_clock::now() < end;)
        std::this_thread::sleep_for(1ms);
    EXPECT_EQ(manager->handlers_running(), 0u);
    EXPECT_EQ(out.all(a), before);
    EXPECT_TRUE(out.all("after").empty());
}

TEST_F(Faults, InvalidUtf8AndNulFromAHandlerStillGiveAFinalAckAToolDecodes) {
    auto b = send("K10Native", "nativeCommand", native("bad-text"));
    EXPECT_EQ(out.final_(b), (Sent{"COMPLETED", "OK", "ok " + FFFD + FFFD + " end " + FFFD + " nul[" + FFFD + "]"}));
    auto p = send("K10Native", "nativeCommand", native("progress-bad"));
    EXPECT_EQ(out.final_(p), (Sent{"COMPLETED", "OK", "done"}));
    auto seq = out.all(p);
    ASSERT_EQ(seq.size(), 4u);
    EXPECT_EQ(seq[1], (Sent{"EXECUTING", "NOT", "p" + FFFD + "q"}));
    EXPECT_EQ(seq[2], (Sent{"EXECUTING", "NOT", "r" + FFFD + FFFD + "s"}));
}

TEST_F(Faults, AHandlersExceptionIsLoggedOnceWithTheCommand) {
    auto b = send("K10Native", "nativeCommand", native("boom"));
    EXPECT_EQ(out.final_(b), (Sent{"COMPLETED", "EXEC_FAILED", "handler error: std::runtime_error: boom"}));
    ASSERT_TRUE(manager->wait_idle(20));
    auto said = out.logs_naming(b);
    ASSERT_EQ(said.size(), 1u);
    EXPECT_NE(said[0].find("K10Native/nativeCommand"), std::string::npos) << said[0];
    EXPECT_NE(said[0].find("std::runtime_error: boom"), std::string::npos) << said[0];
}

// (the repeat rule itself is the spec cases' (validation.yaml); here: nothing runs again
// under the sanitizers, whoever's cmdSrc the repeat carries with the same hdr.srcName)
TEST_F(Faults, AResentAnsweredCmdIdGetsItsStoredFinalAckAndNothingRuns) {
    auto b = send("K10Native", "nativeCommand", native("bad-text"), QueueAction::Bypass, "r1");
    const Sent first = out.final_(b);
    send("K10Native", "nativeCommand", native("boom"), QueueAction::Bypass, "r1");  // same id, same source
    send("K10Native", "nativeCommand", native("boom"), QueueAction::Bypass, "r1", "", "Other");  // another cmdSrc
    auto seq = out.all("r1");
    ASSERT_EQ(seq.size(), 4u);  // EXECUTING, COMPLETED, then COMPLETED again twice: nothing ran
    EXPECT_EQ(seq[2], first);
    EXPECT_EQ(seq[3], first);
    EXPECT_EQ(out.logs_naming("boom").size(), 0u);
}

// valid_utf8 as Python's bytes.decode("utf-8", errors="replace") (the expected values are
// its output), NUL replaced too.
TEST(OutgoingText, EachMaximalInvalidSubsequenceAndEachNulBecomesOneReplacementCharacter) {
    const std::vector<std::pair<std::string, std::string>> cases{
        {"plain é ☃ 😀", "plain é ☃ 😀"},
        {"ok \xff\xfe end", "ok " + FFFD + FFFD + " end"},
        {"a\xe2\x82" "b", "a" + FFFD + "b"},
        {"\xf0\x9f\x98", FFFD},
        {"\xed\xa0\x80x", FFFD + FFFD + FFFD + "x"},  // a surrogate's bytes
        {"\xc0\xafz", FFFD + FFFD + "z"},  // overlong
        {"\xf4\x90\x80\x80", FFFD + FFFD + FFFD + FFFD},  // past U+10FFFF
        {"\xe0\x80\x80", FFFD + FFFD + FFFD},
        {std::string("a\0b", 3), "a" + FFFD + "b"},
    };
    for (const auto& [in, want] : cases) EXPECT_EQ(valid_utf8(in), want) << visible(in);
    // then cut on a character boundary: 126 bytes and a replacement character do not fit in 127
    std::string long_text(126, 'x');
    long_text += "\xff";
    EXPECT_EQ(outgoing(long_text), std::string(126, 'x'));
    EXPECT_TRUE(printable(outgoing(std::string(300, '\xe9'))));
}

}  // namespace
