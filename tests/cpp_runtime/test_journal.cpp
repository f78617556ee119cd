// The manager with a restart journal (GoogleTest, no DDS; docs/runtime.md "Restarts: the
// journal"), on K10's generated tables: every ack and every handler start comes after the
// step it promises is synced; a batch from the intake costs one sync; after a crash the
// unfinished commands are answered and never run again, the last outcomes' final acks are
// written again and their cmdIds count as seen; a damaged journal is reported once and set
// aside; a clean stop answers what is pending or running and the next start begins afresh.
// A "crash" is a copy of the journal file taken while commands are in hand (what a kill -9
// leaves: the file as written), or close(false) (no stop record).
#include <gtest/gtest.h>

#include <dirent.h>
#include <stdlib.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <rapid_runtime/intake.hpp>
#include <rapid_runtime/journal.hpp>
#include <rapid_runtime/manager.hpp>
#include <rapid_runtime/serials.hpp>

#include "k10_tables.hpp"

using namespace rapid_runtime;
using namespace std::chrono_literals;

namespace {

constexpr auto JWAIT = 10s;
const std::string JOP = "RapidWorkbench";
const std::string JASSET = "K10Red";
constexpr int DOMAIN = 5;

std::string temp_dir() {
    std::string pattern = ::testing::TempDir() + "journal-XXXXXX";
    std::vector<char> buf(pattern.begin(), pattern.end());
    buf.push_back('\0');
    EXPECT_NE(::mkdtemp(buf.data()), nullptr);
    return buf.data();
}

std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_file(const std::string& path, const std::string& data) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << data;
}

std::vector<std::string> names_in(const std::string& dir) {
    std::vector<std::string> out;
    if (DIR* d = ::opendir(dir.c_str())) {
        while (dirent* e = ::readdir(d))
            if (e->d_name[0] != '.') out.push_back(e->d_name);
        ::closedir(d);
    }
    return out;
}

struct Rec {
    std::string k, id, c, m;
};

// The journal's records, in file order; false when a line is damaged.
bool records(const std::string& path, std::vector<Rec>& out) {
    std::string raw = read_file(path);
    for (std::size_t pos = 0; pos < raw.size();) {
        std::size_t nl = raw.find('\n', pos);
        std::string line = raw.substr(pos, nl == std::string::npos ? std::string::npos : nl - pos + 1);
        pos = nl == std::string::npos ? raw.size() : nl + 1;
        std::map<std::string, std::string> s;
        std::map<std::string, std::int64_t> n;
        if (!Journal::parse_line(line, s, n)) return false;
        out.push_back({s["k"], s["id"], s["c"], s["m"]});
    }
    return true;
}

// The last step the journal file records for a cmdId ("" for none).
std::string step_of(const std::string& path, const std::string& id) {
    std::vector<Rec> recs;
    std::string last;
    if (!records(path, recs)) return "damaged";
    for (const auto& r : recs)
        if (r.id == id) last = r.k;
    return last;
}

struct JournalAck {
    AckStatus status;
    Completion completion;
    std::string message;
};

// Collects acks; with a journal, checks at each write that the journal holds no unsynced
// record and that its file already records the step the ack promises.
class JournalOutbox : public Outbox {
public:
    void ack(const Cmd& cmd, AckStatus status, Completion completed, const std::string& message) override {
        std::lock_guard<std::mutex> lock(mutex);
        if (journal != nullptr) {
            if (journal->unsynced()) problems.push_back(cmd.cmd_id + ": ack written before the journal's sync");
            const std::string want = status == AckStatus::Queued      ? "q"
                                     : status == AckStatus::Executing ? "x"
                                     : status == AckStatus::Completed ? "c"
                                                                      : "";
            const std::string got = step_of(journal->path(), cmd.cmd_id);
            // (a later step may be on disk already: the batch's acks go out after its one sync)
            if (!want.empty() && got != want && !(want == "q" && (got == "x" || got == "c")) &&
                !(want == "x" && got == "c"))
                problems.push_back(cmd.cmd_id + ": " + want + " ack while the journal says '" + got + "'");
        }
        acks[cmd.cmd_id].push_back({status, completed, message});
        changed.notify_all();
    }
    void queue_state(int, const std::vector<Record>&, const std::vector<Record>&, const std::vector<Record>&) override {
        std::lock_guard<std::mutex> lock(mutex);
        if (journal != nullptr && journal->unsynced()) problems.push_back("QueueState before the journal's sync");
    }
    void access_state(const std::string&, const std::vector<std::string>&) override {}
    void retire(const Cmd&) override {}
    void log(const std::string& text) override {
        std::lock_guard<std::mutex> lock(mutex);
        logs.push_back(text);
    }
    bool has_final(const std::string& id) {
        for (const auto& a : acks[id])
            if (a.status == AckStatus::Completed) return true;
        return false;
    }
    JournalAck final_(const std::string& id) {
        std::unique_lock<std::mutex> lock(mutex);
        EXPECT_TRUE(changed.wait_for(lock, JWAIT, [&] { return has_final(id); })) << id << ": no final ack";
        for (const auto& a : acks[id])
            if (a.status == AckStatus::Completed) return a;
        return {AckStatus::Queued, Completion::Not, ""};
    }
    void until(const std::string& id, AckStatus status) {
        std::unique_lock<std::mutex> lock(mutex);
        EXPECT_TRUE(changed.wait_for(lock, JWAIT, [&] {
            for (const auto& a : acks[id])
                if (a.status == status) return true;
            return false;
        })) << id << ": never " << name_of(status);
    }
    std::size_t count(const std::string& id) {
        std::lock_guard<std::mutex> lock(mutex);
        return acks[id].size();
    }

