// Command intake and the ack lifecycle: the asset's side of rapid_command / rapid_ack,
// without DDS (runtime/rapid_runtime/manager.py is the reference; docs/runtime.md lists
// every answer).
//
//     CommandManager manager(tables, handlers, outbox);
//     manager.receive(cmd);        // every Command read from the asset's partition
//
// Dropped without an ack (logged): a command for another asset, a repeated cmdId still
// running or sent by another source. A repeated cmdId already answered (same cmdSrc) gets
// its stored final ack again (the last FINAL_ACKS_KEPT finished commands' are kept).
// Everything else gets exactly one final COMPLETED ack. Acks go out through the Outbox,
// always under the manager's lock, so the acks of one command keep their order.
//
// Memory stays bounded: the last `window` cmdIds are remembered (duplicates detected
// among them and among those still pending or running); once more than `window` commands
// have completed, the oldest one's acks are retired (Outbox::retire: the ack writer
// unregisters the instance).
//
// With a restart journal (journal.hpp, ManagerOptions::journal), every step an ack
// promises is on disk before that ack: within a locked operation (a Batch) the acks,
// QueueState, AccessControlState and handler starts are held back, the journal is synced
// once at its end, then they go out in order. The intake hands over the commands already
// waiting (up to 32) as one batch: a flood costs one sync per batch.
#ifndef RAPID_RUNTIME_MANAGER_HPP
#define RAPID_RUNTIME_MANAGER_HPP

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <thread>
#include <unordered_map>
#include <string>
#include <unordered_set>
#include <vector>

#include "access.hpp"
#include "command.hpp"
#include "handlers.hpp"
#include "journal.hpp"
#include "pending.hpp"
#include "run.hpp"
#include "tables.hpp"
#include "texts.hpp"
#include "workers.hpp"

