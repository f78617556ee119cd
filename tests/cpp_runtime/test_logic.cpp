// The protocol logic without DDS (GoogleTest) where the protocol specification's cases
// (runtime/spec/cases, replayed by test_spec_cases.cpp) cannot state it: the C++ API
// (on_shutdown, is_control, the window's tables, QueueState's completed records), reasons
// JSON cannot carry (NaN, a QueueAction outside the enum), UTF-8 clipping, serials, the
// intake's turns and the pieces. K10's tables (k10_tables.hpp), a collecting outbox,
// handlers the test controls. Conditions, not sleeps, order the steps.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <rapid_runtime/access.hpp>
#include <rapid_runtime/intake.hpp>
#include <rapid_runtime/log.hpp>
#include <rapid_runtime/manager.hpp>
#include <rapid_runtime/serials.hpp>
#include <rapid_runtime/text.hpp>
#include <rapid_runtime/validate.hpp>

#include "k10_tables.hpp"

using namespace rapid_runtime;
using namespace std::chrono_literals;

namespace {

constexpr auto WAIT = 10s;
const std::string OP = "RapidWorkbench";

struct Ack {
    std::string status;  // QUEUED, EXECUTING, REQUEUED, COMPLETED
    std::string completed;  // NOT, OK, BAD_SYNTAX, EXEC_FAILED, CANCELED
    std::string message;
};
using Seq = std::vector<std::pair<std::string, std::string>>;

class TestOutbox : public Outbox {
public:
    void ack(const Cmd& cmd, AckStatus status, Completion completed, const std::string& message) override {
        std::lock_guard<std::mutex> lock(mutex);
        acks[cmd.cmd_id].push_back({std::string(name_of(status)).substr(4),
                                    std::string(name_of(completed)).substr(14), message});
        changed.notify_all();
    }
    void queue_state(int code, const std::vector<Record>& pending, const std::vector<Record>& active,
                     const std::vector<Record>& completed) override {
        std::lock_guard<std::mutex> lock(mutex);
        std::vector<std::string> p, a;
        for (const auto& r : pending) p.push_back(r.cmd->cmd_id);
        for (const auto& r : active) a.push_back(r.cmd->cmd_id);
        queue.push_back({code, p, a});
        last_completed = completed;
    }
    void access_state(const std::string& controller, const std::vector<std::string>& requestors) override {
        std::lock_guard<std::mutex> lock(mutex);
        access.push_back({controller, requestors});
    }
    void retire(const Cmd& cmd) override {
        std::lock_guard<std::mutex> lock(mutex);
        EXPECT_TRUE(!acks[cmd.cmd_id].empty() && acks[cmd.cmd_id].back().status == "COMPLETED") << cmd.cmd_id;
        EXPECT_TRUE(cmd.args.empty());  // the key only
        retired.push_back(cmd.cmd_id);
    }
    void log(const std::string& text) override {
        std::lock_guard<std::mutex> lock(mutex);
        logs.push_back(text);
    }

    Seq seq(const std::string& id) {
        std::lock_guard<std::mutex> lock(mutex);
        Seq out;
        for (const auto& a : acks[id]) out.emplace_back(a.status, a.completed);
        return out;
    }
    std::vector<Ack> all(const std::string& id) {
        std::lock_guard<std::mutex> lock(mutex);
        return acks[id];
    }
    bool has(const std::string& id, const std::string& status) {
        for (const auto& a : acks[id])
            if (a.status == status) return true;
        return false;
    }
    // The sequence once a COMPLETED came (or WAIT passed).
    Seq final_(const std::string& id) {
        {
            std::unique_lock<std::mutex> lock(mutex);
            changed.wait_for(lock, WAIT, [&] { return has(id, "COMPLETED"); });
        }
        return seq(id);
    }
    void until(const std::string& id, const std::string& status) {
        std::unique_lock<std::mutex> lock(mutex);
        ASSERT_TRUE(changed.wait_for(lock, WAIT, [&] { return has(id, status); })) << id << " never " << status;
    }
    std::string message(const std::string& id, std::size_t i) {
        std::lock_guard<std::mutex> lock(mutex);
        return acks[id].at(i).message;
    }
    std::string last_message(const std::string& id) {
        std::lock_guard<std::mutex> lock(mutex);
        return acks[id].back().message;
    }