    Journal* journal = nullptr;
    std::mutex mutex;
    std::condition_variable changed;
    std::map<std::string, std::vector<JournalAck>> acks;
    std::vector<std::string> problems;
    std::vector<std::string> logs;
};

// K10's PanCam/pointCamera and Mobility/simpleMove block until released or canceled; every handler start is
// recorded, with whether the journal file said "running" already.
class Held : public Handlers {
public:
    Result execute(CommandContext& ctx) override {
        {
            std::lock_guard<std::mutex> lock(mutex);
            ran.push_back(ctx.cmd().cmd_id);
            if (journal_path.empty() || step_of(journal_path, ctx.cmd().cmd_id) != "x")
                early.push_back(ctx.cmd().cmd_id);
        }
        if (ctx.command() == "pointCamera" || ctx.command() == "simpleMove")
            while (!release.load())
                if (!ctx.sleep(0.01)) return Result::ok();  // canceled
        return Result::ok("held");
    }
    std::vector<std::string> runs() {
        std::lock_guard<std::mutex> lock(mutex);
        return ran;
    }
    // The runs once there are n (or JWAIT passed): a handler starts just after its EXECUTING ack.
    std::vector<std::string> runs(std::size_t n) {
        for (auto end = std::chrono::steady_clock::now() + JWAIT; std::chrono::steady_clock::now() < end;) {
            if (runs().size() >= n) break;
            std::this_thread::sleep_for(1ms);
        }
        return runs();
    }
    std::string journal_path;
    std::atomic<bool> release{false};
    std::mutex mutex;
    std::vector<std::string> ran;
    std::vector<std::string> early;  // started before the journal said "running"
};

Cmd journal_cmd(const std::string& id, const std::string& sub, const std::string& name, std::vector<Value> args = {},
         QueueAction action = QueueAction::Bypass) {
    Cmd c;
    c.cmd_id = id;
    c.cmd_src = JOP;
    c.subsystem = sub;
    c.name = name;
    c.args = std::move(args);
    c.action = action;
    c.src_name = "ground";
    c.asset_name = JASSET;
    c.serial = 7;
    return c;
}

Cmd point(const std::string& id, QueueAction action = QueueAction::Append) {
    return journal_cmd(id, "PanCam", "pointCamera", {Value(0.1f), Value(0.0f)}, action);
}

// One bridge's life on a journal folder: the journal opened (recovered), the manager on it.
struct Life {
    explicit Life(const std::string& dir, std::size_t window = 64) {
        journal = Journal::open(dir, JASSET, DOMAIN, window, [this](const std::string& t) { out.log(t); }, recovered);
        EXPECT_NE(journal, nullptr);
        out.journal = journal.get();
        handlers.journal_path = journal ? journal->path() : "";
        ManagerOptions m;
        m.window = window;
        m.journal = journal.get();
        manager = std::make_unique<CommandManager>(k10_tables(), handlers, out, m);
    }
    ~Life() {
        handlers.release = true;
        manager.reset();
    }
    std::string control(const std::string& id) {
        manager->receive(journal_cmd(id, "AccessControl", "requestControl"));
        EXPECT_EQ(out.final_(id).completion, Completion::Ok);
        return id;
    }
    JournalOutbox out;
    Held handlers;
    JournalRecovered recovered;
    std::unique_ptr<Journal> journal;
    std::unique_ptr<CommandManager> manager;
};

}  // namespace