namespace rapid_runtime {

// Commands whose state is kept: the last 4096 cmdIds received and the acks of the last
// 4096 completed commands (late-joining ack readers).
inline constexpr std::size_t COMMAND_WINDOW = 4096;
// Past these, a command is answered EXEC_FAILED at once (docs/runtime.md, "Bounded memory").
inline constexpr std::size_t QUEUE_LIMIT = 1024;
inline constexpr std::size_t BYPASS_LIMIT = 64;
inline constexpr double COMPLETED_KEEP_S = 20.0;  // finished commands stay in QueueState this long (soraCore)
inline constexpr std::size_t RECORDS = 64;  // QueueState's SingleQueue holds at most 64 records
// What a command left unfinished by a restart is answered (docs/runtime.md, "Restarts":
// never run again, since a half-done motion run again is not safe); a stop answers
// SHUTTING_DOWN and DID_NOT_STOP (shut_down()). Every text an ack carries is in texts.hpp
// (generated from runtime/spec/texts.yaml, the Python runtime's too); these are named here
// for the tests.
inline constexpr const char* RESTARTED_QUEUED = texts::RESTARTED_QUEUED;
inline constexpr const char* RESTARTED_RUNNING = texts::RESTARTED_RUNNING;
// Handlers that do not stop (issue 42, docs/runtime.md "The handler contract"): how long a
// handler told to stop may still run (a command's CommandSpec::stop_timeout_ms overrides
// it), how long a shutdown waits for the handlers, and what the commands are answered then.
inline constexpr int DEFAULT_STOP_TIMEOUT_MS = 2000;
inline constexpr int DEFAULT_SHUTDOWN_TIMEOUT_MS = 5000;
inline constexpr const char* DID_NOT_STOP = texts::DID_NOT_STOP;
inline constexpr const char* SHUTTING_DOWN = texts::ASSET_SHUTTING_DOWN;
inline constexpr const char* NO_STOP_HANDLER = texts::NO_HARDWARE_STOP;
// Final acks kept to answer a cmdId sent again (and contexts kept valid after their command).
inline constexpr std::size_t FINAL_ACKS_KEPT = 1024;

// One QueueState record: the command and its result and status.
struct Record {
    std::shared_ptr<const Cmd> cmd;
    RecordResult result = RecordResult::Init;
    RecordStatus status = RecordStatus::Init;
};

// Where the manager's answers go: the DDS layer writes them, tests collect them.
class Outbox {
public:
    virtual ~Outbox() = default;
    virtual void ack(const Cmd& cmd, AckStatus status, Completion completed, const std::string& message) = 0;
    // code: 1 active, 0 idle, -1 suspended
    virtual void queue_state(int code, const std::vector<Record>& pending, const std::vector<Record>& active,
                             const std::vector<Record>& completed) = 0;
    virtual void access_state(const std::string& controller, const std::vector<std::string>& requestors) = 0;
    // The command's acks need not be kept any longer (cmd holds the ack key only: header
    // names, serial and cmdId).
    virtual void retire(const Cmd& cmd) = 0;
    virtual void log(const std::string& text) = 0;
};

// What the intake door hands commands to (intake.hpp): the manager, or a test's recorder.
class CommandSink {
public:
    virtual ~CommandSink() = default;
    virtual void receive(const Cmd& cmd) = 0;
    // Answer a command shed at the door COMPLETED/EXEC_FAILED without running it.
    virtual void refuse(const Cmd& cmd, const std::string& why) = 0;
    // A control command (stopAllMotion, Queue cancelAll, any AccessControl command) goes first.
    virtual bool is_control(const Cmd& cmd) const = 0;
    // A command this sink answers itself at once, without a handler and without waiting
    // (a BYPASS Admin/echo, noOp or AccessControl command, no journal to sync): the intake
    // may hand it over on the thread that offers it when nothing waits before it.
    virtual bool answers_at_once(const Cmd&) const { return false; }
    // The intake's calls between these two are one batch (the manager: one journal sync).
    // Called in pairs, each pair on one thread (the intake's, or the offering thread's for
    // a command handed over at once), never two batches at a time.
    virtual void begin_batch() {}
    virtual void end_batch() {}
};

#ifdef RAPID_RUNTIME_TEST_BREAKS
// Test builds only (the bridge's --break KIND, dds/breaks.hpp): decisions broken on purpose,
// so that the conformance tests can show `rapidgen conform` catching each. A plain build
// has neither these flags nor a branch on them.
struct ManagerBreaks {
    bool no_dedup = false;  // a repeated cmdId runs again (CMD-10)
    bool request_unpublished = false;  // requestControl's grant not written to AccessControlState (ACC-02)
    bool no_control_gate = false;  // commands of a source without control accepted (ACC-03)
    bool grab_refused = false;  // grabControl refused while another source holds control (ACC-04)
    bool grab_unpublished = false;  // grabControl's change not written to AccessControlState (ACC-04)
    bool release_by_anyone = false;  // releaseControl from any source releases (ACC-05)
    bool stop_needs_control = false;  // stopAllMotion gated like any command (ACC-06)
    bool request_steals_control = false;  // requestControl takes control from its holder (ACC-07)
    bool queue_lifo = false;  // the queue served by a 10 Hz tick, newest first (QUE-02)
    bool queue_parallel = false;  // every queued command started at once (QUE-02)
    bool append_target_ignored = false;  // APPEND's targetCmdId never looked at (QUE-03)
    bool delete_wrong_command = false;  // DELETE of a pending command cancels the running one (QUE-04)
};
#endif

struct ManagerOptions {
    std::size_t window = COMMAND_WINDOW;
    std::size_t queue_limit = QUEUE_LIMIT;
    std::size_t bypass_limit = BYPASS_LIMIT;
    std::function<void()> on_shutdown;  // after Admin/shutdown's COMPLETED ack, on a thread of its own
    std::function<double()> clock;  // seconds, monotonic (default: steady_clock)
    int stop_timeout_ms = DEFAULT_STOP_TIMEOUT_MS;  // the stop bound of commands declaring none (>= 1)
    int shutdown_timeout_ms = DEFAULT_SHUTDOWN_TIMEOUT_MS;  // shut_down()'s default bound
#ifdef RAPID_RUNTIME_TEST_BREAKS
    ManagerBreaks breaks;
#endif
    Journal* journal = nullptr;  // the restart journal (outlives the manager); nullptr: none
};

class CommandManager : public CommandSink {
public:
    // tables, handlers and outbox must outlive the manager. Throws std::invalid_argument for a
    // window or limit of 0.
    CommandManager(const Tables& tables, Handlers& handlers, Outbox& outbox, ManagerOptions options = {});
    ~CommandManager() override;  // cancels what runs and joins the handlers' threads
    CommandManager(const CommandManager&) = delete;
    CommandManager& operator=(const CommandManager&) = delete;

