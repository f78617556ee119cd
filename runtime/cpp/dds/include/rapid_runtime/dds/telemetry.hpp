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
#ifndef RAPID_RUNTIME_DDS_TELEMETRY_HPP
#define RAPID_RUNTIME_DDS_TELEMETRY_HPP

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

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

class Telemetry {
public:
    explicit Telemetry(Bridge& bridge);

    // The index-th agent entry's AgentState: values by key; a key not given keeps its
    // declared default (else its type's zero).
    void agent_state(const std::map<std::string, Value>& values, std::size_t index = 0);
    // The index-th position entry's PositionSample; rotations as its config's encodings say.
    void position(const std::array<double, 3>& xyz, const std::array<float, 9>& rot,
                  const std::array<double, 3>& velocity_xyz = {}, const std::array<float, 9>& velocity_rot = {},
                  const std::map<std::string, Value>& values = {}, std::size_t index = 0);
    // The index-th joint entry's JointSample: one position per declared joint (velocities
    // and torques empty or one per joint).
    void joints(const std::vector<double>& positions, const std::vector<double>& velocities = {},
                const std::vector<double>& torques = {}, std::size_t index = 0);
    // A TextMessage on the index-th text entry.
    void text(const std::string& message, const std::string& category = "",
              ::rapid::MessageLevel level = ::rapid::MessageLevel::MSG_INFO, std::size_t index = 0);
    // One picture on the index-th image entry: ImageMetadata names the declared sensor;
    // width, height and mimeType are the picture's own when its header says them (PNG, JPEG,
    // BMP, PNM), else the declared ones. state: also its ImageSensorState.
    void image(const std::vector<std::uint8_t>& data, std::size_t index = 0, bool state = false);
    // The index-th image entry's ImageSensorState (declared size).
    void image_state(std::size_t index = 0);

    const TelemetrySpec& entry(const std::string& kind, std::size_t index) const;

private:
    ::rapid::ImageMetadata meta(const TelemetrySpec& e, int width, int height) const;
    std::vector<::rapid::ParameterUnion> values(const TelemetrySpec& e, const std::map<std::string, Value>& given) const;
    const std::string& topic(const TelemetrySpec& e, const std::string& role, std::string& qos) const;
    template <class T>
    void send(const std::string& topic, T& sample, const TelemetrySpec& e, const std::string& qos);

    Bridge& b_;
    const Tables& t_;
    const Breaks* breaks_ = nullptr;  // a test build's --break (breaks.hpp); null: none
};

}  // namespace dds
}  // namespace rapid_runtime

#endif
