// fastdds_ping: a bare Fast DDS 2.9 round trip with the RAPID Command and Ack types, the
// floor under K10's C++ bridge in bench/cpp_bridge.py. No runtime above Fast DDS: no
// intake, manager, dictionary or client bookkeeping; the same participant and endpoint
// setup as the bridge and rapid_cmd (the runtime's Node, K10's built-in profiles with
// rapid_local: 127.0.0.1 only; the command writer and ack reader as rapid_cmd sets them
// up, the command reader and ack writer as the bridge does).
//
//   fastdds_ping pong --domain D [--acks 1|2]
//       answers each Command with its Ack(s) from the reader's listener (Fast DDS's
//       receive thread), as the bridge's intake hand-over does: --acks 2 writes EXECUTING
//       then COMPLETED (a BYPASS echo's two), 1 only COMPLETED. Prints "pong ready";
//       runs until SIGTERM/SIGINT.
//   fastdds_ping ping --domain D [--count N] [--warmup W] [--wait main|listener]
//       N sequential round trips, write() to the final (COMPLETED) ack taken; prints one
//       JSON line {"count", "answered", "p50_us", "p99_us", "max_us", "per_s"}.
//       --wait main (default): the main thread writes and sleeps on a condition variable
//       the listener signals (rapid_cmd's shape); listener: the listener that takes the
//       final ack writes the next command (one thread, no wake-up in the client: ddsperf
//       ping's shape), its command writer KEEP_LAST 1 (see Ping::Ping).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <unistd.h>
#include <vector>

#include <fastdds/dds/core/status/PublicationMatchedStatus.hpp>
#include <fastdds/dds/core/status/SubscriptionMatchedStatus.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include <rapid_runtime/dds/node.hpp>

namespace rapid_k10red::bridge {
extern const ::std::string_view PROFILES_XML;  // (K10's generated bridge/profiles.cpp)
}