TEST(ManagerJournal, EveryAckAndHandlerStartComesAfterTheSyncOfItsStep) {
    std::string dir = temp_dir();
    Life life(dir);
    life.control("ctl");
    auto& m = *life.manager;
    m.receive(point("run"));  // QUEUED, EXECUTING (handler blocks)
    m.receive(point("next"));  // QUEUED behind it
    m.receive(journal_cmd("fast", "K10Native", "nativeCommand", {Value(std::string("go"))}));  // beside the queue
    m.receive(journal_cmd("gone", "Admin", "noOp", {}, QueueAction::Delete));  // BAD_SYNTAX: no target
    Cmd del = journal_cmd("del", "Admin", "noOp", {}, QueueAction::Delete);
    del.target = "next";
    m.receive(del);
    life.out.until("run", AckStatus::Executing);
    life.handlers.release = true;
    EXPECT_EQ(life.out.final_("run").completion, Completion::Ok);
    EXPECT_EQ(life.out.final_("next").completion, Completion::Canceled);
    EXPECT_EQ(life.out.final_("fast").completion, Completion::Ok);
    EXPECT_EQ(life.out.final_("gone").completion, Completion::BadSyntax);
    EXPECT_EQ(life.out.final_("del").completion, Completion::Ok);
    ASSERT_TRUE(m.wait_idle(10));
    auto ran = life.handlers.runs(2);
    EXPECT_EQ(std::set<std::string>(ran.begin(), ran.end()), (std::set<std::string>{"run", "fast"}));
    std::lock_guard<std::mutex> lock(life.handlers.mutex);
    EXPECT_TRUE(life.handlers.early.empty()) << life.handlers.early.front();
    std::lock_guard<std::mutex> lock2(life.out.mutex);
    EXPECT_TRUE(life.out.problems.empty()) << life.out.problems.front();
}

TEST(ManagerJournal, ABatchOfWaitingCommandsCostsOneSync) {
    std::string dir = temp_dir();
    Life life(dir);
    life.control("ctl");
    const std::size_t before = life.journal->syncs();
    {
        Intake intake(*life.manager, [](const std::string&) {});
        for (int i = 0; i < 40; ++i) intake.offer(journal_cmd("n" + std::to_string(i), "Admin", "noOp"), "w1");
        intake.start();  // 40 waiting: a batch of 32, then one of 8
        for (int i = 0; i < 40; ++i) EXPECT_EQ(life.out.final_("n" + std::to_string(i)).completion, Completion::Ok);
    }
    EXPECT_EQ(life.journal->syncs() - before, 2u);
    std::lock_guard<std::mutex> lock(life.out.mutex);
    EXPECT_TRUE(life.out.problems.empty()) << life.out.problems.front();
}

