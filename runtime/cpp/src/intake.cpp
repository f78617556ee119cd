#include "rapid_runtime/intake.hpp"

#include "rapid_runtime/text.hpp"
#include "rapid_runtime/texts.hpp"

namespace rapid_runtime {

std::string busy_message(std::size_t per_writer) {
    return texts::bridge_busy(static_cast<long long>(per_writer));
}

Intake::Intake(CommandSink& sink, std::function<void(const std::string&)> log, std::size_t per_writer,
               std::size_t shed_answers)
    : sink_(sink), log_(std::move(log)), per_writer_(per_writer), shed_limit_(shed_answers) {}

Intake::~Intake() { stop(); }

void Intake::start() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!thread_.joinable() && !stopping_) thread_ = std::thread([this] { run(); });
}

void Intake::stop() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable() && thread_.get_id() != std::this_thread::get_id()) thread_.join();
}

// ---- the reader thread ----------------------------------------------------------------------

void Intake::offer(Cmd cmd, const std::string& in_writer) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!stopping_ && !working_ && fifos_.empty() && shed_.empty() && thread_.joinable() &&
        sink_.answers_at_once(cmd)) {
        // Nothing waits before it and the sink answers it at once: handed over here, without
        // waking the worker (one thread handoff less; bench/README.md, the C++ bridge).
        working_ = true;
        lock.unlock();
        const std::string id = cmd.cmd_id;
        try {
            hand_over({std::move(cmd), false});
        } catch (...) {  // (the sink's batch calls do not throw; the door must stay open if one did)
            log_("command '" + id + "' not handled: its batch failed");
        }
        lock.lock();
        working_ = false;
        if (!fifos_.empty() || !shed_.empty() || stopping_) wake_.notify_all();
        return;
    }
    std::string writer = in_writer;
    auto found = index_.find(writer);
    if (found == index_.end() && fifos_.size() >= MAX_WRITERS) {
        writer = SHARED_WRITER;
        found = index_.find(writer);
    }
    std::deque<Cmd>* fifo = found == index_.end() ? nullptr : &found->second->second;
    if (fifo == nullptr || fifo->size() < per_writer_) {
        if (fifo == nullptr) {
            fifos_.emplace_back(writer, std::deque<Cmd>());
            index_[writer] = std::prev(fifos_.end());
            fifo = &fifos_.back().second;
        }
        fifo->push_back(std::move(cmd));
    } else if (shed_.size() < shed_limit_) {
        shed_.push_back(std::move(cmd));
        if (++shed_count_[writer] == 1)
            log_("writer " + visible(writer) + " floods: " + std::to_string(per_writer_) +
                 " commands waiting; answering its next ones 'bridge busy' (counted, not logged)");
    } else if (++unanswered_[writer] == 1) {
        log_("writer " + visible(writer) + " floods past " + std::to_string(shed_limit_) +
             " busy answers: dropping its commands unanswered (counted, not logged)");
    }
    wake_.notify_one();
}

std::size_t Intake::waiting() const {
    std::lock_guard<std::mutex> lock(mutex_);
    std::size_t n = shed_.size();
    for (const auto& f : fifos_) n += f.second.size();
    return n;
}

std::size_t Intake::unanswered(const std::string& writer) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = unanswered_.find(writer);
    return it == unanswered_.end() ? 0 : it->second;
}

std::size_t Intake::shed(const std::string& writer) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = shed_count_.find(writer);
    return it == shed_count_.end() ? 0 : it->second;
}

// ---- the worker -----------------------------------------------------------------------------

Intake::Fifos::iterator Intake::control_writer() {
    for (auto it = fifos_.begin(); it != fifos_.end(); ++it)
        if (sink_.is_control(it->second.front())) return it;
    return fifos_.end();
}

bool Intake::next(std::unique_lock<std::mutex>& lock, Next& out) {
    while (!stopping_) {
        if (working_) {  // (a command handed over by offer(): the next ones come after it)
            wake_.wait(lock);
            continue;
        }
        auto writer = control_writer();
        if (writer == fifos_.end()) {
            if (!shed_.empty() && (shed_turn_ || fifos_.empty())) {
                shed_turn_ = false;  // busy answers take turns with real commands
                out = {std::move(shed_.front()), true};
                shed_.pop_front();
                return true;
            }
            writer = fifos_.begin();
        }
        if (writer != fifos_.end()) {
            shed_turn_ = true;
            out = {std::move(writer->second.front()), false};
            writer->second.pop_front();
            if (writer->second.empty()) {
                index_.erase(writer->first);
                fifos_.erase(writer);
            } else {
                fifos_.splice(fifos_.end(), fifos_, writer);  // to the back of the round
            }
            return true;
        }
        wake_.wait(lock);
    }
    return false;
}

void Intake::run() {
    std::vector<Next> batch;
    for (;;) {
        batch.clear();
        {
            std::unique_lock<std::mutex> lock(mutex_);
            Next got{Cmd{}, false};
            if (!next(lock, got)) return;
            batch.push_back(std::move(got));
            // what is waiting already goes in one manager batch: one journal sync
            while (batch.size() < BATCH && (!fifos_.empty() || !shed_.empty()) && next(lock, got))
                batch.push_back(std::move(got));
            working_ = true;  // offer() hands nothing over until this batch is answered
        }
        sink_.begin_batch();
        for (auto& got : batch) hand_over_one(got);
        sink_.end_batch();
        {
            std::lock_guard<std::mutex> lock(mutex_);
            working_ = false;
        }
    }
}

void Intake::hand_over(Next got) {
    sink_.begin_batch();
    hand_over_one(got);
    sink_.end_batch();
}

void Intake::hand_over_one(Next& got) {
    try {
        if (got.shed) sink_.refuse(got.cmd, busy_message(per_writer_));
        else sink_.receive(got.cmd);
    } catch (const std::exception& e) {  // a bad command must not stop intake
        log_("command '" + got.cmd.cmd_id + "' not handled: " + e.what());
    }
}

}  // namespace rapid_runtime
