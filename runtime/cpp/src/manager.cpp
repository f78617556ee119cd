#include "rapid_runtime/manager.hpp"

#include <cxxabi.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <thread>
#include <typeinfo>

#include "rapid_runtime/text.hpp"
#include "rapid_runtime/texts.hpp"
#include "rapid_runtime/validate.hpp"

// A test build's broken decision (ManagerBreaks); the constant false in a plain build, where
// the branches on it compile to nothing.
#ifdef RAPID_RUNTIME_TEST_BREAKS
#define BROKEN(flag) (options_.breaks.flag)
#else
#define BROKEN(flag) false
#endif

namespace rapid_runtime {
namespace {

double steady_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// What retiring a command's acks needs (the ack key: header names and cmdId), without
// its arguments, which the window would otherwise keep alive.
Cmd key_of(const Cmd& c) {
    Cmd k;
    k.cmd_id = c.cmd_id;
    k.cmd_src = c.cmd_src;
    k.subsystem = c.subsystem;
    k.name = c.name;
    k.src_name = c.src_name;
    k.asset_name = c.asset_name;
    k.serial = c.serial;
    return k;
}

std::string type_name(const std::exception& e) {
    int status = 0;
    char* name = abi::__cxa_demangle(typeid(e).name(), nullptr, nullptr, &status);
    std::string out = status == 0 && name != nullptr ? name : typeid(e).name();
    std::free(name);
    return out;
}

bool is(const RunPtr& run, std::string_view type, std::string_view command) {
    return run->ref.type->name == type && run->ref.spec->name == command;
}

// The commands the runtime answers itself (the standard subsystem types' own).
constexpr std::pair<std::string_view, std::string_view> BUILTINS[] = {
    {"Admin", "echo"},
    {"Admin", "noOp"},
    {"Admin", "shutdown"},
    {"Queue", "cancelAll"},
    {"Mobility", "stopAllMotion"},
    {"AccessControl", "requestControl"},
    {"AccessControl", "grabControl"},
    {"AccessControl", "releaseControl"},
    {"AccessControl", "transferControl"},
};

// A journal's completion name back to the enum (an unknown one, from a newer writer: EXEC_FAILED).
Completion completion_named(const std::string& name) {
    for (Completion c : {Completion::Not, Completion::Ok, Completion::BadSyntax, Completion::ExecFailed,
                         Completion::Canceled})
        if (name_of(c) == name) return c;
    return Completion::ExecFailed;
}

// A journal entry as the Cmd its acks need (header names, serial, cmdId).
Cmd entry_cmd(const JournalEntry& e) {
    Cmd c;
    c.cmd_id = e.cmd_id;
    c.src_name = e.src_name;
    c.asset_name = e.asset_name;
    c.serial = static_cast<std::int32_t>(e.serial);
    return c;
}

bool builtin_command(const CommandRef& ref) {
    if (!ref.spec->standard) return false;
    for (const auto& [type, name] : BUILTINS)
        if (ref.type->name == type && ref.spec->name == name) return true;
    return false;
}

}  // namespace

CommandManager::CommandManager(const Tables& tables, Handlers& handlers, Outbox& outbox, ManagerOptions options)
    : tables_(tables), handlers_(handlers), out_(outbox), options_(std::move(options)), journal_(options_.journal) {
    if (options_.window < 1) throw std::invalid_argument("command window 0: at least 1");
    if (options_.queue_limit < 1 || options_.bypass_limit < 1)
        throw std::invalid_argument("queue limit and bypass limit: at least 1 each");
    if (!options_.clock) options_.clock = steady_seconds;
    if (options_.stop_timeout_ms < 1 || options_.shutdown_timeout_ms < 0)
        throw std::invalid_argument("stop timeout: at least 1 ms; shutdown timeout: at least 0 ms");
    has_queue_ = tables_.has_type("Queue");
    has_control_ = tables_.has_type("AccessControl");
    alive_ = std::make_shared<Alive>();
    alive_->manager = this;
    watchdog_ = std::thread([this] { watch(); });
#ifdef RAPID_RUNTIME_TEST_BREAKS
    if (options_.breaks.queue_lifo)  // soraCore's 10 Hz executive tick starts queued commands
        workers_.spawn([this] {
            for (;;) {
                std::this_thread::sleep_for(std::chrono::milliseconds(100));
                Lock lock(mutex_);
                if (closing_) return;
                broken_service(true);
            }
        });
#endif
}

CommandManager::~CommandManager() {
    {
        // a context's progress() under way ends first; later ones reach nothing
        std::unique_lock<std::shared_mutex> gone(alive_->mutex);
        alive_->manager = nullptr;
    }
    {
        Lock lock(mutex_);
        suspended_ = true;  // nothing new starts from the queue
        closing_ = true;
        for (const auto& r : bypass_)
            if (r->ctx) r->ctx->cancel();
        if (active_ && active_->ctx) active_->ctx->cancel();
    }
    watch_.notify_all();
    if (watchdog_.joinable()) watchdog_.join();
    workers_.join_all();
}

// ---- intake -------------------------------------------------------------------------------

// ---- batches: the journal synced before the acks that promise what it holds --------------

void CommandManager::begin_batch() {
    mutex_.lock();
    ++depth_;
}

void CommandManager::end_batch() {
    if (--depth_ == 0) flush();
    mutex_.unlock();
}

void CommandManager::emit(std::function<void()> write) {
    if (journal_ != nullptr && depth_ > 0) outgoing_.push_back(std::move(write));
    else write();
}

void CommandManager::flush() {
    if (journal_ != nullptr) journal_->sync();  // a failure is logged once; the answers go out all the same
    std::vector<std::function<void()>> out;
    out.swap(outgoing_);
    for (auto& write : out) {
        try {
            write();
        } catch (const std::exception& e) {  // (from a batch's end: must not throw)
            out_.log(std::string("a held-back write failed: ") + e.what());
        }
    }
}

// ---- intake -------------------------------------------------------------------------------

void CommandManager::receive(const Cmd& in) {
    Batch batch(*this);
    if (in.asset_name != tables_.name) {
        out_.log("ignored '" + in.cmd_id + "': addressed to asset '" + in.asset_name + "'");
        return;
    }
    if (closed_) return;  // shut down: the intake is closed
    if ((seen_.count(in.cmd_id) != 0 && !BROKEN(no_dedup)) || live(in.cmd_id)) {
        auto f = finals_.find(in.cmd_id);
        // (the same hdr.srcName, the ack instance's key: docs/runtime.md, "Answers")
        const bool same = f != finals_.end() && f->second.key.src_name == in.src_name;
        if (!live(in.cmd_id) && same) {
            // answered already: nothing runs; its final ack once more (a tool that missed it)
            out_.log("'" + in.cmd_id + "' sent again: answered already, its final ack written again");
            emit([this, final = f->second] {
                write_ack(final.key, AckStatus::Completed, final.completion, final.message);
            });
            return;
        }
        out_.log("ignored '" + in.cmd_id + "': repeated cmdId");
        return;
    }
    remember(in.cmd_id);
    auto cmd = std::make_shared<const Cmd>(in);
    if (auto refusal = intake(cmd)) {
        send_ack(*cmd, AckStatus::Completed, refusal->completion, refusal->text);
        std::string kind(name_of(refusal->completion));
        out_.log(cmd->cmd_id + ": " + kind.substr(std::string("ACK_COMPLETED_").size()) + ": " + refusal->text);
    }
}

void CommandManager::refuse(const Cmd& cmd, const std::string& why) {
    Batch batch(*this);
    if (cmd.asset_name != tables_.name || cmd.cmd_id.empty()) return;
    if (seen_.count(cmd.cmd_id) != 0 || live(cmd.cmd_id)) return;  // its acks belong to that command
    send_ack(cmd, AckStatus::Completed, Completion::ExecFailed, why, false);  // not remembered: may come again
}

bool CommandManager::is_control(const Cmd& cmd) const {
    const std::string* kind = tables_.type_of(cmd.subsystem);
    if (kind == nullptr) return false;
    return *kind == "AccessControl" || (*kind == "Mobility" && cmd.name == "stopAllMotion") ||
           (*kind == "Queue" && cmd.name == "cancelAll");
}

bool CommandManager::answers_at_once(const Cmd& cmd) const {
    // (what it reads is set at construction: no lock)
    if (options_.journal != nullptr || cmd.action != QueueAction::Bypass) return false;  // no sync there
    const std::string* kind = tables_.type_of(cmd.subsystem);
    if (kind == nullptr) return false;
    return (*kind == "Admin" && (cmd.name == "echo" || cmd.name == "noOp")) || *kind == "AccessControl";
}

void CommandManager::remember(const std::string& cmd_id) {
    seen_.insert(cmd_id);
    seen_order_.push_back(cmd_id);
    while (seen_order_.size() > options_.window) {
        seen_.erase(seen_order_.front());
        seen_order_.pop_front();
    }
}

std::optional<CommandManager::Refusal> CommandManager::intake(const std::shared_ptr<const Cmd>& cmd) {
#ifdef RAPID_RUNTIME_TEST_BREAKS
    if (options_.breaks.append_target_ignored && cmd->action == QueueAction::Append && !cmd->target.empty()) {
        auto untargeted = std::make_shared<Cmd>(*cmd);
        untargeted->target.clear();
        return intake(untargeted);
    }
#endif
    const auto action = cmd->action;
    const std::string& target = cmd->target;
    const std::string act(name_of(action));
    if (cmd->cmd_id.empty()) return Refusal{Completion::BadSyntax, texts::EMPTY_CMD_ID};
    if (act.empty())
        return Refusal{Completion::BadSyntax, texts::unknown_queue_action(std::to_string(static_cast<int>(action)))};
    if (action != QueueAction::Bypass && !has_queue_)
        return Refusal{Completion::BadSyntax, texts::no_queue(act)};
    if ((action == QueueAction::Bypass || action == QueueAction::Append) && !target.empty())
        return Refusal{Completion::BadSyntax, texts::target_not_taken(act, shorten(target))};
    if (action != QueueAction::Bypass && action != QueueAction::Append && target.empty())
        return Refusal{Completion::BadSyntax, texts::target_needed(act)};
    if (action == QueueAction::Delete) return remove_target(cmd);

    Checked checked = check_command(*cmd, tables_);
    if (checked.why) return Refusal{Completion::BadSyntax, *checked.why};
    if (action == QueueAction::Insert && target != HEAD && !queued_run(target))
        return Refusal{Completion::BadSyntax,
                       texts::unknown_insert_target(shorten(target))};
    if (action == QueueAction::Replace && !queued_run(target))
        return Refusal{Completion::BadSyntax, texts::unknown_target(shorten(target))};
    if (auto denied = authorize(cmd->cmd_src, cmd->subsystem, checked.ref))
        return Refusal{Completion::BadSyntax, *denied};
    if ((action == QueueAction::Append || action == QueueAction::Insert) && pending_.size() >= options_.queue_limit)
        return Refusal{Completion::ExecFailed, texts::queue_full(static_cast<long long>(options_.queue_limit))};
    if (action == QueueAction::Bypass && bypass_.size() >= options_.bypass_limit)
        return Refusal{Completion::ExecFailed, texts::bypass_full(static_cast<long long>(options_.bypass_limit))};

    auto run = std::make_shared<Run>();
    run->cmd = cmd;
    run->ref = checked.ref;
    run->queued = action != QueueAction::Bypass;
    if (action == QueueAction::Bypass) {
        start(run);
        return std::nullopt;
    }
    if (action == QueueAction::Replace) {
        RunPtr old = queued_run(target);
        if (old == active_) {
            if (!old->abortable())
                return Refusal{Completion::ExecFailed, texts::target_not_abortable(shorten(target))};
            cancel(old);
            pending_.push_front(run);
        } else {
            pending_.replace(target, run);
            finish_unstarted(old, texts::replaced_by(shorten(cmd->cmd_id)));
        }
    } else if (action == QueueAction::Insert) {
        if (!pending_.insert_after(target, run)) pending_.push_front(run);  // the running command: go next
    } else {
        pending_.append(run);
    }
    send_ack(*cmd, AckStatus::Queued, Completion::Not, "");
    service();
    return std::nullopt;
}

bool CommandManager::live(const std::string& cmd_id) const {
    if (queued_run(cmd_id)) return true;
    return std::any_of(bypass_.begin(), bypass_.end(), [&](const RunPtr& r) { return r->id() == cmd_id; });
}

RunPtr CommandManager::queued_run(const std::string& cmd_id) const {
    if (active_ && active_->id() == cmd_id) return active_;
    return pending_.find(cmd_id);
}

std::optional<std::string> CommandManager::authorize(const std::string& source, const std::string& subsystem,
                                                     const CommandRef& ref) const {
    const std::string& type = ref.type->name;
    const std::string& name = ref.spec->name;
    if (always_allowed(type, name) && !BROKEN(stop_needs_control)) return std::nullopt;
    if (!allowed(tables_.access, source, subsystem, name))
        return texts::access_not_allowed(shorten(source), shorten(subsystem), shorten(name));
    if (has_control_ && !BROKEN(no_control_gate) && type != "AccessControl" && source != tables_.name &&
        !control_.holds(source))
        return texts::access_no_control(shorten(source));
    return std::nullopt;
}

std::optional<CommandManager::Refusal> CommandManager::remove_target(const std::shared_ptr<const Cmd>& cmd) {
#ifdef RAPID_RUNTIME_TEST_BREAKS
    if (options_.breaks.delete_wrong_command && active_ && active_->id() != cmd->target && queued_run(cmd->target)) {
        auto head = std::make_shared<Cmd>(*cmd);  // the running command canceled instead
        head->target = active_->id();
        return remove_target(head);
    }
#endif
    RunPtr target = queued_run(cmd->target);
    if (!target)
        for (const auto& r : bypass_)
            if (r->id() == cmd->target) target = r;
    if (!target)
        return Refusal{Completion::BadSyntax, texts::unknown_target(shorten(cmd->target))};
    // The DELETE's sender must be allowed to send the target's command.
    if (auto denied = authorize(cmd->cmd_src, target->cmd->subsystem, target->ref))
        return Refusal{Completion::BadSyntax, *denied};
    bool running = false;
    if (pending_.contains(target)) {
        pending_.remove(target);
        finish_unstarted(target, texts::deleted_by(shorten(cmd->cmd_id)));
    } else if (!target->abortable()) {
        return Refusal{Completion::ExecFailed, texts::target_not_abortable(shorten(cmd->target))};
    } else {
        running = !target->done;
        cancel(target);
    }
    send_ack(*cmd, AckStatus::Executing, Completion::Not, "");
    // a running target's handler is only asked: its own final ack follows when it returns
    // (CANCELED) or when its stop bound passes (EXEC_FAILED "handler did not stop")
    send_ack(*cmd, AckStatus::Completed, Completion::Ok,
             running ? texts::cancel_requested(shorten(cmd->target)) : texts::target_canceled(shorten(cmd->target)));
    service();
    return std::nullopt;
}

// ---- running ------------------------------------------------------------------------------

bool CommandManager::busy(const std::string& subsystem) const {
    return std::any_of(bypass_.begin(), bypass_.end(),
                       [&](const RunPtr& r) { return r->cmd->subsystem == subsystem && !r->done; });
}

void CommandManager::service() {
#ifdef RAPID_RUNTIME_TEST_BREAKS
    if (options_.breaks.queue_lifo || options_.breaks.queue_parallel) return broken_service(false);
#endif
    while (!active_ && !suspended_) {
        RunPtr run = pending_.pop_ready([this](const std::string& s) { return busy(s); });
        if (!run) break;
        active_ = run;
        start(run);
    }
    publish_queue();
    idle_.notify_all();
}

void CommandManager::start(const RunPtr& run) {
    if (!run->queued) preempt(run);
    send_ack(*run->cmd, AckStatus::Executing, Completion::Not, "");
    run->record_status = RecordStatus::InProcess;
    if (auto outcome = builtin(run)) {
        complete(run, outcome->completion, outcome->message);
        return;
    }
    if (!run->queued) bypass_.push_back(run);
    std::weak_ptr<Run> weak = run;
    if (run->ctx) run->past.push_back(run->ctx);  // (a preempted run's: a helper may still hold it)
    run->ctx = std::make_shared<CommandContext>(run->cmd, run->ref, [alive = alive_, weak](const std::string& text) {
        std::shared_lock<std::shared_mutex> hold(alive->mutex);  // the manager stays while this runs
        if (alive->manager == nullptr) return;
        if (auto r = weak.lock()) alive->manager->progress(r, text);
    });
    run->handling = true;
    ++handling_;
    // started with the acks, after the journal's sync: a handler never moves hardware for a
    // command whose "running" step a power cut could still erase
    emit([this, run] { workers_.spawn([this, run, ctx = run->ctx] { execute(run); }); });
}

void CommandManager::preempt(const RunPtr& run) {
    if (builtin_command(run->ref)) return;  // the protocol's own commands take nothing over
    std::vector<RunPtr> others(bypass_);
    if (active_) others.insert(others.begin(), active_);
    for (const auto& other : others) {
        if (other->done || other->cmd->subsystem != run->cmd->subsystem || !other->ctx) continue;
        if (other->queued && other->ref.spec->suspendable) {
            other->requeue = true;
            tell_stop(other);
        } else if (other->abortable()) {
            tell_stop(other);
        }
    }
}

void CommandManager::execute(const RunPtr& run) {
    std::shared_ptr<CommandContext> ctx;
    {
        Lock lock(mutex_);
        ctx = run->ctx;
    }
    Completion completion = Completion::Ok;
    std::string message;
    std::string error;  // a handler's exception, for the log
    bool unwritten = false;  // the handler is the stub (stopAllMotion's answer says so)
    try {
        Result result = handlers_.execute(*ctx);
        unwritten = result.is_not_implemented();
        switch (result.completion) {
            case Completion::Ok:
                if (ctx->cancelled()) {
                    completion = Completion::Canceled;
                    message = texts::CANCELED;
                } else {
                    message = result.message;
                }
                break;
            case Completion::Canceled:
                completion = Completion::Canceled;
                message = result.message.empty() ? texts::CANCELED : result.message;
                break;
            case Completion::BadSyntax:  // a handler may judge the arguments itself (Astrobee does)
            case Completion::ExecFailed:
                completion = result.completion;
                message = result.message.empty() ? texts::FAILED : result.message;
                break;
            case Completion::Not:
                completion = Completion::ExecFailed;
                message = texts::NO_COMPLETION;
                break;
        }
    } catch (const Cancelled&) {
        completion = Completion::Canceled;
        message = texts::CANCELED;
    } catch (const CommandFailed& e) {
        completion = Completion::ExecFailed;
        message = *e.what() ? e.what() : texts::FAILED;
    } catch (const std::exception& e) {  // a handler's bug must not stop the bridge; the commander hears of it
        completion = Completion::ExecFailed;
        message = texts::handler_error(type_name(e), e.what());
        error = message;
    } catch (...) {
        completion = Completion::ExecFailed;
        message = texts::HANDLER_ERROR_UNKNOWN;
        error = message;
    }
    Batch batch(*this);
    run->handling = false;
    --handling_;
    stopping_.erase(std::remove(stopping_.begin(), stopping_.end(), run), stopping_.end());
    bypass_.erase(std::remove(bypass_.begin(), bypass_.end(), run), bypass_.end());
    idle_.notify_all();
    if (closed_) return;  // shut down: nothing is written any more
    if (!error.empty()) out_.log(what(run) + ": " + visible(error));  // once, with the command
    if (run->done) return;  // answered already (its stop bound passed, the bridge stopping): nothing follows a COMPLETED
    if (is(run, "Mobility", "stopAllMotion") && builtin_command(run->ref)) {
        // the runtime has canceled the motion commands; the handler stops the hardware
        if (unwritten) {
            completion = Completion::Ok;
            message = texts::NO_HARDWARE_STOP;
        }
        std::size_t moving = 0;
        for (const auto& weak : run->stopped)
            if (auto r = weak.lock(); r && !r->done) ++moving;
        if (moving) message += "; " + texts::motion_not_stopped(static_cast<long long>(moving));
    }
    if (run->requeue && completion == Completion::Canceled) {
        run->requeue = false;
        run->done = false;
        run->stopping = false;
        run->ctx->close();
        send_ack(*run->cmd, AckStatus::Requeued, Completion::Not, texts::PREEMPTED);
        run->record_status = RecordStatus::Paused;
        if (active_ == run) active_.reset();
        pending_.push_front(run);
    } else {
        complete(run, completion, message);
    }
    service();
}

void CommandManager::progress(const RunPtr& run, const std::string& text) {
    Batch batch(*this);
    if (!run->done && !closed_ && run->ctx && !run->ctx->done())
        send_ack(*run->cmd, AckStatus::Executing, Completion::Not, text);
}

void CommandManager::complete(const RunPtr& run, Completion completion, const std::string& message, bool suspend) {
    run->done = true;
    if (run->ctx) {  // calls on it from now on are no-ops; it stays valid a while (FINAL_ACKS_KEPT)
        run->ctx->close();
        contexts_kept_.push_back(run->ctx);
        while (contexts_kept_.size() > FINAL_ACKS_KEPT) contexts_kept_.pop_front();
    }
    send_ack(*run->cmd, AckStatus::Completed, completion, message);
    if (shutdown_after_ == run && options_.on_shutdown)  // once its COMPLETED ack is written
        emit([this] { workers_.spawn(options_.on_shutdown); });
    if (run->queued) {
        if (active_ == run) active_.reset();
        record_done(run, completion);
        // a failed step stops the plan (cancelAll resumes); not one the operator told to stop
        if (completion == Completion::ExecFailed && suspend) suspended_ = true;
    }
    idle_.notify_all();
}

void CommandManager::finish_unstarted(const RunPtr& run, const std::string& why) {
    run->done = true;
    send_ack(*run->cmd, AckStatus::Completed, Completion::Canceled, why);
    record_done(run, Completion::Canceled);
}

void CommandManager::record_done(const RunPtr& run, Completion completion) {
    completed_.push_back({options_.clock(), run, completion});
    while (completed_.size() > RECORDS) completed_.pop_front();
}

void CommandManager::cancel(const RunPtr& run) {
    if (run->ctx) {
        run->requeue = false;
        tell_stop(run);
    }
}

int CommandManager::stop_bound_ms(const RunPtr& run) const {
    int declared = run->ref.spec != nullptr ? run->ref.spec->stop_timeout_ms : 0;
    return declared > 0 ? declared : options_.stop_timeout_ms;
}

void CommandManager::tell_stop(const RunPtr& run) {
    if (!run->ctx || run->done) return;
    run->ctx->cancel();
    if (run->stopping || !run->handling) return;  // (its bound runs already)
    run->stopping = true;
    run->stop_by = std::chrono::steady_clock::now() + std::chrono::milliseconds(stop_bound_ms(run));
    stopping_.push_back(run);
    watch_.notify_all();
}

std::string CommandManager::what(const RunPtr& run) const {
    return "'" + visible(run->id()) + "' (" + visible(run->cmd->subsystem) + "/" + visible(run->cmd->name) + ")";
}

void CommandManager::watch() {
    using Clock = std::chrono::steady_clock;
    Lock lock(mutex_);
    while (!closing_ && !closed_) {
        auto next = Clock::time_point::max();
        std::vector<RunPtr> late;
        const auto now = Clock::now();
        for (const auto& r : stopping_) {
            if (r->stop_by <= now) late.push_back(r);
            else next = std::min(next, r->stop_by);
        }
        if (!late.empty()) {
            Batch batch(*this);  // (the journal synced before these acks)
            for (const auto& r : late) {
                stopping_.erase(std::remove(stopping_.begin(), stopping_.end(), r), stopping_.end());
                if (!r->done && r->handling) give_up(r);
            }
            continue;
        }
        if (next == Clock::time_point::max()) watch_.wait(lock);
        else watch_.wait_until(lock, next);
    }
}

void CommandManager::give_up(const RunPtr& run) {
    // The handler runs on (a thread cannot be stopped from outside); the command is answered
    // and leaves the queue, and whatever the handler returns later is ignored.
    out_.log(what(run) + ": handler did not stop within " + std::to_string(stop_bound_ms(run)) +
             " ms of being told to stop; answered EXEC_FAILED \"" + texts::DID_NOT_STOP +
             "\". Its handler still runs: the robot must stop it in hardware");
    run->requeue = false;
    bypass_.erase(std::remove(bypass_.begin(), bypass_.end(), run), bypass_.end());
    complete(run, Completion::ExecFailed, texts::DID_NOT_STOP, false);
    service();
}

// ---- state topics -------------------------------------------------------------------------

void CommandManager::send_ack(const Cmd& cmd, AckStatus status, Completion completion, const std::string& message,
                              bool journal) {
    std::string text = outgoing(message);  // valid UTF-8, no NUL, within Ack.message's bound
    if (journal_ != nullptr && journal) {  // the step the ack promises, recorded first
        char step = status == AckStatus::Queued      ? 'q'
                    : status == AckStatus::Executing ? 'x'
                    : status == AckStatus::Completed ? 'c'
                                                     : '\0';
        if (step != '\0') {
            bool c = step == 'c';
            journal_->note(JournalEntry{cmd.cmd_id, cmd.src_name, cmd.asset_name, cmd.serial, step,
                                        c ? std::string(name_of(completion)) : std::string(), c ? text : std::string()});
        }
    }
    if (journal_ != nullptr && depth_ > 0)
        outgoing_.push_back([this, key = key_of(cmd), status, completion, text] { write_ack(key, status, completion, text); });
    else
        write_ack(cmd, status, completion, text);
    if (status == AckStatus::Completed) {
        keep(key_of(cmd));  // each command's last ack
        if (journal) store_final(cmd, completion, text);
    }
}

void CommandManager::write_ack(const Cmd& cmd, AckStatus status, Completion completion, const std::string& message) {
    out_.ack(cmd, status, completion, message);
}

void CommandManager::store_final(const Cmd& cmd, Completion completion, const std::string& message) {
    auto [it, added] = finals_.insert_or_assign(cmd.cmd_id, Final{key_of(cmd), completion, message});
    (void)it;
    if (added) finals_order_.push_back(cmd.cmd_id);
    while (finals_order_.size() > FINAL_ACKS_KEPT) {
        finals_.erase(finals_order_.front());
        finals_order_.pop_front();
    }
}

void CommandManager::keep(Cmd key) {
    // keep the last `window` commands' acks
    acked_.push_back(std::move(key));
    while (acked_.size() > options_.window) {
        Cmd old = std::move(acked_.front());
        acked_.pop_front();
        if (live(old.cmd_id)) continue;  // (its id sent again after the window, and still running)
        emit([this, old = std::move(old)] { out_.retire(old); });
    }
}

void CommandManager::publish_queue() {
    if (!has_queue_) return;
    double now = options_.clock();
    while (!completed_.empty() && now - completed_.front().at > COMPLETED_KEEP_S) completed_.pop_front();
    std::vector<Record> pending, active, done;
    for (const auto& r : pending_.items()) {
        if (pending.size() >= RECORDS) break;
        pending.push_back({r->cmd, RecordResult::Init, r->record_status});
    }
    if (active_) active.push_back({active_->cmd, RecordResult::Init, RecordStatus::InProcess});
    for (const auto& d : completed_) done.push_back({d.run->cmd, result_of(d.completion), status_of(d.completion)});
    int code = suspended_ ? -1 : active_ ? 1 : 0;
    if (journal_ != nullptr && depth_ > 0)
        outgoing_.push_back([this, code, pending = std::move(pending), active = std::move(active),
                             done = std::move(done)] { out_.queue_state(code, pending, active, done); });
    else
        out_.queue_state(code, pending, active, done);
}

void CommandManager::publish_access() {
    emit([this, controller = control_.controller(), requestors = control_.requestors()] {
        out_.access_state(controller, requestors);
    });
}

std::pair<std::size_t, std::size_t> CommandManager::restore(const JournalRecovered& recovered) {
    Batch batch(*this);
    for (const auto& e : recovered.finished) {
        Cmd key = entry_cmd(e);
        remember(e.cmd_id);
        emit([this, key, completion = completion_named(e.completion), message = e.message] {
            write_ack(key, AckStatus::Completed, completion, message);
        });
        store_final(key, completion_named(e.completion), e.message);
        keep(std::move(key));
    }
    for (const auto& e : recovered.unfinished) {
        remember(e.cmd_id);
        bool queued = e.state == 'q';
        send_ack(entry_cmd(e), AckStatus::Completed, queued ? Completion::Canceled : Completion::ExecFailed,
                 queued ? texts::RESTARTED_QUEUED : texts::RESTARTED_RUNNING);
    }
    return {recovered.unfinished.size(), recovered.finished.size()};
}

std::size_t CommandManager::abandon() { return shut_down().answered; }

CommandManager::ShutDown CommandManager::shut_down(int timeout_ms) {
    using Clock = std::chrono::steady_clock;
    ShutDown out;
    auto running = [this] {
        std::vector<RunPtr> runs(bypass_);
        if (active_) runs.insert(runs.begin(), active_);
        runs.erase(std::remove_if(runs.begin(), runs.end(), [](const RunPtr& r) { return r->done; }), runs.end());
        return runs;
    };
    {
        Batch batch(*this);
        if (closed_) return {0, handling_};
        suspended_ = true;  // nothing starts any more
        std::vector<RunPtr> waiting(pending_.items().begin(), pending_.items().end());
        for (const auto& r : waiting) {
            pending_.remove(r);
            r->done = true;
            send_ack(*r->cmd, AckStatus::Completed, Completion::Canceled, texts::ASSET_SHUTTING_DOWN);
            ++out.answered;
        }
        for (const auto& r : running()) {
            ++out.answered;  // (answered when its handler returns, or below)
            r->requeue = false;
            if (r->ctx) r->ctx->cancel();  // (the shutdown bound, not each command's stop bound)
        }
        publish_queue();
    }
    const int bound = timeout_ms < 0 ? options_.shutdown_timeout_ms : timeout_ms;
    const auto end = Clock::now() + std::chrono::milliseconds(bound);
    {
        Lock lock(mutex_);
        while (!running().empty() && Clock::now() < end)
            idle_.wait_until(lock, std::min(end, Clock::now() + std::chrono::milliseconds(50)));
    }
    Batch batch(*this);
    for (const auto& r : running()) {
        out_.log(what(r) + ": handler did not stop within the shutdown bound (" + std::to_string(bound) +
                 " ms); answered EXEC_FAILED \"" + texts::DID_NOT_STOP + "\". The robot must stop it in hardware");
        complete(r, Completion::ExecFailed, texts::DID_NOT_STOP, false);
    }
    active_.reset();
    bypass_.clear();
    stopping_.clear();
    publish_queue();
    closed_ = true;  // (what this batch holds back still goes out at its end, after the journal's sync)
    watch_.notify_all();
    idle_.notify_all();
    out.running = handling_;
    return out;
}

std::size_t CommandManager::handlers_running() const {
    Lock lock(mutex_);
    return handling_;
}

Journal* CommandManager::release_journal() {
    Batch batch(*this);  // (what a batch holds back goes out first)
    flush();
    Journal* j = journal_;
    journal_ = nullptr;
    return j;
}

void CommandManager::publish_states() {
    Batch batch(*this);
    publish_queue();
    if (has_control_) publish_access();
}

bool CommandManager::wait_idle(double timeout_s) {
    using Clock = std::chrono::steady_clock;
    auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s));
    Lock lock(mutex_);
    while (active_ || !bypass_.empty() || !pending_.empty()) {
        Clock::duration left = end - Clock::now();
        if (left <= Clock::duration::zero() || (suspended_ && !active_ && bypass_.empty()))
            return !active_ && bypass_.empty();
        idle_.wait_for(lock, std::min<Clock::duration>(left, std::chrono::milliseconds(50)));
    }
    return true;
}