namespace {

using namespace eprosima::fastdds::dds;
using rapid_runtime::dds::Node;
using rapid_runtime::dds::NodeOptions;
using Clock = std::chrono::steady_clock;

constexpr const char* COMMAND_TOPIC = "rapid_command";
constexpr const char* ACK_TOPIC = "rapid_ack";
constexpr const char* ASSET = "K10Red";

std::atomic<bool> stop{false};
extern "C" void on_signal(int) { stop = true; }

std::int64_t now_us() {
    return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

std::unique_ptr<Node> node(int domain) {
    NodeOptions o;
    o.domain = domain;
    o.profiles_xml = std::string(rapid_k10red::bridge::PROFILES_XML);
    o.transport = "local";
    o.partition = ASSET;
    return std::make_unique<Node>(o);
}

// ---- pong: the bridge's endpoints, nothing between them ----------------------------------

class Pong : public DataReaderListener {
public:
    Pong(int domain, int acks) : acks_(acks), node_(node(domain)) {
        // as Bridge::start(): the ack writer first, then the command reader
        writer_ = node_->writer<::rapid::Ack>(ACK_TOPIC, "RapidReliableDurableQos", [](DataWriterQos& q) {
            q.reliable_writer_qos().times.heartbeatPeriod = eprosima::fastrtps::Duration_t(0, 100'000'000);
            rapid_runtime::dds::quiet_nack_suppression(q);
            q.history().kind = KEEP_LAST_HISTORY_QOS;
            q.history().depth = 8;
            q.resource_limits().max_samples_per_instance = 8;
        });
        reader_ = node_->reader<::rapid::Command>(COMMAND_TOPIC, "RapidReliableQos", {}, this);
    }
    ~Pong() override {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            open_ = false;
        }
        node_.reset();
    }

    void on_data_available(DataReader* reader) override {
        std::lock_guard<std::mutex> lock(mutex_);
        SampleInfo info;
        while (open_ && reader->take_next_sample(&command_, &info) == ReturnCode_t::RETCODE_OK) {
            if (!info.valid_data) continue;
            ack_.hdr = command_.hdr;
            ack_.cmdId = command_.cmdId;
            ack_.message.clear();
            if (acks_ > 1) {
                ack_.hdr.timeStamp = now_us();
                ack_.status = ::rapid::AckStatus::ACK_EXECUTING;
                ack_.completedStatus = ::rapid::AckCompletedStatus::ACK_COMPLETED_NOT;
                writer_->write(&ack_);
            }
            ack_.hdr.timeStamp = now_us();
            ack_.status = ::rapid::AckStatus::ACK_COMPLETED;
            ack_.completedStatus = ::rapid::AckCompletedStatus::ACK_COMPLETED_OK;
            writer_->write(&ack_);
        }
    }

private:
    int acks_;
    std::unique_ptr<Node> node_;
    DataWriter* writer_ = nullptr;
    DataReader* reader_ = nullptr;
    std::mutex mutex_;
    bool open_ = true;
    ::rapid::Command command_;
    ::rapid::Ack ack_;
};

// ---- ping: rapid_cmd's endpoints, nothing between them -----------------------------------

class Ping : public DataReaderListener {
public:
    Ping(int domain, bool from_listener) : from_listener_(from_listener), node_(node(domain)) {
        // as Client::Client(): the ack reader, then the command writer
        reader_ = node_->reader<::rapid::Ack>(ACK_TOPIC, "RapidReliableDurableQos", [](DataReaderQos& q) {
            q.history().kind = KEEP_ALL_HISTORY_QOS;
            q.resource_limits().max_samples_per_instance = 64;
        }, this);
        writer_ = node_->writer<::rapid::Command>(COMMAND_TOPIC, "RapidReliableQos", [from_listener](DataWriterQos& q) {
            q.reliable_writer_qos().times.heartbeatPeriod =
                eprosima::fastrtps::Duration_t(0, rapid_runtime::dds::COMMAND_HEARTBEAT_NS);  // as rapid_cmd's
            q.reliability().max_blocking_time = eprosima::fastrtps::Duration_t(10, 0);
            rapid_runtime::dds::quiet_nack_suppression(q);
            // The profile's KEEP_ALL history holds 400 samples (max_samples_per_instance: Fast
            // DDS 2.9 bounds the whole history by it) until the reader acknowledges them, on
            // its next heartbeat: a write past 400 blocks until then. On the receive thread
            // that would wait for the ACKNACK this very thread must read, so a listener that
            // writes keeps one sample per instance (each command is an instance of its own:
            // nothing is replaced) and never blocks.
            if (from_listener) {
                q.history().kind = KEEP_LAST_HISTORY_QOS;
                q.history().depth = 1;
                q.resource_limits().max_samples_per_instance = 1;
            }
        });
        // an Admin/echo as rapid_cmd sends it (its size on the wire: ~300 bytes)
        command_.hdr.srcName = "RapidWorkbench";
        command_.hdr.assetName = ASSET;
        command_.cmdName = "echo";
        command_.cmdSrc = "RapidWorkbench";
        command_.subsysName = "Admin";
        ::rapid::ParameterUnion text;
        text.s("bench");
        command_.arguments.push_back(text);
        command_.cmdAction = ::rapid::QueueAction::QUEUE_BYPASS;
        prefix_ = std::to_string(::getpid()) + "-";
    }
    ~Ping() override {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            open_ = false;
        }
        node_.reset();
    }

    bool matched(double seconds) {
        const auto end = Clock::now() + std::chrono::duration<double>(seconds);
        while (Clock::now() < end) {
            PublicationMatchedStatus pub;
            SubscriptionMatchedStatus sub;
            writer_->get_publication_matched_status(pub);
            reader_->get_subscription_matched_status(sub);
            if (pub.current_count > 0 && sub.current_count > 0) return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(20));
        }
        return false;
    }

    // n round trips; their times (us) in `us`, unanswered ones left out
    void run(long n, std::vector<double>& us) {
        std::unique_lock<std::mutex> lock(mutex_);
        us_ = &us;
        total_ = n;
        index_ = 0;
        if (from_listener_) {
            send_locked();
            done_.wait_for(lock, std::chrono::seconds(10 + n / 10), [this] { return index_ >= total_; });
        } else {
            for (; index_ < total_; ++index_) {
                send_locked();
                if (!done_.wait_for(lock, std::chrono::seconds(10), [this] { return answered_; })) continue;
                us.push_back(std::chrono::duration<double, std::micro>(t_answer_ - t0_).count());
            }
        }
        total_ = 0;
    }

    void on_data_available(DataReader* reader) override {
        std::lock_guard<std::mutex> lock(mutex_);
        SampleInfo info;
        while (open_ && reader->take_next_sample(&ack_, &info) == ReturnCode_t::RETCODE_OK) {
            if (!info.valid_data || ack_.status != ::rapid::AckStatus::ACK_COMPLETED || ack_.cmdId != expected_ ||
                answered_)
                continue;
            t_answer_ = Clock::now();
            answered_ = true;
            if (!from_listener_) {
                done_.notify_one();
                continue;
            }
            us_->push_back(std::chrono::duration<double, std::micro>(t_answer_ - t0_).count());
            if (++index_ < total_) send_locked();
            else done_.notify_one();
        }
    }

