// The simulated robot's telemetry (`--simulate`; simulate.py's on_start and publishing
// threads): every declared telemetry entry at its declared rate from the Simulator's state
// (agent values with a draining battery, the body's position, joint angles), pictures (a
// synthetic landscape of the declared size and MIME type, with the sensor's state) at
// their rate, or every IDLE_PERIOD seconds when no command takes them, a text message at
// start, and extension types through the generated code (CustomPublisher: plausible
// values of the asset's own types). A telemetry entry that cannot be sent is logged once
// and the bridge keeps running.
#ifndef RAPID_RUNTIME_DDS_SIMULATE_HPP
#define RAPID_RUNTIME_DDS_SIMULATE_HPP

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <rapid_runtime/simulator.hpp>

#include "bridge.hpp"
#include "telemetry.hpp"

namespace rapid_runtime {
namespace dds {

// What the generated code gives for a custom (extension) telemetry entry's role: making its
// writer, and publishing one message (config: Bridge::publish_config; sample or state:
// Bridge::publish, paired with the entry's config).
struct CustomPublisher {
    std::size_t entry = 0;  // index in Tables::telemetry
    std::string role;  // config, state or sample
    std::function<void(Bridge&)> writer;
    std::function<void(Bridge&)> publish;
};

class SimulatedTelemetry {
public:
    SimulatedTelemetry(Bridge& bridge, Simulator& simulator, std::vector<CustomPublisher> custom);
    ~SimulatedTelemetry();
    SimulatedTelemetry(const SimulatedTelemetry&) = delete;
    SimulatedTelemetry& operator=(const SimulatedTelemetry&) = delete;

    // Writers of every telemetry topic, then what goes out once (extension configs, each
    // camera's state, a text message). Before Bridge::start.
    void prepare();
    // The publishing threads (after Bridge::start).
    void start();
    // Joins them; idempotent. Before Bridge::stop.
    void stop();

private:
    struct Due {
        std::size_t entry;  // index in Tables::telemetry
        std::size_t index;  // among entries of its kind
        double period;  // s
        double next = 0.0;
    };
    void run(std::vector<Due> due, bool drain);
    void sample(std::size_t entry, std::size_t index);
    void picture(std::size_t index);
    void report(std::size_t entry, const std::exception& e);

    Bridge& bridge_;
    Simulator& sim_;
    Telemetry tel_;
    const Breaks* breaks_;  // a test build's --break (breaks.hpp); null: none
    std::vector<CustomPublisher> custom_;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stopping_ = false;
    std::vector<std::thread> threads_;
    std::map<std::size_t, std::uint32_t> frames_;  // pictures taken per camera
    std::set<std::pair<std::size_t, std::string>> reported_;
};

}  // namespace dds
}  // namespace rapid_runtime

#endif