// ---- built-in commands: the protocol's own ------------------------------------------------

std::optional<Result> CommandManager::builtin(const RunPtr& run) {
    if (!builtin_command(run->ref)) return std::nullopt;
    const auto& args = run->cmd->args;
    if (is(run, "Admin", "echo")) return Result::ok(args.empty() ? "" : str(args[0]));
    if (is(run, "Admin", "noOp")) return Result::ok();
    if (is(run, "Admin", "shutdown")) {
        shutdown_after_ = run;  // once its COMPLETED ack is out
        return Result::ok(texts::SHUTTING_DOWN);
    }
    if (is(run, "Queue", "cancelAll")) return cancel_all(run);
    if (is(run, "Mobility", "stopAllMotion")) {
        stop_all_motion(run);
        return std::nullopt;  // the handler then stops the hardware
    }
    if (run->ref.type->name == "AccessControl") {
        const std::string& src = run->cmd->cmd_src;
        const std::string& name = run->ref.spec->name;
        Control::Outcome done;
#ifdef RAPID_RUNTIME_TEST_BREAKS
        if (auto broken = broken_control(src, name)) return broken;
#endif
        if (name == "requestControl") done = control_.request(src);
        else if (name == "grabControl") done = control_.grab(src);
        else if (name == "releaseControl") done = control_.release(src);
        else done = control_.transfer(src, args.empty() ? "" : str(args[0]));
        if (done.ok) publish_access();
        return done.ok ? Result::ok(done.text) : Result::failed(done.text);
    }
    return std::nullopt;
}