TEST(ManagerJournal, AfterACrashTheUnfinishedAreAnsweredAndNothingRunsTwice) {
    std::string dir = temp_dir(), crashed = temp_dir(), again = temp_dir();
    const std::string file = Journal::file_name(JASSET, DOMAIN);
    {
        Life life(dir);
        EXPECT_FALSE(life.recovered.crashed);
        life.control("ctl");
        life.manager->receive(journal_cmd("done", "PanCam", "takePicture", {Value(std::string("left")), Value(0.0f)}));
        EXPECT_EQ(life.out.final_("done").completion, Completion::Ok);
        life.manager->receive(point("running"));
        life.manager->receive(point("waiting"));
        life.out.until("running", AckStatus::Executing);
        life.out.until("waiting", AckStatus::Queued);
        write_file(crashed + "/" + file, read_file(dir + "/" + file));  // what a kill -9 now leaves
    }
    Life life(crashed);
    ASSERT_TRUE(life.recovered.crashed);
    ASSERT_EQ(life.recovered.unfinished.size(), 2u);
    EXPECT_EQ(life.recovered.unfinished[0].cmd_id, "running");
    EXPECT_EQ(life.recovered.unfinished[0].state, 'x');
    EXPECT_EQ(life.recovered.unfinished[1].cmd_id, "waiting");
    EXPECT_EQ(life.recovered.unfinished[1].state, 'q');
    auto [answered, rewritten] = life.manager->restore(life.recovered);
    EXPECT_EQ(answered, 2u);
    EXPECT_EQ(rewritten, 2u);  // ctl's and done's final acks
    JournalAck running = life.out.final_("running"), waiting = life.out.final_("waiting"), done = life.out.final_("done");
    EXPECT_EQ(running.completion, Completion::ExecFailed);
    EXPECT_EQ(running.message, RESTARTED_RUNNING);
    EXPECT_EQ(waiting.completion, Completion::Canceled);
    EXPECT_EQ(waiting.message, RESTARTED_QUEUED);
    EXPECT_EQ(done.completion, Completion::Ok);
    EXPECT_EQ(done.message, "held");  // the outcome it had, written again
    EXPECT_EQ(life.out.final_("ctl").completion, Completion::Ok);
    EXPECT_EQ(life.manager->acks_kept(), (std::vector<std::string>{"ctl", "done", "running", "waiting"}));
    // the ground sends them again (same cmdIds): nothing runs; each gets its final ack again
    // (issue 42), the same as the one before
    life.control("ctl2");
    for (const char* id : {"running", "waiting", "done", "ctl"}) life.manager->receive(point(id));
    life.manager->receive(point("fresh", QueueAction::Bypass));
    life.out.until("fresh", AckStatus::Executing);
    EXPECT_EQ(life.handlers.runs(1), std::vector<std::string>{"fresh"});
    {
        std::lock_guard<std::mutex> lock(life.out.mutex);
        for (const char* id : {"running", "waiting", "done"}) {
            const auto& seq = life.out.acks[id];
            ASSERT_EQ(seq.size(), 2u) << id;
            EXPECT_EQ(seq[1].status, AckStatus::Completed) << id;
            EXPECT_EQ(seq[1].completion, seq[0].completion) << id;
            EXPECT_EQ(seq[1].message, seq[0].message) << id;
        }
        EXPECT_TRUE(life.out.problems.empty()) << life.out.problems.front();
        std::size_t again = 0;
        for (const auto& l : life.out.logs) again += l.find("answered already, its final ack written again") != std::string::npos;
        EXPECT_EQ(again, 4u);
    }
    // the answers were journaled first: a second crash now finds them finished
    write_file(again + "/" + file, read_file(crashed + "/" + file));
    JournalRecovered rec;
    auto j = Journal::open(again, JASSET, DOMAIN, 64, [](const std::string&) {}, rec);
    ASSERT_TRUE(j && rec.crashed);
    ASSERT_EQ(rec.unfinished.size(), 1u);  // fresh, running now
    EXPECT_EQ(rec.unfinished[0].cmd_id, "fresh");
    std::map<std::string, std::string> finished;
    for (const auto& e : rec.finished) finished[e.cmd_id] = e.message;
    EXPECT_EQ(finished["running"], RESTARTED_RUNNING);
    EXPECT_EQ(finished["waiting"], RESTARTED_QUEUED);
}

TEST(ManagerJournal, ADamagedJournalIsReportedOnceSetAsideAndItsSoundLinesServe) {
    std::string dir = temp_dir();
    const std::string path = dir + "/" + Journal::file_name(JASSET, DOMAIN);
    {
        JournalRecovered rec;
        auto j = Journal::open(dir, JASSET, DOMAIN, 64, [](const std::string&) {}, rec);
        ASSERT_TRUE(j);
        j->start(100);
        j->note(JournalEntry{"a", "ground", JASSET, 7, 'q', "", ""});
        j->note(JournalEntry{"b", "ground", JASSET, 7, 'q', "", ""});
        j->note(JournalEntry{"b", "ground", JASSET, 7, 'x', "", ""});
        j->sync();
        j->close(false);  // no stop record: a crash
    }
    std::string raw = read_file(path);
    std::size_t second = raw.find('\n') + 1;
    // a damaged block in the middle (binary junk), a torn record at the end (never synced)
    write_file(path, raw.substr(0, second) + std::string("0badc0de {\"k\":\"x\",\"id\":\"gar\0\xff\"}\n", 32) +
                         raw.substr(second) + "1234abcd {\"k\":\"q\",\"id\":\"torn-");
    Life life(dir);
    ASSERT_TRUE(life.recovered.crashed);
    std::vector<std::string> aside;
    for (const auto& n : names_in(dir))
        if (n.find(".damaged-") != std::string::npos) aside.push_back(n);
    ASSERT_EQ(aside.size(), 1u);
    {
        std::lock_guard<std::mutex> lock(life.out.mutex);
        ASSERT_EQ(life.out.logs.size(), 1u);
        EXPECT_NE(life.out.logs[0].find("2 damaged line(s)"), std::string::npos) << life.out.logs[0];
        EXPECT_NE(life.out.logs[0].find(aside[0]), std::string::npos) << life.out.logs[0];
    }
    std::vector<Rec> recs;
    EXPECT_TRUE(records(path, recs));  // the new journal: the sound lines only
    ASSERT_EQ(life.recovered.unfinished.size(), 2u);
    EXPECT_EQ(life.recovered.last_serial, 100);
    life.manager->restore(life.recovered);
    EXPECT_EQ(life.out.final_("a").message, RESTARTED_QUEUED);
    EXPECT_EQ(life.out.final_("b").message, RESTARTED_RUNNING);
    life.journal->close(false);
    JournalRecovered rec;
    std::vector<std::string> logs;
    auto j = Journal::open(dir, JASSET, DOMAIN, 64, [&](const std::string& t) { logs.push_back(t); }, rec);
    EXPECT_TRUE(j && logs.empty() && rec.unfinished.empty());  // sound now: nothing reported again
}