private:
    void send_locked() {  // (under mutex_)
        expected_ = prefix_ + std::to_string(++counter_);
        command_.cmdId = expected_;
        answered_ = false;
        t0_ = Clock::now();
        command_.hdr.timeStamp = now_us();
        writer_->write(&command_);
    }

    bool from_listener_;
    std::unique_ptr<Node> node_;
    DataReader* reader_ = nullptr;
    DataWriter* writer_ = nullptr;
    std::mutex mutex_;
    std::condition_variable done_;
    bool open_ = true;
    ::rapid::Command command_;
    ::rapid::Ack ack_;
    std::string prefix_, expected_;
    long counter_ = 0, index_ = 0, total_ = 0;
    bool answered_ = false;
    Clock::time_point t0_, t_answer_;
    std::vector<double>* us_ = nullptr;
};

double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    auto i = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
    return v[std::min(v.size() - 1, i == 0 ? 0 : i - 1)];
}

int usage() {
    std::fprintf(stderr,
                 "usage: fastdds_ping pong --domain D [--acks 1|2]\n"
                 "       fastdds_ping ping --domain D [--count N] [--warmup W] [--wait main|listener]\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) return usage();
    const std::string mode = argv[1];
    int domain = 0, acks = 1;
    long count = 2000, warmup = 50;
    std::string wait = "main";
    for (int i = 2; i < argc; i += 2) {
        if (i + 1 >= argc) return usage();
        const std::string key = argv[i], value = argv[i + 1];
        if (key == "--domain") domain = std::atoi(value.c_str());
        else if (key == "--acks") acks = std::atoi(value.c_str());
        else if (key == "--count") count = std::atol(value.c_str());
        else if (key == "--warmup") warmup = std::atol(value.c_str());
        else if (key == "--wait") wait = value;
        else return usage();
    }
    if ((mode != "ping" && mode != "pong") || domain < 0 || domain > 232 || acks < 1 || acks > 2 || count < 1 ||
        warmup < 0 || (wait != "main" && wait != "listener"))
        return usage();
    std::signal(SIGTERM, on_signal);
    std::signal(SIGINT, on_signal);
    try {
        if (mode == "pong") {
            Pong pong(domain, acks);
            std::printf("pong ready\n");
            std::fflush(stdout);
            while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
            return 0;
        }
        Ping ping(domain, wait == "listener");
        if (!ping.matched(30)) {
            std::fprintf(stderr, "fastdds_ping: no pong matched on domain %d within 30 s\n", domain);
            return 1;
        }
        std::vector<double> us;
        if (warmup > 0) ping.run(warmup, us);  // (the first samples may wait for a heartbeat)
        us.clear();
        us.reserve(static_cast<std::size_t>(count));
        const auto start = Clock::now();
        ping.run(count, us);
        const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
        std::printf("{\"count\": %ld, \"answered\": %zu, \"p50_us\": %.1f, \"p99_us\": %.1f, \"max_us\": %.1f, "
                    "\"per_s\": %.1f}\n",
                    count, us.size(), percentile(us, 0.5), percentile(us, 0.99), percentile(us, 1.0),
                    static_cast<double>(us.size()) / seconds);
        return static_cast<long>(us.size()) == count ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fastdds_ping: %s\n", e.what());
        return 1;
    }
}
