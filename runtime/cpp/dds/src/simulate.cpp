#include "rapid_runtime/dds/simulate.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <rapid_runtime/images.hpp>

#include "rapid_runtime/dds/breaks.hpp"

namespace rapid_runtime {
namespace dds {

namespace {

double now_s() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string lower(std::string s) {
    for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string category_of(const TelemetrySpec& t) {
    if (std::find(t.categories.begin(), t.categories.end(), "system") != t.categories.end()) return "system";
    return t.categories.empty() ? std::string() : t.categories.front();
}

template <class T>
void make_writer(Bridge& b, const TelemetrySpec& e, const char* role) {
    if (const TelemetryTopic* t = e.topic(role)) b.node().writer<T>(t->topic, t->qos);
}

std::string fixed1(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", x);
    return buf;
}

}  // namespace

SimulatedTelemetry::SimulatedTelemetry(Bridge& bridge, Simulator& simulator, std::vector<CustomPublisher> custom)
    : bridge_(bridge),
      sim_(simulator),
      tel_(bridge),
      breaks_(bridge.breaks().any() ? &bridge.breaks() : nullptr),
      custom_(std::move(custom)) {
    sim_.on_picture([this](std::size_t index) { picture(index); });
}

SimulatedTelemetry::~SimulatedTelemetry() {
    stop();
    sim_.on_picture({});
}

void SimulatedTelemetry::prepare() {
    const auto& entries = bridge_.tables().telemetry;
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const auto& e = entries[i];
        std::size_t k = seen[e.kind]++;
        try {
            if (e.kind == "agent") {
                make_writer<::rapid::AgentState>(bridge_, e, "state");
            } else if (e.kind == "position") {
                make_writer<::rapid::PositionSample>(bridge_, e, "sample");
            } else if (e.kind == "joint") {
                make_writer<::rapid::JointSample>(bridge_, e, "sample");
            } else if (e.kind == "text") {
                make_writer<::rapid::TextMessage>(bridge_, e, "sample");
                tel_.text(bridge_.tables().name + " simulated: " + std::to_string(entries.size()) +
                              " telemetry entries",
                          category_of(e), ::rapid::MessageLevel::MSG_INFO, k);
            } else if (e.kind == "image") {
                make_writer<::rapid::ImageSensorSample>(bridge_, e, "sample");
                make_writer<::rapid::ImageSensorState>(bridge_, e, "state");
                if (e.topic("state") != nullptr) tel_.image_state(k);
            } else if (e.kind == "custom") {
                for (const auto& c : custom_) {
                    if (c.entry != i) continue;
                    if (c.role != "config" && c.writer) c.writer(bridge_);
                    if (c.role == "config" && c.publish) c.publish(bridge_);  // durable: once
                }
            }
        } catch (const std::exception& ex) {
            report(i, ex);
        }
    }
}

void SimulatedTelemetry::start() {
    const auto& entries = bridge_.tables().telemetry;
    std::vector<Due> fast, slow;
    std::map<std::string, std::size_t> seen;
    double now = now_s();
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const auto& e = entries[i];
        std::size_t k = seen[e.kind]++;
        double rate = e.rate.value_or(0.0);
        if (breaks_ != nullptr) rate = breaks_->rate(rate);
        if (e.kind == "agent" || e.kind == "position" || e.kind == "joint") {
            fast.push_back({i, k, 1.0 / (rate > 0 ? rate : 1.0), now});
        } else if (e.kind == "custom") {
            bool periodic = false;
            for (const auto& c : custom_) periodic = periodic || (c.entry == i && c.role != "config");
            if (periodic) fast.push_back({i, k, rate > 0 ? 1.0 / rate : sim::IDLE_PERIOD, now});
        } else if (e.kind == "text" && rate > 0) {
            fast.push_back({i, k, 1.0 / rate, now});
        } else if (e.kind == "image" && (rate > 0 || !sim_.has_picture_command(e.subsystem))) {
            // pictures take a while to paint: their own thread keeps the others' rates
            slow.push_back({i, k, rate > 0 ? 1.0 / rate : sim::IDLE_PERIOD, now});
        }
    }
    threads_.emplace_back([this, fast] { run(fast, true); });
    if (!slow.empty()) threads_.emplace_back([this, slow] { run(slow, false); });
}

void SimulatedTelemetry::stop() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    for (auto& t : threads_)
        if (t.joinable()) t.join();
    threads_.clear();
}

