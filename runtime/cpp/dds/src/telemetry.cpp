#include "rapid_runtime/dds/telemetry.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <rapid_runtime/images.hpp>
#include <rapid_runtime/text.hpp>

#include "rapid_runtime/dds/breaks.hpp"

namespace rapid_runtime {
namespace dds {

namespace {

bool number(const Value& v, double& out) {
    if (auto* d = std::get_if<double>(&v)) out = *d;
    else if (auto* f = std::get_if<float>(&v)) out = *f;
    else if (auto* i = std::get_if<std::int32_t>(&v)) out = *i;
    else if (auto* l = std::get_if<std::int64_t>(&v)) out = static_cast<double>(*l);
    else return false;
    return true;
}

std::string kind_name(DataType t) { return std::string(name_of(t)); }

Value zero(DataType t) {
    switch (t) {
        case DataType::Bool: return false;
        case DataType::Double: return 0.0;
        case DataType::Float: return 0.0f;
        case DataType::Int: return std::int32_t{0};
        case DataType::LongLong: return std::int64_t{0};
        case DataType::String: return std::string();
        case DataType::Vec3d: return Vec3d{};
        case DataType::Mat33f: return Mat33f{};
    }
    return false;
}

}  // namespace

Value coerce(DataType type, const Value& v, const std::string& key) {
    double x = 0.0;
    bool is_number = number(v, x);
    auto wrong = [&]() {
        return TelemetryError("value " + key + ": " + repr(v) + " is not a " + kind_name(type));
    };
    switch (type) {
        case DataType::Bool:
            if (!std::holds_alternative<bool>(v)) throw wrong();
            return v;
        case DataType::Double:
            if (!is_number) throw wrong();
            return x;
        case DataType::Float:
            if (!is_number) throw wrong();
            return static_cast<float>(x);
        case DataType::Int:
            if (!is_number || x != std::trunc(x) || x < -2147483648.0 || x > 2147483647.0) throw wrong();
            return static_cast<std::int32_t>(x);
        case DataType::LongLong:
            if (auto* l = std::get_if<std::int64_t>(&v)) return *l;
            if (!is_number || x != std::trunc(x) || std::abs(x) > 9.2e18) throw wrong();
            return static_cast<std::int64_t>(x);
        case DataType::String: {
            auto* s = std::get_if<std::string>(&v);
            if (s == nullptr) throw wrong();
            if (auto why = shape_error(v)) throw TelemetryError("value " + key + ": " + *why);
            return v;
        }
        case DataType::Vec3d:
            if (!std::holds_alternative<Vec3d>(v)) throw wrong();
            return v;
        case DataType::Mat33f:
            if (!std::holds_alternative<Mat33f>(v)) throw wrong();
            return v;
    }
    throw wrong();
}

std::array<float, 9> rotation_about_z(const std::string& encoding, double heading) {
    std::array<float, 9> r{};
    if (encoding == "RAPID_ROT_QUAT") {
        r[2] = static_cast<float>(std::sin(heading / 2));
        r[3] = static_cast<float>(std::cos(heading / 2));
    } else if (encoding == "RAPID_ROT_M33") {
        float c = static_cast<float>(std::cos(heading)), s = static_cast<float>(std::sin(heading));
        r = {c, -s, 0, s, c, 0, 0, 0, 1};
    } else if (encoding == "RAPID_ROT_XYZ" || encoding == "RAPID_ROT_VEL") {
        r[2] = static_cast<float>(heading);
    } else if (encoding == "RAPID_ROT_ZYX" || encoding == "RAPID_ROT_ZYZ") {
        r[0] = static_cast<float>(heading);
    }
    return r;
}

// ---- StaleWatch ---------------------------------------------------------------------------------

StaleWatch::StaleWatch(const Tables& tables) {
    for (const auto& e : tables.telemetry)
        if (auto bound = stale_after_ms(e)) freshness_.watch(stale_name(e), *bound);
}

StaleWatch::~StaleWatch() { stop(); }

void StaleWatch::remember(std::size_t agent, const std::map<std::string, Value>& values) {
    std::lock_guard<std::mutex> lock(mutex_);
    agents_[agent] = values;
}

std::map<std::string, Value> StaleWatch::last(std::size_t agent) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto found = agents_.find(agent);
    return found == agents_.end() ? std::map<std::string, Value>{} : found->second;
}

void StaleWatch::start(Bridge& bridge) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (started_ || stopping_ || freshness_.empty()) return;
    started_ = true;
    double tick = std::min(0.5, std::max(0.05, freshness_.smallest_bound_ms() / 4000.0));
    thread_ = std::thread([this, &bridge, tick] { run(bridge, tick); });
}