    void receive(const Cmd& cmd) override;
    void refuse(const Cmd& cmd, const std::string& why) override;
    bool is_control(const Cmd& cmd) const override;
    bool answers_at_once(const Cmd& cmd) const override;
    void begin_batch() override;  // takes the lock (held until end_batch)
    void end_batch() override;

    // After a crash (the journal's recovery): answer what was accepted and not finished
    // (never run again), write the last outcomes' final acks again, remember their cmdIds.
    // Before the first command is read. Returns (commands answered now, final acks again).
    std::pair<std::size_t, std::size_t> restore(const JournalRecovered& recovered);
    // The bridge stops: shut_down() with the options' bound; returns the commands answered.
    std::size_t abandon();
    // The asset shuts down (Admin shutdown, SIGTERM): nothing starts any more; pending
    // commands are answered CANCELED "asset shutting down"; every running handler is told
    // to stop and waited for at most timeout_ms (-1: the options' shutdown bound); those
    // still running then are answered EXEC_FAILED "handler did not stop". The journal is
    // synced, and from then on the manager writes nothing (a handler returning later is
    // ignored). Returns (commands in flight it answered or saw answered: the pending
    // and the running ones, handler calls still running). With
    // handler calls still running the manager must not be destroyed (its destructor waits
    // for them): the bridge ends the process instead.
    struct ShutDown {
        std::size_t answered = 0;
        std::size_t running = 0;
    };
    ShutDown shut_down(int timeout_ms = -1);
    // No journal from now on (the bridge closes it); returns the one there was.
    Journal* release_journal();

    // Publish QueueState and AccessControlState as they are (at start-up).
    void publish_states();
    // True once no queued or bypass command runs, or the queue is suspended with nothing running.
    bool wait_idle(double timeout_s);

    // What tests look at (each takes the lock).
    std::vector<std::string> pending_ids() const;
    std::size_t pending_count() const;
    bool suspended() const;
    std::string controller() const;
    std::vector<std::string> requestors() const;
    std::size_t remembered() const;  // cmdIds in the duplicate window
    std::size_t handlers_running() const;  // handler calls not returned (those given up on included)
    std::vector<std::string> acks_kept() const;  // completed commands whose acks are kept, oldest first
    const Tables& tables() const { return tables_; }

private:
    using Lock = std::unique_lock<std::recursive_mutex>;
    // The lock, and with a journal the held-back writes: flushed when the outermost ends.
    class Batch {
    public:
        explicit Batch(CommandManager& m) : m_(m) { m_.begin_batch(); }
        ~Batch() { m_.end_batch(); }
        Batch(const Batch&) = delete;
        Batch& operator=(const Batch&) = delete;

    private:
        CommandManager& m_;
    };
    void emit(std::function<void()> write);  // now, or at the batch's end with a journal
    void flush();
    struct Refusal {
        Completion completion;
        std::string text;
    };

    std::optional<Refusal> intake(const std::shared_ptr<const Cmd>& cmd);
    std::optional<Refusal> remove_target(const std::shared_ptr<const Cmd>& cmd);
    std::optional<std::string> authorize(const std::string& source, const std::string& subsystem,
                                         const CommandRef& ref) const;
    bool live(const std::string& cmd_id) const;
    RunPtr queued_run(const std::string& cmd_id) const;
    bool busy(const std::string& subsystem) const;
    void remember(const std::string& cmd_id);

