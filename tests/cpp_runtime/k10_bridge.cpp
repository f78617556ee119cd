// K10Red's bridge on the C++ runtime, assembled by hand from what phase 2 of issue 21 will
// generate: the tables (k10_tables.cpp), the generated C++ types and configs (asset.hpp of
// `rapidgen generate specs/assets/k10.yaml --lang cpp`), and handlers that simulate the
// rover plainly (moves take a while and can be canceled; everything else completes after
// 50 ms). Telemetry: agent state 4 Hz, position and GPS 1 Hz, the hazard camera 0.5 Hz,
// each camera's state and a text message at start.
//
//   k10_bridge --qos PROFILES_XML [--domain N] [--seconds S] [--command-window N]
//   prints "bridge ready: ..." once configs and states are out and commands are read.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <string>

#include <rapid_k10red/asset.hpp>
#include <rapid_runtime/dds/bridge.hpp>

#include "k10_tables.hpp"

using namespace rapid_runtime;
namespace rr = rapid_runtime::dds;
using Clock = std::chrono::steady_clock;

namespace {

std::atomic<bool> signalled{false};

class Rover : public Handlers {
public:
    Result execute(CommandContext& ctx) override {
        if (ctx.type() == "Mobility" && ctx.command() == "stopAllMotion") return Result::ok("stopped");
        double seconds = ctx.type() == "Mobility" ? 0.5 : 0.05;
        if (ctx.command() == "takePanorama") seconds = 0.02 * ctx.arg<std::int32_t>(3);
        if (!ctx.sleep(seconds)) return Result::canceled();
        return Result::ok();
    }
};

template <class T>
struct Every {
    Clock::duration period;
    Clock::time_point next = Clock::now();
    bool due(Clock::time_point now) {
        if (now < next) return false;
        next += period;
        if (next < now) next = now + period;  // fell behind: no burst
        return true;
    }
};

Clock::duration period(double hz) {
    return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / hz));
}

}  // namespace

int main(int argc, char** argv) {
    rr::BridgeOptions options;
    double seconds = -1;
    for (int i = 1; i + 1 < argc; i += 2) {
        std::string key = argv[i], value = argv[i + 1];
        if (key == "--qos") options.profiles_file = value;
        else if (key == "--domain") options.domain = std::atoi(value.c_str());
        else if (key == "--seconds") seconds = std::atof(value.c_str());
        else if (key == "--command-window") options.command_window = std::strtoul(value.c_str(), nullptr, 10);
        else {
            std::cerr << "usage: k10_bridge --qos PROFILES_XML [--domain N] [--seconds S] [--command-window N]\n";
            return 2;
        }
    }
    Rover rover;
    try {
        rr::Bridge bridge(k10_tables(), rover, options);
        bridge.publish_config("rapid_command_config", rapid_k10red::config_rapid_command_config());
        bridge.publish_config("rapid_position_config", rapid_k10red::config_rapid_position_config());
        auto agent_config = rapid_k10red::config_rapid_agent_config();
        bridge.publish_config("rapid_agent_config", agent_config);
        ::rapid::ext::arc::GpsConfig gps_config;
        gps_config.receiverModel = "simulated";
        gps_config.datum = "WGS84";
        bridge.publish_config("rapid_ext_arc_gps_config", gps_config);
        bridge.start();

        // state and samples: values as the configs declare them
        ::rapid::AgentState agent;
        for (const auto& k : agent_config.valueKeys) agent.values.push_back(k.value);
        agent.values[0].f(87.0f);  // batteryCharge
        agent.values[1].f(28.0f);  // batteryVoltage
        ::rapid::PositionSample position;
        position.pose.rot = {0, 0, 0, 1, 0, 0, 0, 0, 0};  // RAPID_ROT_QUAT: x, y, z, w
        position.values.push_back(rr::union_of(Value(0.0f)));
        position.values.push_back(rr::union_of(Value(0.0)));
        position.values.push_back(rr::union_of(Value(0.0f)));
        ::rapid::ext::arc::GpsSample gps;
        gps.latitude = 37.4;
        gps.longitude = -122.06;
        struct Camera {
            const char* topic;
            const char* sensor;
            const char* type;
            const char* mime;
            std::int32_t width, height;
        };
        const Camera cameras[] = {{"panCamLeft", "PanCamLeft", "stereo-left", "image/jpeg", 1360, 1024},
                                  {"panCamRight", "PanCamRight", "stereo-right", "image/jpeg", 1360, 1024},
                                  {"hazCam", "HazCamFront", "stereo-left", "image/png", 640, 480}};
        for (const auto& c : cameras) {
            ::rapid::ImageSensorState state;
            state.meta.sensorName = c.sensor;
            state.meta.sensorType = c.type;
            state.meta.width = c.width;
            state.meta.height = c.height;
            bridge.publish(std::string("rapid_imagesensor_state-") + c.topic, state, "", "RapidStateQos");
        }
        ::rapid::ImageSensorSample image;
        image.meta.sensorName = "HazCamFront";
        image.meta.sensorType = "stereo-left";
        image.meta.width = 640;
        image.meta.height = 480;
        image.mimeType = "image/png";
        image.data.assign(64, 0);
        ::rapid::TextMessage text;
        text.level = ::rapid::MessageLevel::MSG_INFO;
        text.category = "system";
        text.message = "K10Red on the C++ runtime";
        bridge.publish("rapid_textmessage", text, "", "RapidReliableDurableQos");

        std::signal(SIGINT, [](int) { signalled = true; });
        std::signal(SIGTERM, [](int) { signalled = true; });
        std::cout << "bridge ready: asset K10Red, domain " << (options.domain < 0 ? 0 : options.domain)
                  << ", partition K10Red, C++ runtime" << std::endl;

        Every<int> agent_rate{period(4)}, position_rate{period(1)}, gps_rate{period(1)}, image_rate{period(0.5)};
        const auto end = seconds < 0 ? Clock::time_point::max()
                                     : Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                          std::chrono::duration<double>(seconds));
        while (!signalled && !bridge.wait(0.01) && Clock::now() < end) {
            auto now = Clock::now();
            if (agent_rate.due(now)) bridge.publish("rapid_agent_state", agent, "rapid_agent_config");
            if (position_rate.due(now)) bridge.publish("rapid_position_sample", position, "rapid_position_config");
            if (gps_rate.due(now)) bridge.publish("rapid_ext_arc_gps_sample", gps, "rapid_ext_arc_gps_config");
            if (image_rate.due(now)) {
                ::rapid::ImageSensorState state;
                state.meta = image.meta;
                bridge.publish("rapid_imagesensor_state-hazCam", state, "", "RapidStateQos");
                bridge.publish("rapid_imagesensor_sample-hazCam", image, "");
            }
        }
        bridge.stop();
    } catch (const std::exception& e) {
        std::cerr << "k10_bridge: " << e.what() << std::endl;
        return 3;
    }
    std::cout << "bridge stopped" << std::endl;
    return 0;
}
