// The ack writers: one DataWriter per generation of commands, deleted whole once all its
// commands are retired (the Python runtime's rapid_runtime/ack_writers.py, the Rust one's
// outbox).
//
// Every Ack instance (key: the command's hdr.srcName, hdr.assetName and cmdId) is new. A
// Fast DDS 2.9 writer frees an unregistered instance's kept acks one change at a time, each
// found by a linear search of the writer's whole history (~8,000 changes with the default
// window), on the receive thread that also reads the commands: 1-16 ms stalls every ~230
// commands once commands are retired (bench/README.md, issue 40). So no instance is
// unregistered: commands are dealt to writer generations of `size` commands each, all the
// acks of one command go through the writer of the generation that took it (a commander
// never sees two writers answer one command), and a generation no longer current is deleted,
// its history with it, once every command it took has been retired (manager.hpp: more than
// `window` commands completed since). At most about window/size + 2 writers live.
//
// The next generation's writer is made half a generation early, on a thread of this class's,
// so ack readers have matched it by the time it writes and the command path never waits for
// a writer to be made; old writers are deleted on that thread too.
//
// Nothing here decides what is acked or retired: the manager does. W is a writer handle
// (the bridge's DataWriter*; a test's plain value).
#ifndef RAPID_RUNTIME_DDS_ACK_WRITERS_HPP
#define RAPID_RUNTIME_DDS_ACK_WRITERS_HPP

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

namespace rapid_runtime {
namespace dds {

// As the Python runtime (bridge.py): a new writer every window/4 commands, at least every 256
// (each new writer is discovered anew by every ack reader).
inline constexpr std::size_t ACK_GENERATIONS = 4;
inline constexpr std::size_t ACK_GENERATION_MIN = 256;
inline std::size_t ack_generation_size(std::size_t window) {
    return window / ACK_GENERATIONS > ACK_GENERATION_MIN ? window / ACK_GENERATIONS : ACK_GENERATION_MIN;
}

// The ack instance's key, each part length-prefixed (no two keys share a string).
inline std::string ack_key(const std::string& src_name, const std::string& asset_name, const std::string& cmd_id) {
    std::string key;
    for (const std::string* part : {&src_name, &asset_name, &cmd_id}) key += std::to_string(part->size()) + ":" + *part;
    return key;
}

template <class W>
class AckWriters {
public:
    using Make = std::function<W()>;
    using Destroy = std::function<void(W)>;

    // Makes the first writer now (commanders wait to match it); `destroy` runs on the
    // class's thread, `make` there too except when a generation turns before its successor
    // is ready.
    AckWriters(Make make, std::size_t size, Destroy destroy)
        : make_(std::move(make)), destroy_(std::move(destroy)), size_(size) {
        if (size < 1) throw std::invalid_argument("ack writer generation size 0: at least 1");
        current_ = std::make_shared<Generation>(make_());
        created_ = 1;
        worker_ = std::thread([this] { work(); });
    }
    ~AckWriters() { close(); }
    AckWriters(const AckWriters&) = delete;
    AckWriters& operator=(const AckWriters&) = delete;

    // The writer of the command's generation (the current one for a command not seen yet).
    W writer_for(const std::string& key) {
        std::unique_lock<std::mutex> lock(mutex_);
        auto found = of_.find(key);
        if (found != of_.end()) return found->second->writer;
        if (current_->taken >= size_) {
            if (!next_ && making_) ready_.wait(lock, [this] { return !making_; });
            std::optional<W> writer = next_;
            next_.reset();
            if (!writer) writer = made(lock);
            if (writer) {  // (else the current generation grows: its acks still go out)
                auto old = current_;
                current_ = std::make_shared<Generation>(*writer);
                drop_if_done(old);
            }
        } else if (!next_ && !making_ && current_->taken >= size_ / 2) {
            making_ = true;  // the worker makes it
            jobs_.push_back(std::nullopt);
            wake_.notify_one();
        }
        auto& gen = of_[key] = current_;
        ++gen->taken;
        ++gen->live;
        return gen->writer;
    }