    std::mutex mutex;
    std::condition_variable changed;
    std::map<std::string, std::vector<Ack>> acks;
    std::vector<std::tuple<int, std::vector<std::string>, std::vector<std::string>>> queue;
    std::vector<Record> last_completed;
    std::vector<std::pair<std::string, std::vector<std::string>>> access;
    std::vector<std::string> retired;
    std::vector<std::string> logs;
};

// K10's handlers the tests below use.
class Camera : public Handlers {
public:
    Result execute(CommandContext& ctx) override {
        const std::string& c = ctx.command();
        if (c == "takePicture") return Result::ok(ctx.arg<std::string>(0) + " picture");
        if (c == "nativeCommand") {
            if (ctx.arg<std::string>(0) == "cancel-me") throw Cancelled();
            return Result::ok("ran " + ctx.arg<std::string>(0));
        }
        return Handlers::execute(ctx);
    }
};

Cmd make(const std::string& id, const std::string& sub, const std::string& name, std::vector<Value> args = {},
         QueueAction action = QueueAction::Bypass, const std::string& target = "", const std::string& src = OP,
         const std::string& asset = "K10Red") {
    Cmd c;
    c.cmd_id = id;
    c.cmd_src = src;
    c.subsystem = sub;
    c.name = name;
    c.args = std::move(args);
    c.action = action;
    c.target = target;
    c.src_name = "ground";
    c.asset_name = asset;
    return c;
}

// K10's manager with RapidWorkbench in control (as the Python fixture).
class K10 : public ::testing::Test {
protected:
    void SetUp() override {
        manager = std::make_unique<CommandManager>(k10_tables(), camera, out, options());
        auto id = send("AccessControl", "requestControl");
        ASSERT_EQ(out.final_(id), (Seq{{"EXECUTING", "NOT"}, {"COMPLETED", "OK"}}));
    }
    void TearDown() override { manager.reset(); }
    virtual ManagerOptions options() { return {}; }
    std::string send(const std::string& sub, const std::string& name, std::vector<Value> args = {},
                     QueueAction action = QueueAction::Bypass, const std::string& target = "",
                     const std::string& src = OP, std::string id = "") {
        if (id.empty()) id = "c" + std::to_string(++n);
        manager->receive(make(id, sub, name, std::move(args), action, target, src));
        return id;
    }
    std::string bad_syntax(const std::string& sub, const std::string& name, std::vector<Value> args = {},
                           QueueAction action = QueueAction::Bypass, const std::string& target = "") {
        auto id = send(sub, name, std::move(args), action, target);
        EXPECT_EQ(out.final_(id), (Seq{{"COMPLETED", "BAD_SYNTAX"}}));
        return out.message(id, 0);
    }
    TestOutbox out;
    Camera camera;
    std::unique_ptr<CommandManager> manager;
    int n = 0;
};

const Seq BYPASS_OK{{"EXECUTING", "NOT"}, {"COMPLETED", "OK"}};

}  // namespace

// ---- the manager ----------------------------------------------------------------------------------

// (queue.yaml's case has the refusal; a case cannot say that no QueueState is written)
TEST(Logic, AnAssetWithoutAQueuePublishesNoQueueState) {
    Tables t;
    t.name = "Chariot";
    t.subsystems = {{"Admin", "Admin"}};
    t.types = {{"Admin", {{"noOp", {}, false, false, true, ""}}}};
    TestOutbox out;
    Handlers none;
    CommandManager m(t, none, out);
    m.publish_states();
    m.receive(make("q1", "Admin", "noOp", {}, QueueAction::Append, "", OP, "Chariot"));
    EXPECT_EQ(out.final_("q1"), (Seq{{"COMPLETED", "BAD_SYNTAX"}}));
    m.receive(make("q2", "Admin", "noOp", {}, QueueAction::Bypass, "", OP, "Chariot"));
    EXPECT_EQ(out.final_("q2"), BYPASS_OK);
    std::lock_guard<std::mutex> lock(out.mutex);
    EXPECT_TRUE(out.queue.empty());
}