void SimulatedTelemetry::run(std::vector<Due> due, bool drain) {
    double last = now_s();
    for (;;) {
        double wait = sim::TICK, now = now_s();
        for (const auto& d : due) wait = std::min(wait, d.next - now);
        {
            std::unique_lock<std::mutex> lock(mutex_);
            // Wake for the next sample due, not every TICK: a declared 500 Hz goes out at 500 Hz.
            if (wake_.wait_for(lock, std::chrono::duration<double>(std::max(0.0, wait)), [this] { return stopping_; }))
                return;
        }
        now = now_s();
        if (drain) sim_.advance(now - last);
        last = now;
        for (auto& d : due) {
            if (now < d.next) continue;
            d.next = std::max(d.next + d.period, now);
            try {
                sample(d.entry, d.index);
            } catch (const std::exception& e) {  // telemetry may be dropped; the bridge keeps running
                report(d.entry, e);
            }
        }
    }
}

void SimulatedTelemetry::sample(std::size_t entry, std::size_t index) {
    const auto& e = bridge_.tables().telemetry[entry];
    if (breaks_ != nullptr && breaks_->silent(e.kind, index)) return;  // (its writer exists)
    if (e.kind == "agent") {
        auto all = sim_.agent();
        std::map<std::string, Value> mine;
        for (const auto& k : e.values) {
            auto found = all.find(k.name);
            if (found != all.end()) mine.emplace(k.name, found->second);
        }
        tel_.agent_state(mine, index);
    } else if (e.kind == "position") {
        auto body = sim_.pose(e.subsystem);  // the body, or the part a setpoint stream drives
        std::map<std::string, Value> values;
        for (const auto& k : e.values) {
            if (k.name == "speed") values.emplace("speed", std::hypot(body.velocity[0], body.velocity[1]));
            else if (k.name == "odometer") values.emplace("odometer", body.odometer);
        }
        tel_.position(body.xyz, rotation_about_z(e.pose_encoding, body.heading), body.velocity, {}, values, index);
    } else if (e.kind == "joint") {
        tel_.joints(sim_.joints(index), {}, {}, index);
    } else if (e.kind == "text") {
        auto body = sim_.body();
        tel_.text(bridge_.tables().name + " at " + fixed1(body.xyz[0]) + ", " + fixed1(body.xyz[1]) + " (simulated)",
                  category_of(e), ::rapid::MessageLevel::MSG_INFO, index);
    } else if (e.kind == "image") {
        picture(index);
    } else if (e.kind == "custom") {
        for (const auto& c : custom_)
            if (c.entry == entry && c.role != "config" && c.publish) c.publish(bridge_);
    }
}

void SimulatedTelemetry::picture(std::size_t index) {
    const auto& e = tel_.entry("image", index);
    std::uint32_t frame;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        frame = frames_[index]++;
    }
    std::string type = lower(e.sensor_type);
    bool grey = type.find("mono") != std::string::npos || type.find("gray") != std::string::npos ||
                type.find("grey") != std::string::npos;
    auto data = synthetic_image(e.mime.empty() ? "image/jpeg" : e.mime, e.width > 0 ? e.width : 640,
                                e.height > 0 ? e.height : 480, sim_.body().heading, frame, grey);
    tel_.image(data, index, true);
}

void SimulatedTelemetry::report(std::size_t entry, const std::exception& e) {
    std::string what = e.what();
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!reported_.insert({entry, what}).second) return;
    }
    bridge_.log("simulated " + bridge_.tables().telemetry[entry].kind + " telemetry " + std::to_string(entry) +
                " not sent: " + what);
}

}  // namespace dds
}  // namespace rapid_runtime