TEST(ManagerJournal, ACleanStopAnswersPendingAndRunningAndTheNextStartBeginsAfresh) {
    std::string dir = temp_dir();
    {
        Life life(dir);
        life.control("ctl");
        life.manager->receive(point("running"));
        life.manager->receive(point("waiting"));
        life.manager->receive(journal_cmd("beside", "Mobility", "simpleMove",
                                   {Value(std::string("SITE")), Value(Vec3d{1.0, 2.0, 0.0})}));
        life.out.until("running", AckStatus::Executing);
        life.out.until("waiting", AckStatus::Queued);
        life.out.until("beside", AckStatus::Executing);
        // (issue 42) the handlers are told to stop and waited for (they honour it: CANCELED);
        // what waits is answered at once
        EXPECT_EQ(life.manager->abandon(), 3u);
        EXPECT_EQ(life.out.final_("running").message, "canceled");
        EXPECT_EQ(life.out.final_("running").completion, Completion::Canceled);
        EXPECT_EQ(life.out.final_("waiting").message, SHUTTING_DOWN);
        EXPECT_EQ(life.out.final_("waiting").completion, Completion::Canceled);
        EXPECT_EQ(life.out.final_("beside").message, "canceled");
        Journal* j = life.manager->release_journal();
        ASSERT_EQ(j, life.journal.get());
        j->close(true);
        life.handlers.release = true;
        life.manager.reset();  // the handlers return: nothing follows their COMPLETED
        EXPECT_EQ(life.out.count("running"), 3u);  // QUEUED, EXECUTING, COMPLETED
        EXPECT_EQ(life.out.count("waiting"), 2u);
    }
    JournalRecovered rec;
    auto j = Journal::open(dir, JASSET, DOMAIN, 64, [](const std::string&) {}, rec);
    ASSERT_TRUE(j);
    EXPECT_FALSE(rec.crashed);
    EXPECT_TRUE(rec.unfinished.empty() && rec.finished.empty());
}

TEST(ManagerJournal, ConfigSerialsComeBackAboveTheHighestRecorded) {
    std::string dir = temp_dir();
    std::int64_t now = 1000;
    {
        JournalRecovered rec;
        auto j = Journal::open(dir, JASSET, DOMAIN, 64, [](const std::string&) {}, rec);
        ASSERT_TRUE(j);
        Serials serials(restart_serial(-1, rec, now), [&] { return now; }, [&](std::int32_t s) { j->serial(s); });
        j->start(serials.start());
        serials.update("cfg", "a");
        serials.update("cfg", "b");  // 1001
        serials.update("cfg", "c");  // 1002, less than a second after the start
        j->close(false);  // a crash: no sync after the last serial (a kill -9 keeps what was written)
    }
    JournalRecovered rec;
    auto j = Journal::open(dir, JASSET, DOMAIN, 64, [](const std::string&) {}, rec);
    ASSERT_TRUE(j);
    EXPECT_EQ(rec.last_serial, 1002);
    EXPECT_EQ(restart_serial(-1, rec, now), 1003);  // the clock has not moved past it
    EXPECT_EQ(restart_serial(-1, rec, 5000), 5000);
    EXPECT_EQ(restart_serial(42, rec, 5000), 42);  // asked for: kept
    EXPECT_EQ(restart_serial(-1, JournalRecovered{}, 5000), -1);  // no journal: the start time
}