Result CommandManager::cancel_all(const RunPtr& run) {
    std::vector<RunPtr> waiting(pending_.items().begin(), pending_.items().end());
    for (const auto& r : waiting) {
        pending_.remove(r);
        finish_unstarted(r, texts::CANCELED_BY_CANCEL_ALL);
    }
    std::vector<RunPtr> running(bypass_);
    if (active_) running.insert(running.begin(), active_);
    int kept = 0;
    int asked = 0;
    for (const auto& r : running) {
        if (r == run || r->done) continue;
        if (r->abortable()) {
            if (r->ctx && r->handling) ++asked;  // (each still running: its handler holds the lock's next turn)
            cancel(r);
        } else {
            ++kept;
        }
    }
    suspended_ = false;
    publish_queue();  // whatever the queue's state was (a suspended one included)
    std::string text;
    if (asked) text = texts::handlers_asked_to_stop(asked);
    if (kept) text += (text.empty() ? "" : "; ") + texts::non_abortable_running(kept);
    return Result::ok(text);
}

void CommandManager::stop_all_motion(const RunPtr& run) {
    // Motion stops first (every Mobility command canceled, abortable or not), then the
    // handler stops the hardware.
    auto mobility = tables_.subsystems_of_type("Mobility");
    auto moving = [&](const RunPtr& r) {
        return std::find(mobility.begin(), mobility.end(), r->cmd->subsystem) != mobility.end();
    };
    std::vector<RunPtr> waiting(pending_.items().begin(), pending_.items().end());
    for (const auto& r : waiting) {
        if (!moving(r)) continue;
        pending_.remove(r);
        finish_unstarted(r, texts::CANCELED_BY_STOP_ALL_MOTION);
    }
    std::vector<RunPtr> running(bypass_);
    if (active_) running.insert(running.begin(), active_);
    for (const auto& r : running) {
        if (r == run || !moving(r) || r->done) continue;
        cancel(r);
        run->stopped.push_back(r);  // (its answer says how many have not stopped when it completes)
    }
    publish_queue();
}

