// Handlers that also hear when the bridge starts (to publish telemetry of their own with
// rapid_runtime::dds::Telemetry or Bridge::publish, from telemetry.hpp and bridge.hpp) and
// before it stops. A generated bridge's glue (Dispatch) is one. Light on purpose: no Fast
// DDS header, so the generated handler files compile quickly.
#ifndef RAPID_RUNTIME_DDS_BRIDGE_HANDLERS_HPP
#define RAPID_RUNTIME_DDS_BRIDGE_HANDLERS_HPP

#include <rapid_runtime/handlers.hpp>

namespace rapid_runtime {
namespace dds {

class Bridge;

class BridgeHandlers : public Handlers {
public:
    virtual void on_start(Bridge&) {}
    virtual void on_stop() {}
};

}  // namespace dds
}  // namespace rapid_runtime

#endif
