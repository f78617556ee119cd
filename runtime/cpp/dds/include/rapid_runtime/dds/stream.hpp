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
// the handlers' on_state hook and, when the asset has Mobility, stopAllMotion through the
// command manager; hold: the hook, whose cue is to keep the last setpoint; none: nothing,
// the hook is not called), publishes a TextMessage on the asset's text telemetry saying
// why (no sample within the deadline, or the writer's liveliness lapsed) and the AgentState
// with the state and missed keys, and does so again on recovery. A writer whose liveliness
// lapses after a deadline already lost the stream is reported too. AgentState also goes
// out at the agent entry's rate.
//
// A sample with a NaN or an infinity in it (finite_sample: every float of a PositionSample or
// JointSample, their ParameterUnion values included; other message types are handed on as
// they are) never reaches the callback: it is counted, the first of a run of them is
// reported (log line and TextMessage, MSG_WARN), and it does not keep the stream alive: when
// no finite sample came within the deadline the stream is lost and its on_loss action taken,
// even though DDS's DEADLINE (met by any sample) never fires (stream.hpp StreamMonitor).
//
// Under --simulate, SimulatedStreams (below) runs the same set with the simulated robot
// behind it: input setpoints move its joints or pose, output streams carry its state.
#ifndef RAPID_RUNTIME_DDS_STREAM_HPP
#define RAPID_RUNTIME_DDS_STREAM_HPP

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
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

#include <rapid_runtime/simulator.hpp>
#include <rapid_runtime/stream.hpp>
#include <rapid_runtime/text.hpp>
#include <rapid_runtime/value.hpp>

#include "bridge.hpp"
#include "telemetry.hpp"