void StaleWatch::stop() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable() && thread_.get_id() != std::this_thread::get_id()) thread_.join();
}

void StaleWatch::run(Bridge& bridge, double tick) {
    for (;;) {
        {
            std::unique_lock<std::mutex> lock(mutex_);
            if (wake_.wait_for(lock, std::chrono::duration<double>(tick), [this] { return stopping_; })) return;
        }
        for (const auto& [name, age] : freshness_.check())
            Telemetry(bridge).announce(silent_text(name, age), ::rapid::MessageLevel::MSG_WARN);
    }
}

// ---- Telemetry ----------------------------------------------------------------------------------

Telemetry::Telemetry(Bridge& bridge)
    : b_(bridge), t_(bridge.tables()), breaks_(bridge.breaks().any() ? &bridge.breaks() : nullptr) {}

const TelemetrySpec& Telemetry::entry(const std::string& kind, std::size_t index) const {
    const TelemetrySpec* e = t_.telemetry_of(kind, index);
    if (e == nullptr)
        throw TelemetryError("asset " + t_.name + " declares " + std::to_string(t_.count_of(kind)) + " " + kind +
                             " telemetry entries (no index " + std::to_string(index) + ")");
    return *e;
}

const std::string& Telemetry::topic(const TelemetrySpec& e, const std::string& role, std::string& qos) const {
    const TelemetryTopic* t = e.topic(role);
    if (t == nullptr) throw TelemetryError(e.kind + " telemetry entry has no " + role + " topic");
    qos = t->qos;
    return t->topic;
}

std::vector<::rapid::ParameterUnion> Telemetry::values(const TelemetrySpec& e,
                                                        const std::map<std::string, Value>& given) const {
    for (const auto& [key, v] : given) {
        bool known = false;
        for (const auto& k : e.values) known = known || k.name == key;
        if (!known) throw TelemetryError("undeclared value key: " + key);
    }
    std::vector<::rapid::ParameterUnion> out;
    out.reserve(e.values.size());
    for (const auto& k : e.values) {
        auto found = given.find(k.name);
        Value v = found != given.end() ? coerce(k.type, found->second, k.name)
                  : k.default_value   ? coerce(k.type, *k.default_value, k.name)
                                      : zero(k.type);
        out.push_back(union_of(v));
    }
    if (breaks_ != nullptr) breaks_->values(e, out);
    return out;
}

namespace {
const std::string& config_topic(const TelemetrySpec& e) {
    static const std::string none;
    const TelemetryTopic* c = e.topic("config");
    return c ? c->topic : none;
}
}  // namespace

template <class T>
void Telemetry::send(const std::string& topic, T& sample, const TelemetrySpec& e, const std::string& qos,
                     std::optional<std::int64_t> stamp) {
    if ((breaks_ == nullptr || !breaks_->samples_broken()) && !stamp)
        return b_.publish(topic, sample, config_topic(e), qos);
    // Bridge::publish's header, stamped with the source's time, then broken
    sample.hdr = header(t_.name, t_.name, b_.serial_of(config_topic(e)));
    if (stamp) sample.hdr.timeStamp = *stamp;
    if (breaks_ != nullptr && breaks_->samples_broken()) breaks_->sample_header(sample.hdr);
    b_.node().writer<T>(topic, qos)->write(&sample);
}

std::optional<std::int64_t> Telemetry::current(const TelemetrySpec& e, std::optional<std::int64_t> stamp) {
    const std::int64_t when = stamp ? *stamp : now_us();
    const std::string name = stale_name(e);
    StaleWatch& watch = b_.stale();
    if (!watch.freshness().watched(name)) return when;
    auto offer = watch.freshness().offer(name, when);
    watch.start(b_);
    if (offer.back) announce(back_text(name), ::rapid::MessageLevel::MSG_INFO);
    if (!offer.ok) return std::nullopt;
    return when;
}

namespace {
bool declares_stale_key(const TelemetrySpec& e) {
    for (const auto& k : e.values)
        if (k.name == STALE_KEY && k.type == DataType::String) return true;
    return false;
}
}  // namespace

void Telemetry::announce(const std::string& text, ::rapid::MessageLevel level) {
    b_.log(text);
    try {
        if (const TelemetrySpec* texts = t_.telemetry_of("text")) {
            const auto& c = texts->categories;
            std::string category = std::find(c.begin(), c.end(), "system") != c.end() ? "system"
                                   : c.empty()                                        ? ""
                                                                                      : c.front();
            this->text(text, category, level);
        }
        const std::int64_t now = now_us();
        for (std::size_t i = 0; i < t_.count_of("agent"); ++i) {
            const auto& e = entry("agent", i);
            if (declares_stale_key(e)) write_agent(e, b_.stale().last(i), now);
        }
    } catch (const std::exception& x) {  // a writer gone at shutdown: the log line is what is left
        b_.log(std::string("stale telemetry not published: ") + x.what());
    }
}

