// Setpoint streams on Fast DDS (docs/realtime.md, docs/asset-descriptor.md "Setpoint
// streams"): input streams read outside the command queue, a typed callback per sample;
// output streams written from one preallocated sample. Header-only (templates over the
// asset's types), so no build file changes with it.
//
//     rapid_runtime::dds::StreamSet streams(bridge, specs, hooks);
//     streams.read<::rapid::PositionSample>(0, [&](const ::rapid::PositionSample& s) { ... });
//     auto& out = streams.writer<::rapid::JointSample>(1);  out.sample().anglePos = ...; out.write();
//     streams.start();   // the reporting thread
//
// Per sample, nothing allocates once the first samples have sized the reused one: the
// reader's history is preallocated (profile RapidStream_<name>: PREALLOCATED_WITH_REALLOC,
// every sample allocated up front), the listener reads into one sample kept for the whole
// run (its strings and sequences keep their capacity), the callback is a std::function
// called by reference. The callback runs on Fast DDS's receive thread: keep it short.
//
// Deadline misses (Fast DDS's event thread) and liveliness changes only flip the stream's
// StreamMonitor and wake the reporting thread, which then runs the declared action (stop:
// the handlers' on_loss hook and, when the asset has Mobility, stopAllMotion through the
// command manager; hold: the last setpoint is kept, the hook told so; none), publishes a
// TextMessage on the asset's text telemetry and the AgentState with the state and missed
// keys, and does so again on recovery. AgentState also goes out at the agent entry's rate.
#ifndef RAPID_RUNTIME_DDS_STREAM_HPP
#define RAPID_RUNTIME_DDS_STREAM_HPP

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/subscriber/qos/SubscriberQos.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <rapid_runtime/stream.hpp>
#include <rapid_runtime/text.hpp>
#include <rapid_runtime/value.hpp>

#include "bridge.hpp"
#include "telemetry.hpp"

namespace rapid_runtime {
namespace dds {

// What the generated glue tells the stream set about the user's handlers.
struct StreamHooks {
    // The stream changed state (lost: the declared action is being taken; active again).
    std::function<void(const StreamSpec&, StreamState)> on_state;
    // The asset's own agent values, merged under the stream keys when the set publishes
    // AgentState (unset: declared defaults).
    std::function<std::map<std::string, Value>()> agent_values;
};

class StreamSet;

namespace detail {

class ReaderBase : public eprosima::fastdds::dds::DataReaderListener {
public:
    ReaderBase(StreamSet& set, std::size_t index) : set_(set), index_(index) {}
    void on_requested_deadline_missed(eprosima::fastdds::dds::DataReader*,
                                      const eprosima::fastdds::dds::RequestedDeadlineMissedStatus& s) override;
    void on_liveliness_changed(eprosima::fastdds::dds::DataReader*,
                               const eprosima::fastdds::dds::LivelinessChangedStatus& s) override;

    eprosima::fastdds::dds::DataReader* reader = nullptr;
    eprosima::fastdds::dds::Subscriber* subscriber = nullptr;

protected:
    void arrived();
    StreamSet& set_;
    std::size_t index_;
};

template <class T>
class Reader final : public ReaderBase {
public:
    Reader(StreamSet& set, std::size_t index, std::function<void(const T&)> callback)
        : ReaderBase(set, index), callback_(std::move(callback)) {}

    // read, not take: the history (keep last 1 per writer) replaces the read sample with the
    // next one, so the writer's instance stays among Fast DDS 2.9's instances with data; a
    // take emptied it and the next sample put it back, a std::map node allocated per sample.
    void on_data_available(eprosima::fastdds::dds::DataReader* r) override {
        while (r->read_next_sample(&sample_, &info_) == eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
            if (!info_.valid_data) continue;
            if (callback_) callback_(sample_);
            arrived();  // after the callback: a state hook never sees "active" before its sample
        }
    }

private:
    std::function<void(const T&)> callback_;
    T sample_{};  // reused: decoding keeps its strings' and sequences' capacity
    eprosima::fastdds::dds::SampleInfo info_{};
};

}  // namespace detail

// An output stream: one sample, filled in place and written; its header's names and
// timeStamp are set here (srcName and assetName the asset, serial 0: a stream has no config).
template <class T>
class StreamWriter {
public:
    StreamWriter(Bridge& bridge, const StreamSpec& spec)
        : writer_(bridge.node().writer<T>(spec.topic, spec.profile)) {
        sample_.hdr = header(bridge.tables().name, bridge.tables().name, 0);
    }
    T& sample() { return sample_; }
    // Stamps hdr.timeStamp (microseconds, UTC) and writes; false when Fast DDS refused it.
    bool write() {
        sample_.hdr.timeStamp = now_us();
        return writer_->write(&sample_);
    }

private:
    eprosima::fastdds::dds::DataWriter* writer_;
    T sample_{};
};

class StreamSet {
public:
    StreamSet(Bridge& bridge, std::vector<StreamSpec> specs, StreamHooks hooks = {})
        : bridge_(bridge), specs_(std::move(specs)), hooks_(std::move(hooks)), monitors_(specs_.size()),
          reported_(specs_.size(), StreamState::Waiting) {}
    ~StreamSet() { stop(); }
    StreamSet(const StreamSet&) = delete;
    StreamSet& operator=(const StreamSet&) = delete;