namespace rapid_runtime {
namespace dds {

// What the generated glue tells the stream set about the user's handlers.
struct StreamHooks {
    // A stream with on_loss stop or hold changed state (lost: the declared action is being
    // taken; active: first sample or recovered). Not called for on_loss none.
    std::function<void(const StreamSpec&, StreamState)> on_state;
    // The asset's own agent values, merged under the stream keys when the set publishes
    // AgentState (unset: declared defaults).
    std::function<std::map<std::string, Value>()> agent_values;
    // false: AgentState only when a stream's state or missed count changed (the simulated
    // robot publishes it at the agent entry's rate).
    bool periodic_agent = true;
};

class StreamSet;

// Whether every floating-point number of a setpoint is finite (NaN and infinities are not).
inline bool finite_values(const float* v, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}
inline bool finite_values(const double* v, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(v[i])) return false;
    return true;
}
inline bool finite_sample(const ::rapid::ParameterUnion& p) {
    switch (p._d()) {
    case ::rapid::DataType::RAPID_DOUBLE: return std::isfinite(p.d());
    case ::rapid::DataType::RAPID_FLOAT: return std::isfinite(p.f());
    case ::rapid::DataType::RAPID_VEC3d: return finite_values(p.vec3d().data(), p.vec3d().size());
    case ::rapid::DataType::RAPID_MAT33f: return finite_values(p.mat33f().data(), p.mat33f().size());
    default: return true;
    }
}
inline bool finite_sample(const ::rapid::Transform3D& t) {
    return finite_values(t.xyz.data(), t.xyz.size()) && finite_values(t.rot.data(), t.rot.size());
}
inline bool finite_sample(const ::rapid::PositionSample& s) {
    if (!finite_sample(s.pose) || !finite_sample(s.velocity)) return false;
    for (const auto& v : s.values)
        if (!finite_sample(v)) return false;
    return true;
}
inline bool finite_sample(const ::rapid::JointSample& s) {
    for (const auto* seq : {&s.anglePos, &s.angleVel, &s.angleAcc, &s.current, &s.torque, &s.temperature})
        if (!finite_values(seq->data(), seq->size())) return false;
    for (const auto& aux : s.auxFloat)
        if (!finite_values(aux.values.data(), aux.values.size())) return false;
    return true;
}
template <class T>
bool finite_sample(const T&) {
    return true;  // another message type: its handler checks what it uses
}

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
    void dropped();  // a sample with a NaN or an infinity
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
            if (!finite_sample(sample_)) {
                dropped();  // never handed on, and not a sample that keeps the stream alive
                continue;
            }
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
        if (topic == nullptr) fail("cannot create topic " + s.topic + " of " + type);
        readers_.push_back(std::make_unique<detail::Reader<T>>(*this, index, std::move(callback)));
        detail::ReaderBase& reader = *readers_.back();
        fd::SubscriberQos sq = participant->get_default_subscriber_qos();
        sq.partition().clear();
        sq.partition().push_back(s.partition.c_str());  // the writing asset's partition
        reader.subscriber = participant->create_subscriber(sq);
        fd::DataReaderQos rq;
        if (reader.subscriber == nullptr ||
            reader.subscriber->get_datareader_qos_from_profile(s.profile, rq) !=
                eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK)
            fail("no reader profile " + s.profile + " in the loaded QoS profiles");
        fd::StatusMask mask = fd::StatusMask::data_available() << fd::StatusMask::requested_deadline_missed()
                              << fd::StatusMask::liveliness_changed();
        reader.reader = reader.subscriber->create_datareader(topic, rq, &reader, mask);
        // (under DDS Security: refused when the permissions do not grant the stream's topic in its partition)
        if (reader.reader == nullptr) fail("cannot create the reader of stream " + s.name);
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
                                std::to_string(monitors_[i].losses()) + " losses, " +
                                std::to_string(monitors_[i].non_finite()) + " non-finite dropped");
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
    // A set that could not be made is stopped before the error leaves it: its readers and
    // subscribers deleted while the bridge lives, so that whoever owns the set (the generated
    // handlers, freed after the Bridge when on_start throws) destroys it without touching
    // the bridge (it used to end the process with "pure virtual method called").
    [[noreturn]] void fail(const std::string& why) {
        summarized_ = true;  // nothing ran: no summary
        stop();
        throw DdsError(why);
    }

    void report_loop() {
        const TelemetrySpec* agent = bridge_.tables().telemetry_of("agent");
        bool reports = false;
        for (const auto& s : specs_) reports = reports || !s.state_key.empty() || !s.missed_key.empty();
        double rate = agent != nullptr && agent->rate ? *agent->rate : 1.0;
        auto period = std::chrono::duration<double>(1.0 / (rate > 0 ? rate : 1.0));
        std::vector<std::uint64_t> gone(specs_.size(), 0);  // writers gone, as reported
        std::vector<std::uint64_t> runs(specs_.size(), 0);  // runs of non-finite samples, as reported
        std::unique_lock<std::mutex> lock(mutex_);
        while (!stopping_) {
            wake_.wait_for(lock, period, [this] { return stopping_ || poked_; });
            if (stopping_) break;
            bool poked = poked_;
            poked_ = false;
            lock.unlock();
            for (std::size_t i = 0; i < specs_.size(); ++i) {
                StreamState now = monitors_[i].state();
                bool went = monitors_[i].writers_gone() != gone[i];
                gone[i] = monitors_[i].writers_gone();
                if (monitors_[i].non_finite_runs() != runs[i]) {
                    runs[i] = monitors_[i].non_finite_runs();
                    say("stream " + visible(specs_[i].name) + ": samples with NaN or Inf dropped (" +
                            std::to_string(monitors_[i].non_finite()) + " so far); lost without a finite one in " +
                            format_ms(specs_[i].deadline_ms),
                        ::rapid::MessageLevel::MSG_WARN);
                }
                if (now != reported_[i]) {
                    StreamState was = reported_[i];
                    reported_[i] = now;
                    changed(i, was, now);
                }
                if (went && now == StreamState::Lost && monitors_[i].cause() == LossCause::Deadline) {
                    // a deadline lost it first: the writer's going is news of its own
                    say("stream " + visible(specs_[i].name) + ": its writer is gone (no liveliness within " +
                            format_ms(specs_[i].liveliness_ms) + ")",
                        ::rapid::MessageLevel::MSG_WARN);
                }
            }
            if (agent != nullptr && reports && (poked || hooks_.periodic_agent)) publish_agent();
            lock.lock();
        }
    }

    void changed(std::size_t i, StreamState was, StreamState now) {
        // Only an active stream is lost (StreamMonitor::lose): waiting then lost at two polls is
        // a first sample and a missed deadline between them, said in the order they came
        if (was == StreamState::Waiting && now == StreamState::Lost) changed(i, was, StreamState::Active);
        const StreamSpec& s = specs_[i];
        std::string text;
        if (now == StreamState::Lost) {
            LossCause cause = monitors_[i].cause();
            std::string why = cause == LossCause::Liveliness
                                  ? "its writer is gone: no liveliness within " + format_ms(s.liveliness_ms)
                              : cause == LossCause::NonFinite
                                  ? "no finite sample within its " + format_ms(s.deadline_ms) + " deadline, " +
                                        std::to_string(monitors_[i].non_finite()) + " with NaN or Inf dropped"
                                  : "no sample within its " + format_ms(s.deadline_ms) + " deadline";
            text = "stream " + visible(s.name) + " lost (" + why + "; " + std::to_string(monitors_[i].missed()) +
                   " deadlines missed): " + action_text(s.on_loss);
            if (s.on_loss == LossAction::Stop) stop_motion(s);
        } else if (now == StreamState::Active) {
            text = was == StreamState::Lost ? "stream " + visible(s.name) + " recovered" :
                                              "stream " + visible(s.name) + " active";
        }
        if (hooks_.on_state && s.on_loss != LossAction::None) {  // none: reported, nothing done
            try {
                hooks_.on_state(s, now);
            } catch (const std::exception& e) {
                bridge_.log("stream " + visible(s.name) + ": handler failed: " + e.what());
            }
        }
        if (!text.empty())
            say(text, now == StreamState::Lost ? ::rapid::MessageLevel::MSG_WARN : ::rapid::MessageLevel::MSG_INFO);
    }

    // The log and the asset's text telemetry (when it has one).
    void say(const std::string& text, ::rapid::MessageLevel level) {
        bridge_.log(text);
        if (bridge_.tables().telemetry_of("text") == nullptr) return;
        try {
            Telemetry(bridge_).text(clip(text), "stream", level);
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

// ---- --simulate ------------------------------------------------------------------------------

// What the simulated robot does with a setpoint (other types: counted and watched only):
// a JointSample's positions move the joints the stream drives, a PositionSample's xyz the
// pose (Simulator::stream_joints / stream_pose).
inline void simulated_setpoint(Simulator& sim, const StreamSpec& s, const ::rapid::JointSample& sample) {
    std::vector<double> pos(sample.anglePos.begin(), sample.anglePos.end());
    sim.stream_joints(s.subsystem, pos);
}
inline void simulated_setpoint(Simulator& sim, const StreamSpec& s, const ::rapid::PositionSample& sample) {
    sim.stream_pose(s.subsystem, sample.pose.xyz);
}
template <class T>
void simulated_setpoint(Simulator&, const StreamSpec&, const T&) {}

// What the simulated robot writes on an output stream at time t (simulated seconds): its
// own state with a slow sweep on top, so a consumer has something to follow: the pose of
// the stream's subsystem (or the body) circling 10 cm around it every 20 s, the joints it
// names (or the first joint entry's) swinging 0.2 rad every 10 s. Other types: the header.
inline void simulated_output(const Simulator& sim, const StreamSpec& s, double t, ::rapid::JointSample& out) {
    auto pos = sim.stream_joint_positions(s.subsystem);
    out.anglePos.resize(pos.size());
    double swing = 0.2 * std::sin(2 * 3.141592653589793 * t / 10.0);
    for (std::size_t i = 0; i < pos.size(); ++i) out.anglePos[i] = static_cast<float>(pos[i] + swing);
}
inline void simulated_output(const Simulator& sim, const StreamSpec& s, double t, ::rapid::PositionSample& out) {
    auto pose = sim.pose(s.subsystem);
    double a = 2 * 3.141592653589793 * t / 20.0;
    out.pose.xyz = {pose.xyz[0] + 0.1 * std::cos(a), pose.xyz[1] + 0.1 * std::sin(a), pose.xyz[2]};
    out.pose.rot = {1, 0, 0, 0, 1, 0, 0, 0, 1};
}
template <class T>
void simulated_output(const Simulator&, const StreamSpec&, double, T&) {}

// The asset's streams on the simulated robot (program.cpp runs it under --simulate; the
// generated glue registers each stream's type):
//   input   read like the real bridge's (same QoS, state, TextMessages, AgentState keys);
//           each sample drives the simulator (simulated_setpoint); on a loss, stop halts what
//           the stream drives (and Mobility/stopAllMotion goes to the simulator through the
//           command manager), hold keeps moving to the last setpoint, none does nothing.
//   output  written at the stream's rate by one thread (simulated_output).
// The streams' agent keys go out with the simulated robot's AgentState.
class SimulatedStreams {
public:
    SimulatedStreams(Bridge& bridge, Simulator& sim, std::vector<StreamSpec> specs)
        : sim_(sim), set_(bridge, std::move(specs), hooks(sim)) {
        sim_.agent_source([this] { return set_.agent_values(); });
    }
    ~SimulatedStreams() { stop(); }
    SimulatedStreams(const SimulatedStreams&) = delete;
    SimulatedStreams& operator=(const SimulatedStreams&) = delete;

    template <class T>
    void read(std::size_t index) {
        const StreamSpec& s = set_.spec(index);
        Simulator& sim = sim_;
        set_.read<T>(index, [&sim, &s](const T& sample) { simulated_setpoint(sim, s, sample); });
    }

    template <class T>
    void write(std::size_t index) {
        StreamWriter<T>* w = &set_.writer<T>(index);
        const StreamSpec& s = set_.spec(index);
        double rate = s.rate_hz > 0 ? s.rate_hz : 1.0;
        outputs_.push_back({1.0 / rate, [this, w, &s](double t) {
                                simulated_output(sim_, s, t, w->sample());
                                w->write();
                            }});
    }

    void start() {
        set_.start();
        if (outputs_.empty() || running_.exchange(true)) return;
        thread_ = std::thread([this] { write_loop(); });
    }

    void stop() {
        running_ = false;
        if (thread_.joinable()) thread_.join();
        set_.stop();
        sim_.agent_source({});
    }

    const StreamSet& set() const { return set_; }

private:
    struct Output {
        double period;  // s
        std::function<void(double)> send;
        double next = 0;
    };

    static StreamHooks hooks(Simulator& sim) {
        StreamHooks h;
        h.on_state = [&sim](const StreamSpec& s, StreamState state) {
            if (state == StreamState::Lost && s.on_loss == LossAction::Stop) sim.stream_halt(s.subsystem);
        };
        h.agent_values = [&sim] { return sim.agent(); };
        h.periodic_agent = false;
        return h;
    }

    void write_loop() {
        using clock = std::chrono::steady_clock;
        const auto t0 = clock::now();
        while (running_) {
            double now = std::chrono::duration<double>(clock::now() - t0).count();
            double next = now + 0.1;
            for (auto& o : outputs_) {
                if (now >= o.next) {
                    o.send(now * sim_.speed());
                    o.next = std::max(o.next + o.period, now);
                }
                next = std::min(next, o.next);
            }
            std::this_thread::sleep_until(t0 + std::chrono::duration_cast<clock::duration>(
                                                   std::chrono::duration<double>(next)));
        }
    }

    Simulator& sim_;
    StreamSet set_;
    std::vector<Output> outputs_;
    std::atomic<bool> running_{false};
    std::thread thread_;
};

namespace detail {

inline void ReaderBase::arrived() {
    if (set_.monitor_of(index_).sample()) set_.poke();
}

inline void ReaderBase::dropped() {
    auto r = set_.monitor_of(index_).non_finite_sample(set_.spec(index_).deadline_ms);
    if (r.lost || r.first_of_run) set_.poke();
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