    void service();
    void start(const RunPtr& run);
    void preempt(const RunPtr& run);
    void execute(const RunPtr& run);
    void progress(const RunPtr& run, const std::string& text);
    // suspend: a queued command's EXEC_FAILED suspends the queue (not when it was told to stop)
    void complete(const RunPtr& run, Completion completion, const std::string& message, bool suspend = true);
    void finish_unstarted(const RunPtr& run, const std::string& why);
    void record_done(const RunPtr& run, Completion completion);
    void cancel(const RunPtr& run);
    void tell_stop(const RunPtr& run);  // cancel its context and start its stop bound
    int stop_bound_ms(const RunPtr& run) const;
    void watch();  // the stop bound's thread
    void give_up(const RunPtr& run);  // its bound passed: answered "handler did not stop"
    std::string what(const RunPtr& run) const;  // "cmdId (Subsystem/command)" for logs
    void store_final(const Cmd& cmd, Completion completion, const std::string& message);
    // journal: false for answers not remembered (a refusal at the door)
    void send_ack(const Cmd& cmd, AckStatus status, Completion completion, const std::string& message,
                  bool journal = true);
    void write_ack(const Cmd& cmd, AckStatus status, Completion completion, const std::string& message);
    void keep(Cmd key);
    void publish_queue();
    void publish_access();

    // Built-in commands (Admin, Queue, AccessControl, stopAllMotion). Each returns the
    // outcome, or nothing to go on to the handler.
    std::optional<Result> builtin(const RunPtr& run);
    Result cancel_all(const RunPtr& run);
    void stop_all_motion(const RunPtr& run);

    const Tables& tables_;
    Handlers& handlers_;
    Outbox& out_;
    ManagerOptions options_;
    bool has_queue_;
    bool has_control_;

    mutable std::recursive_mutex mutex_;
    std::condition_variable_any idle_;
    std::unordered_set<std::string> seen_;  // the ids of seen_order_
    std::deque<std::string> seen_order_;  // the last `window` cmdIds, oldest first
    std::deque<Cmd> acked_;  // completed, acks still kept; the ack key only; oldest first
    Pending pending_;
    RunPtr active_;  // the queue's running command
    std::vector<RunPtr> bypass_;  // BYPASS commands running
    struct Done {
        double at;
        RunPtr run;
        Completion completion;
    };
    std::deque<Done> completed_;
    bool suspended_ = false;
    Control control_;
    RunPtr shutdown_after_;
    Journal* journal_;
    // Handlers told to stop, each until it returns or its bound passes (watch()).
    std::vector<RunPtr> stopping_;
    std::condition_variable_any watch_;
    bool closing_ = false;  // the manager goes: the watchdog ends
    bool closed_ = false;  // shut down: nothing is written any more
    std::size_t handling_ = 0;  // handler calls not returned
    // The final acks of the last FINAL_ACKS_KEPT commands answered, by cmdId (a resent
    // cmdId's answer), and the contexts of as many finished commands (kept valid).
    struct Final {
        Cmd key;
        Completion completion;
        std::string message;
    };
    std::unordered_map<std::string, Final> finals_;
    std::deque<std::string> finals_order_;
    std::deque<std::shared_ptr<CommandContext>> contexts_kept_;
    // What a context's progress() reaches: the manager while it lives (its destructor
    // clears it, waiting for a call under way).
    struct Alive {
        std::shared_mutex mutex;
        CommandManager* manager = nullptr;
    };
    std::shared_ptr<Alive> alive_;
    int depth_ = 0;  // nested batches
    std::vector<std::function<void()>> outgoing_;  // held until the journal is synced
#ifdef RAPID_RUNTIME_TEST_BREAKS
    void broken_service(bool tick);  // queue-lifo's tick, queue-parallel's start-all
    // The AccessControl command's outcome when a break changes it, else nothing.
    std::optional<Result> broken_control(const std::string& src, const std::string& name);
#endif
    Workers workers_;  // joined when the manager goes
    std::thread watchdog_;  // watch(): joined first
};

}  // namespace rapid_runtime

#endif