#ifdef RAPID_RUNTIME_TEST_BREAKS
std::optional<Result> CommandManager::broken_control(const std::string& src, const std::string& name) {
    const ManagerBreaks& b = options_.breaks;
    Control::Outcome done;
    bool publish = true;
    if (name == "requestControl" && (b.request_steals_control || b.request_unpublished)) {
        done = b.request_steals_control ? control_.grab(src) : control_.request(src);
        publish = !b.request_unpublished;
    } else if (name == "grabControl" && (b.grab_refused || b.grab_unpublished)) {
        if (b.grab_refused && !control_.controller().empty() && control_.controller() != src)
            return Result::failed("control is held by " + control_.controller());
        done = control_.grab(src);
        publish = !b.grab_unpublished;
    } else if (name == "releaseControl" && b.release_by_anyone) {
        done = control_.release(control_.controller());  // on behalf of whoever holds it
    } else {
        return std::nullopt;
    }
    if (done.ok && publish) publish_access();
    return done.ok ? Result::ok(done.text) : Result::failed(done.text);
}

void CommandManager::broken_service(bool tick) {
    if (options_.breaks.queue_parallel) {
        // each waiting command started at once, none waiting for the one before; kept among
        // the bypass commands, where cancelAll and stopAllMotion still reach it
        while (!suspended_ && !pending_.empty()) {
            RunPtr run = pending_.items().front();
            pending_.remove(run);
            active_ = run;
            start(run);
            if (!run->done && std::find(bypass_.begin(), bypass_.end(), run) == bypass_.end()) bypass_.push_back(run);
        }
    } else if (tick) {  // queue-lifo: the tick starts the newest waiting command
        while (!active_ && !suspended_ && !pending_.empty() && !busy(pending_.items().back()->cmd->subsystem)) {
            RunPtr run = pending_.items().back();
            pending_.remove(run);
            active_ = run;
            start(run);
        }
    }
    publish_queue();
    idle_.notify_all();
}
#endif

// ---- what tests look at ---------------------------------------------------------------------

std::vector<std::string> CommandManager::pending_ids() const {
    Lock lock(mutex_);
    std::vector<std::string> ids;
    for (const auto& r : pending_.items()) ids.push_back(r->id());
    return ids;
}

std::size_t CommandManager::pending_count() const {
    Lock lock(mutex_);
    return pending_.size();
}

bool CommandManager::suspended() const {
    Lock lock(mutex_);
    return suspended_;
}

std::string CommandManager::controller() const {
    Lock lock(mutex_);
    return control_.controller();
}

std::vector<std::string> CommandManager::requestors() const {
    Lock lock(mutex_);
    return control_.requestors();
}

std::size_t CommandManager::remembered() const {
    Lock lock(mutex_);
    return seen_.size();
}

std::vector<std::string> CommandManager::acks_kept() const {
    Lock lock(mutex_);
    std::vector<std::string> ids;
    for (const auto& c : acked_) ids.push_back(c.cmd_id);
    return ids;
}

}  // namespace rapid_runtime