void Telemetry::write_agent(const TelemetrySpec& e, std::map<std::string, Value> given, std::int64_t stamp) {
    if (declares_stale_key(e)) {
        std::string names;
        for (const auto& n : b_.stale().freshness().silent_names()) names += (names.empty() ? "" : ", ") + n;
        given[STALE_KEY] = names;
    }
    std::string qos;
    const auto& name = topic(e, "state", qos);
    ::rapid::AgentState s;
    s.values = values(e, given);
    send(name, s, e, qos, stamp);
}

bool Telemetry::agent_state(const std::map<std::string, Value>& given, std::size_t index,
                            std::optional<std::int64_t> stamp) {
    const auto& e = entry("agent", index);
    auto when = current(e, stamp);
    if (!when) return false;
    b_.stale().remember(index, given);
    write_agent(e, given, *when);
    return true;
}

bool Telemetry::position(const std::array<double, 3>& xyz, const std::array<float, 9>& rot,
                         const std::array<double, 3>& velocity_xyz, const std::array<float, 9>& velocity_rot,
                         const std::map<std::string, Value>& given, std::size_t index,
                         std::optional<std::int64_t> stamp) {
    const auto& e = entry("position", index);
    std::string qos;
    const auto& name = topic(e, "sample", qos);
    ::rapid::PositionSample s;
    s.pose.xyz = xyz;
    s.pose.rot = rot;
    s.velocity.xyz = velocity_xyz;
    s.velocity.rot = velocity_rot;
    s.values = values(e, given);
    auto when = current(e, stamp);
    if (!when) return false;
    send(name, s, e, qos, *when);
    return true;
}

bool Telemetry::joints(const std::vector<double>& positions, const std::vector<double>& velocities,
                       const std::vector<double>& torques, std::size_t index, std::optional<std::int64_t> stamp) {
    const auto& e = entry("joint", index);
    std::size_t n = e.joints.size();
    if (positions.size() != n || (!velocities.empty() && velocities.size() != n) ||
        (!torques.empty() && torques.size() != n))
        throw TelemetryError("joint sample: " + std::to_string(positions.size()) + " positions for " +
                             std::to_string(n) + " joints");
    std::string qos;
    const auto& name = topic(e, "sample", qos);
    ::rapid::JointSample s;
    s.anglePos.assign(positions.begin(), positions.end());
    s.angleVel.assign(velocities.begin(), velocities.end());
    s.torque.assign(torques.begin(), torques.end());
    auto when = current(e, stamp);
    if (!when) return false;
    send(name, s, e, qos, *when);
    return true;
}

void Telemetry::text(const std::string& message, const std::string& category, ::rapid::MessageLevel level,
                     std::size_t index) {
    const auto& e = entry("text", index);
    std::string qos;
    const auto& name = topic(e, "sample", qos);
    ::rapid::TextMessage s;
    s.level = level;
    // valid UTF-8 without NUL, within String64 / String2K (issue 42: a handler's text)
    s.category = outgoing(category, 63);
    s.message = outgoing(message, 2047);
    send(name, s, e, qos);
}

::rapid::ImageMetadata Telemetry::meta(const TelemetrySpec& e, int width, int height) const {
    ::rapid::ImageMetadata m;
    m.sensorName = e.sensor;
    m.sensorType = e.sensor_type;
    m.offset.rot = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    m.width = width;
    m.height = height;
    return m;
}

bool Telemetry::image(const std::vector<std::uint8_t>& data, std::size_t index, bool state,
                      std::optional<std::int64_t> stamp) {
    const auto& e = entry("image", index);
    ImageInfo info{e.mime, e.width, e.height};
    describe_image(data, info);
    auto when = current(e, stamp);
    if (!when) return false;
    std::string qos;
    if (state && e.topic("state") != nullptr) {
        const auto& name = topic(e, "state", qos);
        ::rapid::ImageSensorState s;
        s.meta = meta(e, info.width, info.height);
        send(name, s, e, qos, *when);
    }
    const auto& name = topic(e, "sample", qos);
    ::rapid::ImageSensorSample s;
    s.meta = meta(e, info.width, info.height);
    s.mimeType = info.mime;
    s.data = data;
    send(name, s, e, qos, *when);
    return true;
}

void Telemetry::image_state(std::size_t index) {
    const auto& e = entry("image", index);
    std::string qos;
    const auto& name = topic(e, "state", qos);
    ::rapid::ImageSensorState s;
    s.meta = meta(e, e.width, e.height);
    send(name, s, e, qos);
}

}  // namespace dds
}  // namespace rapid_runtime