    // The index-th stream's reader (an input stream), calling back for every sample.
    template <class T>
    void read(std::size_t index, std::function<void(const T&)> callback) {
        namespace fd = eprosima::fastdds::dds;
        const StreamSpec& s = specs_.at(index);
        auto* participant = bridge_.node().participant();
        const char* type = rapidgen::dds::Traits<T>::name;
        if (participant->find_type(type).empty()) fd::TypeSupport(new rapidgen::dds::TopicType<T>()).register_type(participant);
        fd::TopicDescription* topic = participant->lookup_topicdescription(s.topic);
        if (topic == nullptr) topic = participant->create_topic(s.topic, type, fd::TOPIC_QOS_DEFAULT);
        if (topic == nullptr) throw DdsError("cannot create topic " + s.topic + " of " + type);
        auto reader = std::make_unique<detail::Reader<T>>(*this, index, std::move(callback));
        fd::SubscriberQos sq = participant->get_default_subscriber_qos();
        sq.partition().clear();
        sq.partition().push_back(s.partition.c_str());  // the writing asset's partition
        reader->subscriber = participant->create_subscriber(sq);
        fd::DataReaderQos rq;
        if (reader->subscriber == nullptr ||
            reader->subscriber->get_datareader_qos_from_profile(s.profile, rq) !=
                eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK)
            throw DdsError("no reader profile " + s.profile + " in the loaded QoS profiles");
        fd::StatusMask mask = fd::StatusMask::data_available() << fd::StatusMask::requested_deadline_missed()
                              << fd::StatusMask::liveliness_changed();
        reader->reader = reader->subscriber->create_datareader(topic, rq, reader.get(), mask);
        if (reader->reader == nullptr) throw DdsError("cannot create the reader of stream " + s.name);
        readers_.push_back(std::move(reader));
    }

    // The index-th stream's writer (an output stream), made on first use.
    template <class T>
    StreamWriter<T>& writer(std::size_t index) {
        auto& slot = writers_[index];
        if (!slot) slot = std::make_shared<StreamWriter<T>>(bridge_, specs_.at(index));
        return *std::static_pointer_cast<StreamWriter<T>>(slot);
    }

    // The reporting thread: actions, TextMessages, AgentState.
    void start() {
        std::lock_guard<std::mutex> lock(mutex_);
        if (thread_.joinable()) return;
        stopping_ = false;
        thread_ = std::thread([this] { report_loop(); });
    }

    // Readers deleted (no callback after this returns), the thread joined; idempotent.
    void stop() {
        if (!summarized_) {
            summarized_ = true;
            for (std::size_t i = 0; i < specs_.size(); ++i)
                if (specs_[i].input)
                    bridge_.log("stream " + visible(specs_[i].name) + ": " + std::to_string(monitors_[i].samples()) +
                                " samples, " + std::to_string(monitors_[i].missed()) + " deadlines missed, " +
                                std::to_string(monitors_[i].losses()) + " losses");
        }
        for (auto& r : readers_) {
            if (r->reader != nullptr) {
                r->reader->set_listener(nullptr);
                r->subscriber->delete_datareader(r->reader);
                r->reader = nullptr;
            }
            if (r->subscriber != nullptr) bridge_.node().participant()->delete_subscriber(r->subscriber);
            r->subscriber = nullptr;
        }
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        if (thread_.joinable()) thread_.join();
    }

    const StreamSpec& spec(std::size_t index) const { return specs_.at(index); }
    const StreamMonitor& monitor(std::size_t index) const { return monitors_.at(index); }
    std::size_t size() const { return specs_.size(); }

    // The stream keys' values now (state and missed count of every input stream that names them).
    std::map<std::string, Value> agent_values() const {
        std::map<std::string, Value> out;
        for (std::size_t i = 0; i < specs_.size(); ++i) {
            const auto& s = specs_[i];
            if (!s.state_key.empty()) out[s.state_key] = std::string(state_name(monitors_[i].state()));
            if (!s.missed_key.empty())
                out[s.missed_key] = static_cast<std::int32_t>(std::min<std::uint64_t>(monitors_[i].missed(), INT32_MAX));
        }
        return out;
    }

