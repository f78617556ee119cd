// The protocol logic without DDS (GoogleTest): K10's tables (k10_tables.cpp), a collecting
// outbox, handlers the test controls. Mirrors tests/runtime/test_logic.py,
// test_intake.py, test_command_window.py and test_flood_limits.py (their tables-only
// parts) and adds the validation messages. Conditions, not sleeps, order the steps.
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

// K10's PanCam handlers: pointCamera blocks until released (or canceled).
class Camera : public Handlers {
public:
    Result execute(CommandContext& ctx) override {
        const std::string& c = ctx.command();
        if (c == "pointCamera") {
            {
                std::lock_guard<std::mutex> lock(mutex);
                calls.emplace_back(ctx.arg<float>(0), ctx.arg<float>(1));
            }
            while (!release.load())
                if (!ctx.sleep(0.01)) return Result::ok();  // canceled
            return Result::ok("pointed");
        }
        if (c == "takePicture") {
            if (ctx.arg<std::string>(0) == "right") throw CommandFailed("right camera offline");
            return Result::ok(ctx.arg<std::string>(0) + " picture");
        }
        if (c == "simpleMove") {
            while (!ctx.cancelled()) ctx.sleep(0.01);
            return Result::ok();
        }
        if (c == "nativeCommand") {
            const auto& text = ctx.arg<std::string>(0);
            if (text == "boom") throw std::runtime_error("boom");
            if (text == "cancel-me") throw Cancelled();
            ctx.progress("step 1");
            ctx.progress("step 2");
            return Result::ok("ran " + text);
        }
        return Handlers::execute(ctx);
    }
    std::vector<std::pair<float, float>> points() {
        std::lock_guard<std::mutex> lock(mutex);
        return calls;
    }
    std::atomic<bool> release{false};
    std::mutex mutex;
    std::vector<std::pair<float, float>> calls;
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

std::vector<Value> point(float pan = 0.1f) { return {Value(pan), Value(0.0f)}; }

// K10's manager with RapidWorkbench in control (as the Python fixture).
class K10 : public ::testing::Test {
protected:
    void SetUp() override {
        manager = std::make_unique<CommandManager>(k10_tables(), camera, out, options());
        auto id = send("AccessControl", "requestControl");
        ASSERT_EQ(out.final_(id), (Seq{{"EXECUTING", "NOT"}, {"COMPLETED", "OK"}}));
    }
    void TearDown() override {
        camera.release = true;
        manager.reset();
    }
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

const Seq QUEUED_OK{{"QUEUED", "NOT"}, {"EXECUTING", "NOT"}, {"COMPLETED", "OK"}};
const Seq BYPASS_OK{{"EXECUTING", "NOT"}, {"COMPLETED", "OK"}};

}  // namespace

// ---- test_logic.py ------------------------------------------------------------------------------

TEST_F(K10, QueueOrderInsertReplaceDelete) {
    auto a = send("PanCam", "pointCamera", point(), QueueAction::Append);
    out.until(a, "EXECUTING");
    auto b = send("PanCam", "pointCamera", point(0.2f), QueueAction::Append);
    auto c = send("PanCam", "pointCamera", point(0.3f), QueueAction::Insert, "head");  // before b
    auto d = send("PanCam", "pointCamera", point(0.4f), QueueAction::Replace, b);  // b canceled, d in its place
    auto e = send("Admin", "noOp", {}, QueueAction::Delete, c);  // c canceled before it ran
    EXPECT_EQ(out.seq(b), (Seq{{"QUEUED", "NOT"}, {"COMPLETED", "CANCELED"}}));
    EXPECT_EQ(out.seq(c), (Seq{{"QUEUED", "NOT"}, {"COMPLETED", "CANCELED"}}));
    EXPECT_EQ(out.final_(e), BYPASS_OK);
    EXPECT_EQ(manager->pending_ids(), std::vector<std::string>{d});
    camera.release = true;
    EXPECT_EQ(out.final_(a), QUEUED_OK);
    EXPECT_EQ(out.final_(d), QUEUED_OK);
    EXPECT_EQ(camera.points(), (std::vector<std::pair<float, float>>{{0.1f, 0.0f}, {0.4f, 0.0f}}));
    ASSERT_TRUE(manager->wait_idle(10));
    std::lock_guard<std::mutex> lock(out.mutex);
    EXPECT_EQ(std::get<0>(out.queue.back()), 0);  // idle
}

TEST_F(K10, DeleteAbortsARunningAbortableCommand) {
    auto a = send("PanCam", "pointCamera", point(), QueueAction::Append);
    out.until(a, "EXECUTING");
    auto d = send("Admin", "noOp", {}, QueueAction::Delete, a);
    EXPECT_EQ(out.final_(a).back(), (std::pair<std::string, std::string>{"COMPLETED", "CANCELED"}));
    EXPECT_EQ(out.final_(d).back(), (std::pair<std::string, std::string>{"COMPLETED", "OK"}));
    // (issue 42) the handler was asked; its own final ack says it stopped
    EXPECT_EQ(out.last_message(d), a + " cancel requested; handler has not stopped yet");
}

TEST_F(K10, DeleteOfARunningCommandThatIsNotAbortableFails) {
    auto a = send("K10Native", "nativeCommand", {Value(std::string("x"))}, QueueAction::Append);
    out.final_(a);
    auto p = send("PanCam", "takePicture", {Value(std::string("left")), Value(0.0f)}, QueueAction::Append);
    out.final_(p);
    auto unknown = send("Admin", "noOp", {}, QueueAction::Delete, p);  // finished: no longer a target
    EXPECT_EQ(out.final_(unknown), (Seq{{"COMPLETED", "BAD_SYNTAX"}}));
    EXPECT_EQ(out.message(unknown, 0), "unknown targetCmdId '" + p + "' (not pending or running)");
}

TEST_F(K10, BypassPreemptsASuspendableQueuedCommandWhichIsRequeued) {
    std::vector<Value> move{Value(std::string("site")), Value(Vec3d{1.0, 0.0, 0.0})};
    auto a = send("Mobility", "simpleMove", move, QueueAction::Append);
    out.until(a, "EXECUTING");
    auto b = send("Mobility", "simpleMove", move);  // BYPASS on the same subsystem
    out.until(a, "REQUEUED");
    out.until(b, "EXECUTING");
    auto stop = send("Mobility", "stopAllMotion", {}, QueueAction::Bypass, "", "Intruder");  // always allowed
    EXPECT_EQ(out.final_(b).back(), (std::pair<std::string, std::string>{"COMPLETED", "CANCELED"}));
    // no handler (the stub): the runtime's cancel is the answer (ACC-06), OK; b may not have
    // returned yet when it completes (its answer then says so)
    EXPECT_EQ(out.final_(stop), (Seq{{"EXECUTING", "NOT"}, {"COMPLETED", "OK"}}));
    const std::string said = out.last_message(stop);
    EXPECT_TRUE(said == NO_STOP_HANDLER || said == std::string(NO_STOP_HANDLER) + "; 1 motion handler(s) not stopped yet")
        << said;
    auto seq = out.final_(a);
    ASSERT_GE(seq.size(), 4u);
    EXPECT_EQ(Seq(seq.begin(), seq.begin() + 3), (Seq{{"QUEUED", "NOT"}, {"EXECUTING", "NOT"}, {"REQUEUED", "NOT"}}));
    EXPECT_EQ(seq.back(), (std::pair<std::string, std::string>{"COMPLETED", "CANCELED"}));  // then stopAllMotion
}

TEST_F(K10, AFailureSuspendsTheQueueUntilCancelAll) {
    auto a = send("PanCam", "takePicture", {Value(std::string("right")), Value(0.0f)}, QueueAction::Append);
    EXPECT_EQ(out.final_(a).back(), (std::pair<std::string, std::string>{"COMPLETED", "EXEC_FAILED"}));
    EXPECT_EQ(out.last_message(a), "right camera offline");
    auto b = send("PanCam", "takePicture", {Value(std::string("left")), Value(0.0f)}, QueueAction::Append);
    EXPECT_EQ(out.seq(b), (Seq{{"QUEUED", "NOT"}}));
    {
        std::lock_guard<std::mutex> lock(out.mutex);
        EXPECT_EQ(std::get<0>(out.queue.back()), -1);  // suspended
    }
    EXPECT_TRUE(manager->suspended());
    auto c = send("Queue", "cancelAll");
    EXPECT_EQ(out.final_(c).back(), (std::pair<std::string, std::string>{"COMPLETED", "OK"}));
    EXPECT_EQ(out.final_(b).back(), (std::pair<std::string, std::string>{"COMPLETED", "CANCELED"}));
    auto d = send("PanCam", "takePicture", {Value(std::string("left")), Value(0.0f)}, QueueAction::Append);
    EXPECT_EQ(out.final_(d).back(), (std::pair<std::string, std::string>{"COMPLETED", "OK"}));
    EXPECT_EQ(out.last_message(d), "left picture");
}

TEST_F(K10, AccessControlRequestQueueReleaseTransfer) {
    const std::string other = "MultiCenterCockpit";
    auto r = send("AccessControl", "requestControl", {}, QueueAction::Bypass, "", other);
    EXPECT_EQ(out.final_(r).back().second, "OK");
    EXPECT_EQ(manager->requestors(), std::vector<std::string>{other});
    EXPECT_EQ(out.final_(send("AccessControl", "releaseControl", {}, QueueAction::Bypass, "", other)).back().second,
              "EXEC_FAILED");
    EXPECT_EQ(out.final_(send("AccessControl", "releaseControl")).back().second, "OK");
    EXPECT_EQ(manager->controller(), other);
    {
        std::lock_guard<std::mutex> lock(out.mutex);
        EXPECT_EQ(out.access.back(), (std::pair<std::string, std::vector<std::string>>{other, {}}));
    }
    EXPECT_EQ(out.final_(send("AccessControl", "grabControl")).back().second, "OK");
    EXPECT_EQ(manager->controller(), OP);
    EXPECT_EQ(out.final_(send("AccessControl", "transferControl", {Value(other)})).back().second, "OK");
    EXPECT_EQ(manager->controller(), other);
    auto denied = send("Admin", "echo", {Value(std::string("x"))});
    EXPECT_EQ(out.final_(denied), (Seq{{"COMPLETED", "BAD_SYNTAX"}}));
    EXPECT_EQ(out.message(denied, 0), "RAPID access violation: RapidWorkbench does not have control (send requestControl)");
}

TEST_F(K10, TheAllowListComesBeforeControl) {
    auto id = send("K10Native", "nativeCommand", {Value(std::string("x"))}, QueueAction::Bypass, "", "ScienceBackroom");
    EXPECT_EQ(out.final_(id), (Seq{{"COMPLETED", "BAD_SYNTAX"}}));
    EXPECT_EQ(out.message(id, 0), "RAPID access violation: ScienceBackroom may not send K10Native/nativeCommand");
    auto self = send("Admin", "noOp", {}, QueueAction::Bypass, "", "K10Red");  // the asset itself: no control needed
    EXPECT_EQ(out.final_(self).back().second, "BAD_SYNTAX");  // but K10's allow-list names no "K10Red": denied
}

TEST(Logic, AnAssetWithoutAQueueTakesBypassOnly) {
    Tables t;
    t.name = "Chariot";
    t.subsystems = {{"Admin", "Admin"}};
    t.types = {{"Admin", {{"noOp", {}, false, false, true, ""}}}};
    TestOutbox out;
    Handlers none;
    CommandManager m(t, none, out);
    m.receive(make("q1", "Admin", "noOp", {}, QueueAction::Append, "", OP, "Chariot"));
    EXPECT_EQ(out.final_("q1"), (Seq{{"COMPLETED", "BAD_SYNTAX"}}));
    EXPECT_EQ(out.message("q1", 0), "QUEUE_APPEND refused: this asset has no command queue (send QUEUE_BYPASS)");
    m.receive(make("q2", "Admin", "noOp", {}, QueueAction::Bypass, "", OP, "Chariot"));
    EXPECT_EQ(out.final_("q2"), BYPASS_OK);
    EXPECT_TRUE(out.queue.empty());  // no QueueState without a Queue subsystem
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

// ---- validation, in soraCore's order, with the Python runtime's reasons ----------------------

TEST_F(K10, ChecksInOrderWithTheirReasons) {
    EXPECT_EQ(bad_syntax("Arm", "x"), "unknown subsystem 'Arm'");
    EXPECT_EQ(bad_syntax("PanCam", "zoom"), "unknown command 'zoom' for subsystem 'PanCam'");
    EXPECT_EQ(bad_syntax("PanCam", "pointCamera", {Value(0.1f)}), "pointCamera takes 2 arguments, got 1");
    EXPECT_EQ(bad_syntax("Admin", "echo", {}), "echo takes 1 argument, got 0");
    EXPECT_EQ(bad_syntax("PanCam", "pointCamera", {Value(0.1), Value(0.0f)}),
              "argument 1 (pan) must be RAPID_FLOAT, got RAPID_DOUBLE");
    EXPECT_EQ(bad_syntax("PanCam", "pointCamera", {Value(5.0f), Value(0.0f)}), "argument 1 (pan): 5 not in [-3.05, 3.05]");
    EXPECT_EQ(bad_syntax("PanCam", "pointCamera", {Value(0.0f), Value(std::nanf(""))}),
              "argument 2 (tilt): nan not in [-1.4, 1.4]");
    EXPECT_EQ(bad_syntax("PanCam", "takePicture", {Value(std::string("up")), Value(0.0f)}),
              "argument 1 (mode): 'up' not one of left|right|stereo");
    EXPECT_EQ(bad_syntax("PanCam", "takePanorama", {Value(0.0f), Value(1.0f), Value(0.0f), Value(std::int32_t{65})}),
              "argument 4 (tiles): 65 not in [1, 64]");
    EXPECT_EQ(bad_syntax("Admin", "echo", {Value(std::string(128, 'x'))}), "argument 1 (text): 128 bytes (max 127)");
    // the queue's own rules come first
    EXPECT_EQ(bad_syntax("Admin", "noOp", {}, QueueAction::Append, "x"), "QUEUE_APPEND takes no targetCmdId (got 'x')");
    EXPECT_EQ(bad_syntax("Admin", "noOp", {}, QueueAction::Insert), "QUEUE_INSERT needs a targetCmdId");
    EXPECT_EQ(bad_syntax("Admin", "noOp", {}, QueueAction::Insert, "nope"),
              "unknown targetCmdId 'nope' (pending ids, the running one or 'head')");
    EXPECT_EQ(bad_syntax("Admin", "noOp", {}, QueueAction::Replace, "nope"),
              "unknown targetCmdId 'nope' (not pending or running)");
    EXPECT_EQ(bad_syntax("Admin", "noOp", {}, static_cast<QueueAction>(9)), "unknown queue action 9");
    EXPECT_EQ(bad_syntax("Admin", "noOp", {}, QueueAction::Delete, "nope"),
              "unknown targetCmdId 'nope' (not pending or running)");
    manager->receive(make("", "Admin", "noOp"));
    EXPECT_EQ(out.final_(""), (Seq{{"COMPLETED", "BAD_SYNTAX"}}));
    EXPECT_EQ(out.message("", 0), "empty cmdId");
}

TEST_F(K10, AnotherAssetsCommandsAreDroppedAndARepeatedIdGetsItsFinalAckAgain) {
    manager->receive(make("x1", "Admin", "noOp", {}, QueueAction::Bypass, "", OP, "K10Blue"));
    auto id = send("Admin", "echo", {Value(std::string("first"))});
    out.final_(id);
    send("Admin", "echo", {Value(std::string("again"))}, QueueAction::Bypass, "", OP, id);
    EXPECT_TRUE(out.seq("x1").empty());
    // nothing ran again: the stored final ack, written once more (issue 42)
    EXPECT_EQ(out.seq(id), (Seq{{"EXECUTING", "NOT"}, {"COMPLETED", "OK"}, {"COMPLETED", "OK"}}));
    EXPECT_EQ(out.last_message(id), "first");
    std::lock_guard<std::mutex> lock(out.mutex);
    EXPECT_EQ(out.logs.size(), 2u);
}

TEST_F(K10, BuiltinsAnswerAtOnceAndHandlersReportProgressAndFailures) {
    auto echo = send("Admin", "echo", {Value(std::string("hello"))});
    EXPECT_EQ(out.final_(echo), BYPASS_OK);
    EXPECT_EQ(out.last_message(echo), "hello");
    auto native = send("K10Native", "nativeCommand", {Value(std::string("go"))});
    EXPECT_EQ(out.final_(native),
              (Seq{{"EXECUTING", "NOT"}, {"EXECUTING", "NOT"}, {"EXECUTING", "NOT"}, {"COMPLETED", "OK"}}));
    EXPECT_EQ(out.message(native, 1), "step 1");
    EXPECT_EQ(out.last_message(native), "ran go");
    auto boom = send("K10Native", "nativeCommand", {Value(std::string("boom"))});
    EXPECT_EQ(out.final_(boom).back().second, "EXEC_FAILED");
    EXPECT_EQ(out.last_message(boom), "handler error: std::runtime_error: boom");
    auto cancel = send("K10Native", "nativeCommand", {Value(std::string("cancel-me"))});
    EXPECT_EQ(out.final_(cancel).back().second, "CANCELED");
    auto macro = send("Queue", "loadMacro", {Value(std::string("m"))});  // standard, but the handler's
    EXPECT_EQ(out.final_(macro).back().second, "EXEC_FAILED");
    EXPECT_EQ(out.last_message(macro), "not implemented");
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

TEST_F(K10, StopAllMotionCancelsPendingAndRunningMobilityCommands) {
    std::vector<Value> move{Value(std::string("site")), Value(Vec3d{1.0, 0.0, 0.0})};
    auto a = send("Mobility", "simpleMove", move, QueueAction::Append);
    out.until(a, "EXECUTING");
    auto b = send("Mobility", "simpleMove", move, QueueAction::Append);
    auto p = send("PanCam", "takePicture", {Value(std::string("left")), Value(0.0f)}, QueueAction::Append);
    send("Mobility", "stopAllMotion");
    EXPECT_EQ(out.final_(a).back().second, "CANCELED");
    EXPECT_EQ(out.final_(b), (Seq{{"QUEUED", "NOT"}, {"COMPLETED", "CANCELED"}}));
    EXPECT_EQ(out.last_message(b), "stopAllMotion");
    EXPECT_EQ(out.final_(p), QUEUED_OK);  // not motion: runs on
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

// ---- test_command_window.py (tables only) ---------------------------------------------------------

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

TEST_F(Window, TablesStayWithinTheWindowAndTheOldestAcksAreRetired) {
    auto w = [](int i) { return "w" + std::to_string(i); };
    for (int i = 0; i < 40; ++i) {
        send("Admin", "noOp", {}, QueueAction::Bypass, "", OP, w(i));
        EXPECT_LE(manager->remembered(), 5u);
        EXPECT_LE(manager->acks_kept().size(), 5u);
    }
    for (int i = 0; i < 40; ++i) EXPECT_EQ(out.seq(w(i)), BYPASS_OK);
    std::vector<std::string> retired{"c1"};  // the fixture's requestControl, then completion order
    for (int i = 0; i < 35; ++i) retired.push_back(w(i));
    {
        std::lock_guard<std::mutex> lock(out.mutex);
        EXPECT_EQ(out.retired, retired);
    }
    EXPECT_EQ(manager->acks_kept(), (std::vector<std::string>{"w35", "w36", "w37", "w38", "w39"}));
    send("Admin", "noOp", {}, QueueAction::Bypass, "", OP, "w39");  // within the window: its final ack again
    EXPECT_EQ(out.seq("w39"), (Seq{{"EXECUTING", "NOT"}, {"COMPLETED", "OK"}, {"COMPLETED", "OK"}}));
    send("Admin", "noOp", {}, QueueAction::Bypass, "", OP, "w30");  // 9 newer since: a new command
    EXPECT_EQ(out.seq("w30"), (Seq{{"EXECUTING", "NOT"}, {"COMPLETED", "OK"}, {"EXECUTING", "NOT"}, {"COMPLETED", "OK"}}));
    EXPECT_EQ(manager->acks_kept().size(), 5u);  // (the manager's lock, then the outbox's: never both)
    std::lock_guard<std::mutex> lock(out.mutex);
    EXPECT_EQ(out.retired.back(), "w35");
}

TEST_F(Window, ARunningCommandIsNeverTakenForNewNorRetired) {
    window = 3;
    manager = std::make_unique<CommandManager>(k10_tables(), camera, out, options());
    send("AccessControl", "requestControl", {}, QueueAction::Bypass, "", OP, "control");
    send("PanCam", "pointCamera", point(), QueueAction::Bypass, "", OP, "long");
    for (int i = 0; i < 10; ++i) send("Admin", "noOp", {}, QueueAction::Bypass, "", OP, "w" + std::to_string(i));
    send("PanCam", "pointCamera", point(), QueueAction::Bypass, "", OP, "long");  // out of the window but running
    EXPECT_EQ(out.seq("long"), (Seq{{"EXECUTING", "NOT"}}));
    camera.release = true;
    ASSERT_TRUE(manager->wait_idle(10));
    EXPECT_EQ(out.seq("long"), BYPASS_OK);
    auto kept = manager->acks_kept();
    EXPECT_EQ(kept.size(), 3u);
    EXPECT_EQ(kept.back(), "long");
    std::lock_guard<std::mutex> lock(out.mutex);
    EXPECT_EQ(std::count(out.retired.begin(), out.retired.end(), "long"), 0);
}

// ---- test_flood_limits.py -----------------------------------------------------------------------

class Limits : public K10 {
protected:
    ManagerOptions options() override {
        ManagerOptions o;
        o.queue_limit = 3;
        o.bypass_limit = 2;
        return o;
    }
};

TEST_F(Limits, AFullQueueRefusesNewCommandsAndKeepsTheQueuedOnes) {
    auto hold = send("PanCam", "pointCamera", point(), QueueAction::Append);  // runs, holding the queue
    out.until(hold, "EXECUTING");
    for (int i = 0; i < 3; ++i) send("Admin", "noOp", {}, QueueAction::Append, "", OP, "q" + std::to_string(i));
    EXPECT_EQ(manager->pending_count(), 3u);
    send("Admin", "noOp", {}, QueueAction::Append, "", OP, "over");
    EXPECT_EQ(out.seq("over"), (Seq{{"COMPLETED", "EXEC_FAILED"}}));
    EXPECT_EQ(out.message("over", 0), "queue full (3 pending); retry later");
    EXPECT_EQ(manager->pending_count(), 3u);
    camera.release = true;
    ASSERT_TRUE(manager->wait_idle(10));
    EXPECT_FALSE(manager->suspended());
    for (int i = 0; i < 3; ++i) EXPECT_EQ(out.seq("q" + std::to_string(i)), QUEUED_OK);
    send("Admin", "noOp", {}, QueueAction::Append, "", OP, "after");  // room again
    ASSERT_TRUE(manager->wait_idle(10));
    EXPECT_EQ(out.final_("after"), QUEUED_OK);
}

TEST_F(Limits, TooManyBypassCommandsAtOnceAreRefused) {
    send("PanCam", "pointCamera", point(), QueueAction::Bypass, "", OP, "b0");
    send("PanCam", "pointCamera", point(), QueueAction::Bypass, "", OP, "b1");  // b0 canceled, still returning
    send("Admin", "noOp", {}, QueueAction::Bypass, "", OP, "b2");
    auto b2 = out.final_("b2");
    // b0 may have returned already (it notices cancellation within 10 ms): then b2 runs
    if (b2.size() == 1) {
        EXPECT_EQ(b2, (Seq{{"COMPLETED", "EXEC_FAILED"}}));
        EXPECT_EQ(out.message("b2", 0), "2 commands already running beside the queue; retry later");
    }
    camera.release = true;
    ASSERT_TRUE(manager->wait_idle(10));
    EXPECT_EQ(out.final_("b0").back().second, "CANCELED");
    EXPECT_EQ(out.final_("b1").back().second, "OK");
    send("Admin", "noOp", {}, QueueAction::Bypass, "", OP, "b3");
    EXPECT_EQ(out.final_("b3"), BYPASS_OK);
}

// A handler that holds its command until released: the bypass limit without a race.
TEST(Logic, BypassLimitWithHeldHandlers) {
    struct Held : Handlers {
        std::atomic<bool> go{false};
        Result execute(CommandContext&) override {
            while (!go) std::this_thread::sleep_for(1ms);
            return Result::ok();
        }
    } held;
    TestOutbox out;
    ManagerOptions o;
    o.bypass_limit = 2;
    CommandManager m(k10_tables(), held, out, o);
    m.receive(make("r", "AccessControl", "requestControl"));
    m.receive(make("n1", "K10Native", "nativeCommand", {Value(std::string("a"))}));
    m.receive(make("n2", "K10Native", "nativeCommand", {Value(std::string("b"))}));
    m.receive(make("n3", "K10Native", "nativeCommand", {Value(std::string("c"))}));
    EXPECT_EQ(out.seq("n3"), (Seq{{"COMPLETED", "EXEC_FAILED"}}));
    EXPECT_EQ(out.message("n3", 0), "2 commands already running beside the queue; retry later");
    EXPECT_FALSE(m.suspended());
    held.go = true;
    ASSERT_TRUE(m.wait_idle(10));
    EXPECT_EQ(out.seq("n1"), BYPASS_OK);
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

TEST(Intake, RefuseAnswersBusyOnceAndForgetsTheId) {
    TestOutbox out;
    Handlers none;
    CommandManager m(k10_tables(), none, out);
    m.refuse(noop("x1"), "bridge busy");
    EXPECT_EQ(out.seq("x1"), (Seq{{"COMPLETED", "EXEC_FAILED"}}));
    EXPECT_EQ(out.message("x1", 0), "bridge busy");
    m.refuse(make("other", "Admin", "noOp", {}, QueueAction::Bypass, "", OP, "K10Blue"), "bridge busy");  // not ours
    m.refuse(noop(""), "bridge busy");
    EXPECT_TRUE(out.seq("other").empty());
    EXPECT_TRUE(out.seq("").empty());
    m.receive(noop("x1"));  // sent again once the flood is over: a new command, judged
    ASSERT_EQ(out.all("x1").size(), 2u);
    EXPECT_NE(out.message("x1", 1), "bridge busy");
    m.refuse(noop("x1"), "bridge busy");  // a seen id: its acks belong to that command
    EXPECT_EQ(out.all("x1").size(), 2u);
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
