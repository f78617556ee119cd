// Telemetry helpers over a Bridge (the C++ twin of the Python runtime's TelemetryPublisher):
// samples of the descriptor's telemetry entries with their headers filled (the paired
// config's serial, timeStamp in microseconds), values in the config's order and of the
// declared DataTypes, each on its topic with its QoS profile. `index` picks among entries
// of the same kind. A value that does not fit, or an entry the asset does not declare:
// TelemetryError.
//
//     rapid_runtime::dds::Telemetry tel(bridge);
//     tel.agent_state({{"batteryCharge", 87.0f}});
//     tel.position({x, y, 0}, quaternion_z(heading));
//     tel.joints(angles);
//     tel.image(jpeg_bytes);  // size and MIME type from the picture's own header
//
// Stale telemetry (docs/runtime.md, freshness.hpp): a sample's header.timeStamp is its
// source's time, the `stamp` given (microseconds since the epoch: when the value was measured
// or received), else the time of the call. A position, joint, agent or image entry with a
// bound refuses a sample older than it (nothing written, the call returns false); once its
// newest sample is older than the bound the bridge's StaleWatch says the source is silent
// (log line, one TextMessage, the agent entries' stale_telemetry key) and, when a current
// sample comes again, that it is back.
#ifndef RAPID_RUNTIME_DDS_TELEMETRY_HPP
#define RAPID_RUNTIME_DDS_TELEMETRY_HPP

#include <array>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <rapid_runtime/freshness.hpp>
#include <rapid_runtime/tables.hpp>

#include "bridge.hpp"

namespace rapid_runtime {
namespace dds {

class TelemetryError : public std::invalid_argument {
public:
    explicit TelemetryError(const std::string& why) : std::invalid_argument(why) {}
};

// A value as the DataType wants it (numbers convert between number types; a vector needs
// its count), or TelemetryError.
Value coerce(DataType type, const Value& v, const std::string& key);

// Transform3D.rot for a heading about z in the given RotationEncoding (enumerator name):
// RAPID_ROT_QUAT x, y, z, w; RAPID_ROT_M33 the matrix; Euler encodings the angles; NONE zeros.
std::array<float, 9> rotation_about_z(const std::string& encoding, double heading);

// One bridge's stale-source watch, shared by every Telemetry made on it (Bridge::stale()):
// the Freshness of its watched entries, each agent entry's last values (republished with the
// stale_telemetry key), and the watcher thread, started at the first watched sample, checking
// every quarter of the smallest bound (50-500 ms), stopped and joined by Bridge::stop() before
// the DDS node goes.
class StaleWatch {
public:
    explicit StaleWatch(const Tables& tables);
    ~StaleWatch();
    StaleWatch(const StaleWatch&) = delete;
    StaleWatch& operator=(const StaleWatch&) = delete;

    Freshness& freshness() { return freshness_; }
    void remember(std::size_t agent, const std::map<std::string, Value>& values);
    std::map<std::string, Value> last(std::size_t agent) const;
    void start(Bridge& bridge);  // the watcher thread, once (not after stop())
    void stop();                 // idempotent; joins the watcher

private:
    void run(Bridge& bridge, double tick_seconds);

    Freshness freshness_;
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::map<std::size_t, std::map<std::string, Value>> agents_;
    std::thread thread_;
    bool started_ = false;
    bool stopping_ = false;
};

class Telemetry {
public:
    explicit Telemetry(Bridge& bridge);

    // `stamp` on agent_state, position, joints and image: the source's time (microseconds since
    // the epoch), none: now. They return false when nothing was written (the sample is older
    // than its entry's stale bound).

    // The index-th agent entry's AgentState: values by key; a key not given keeps its
    // declared default (else its type's zero). A declared stale_telemetry (RAPID_STRING) is
    // the runtime's: the silent entries' names.
    bool agent_state(const std::map<std::string, Value>& values, std::size_t index = 0,
                     std::optional<std::int64_t> stamp = std::nullopt);
    // The index-th position entry's PositionSample; rotations as its config's encodings say.
    bool position(const std::array<double, 3>& xyz, const std::array<float, 9>& rot,
                  const std::array<double, 3>& velocity_xyz = {}, const std::array<float, 9>& velocity_rot = {},
                  const std::map<std::string, Value>& values = {}, std::size_t index = 0,
                  std::optional<std::int64_t> stamp = std::nullopt);
    // The index-th joint entry's JointSample: one position per declared joint (velocities
    // and torques empty or one per joint).
    bool joints(const std::vector<double>& positions, const std::vector<double>& velocities = {},
                const std::vector<double>& torques = {}, std::size_t index = 0,
                std::optional<std::int64_t> stamp = std::nullopt);
    // A TextMessage on the index-th text entry.
    void text(const std::string& message, const std::string& category = "",
              ::rapid::MessageLevel level = ::rapid::MessageLevel::MSG_INFO, std::size_t index = 0);
    // One picture on the index-th image entry: ImageMetadata names the declared sensor;
    // width, height and mimeType are the picture's own when its header says them (PNG, JPEG,
    // BMP, PNM), else the declared ones. state: also its ImageSensorState.
    bool image(const std::vector<std::uint8_t>& data, std::size_t index = 0, bool state = false,
               std::optional<std::int64_t> stamp = std::nullopt);
    // The index-th image entry's ImageSensorState (declared size).
    void image_state(std::size_t index = 0);

    const TelemetrySpec& entry(const std::string& kind, std::size_t index) const;

    // A source gone silent or back (the watcher; a sample): the log, one TextMessage on the
    // first text entry (category system when declared, else its first), an AgentState on each
    // agent entry declaring stale_telemetry (its last values, stamped now).
    void announce(const std::string& text, ::rapid::MessageLevel level);

private:
    // The sample's stamp, or none when it is older than its entry's bound (says "back").
    std::optional<std::int64_t> current(const TelemetrySpec& e, std::optional<std::int64_t> stamp);
    void write_agent(const TelemetrySpec& e, std::map<std::string, Value> values, std::int64_t stamp);
    ::rapid::ImageMetadata meta(const TelemetrySpec& e, int width, int height) const;
    std::vector<::rapid::ParameterUnion> values(const TelemetrySpec& e, const std::map<std::string, Value>& given) const;
    const std::string& topic(const TelemetrySpec& e, const std::string& role, std::string& qos) const;
    template <class T>
    void send(const std::string& topic, T& sample, const TelemetrySpec& e, const std::string& qos,
              std::optional<std::int64_t> stamp = std::nullopt);

    Bridge& b_;
    const Tables& t_;
    const Breaks* breaks_ = nullptr;  // a test build's --break (breaks.hpp); null: none
};

}  // namespace dds
}  // namespace rapid_runtime

#endif