    // From the listeners: a state may have changed.
    void poke() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            poked_ = true;
        }
        wake_.notify_one();
    }
    StreamMonitor& monitor_of(std::size_t index) { return monitors_.at(index); }

private:
    void report_loop() {
        const TelemetrySpec* agent = bridge_.tables().telemetry_of("agent");
        bool reports = false;
        for (const auto& s : specs_) reports = reports || !s.state_key.empty() || !s.missed_key.empty();
        double rate = agent != nullptr && agent->rate ? *agent->rate : 1.0;
        auto period = std::chrono::duration<double>(1.0 / (rate > 0 ? rate : 1.0));
        std::unique_lock<std::mutex> lock(mutex_);
        while (!stopping_) {
            wake_.wait_for(lock, period, [this] { return stopping_ || poked_; });
            if (stopping_) break;
            poked_ = false;
            lock.unlock();
            for (std::size_t i = 0; i < specs_.size(); ++i) {
                StreamState now = monitors_[i].state();
                if (now != reported_[i]) {
                    StreamState was = reported_[i];
                    reported_[i] = now;
                    changed(i, was, now);
                }
            }
            if (agent != nullptr && reports) publish_agent();
            lock.lock();
        }
    }

    void changed(std::size_t i, StreamState was, StreamState now) {
        const StreamSpec& s = specs_[i];
        std::string text;
        if (now == StreamState::Lost) {
            text = "stream " + visible(s.name) + " lost (" + std::to_string(monitors_[i].missed()) +
                   " deadlines of " + format_ms(s.deadline_ms) + " missed): " + action_text(s.on_loss);
            if (s.on_loss == LossAction::Stop) stop_motion(s);
        } else if (now == StreamState::Active) {
            text = was == StreamState::Lost ? "stream " + visible(s.name) + " recovered" :
                                              "stream " + visible(s.name) + " active";
        }
        if (hooks_.on_state) {
            try {
                hooks_.on_state(s, now);
            } catch (const std::exception& e) {
                bridge_.log("stream " + visible(s.name) + ": handler failed: " + e.what());
            }
        }
        if (text.empty()) return;
        bridge_.log(text);
        if (bridge_.tables().telemetry_of("text") == nullptr) return;
        try {
            Telemetry(bridge_).text(clip(text), "stream",
                                    now == StreamState::Lost ? ::rapid::MessageLevel::MSG_WARN
                                                             : ::rapid::MessageLevel::MSG_INFO);
        } catch (const std::exception& e) {
            bridge_.log(std::string("stream text not sent: ") + e.what());
        }
    }

    // stopAllMotion's effect through the runtime: the command manager runs it as if the
    // asset had sent it (it cancels Mobility commands, then the handler stops the hardware).
    void stop_motion(const StreamSpec& s) {
        auto mobility = bridge_.tables().subsystems_of_type("Mobility");
        if (mobility.empty()) return;
        Cmd cmd;
        cmd.cmd_id = "stream-" + s.name + "-stop-" + std::to_string(++stops_);
        cmd.cmd_src = bridge_.tables().name;
        cmd.src_name = bridge_.tables().name;
        cmd.asset_name = bridge_.tables().name;
        cmd.subsystem = mobility.front();
        cmd.name = "stopAllMotion";
        cmd.stamp = now_us();
        bridge_.manager().receive(cmd);
    }

    void publish_agent() {
        std::map<std::string, Value> values;
        if (hooks_.agent_values) {
            try {
                values = hooks_.agent_values();
            } catch (const std::exception& e) {
                bridge_.log(std::string("agent values: ") + e.what());
            }
        }
        for (auto& [k, v] : agent_values()) values[k] = v;
        try {
            Telemetry(bridge_).agent_state(values);
        } catch (const std::exception& e) {
            bridge_.log(std::string("stream AgentState not sent: ") + e.what());
        }
    }

    static std::string action_text(LossAction a) {
        switch (a) {
        case LossAction::Stop: return "motion stopped";
        case LossAction::Hold: return "holding the last setpoint";
        default: return "no action";
        }
    }
    static std::string format_ms(double ms) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g ms", ms);
        return buf;
    }

    Bridge& bridge_;
    std::vector<StreamSpec> specs_;
    StreamHooks hooks_;
    std::vector<StreamMonitor> monitors_;
    std::vector<StreamState> reported_;  // the reporting thread's own
    std::vector<std::unique_ptr<detail::ReaderBase>> readers_;
    std::map<std::size_t, std::shared_ptr<void>> writers_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stopping_ = false;
    bool poked_ = false;
    std::uint64_t stops_ = 0;
    bool summarized_ = false;
    std::thread thread_;
};

namespace detail {

inline void ReaderBase::arrived() {
    if (set_.monitor_of(index_).sample()) set_.poke();
}

inline void ReaderBase::on_requested_deadline_missed(eprosima::fastdds::dds::DataReader*,
                                                     const eprosima::fastdds::dds::RequestedDeadlineMissedStatus& s) {
    std::uint64_t n = s.total_count_change > 0 ? static_cast<std::uint64_t>(s.total_count_change) : 1;
    set_.monitor_of(index_).deadline_missed(n);
    set_.poke();  // the missed count changed even when the state did not
}

inline void ReaderBase::on_liveliness_changed(eprosima::fastdds::dds::DataReader*,
                                              const eprosima::fastdds::dds::LivelinessChangedStatus& s) {
    if (set_.monitor_of(index_).writers_alive(s.alive_count)) set_.poke();
}

}  // namespace detail

}  // namespace dds
}  // namespace rapid_runtime

#endif