    // The command's acks need not be kept: forget it, and delete its generation's writer if
    // it was the last live command of a generation no longer current.
    void retire(const std::string& key) {
        std::lock_guard<std::mutex> lock(mutex_);
        auto found = of_.find(key);
        if (found == of_.end()) return;  // never written, or retired already
        auto gen = found->second;
        of_.erase(found);
        --gen->live;
        drop_if_done(gen);
    }

    // Every writer still alive, the one made early aside (stop() waits for their acks).
    std::vector<W> writers() const {
        std::lock_guard<std::mutex> lock(mutex_);
        std::vector<W> out{current_->writer};
        std::vector<const Generation*> seen{current_.get()};
        for (const auto& [key, gen] : of_) {
            (void)key;
            bool known = false;
            for (const Generation* g : seen) known = known || g == gen.get();
            if (!known) {
                seen.push_back(gen.get());
                out.push_back(gen->writer);
            }
        }
        return out;
    }

    std::size_t created() const {  // writers made so far (tests read it)
        std::lock_guard<std::mutex> lock(mutex_);
        return created_;
    }
    std::size_t deleted() const {  // old generations' writers given to the thread to delete
        std::lock_guard<std::mutex> lock(mutex_);
        return deleted_;
    }

    // The writers due for deletion deleted, the one made early too, the thread joined; the
    // live writers are left to their owner (the node deletes them with the participant).
    void close() {
        {
            std::unique_lock<std::mutex> lock(mutex_);
            if (closed_) return;
            closed_ = true;
            ready_.wait(lock, [this] { return !making_; });
            if (next_) jobs_.push_back(*next_);
            next_.reset();
            wake_.notify_one();
        }
        worker_.join();
    }

private:
    struct Generation {
        explicit Generation(W w) : writer(w) {}
        W writer;
        std::size_t taken = 0;  // commands dealt to it
        std::size_t live = 0;  // of those, not retired yet
    };

    // A writer made on the caller's thread (none was ready), or none when making it failed.
    std::optional<W> made(std::unique_lock<std::mutex>& lock) {
        std::optional<W> w;
        lock.unlock();
        try {
            w = make_();
        } catch (...) {
        }
        lock.lock();
        if (w) ++created_;
        return w;
    }

    void drop_if_done(const std::shared_ptr<Generation>& gen) {
        if (gen == current_ || gen->live != 0) return;
        jobs_.push_back(gen->writer);
        ++deleted_;
        wake_.notify_one();
    }

    // Jobs: nullopt makes the next writer, a writer is deleted.
    void work() {
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;) {
            wake_.wait(lock, [this] { return closed_ || !jobs_.empty(); });
            if (jobs_.empty()) return;  // closed, nothing left to do
            std::optional<W> job = jobs_.front();
            jobs_.pop_front();
            lock.unlock();
            std::optional<W> fresh;
            try {
                if (job) destroy_(*job);
                else fresh = make_();
            } catch (...) {  // a writer not made is made on the command path; one not deleted is memory
            }
            lock.lock();
            if (!job) {
                if (fresh) ++created_;
                if (fresh && closed_) jobs_.push_back(*fresh);
                else next_ = fresh;
                making_ = false;
                ready_.notify_all();
            }
        }
    }

    Make make_;
    Destroy destroy_;
    const std::size_t size_;
    mutable std::mutex mutex_;
    std::shared_ptr<Generation> current_;
    std::optional<W> next_;  // made early, for the next generation
    bool making_ = false;  // the worker is making next_
    std::unordered_map<std::string, std::shared_ptr<Generation>> of_;  // command key -> its generation, until retired
    std::deque<std::optional<W>> jobs_;
    std::condition_variable wake_;  // the worker: a job, or closing
    std::condition_variable ready_;  // making_ turned false
    std::size_t created_ = 0;
    std::size_t deleted_ = 0;
    bool closed_ = false;
    std::thread worker_;
};

}  // namespace dds
}  // namespace rapid_runtime

#endif