TEST_F(K10, MessagesFit127BytesEvenForLongHostileNames) {
    std::string long_name;
    for (int i = 0; i < 60; ++i) long_name += "\xc3\xa9";  // é
    long_name += "\x1b[31m";
    auto a = send(long_name, long_name);
    EXPECT_EQ(out.final_(a), (Seq{{"COMPLETED", "BAD_SYNTAX"}}));
    auto m = out.message(a, 0);
    EXPECT_LE(m.size(), 127u);
    EXPECT_EQ(m.find('\x1b'), std::string::npos);
    EXPECT_EQ(m, "unknown subsystem '\\xe9\\xe9\\xe9\\xe9\\xe9\\...'");  // 21 escaped characters, as Python cuts
    std::string text;
    for (int i = 0; i < 100; ++i) text += "\xc3\xa9";
    auto e = send("Admin", "echo", {Value(text)});
    out.final_(e);
    EXPECT_LE(out.last_message(e).size(), 127u);
    std::string e64, e63;
    for (int i = 0; i < 64; ++i) e64 += "\xc3\xa9";
    for (int i = 0; i < 63; ++i) e63 += "\xc3\xa9";
    EXPECT_EQ(clip(e64), e63);  // never half a character
}

TEST(Logic, SerialsChangeWithContentOnly) {
    Serials s(1'700'000'000, [] { return std::int64_t{1'700'000'000}; });
    EXPECT_EQ(s.update("t", "a=1"), (std::pair<std::int32_t, bool>{1'700'000'000, true}));
    EXPECT_EQ(s.update("t", "a=1"), (std::pair<std::int32_t, bool>{1'700'000'000, false}));
    auto [serial, changed] = s.update("t", "a=2");
    EXPECT_TRUE(changed);
    EXPECT_GT(serial, 1'700'000'000);
    EXPECT_EQ(s.of("t"), serial);
    EXPECT_EQ(s.of("other"), 1'700'000'000);
}

// ---- reasons the cases' JSON cannot carry (validation.yaml and queue.yaml have the rest) -------

TEST_F(K10, NanIsOutsideEveryRangeAndAnActionOutsideTheEnumIsNamedByNumber) {
    EXPECT_EQ(bad_syntax("PanCam", "pointCamera", {Value(0.0f), Value(std::nanf(""))}),
              "argument 2 (tilt): nan not in [-1.4, 1.4]");
    EXPECT_EQ(bad_syntax("Admin", "noOp", {}, static_cast<QueueAction>(9)), "unknown queue action 9");
}

// (validation.yaml's builtins case has the rest: a handler's own Cancelled is no behaviour of its)
TEST_F(K10, AHandlerThrowingCancelledIsCanceled) {
    auto cancel = send("K10Native", "nativeCommand", {Value(std::string("cancel-me"))});
    EXPECT_EQ(out.final_(cancel), (Seq{{"EXECUTING", "NOT"}, {"COMPLETED", "CANCELED"}}));
}

TEST(Logic, ShutdownCallsBackAfterItsCompletedAck) {
    TestOutbox out;
    Camera camera;
    std::atomic<bool> down{false};
    ManagerOptions o;
    o.on_shutdown = [&] { down = true; };
    CommandManager m(k10_tables(), camera, out, o);
    m.receive(make("r", "AccessControl", "requestControl"));
    m.receive(make("s", "Admin", "shutdown"));
    EXPECT_EQ(out.final_("s"), BYPASS_OK);
    EXPECT_EQ(out.last_message("s"), "shutting down");
    for (int i = 0; i < 500 && !down; ++i) std::this_thread::sleep_for(10ms);
    EXPECT_TRUE(down);
}

TEST_F(K10, QueueStateRecordsCompletedCommands) {
    auto a = send("PanCam", "takePicture", {Value(std::string("left")), Value(0.0f)}, QueueAction::Append);
    out.final_(a);
    ASSERT_TRUE(manager->wait_idle(10));
    std::lock_guard<std::mutex> lock(out.mutex);
    ASSERT_FALSE(out.last_completed.empty());
    EXPECT_EQ(out.last_completed.back().cmd->cmd_id, a);
    EXPECT_EQ(out.last_completed.back().status, RecordStatus::Succeeded);
    EXPECT_EQ(out.last_completed.back().result, RecordResult::Succeeded);
}

// ---- the command window --------------------------------------------------------------------------

class Window : public K10 {
protected:
    ManagerOptions options() override {
        ManagerOptions o;
        o.window = window;
        return o;
    }
    std::size_t window = 5;
};

TEST(Logic, DefaultWindowIsAFewThousandCommands) {
    EXPECT_EQ(COMMAND_WINDOW, 4096u);
    EXPECT_EQ(QUEUE_LIMIT, 1024u);
    EXPECT_EQ(BYPASS_LIMIT, 64u);
}

// (window.yaml has the retirements and repeats; the manager's own tables stay bounded)
TEST_F(Window, TablesStayWithinTheWindow) {
    auto w = [](int i) { return "w" + std::to_string(i); };
    for (int i = 0; i < 40; ++i) {
        send("Admin", "noOp", {}, QueueAction::Bypass, "", OP, w(i));
        EXPECT_LE(manager->remembered(), 5u);
        EXPECT_LE(manager->acks_kept().size(), 5u);
    }
    for (int i = 0; i < 40; ++i) EXPECT_EQ(out.seq(w(i)), BYPASS_OK);
    EXPECT_EQ(manager->acks_kept(), (std::vector<std::string>{"w35", "w36", "w37", "w38", "w39"}));
}

// ---- test_intake.py ---------------------------------------------------------------------------

namespace {

// A manager stand-in that records what the intake hands it, blocking until released.
class Recorder : public CommandSink {
public:
    void receive(const Cmd& cmd) override { got_one("run", cmd.cmd_id); }
    void refuse(const Cmd& cmd, const std::string&) override { got_one("busy", cmd.cmd_id); }
    bool is_control(const Cmd& cmd) const override {
        return cmd.subsystem == "AccessControl" || cmd.name == "stopAllMotion" || cmd.name == "cancelAll";
    }
    std::vector<std::pair<std::string, std::string>> wait_for(std::size_t n) {
        std::unique_lock<std::mutex> lock(mutex);
        EXPECT_TRUE(done.wait_for(lock, WAIT, [&] { return got.size() >= n; }));
        return got;
    }
    void open() {
        std::lock_guard<std::mutex> lock(mutex);
        gate = true;
        done.notify_all();
    }

private:
    void got_one(const char* kind, const std::string& id) {
        std::unique_lock<std::mutex> lock(mutex);
        done.wait(lock, [&] { return gate; });
        got.emplace_back(kind, id);
        done.notify_all();
    }
    std::mutex mutex;
    std::condition_variable done;
    bool gate = false;
    std::vector<std::pair<std::string, std::string>> got;
};

Cmd noop(const std::string& id, const std::string& sub = "Admin", const std::string& name = "noOp") {
    return make(id, sub, name);
}

std::vector<std::string> ids(const std::vector<std::pair<std::string, std::string>>& got) {
    std::vector<std::string> out;
    for (const auto& g : got) out.push_back(g.second);
    return out;
}

std::size_t index_of(const std::vector<std::string>& v, const std::string& x) {
    return static_cast<std::size_t>(std::find(v.begin(), v.end(), x) - v.begin());
}

}  // namespace

TEST(Intake, WritersTakeTurnsAndControlGoesFirst) {
    Recorder rec;
    std::vector<std::string> logs;
    Intake intake(rec, [&](const std::string& t) { logs.push_back(t); }, 100);
    for (int i = 0; i < 5; ++i) intake.offer(noop("flood-" + std::to_string(i)), "w1");
    intake.offer(noop("op-1"), "w2");
    intake.offer(noop("op-stop", "Mobility", "stopAllMotion"), "w3");
    intake.offer(noop("op-2"), "w2");
    intake.start();
    rec.open();
    auto got = ids(rec.wait_for(8));
    intake.stop();
    EXPECT_EQ(got[0], "op-stop");  // the control command first, whoever was there before
    EXPECT_LE(index_of(got, "op-1"), 2u);  // one flood command between operator turns
    EXPECT_LE(index_of(got, "op-2"), 4u);
    std::vector<std::string> flood;
    for (const auto& g : got)
        if (g.rfind("flood", 0) == 0) flood.push_back(g);
    EXPECT_EQ(flood, (std::vector<std::string>{"flood-0", "flood-1", "flood-2", "flood-3", "flood-4"}));
}

TEST(Intake, AWriterKeepsItsOwnOrderEvenAroundControl) {
    Recorder rec;
    Intake intake(rec, [](const std::string&) {});
    intake.offer(noop("a-1"), "w7");
    intake.offer(noop("a-release", "AccessControl", "releaseControl"), "w7");
    intake.start();
    rec.open();
    EXPECT_EQ(ids(rec.wait_for(2)), (std::vector<std::string>{"a-1", "a-release"}));
}

TEST(Intake, AFloodIsAnsweredBusyThenDroppedAndCounted) {
    Recorder rec;
    std::vector<std::string> logs;
    Intake intake(rec, [&](const std::string& t) { logs.push_back(t); }, 4, 3);
    for (int i = 0; i < 10; ++i) intake.offer(noop("f" + std::to_string(i)), "w9");
    intake.offer(noop("op"), "w2");
    EXPECT_EQ(intake.waiting(), 4u + 1u + 3u);  // 4 + the operator's in FIFOs, 3 busy answers
    EXPECT_EQ(intake.unanswered("w9"), 3u);
    EXPECT_EQ(intake.shed("w9"), 3u);
    ASSERT_EQ(logs.size(), 2u);  // once each, not per command
    EXPECT_NE(logs[0].find("floods"), std::string::npos);
    EXPECT_NE(logs[1].find("unanswered"), std::string::npos);
    intake.start();
    rec.open();
    auto got = rec.wait_for(8);
    intake.stop();
    auto all = ids(got);
    EXPECT_LE(index_of(all, "op"), 2u);
    std::vector<std::string> busy, run;
    for (const auto& [kind, id] : got) (kind == "busy" ? busy : id == "op" ? busy : run).push_back(id);
    busy.erase(std::remove(busy.begin(), busy.end(), "op"), busy.end());
    EXPECT_EQ(busy, (std::vector<std::string>{"f4", "f5", "f6"}));
    EXPECT_EQ(run, (std::vector<std::string>{"f0", "f1", "f2", "f3"}));
}

// (validation.yaml's door case has the rest)
TEST(Intake, ARefusedEmptyCmdIdIsNotAnswered) {
    TestOutbox out;
    Handlers none;
    CommandManager m(k10_tables(), none, out);
    m.refuse(noop(""), "bridge busy");
    m.refuse(noop("x1"), "bridge busy");
    EXPECT_EQ(out.seq("x1"), (Seq{{"COMPLETED", "EXEC_FAILED"}}));  // (the door does answer)
    EXPECT_TRUE(out.seq("").empty());
}

TEST(Intake, TheManagerNamesControlCommands) {
    TestOutbox out;
    Handlers none;
    CommandManager m(k10_tables(), none, out);
    EXPECT_TRUE(m.is_control(noop("a", "Mobility", "stopAllMotion")));
    EXPECT_TRUE(m.is_control(noop("b", "Queue", "cancelAll")));
    EXPECT_TRUE(m.is_control(noop("c", "AccessControl", "grabControl")));
    EXPECT_FALSE(m.is_control(noop("d", "Admin", "noOp")));
    EXPECT_FALSE(m.is_control(noop("e", "Nowhere", "stopAllMotion")));
    EXPECT_EQ(busy_message(256), "bridge busy: 256 commands from this writer already waiting; retry later");
}

// ---- pieces ---------------------------------------------------------------------------------

TEST(Pieces, AllowListPatterns) {
    const auto& spec = k10_tables().access;
    EXPECT_TRUE(allowed(spec, "RapidWorkbench", "K10Native", "nativeCommand"));
    EXPECT_TRUE(allowed(spec, "MultiCenterCockpit", "Mobility", "move"));
    EXPECT_TRUE(allowed(spec, "MultiCenterCockpit", "Admin", "echo"));
    EXPECT_FALSE(allowed(spec, "MultiCenterCockpit", "Admin", "shutdown"));
    EXPECT_FALSE(allowed(spec, "Stranger", "Admin", "echo"));  // default deny
    EXPECT_TRUE(allowed(std::nullopt, "Stranger", "Admin", "echo"));
    EXPECT_TRUE(always_allowed("Mobility", "stopAllMotion"));
}

TEST(Pieces, ControlQueuesAtMost16Requestors) {
    Control c;
    EXPECT_EQ(c.request("a").text, "control granted to a");
    for (int i = 0; i < 16; ++i) EXPECT_TRUE(c.request("r" + std::to_string(i)).ok);
    auto full = c.request("late");
    EXPECT_FALSE(full.ok);
    EXPECT_EQ(full.text, "16 requests already queued");
    EXPECT_EQ(c.request("r3").text, "request already queued; a has control");
    EXPECT_EQ(c.transfer("a", "  ").text, "newController is empty");
    EXPECT_EQ(c.transfer("a", std::string(32, 'n')).text, "newController longer than 31 bytes");
    EXPECT_EQ(c.grab("b").text, "control taken from a");
    EXPECT_EQ(c.release("b").text, "control released to r0");
}

TEST(Pieces, TextIsShortenedEscapedAndClipped) {
    EXPECT_EQ(shorten("short"), "short");
    EXPECT_EQ(shorten(std::string(30, 'a')), std::string(21, 'a') + "...");
    EXPECT_EQ(shorten("a\nb"), "a\\nb");
    EXPECT_EQ(shorten("\xc3\xa9t\xc3\xa9"), "\xc3\xa9t\xc3\xa9");  // printable non-ASCII stays
    EXPECT_EQ(shorten("\xc3\xa9\x01"), "\\xe9\\x01");  // any control: all escaped, as unicode_escape
    EXPECT_EQ(shorten("\xe2\x82\xac\x7f"), "\\u20ac\\x7f");
    EXPECT_EQ(shorten("\xff"), "\\xff");  // not UTF-8
    EXPECT_EQ(clip(std::string(200, 'x')).size(), 127u);
    EXPECT_EQ(visible("a\x1b[0m"), "a\\x1b[0m");
}

TEST(Pieces, ValuesPrintAsPythonDoes) {
    EXPECT_EQ(repr(Value(0.5)), "0.5");
    EXPECT_EQ(repr(Value(2.0)), "2.0");
    EXPECT_EQ(repr(Value(1e20)), "1e+20");
    EXPECT_EQ(repr(Value(0.3f)), "0.30000001192092896");
    EXPECT_EQ(repr(Value(0.0001)), "0.0001");
    EXPECT_EQ(repr(Value(0.00001)), "1e-05");
    EXPECT_EQ(repr(Value(std::string("it's"))), "\"it's\"");
    EXPECT_EQ(repr(Value(true)), "True");
    EXPECT_EQ(repr(Value(Vec3d{1, 2.5, -3})), "[1.0, 2.5, -3.0]");
    EXPECT_TRUE(same_value(Value(0.0f), Value(std::int32_t{0})));
    EXPECT_FALSE(same_value(Value(std::string("0")), Value(std::int32_t{0})));
    Param p;
    p.type = DataType::Vec3d;
    p.min = -1;
    p.max = 1;
    EXPECT_EQ(limit_error(p, Value(Vec3d{0, 2, 0})).value_or(""), "2 not in [-1, 1]");  // element-wise
    EXPECT_FALSE(limit_error(p, Value(Vec3d{0, 1, -1})));
}

TEST(Pieces, TheLogKeepsToItsRate) {
    double now = 0;
    std::vector<std::string> lines;
    Log log([&](const std::string& t) { lines.push_back(t); }, 3, [&] { return now; });
    for (int i = 0; i < 10; ++i) log("line\x1b" + std::to_string(i));
    EXPECT_EQ(lines.size(), 3u);
    EXPECT_EQ(lines[0], "line\\x1b0");
    now = 1.5;
    log("next");
    ASSERT_EQ(lines.size(), 5u);
    EXPECT_EQ(lines[3], "(7 log lines left out in the last second)");
}
