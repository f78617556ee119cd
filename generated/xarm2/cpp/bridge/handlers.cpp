// Handlers of asset XArm2: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the
// descriptor changes, handlers.hpp changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see handlers.hpp
// for the rules (results, progress, cancellation). `rapid_xarm2_bridge --simulate` runs
// a simulated robot instead of these. To publish telemetry of your own, set
// HandlerSet::on_start and use rapid_runtime::dds::Telemetry
// (#include <rapid_runtime/dds/telemetry.hpp>).
#include "handlers.hpp"

namespace rapid_xarm2::bridge {

namespace {

class Exoskeleton final : public ExoskeletonHandler {
public:
    // Exoskeleton/enableForceFeedback: no description
    ::rapid_runtime::Result enableForceFeedback([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] bool enabled) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // Exoskeleton/setJointTorques: torques fed back to the operator, one per joint
    ::rapid_runtime::Result setJointTorques([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] float shoulderAbduction,
        [[maybe_unused]] float shoulderFlexion,
        [[maybe_unused]] float shoulderRotation,
        [[maybe_unused]] float elbowFlexion,
        [[maybe_unused]] float forearmRotation,
        [[maybe_unused]] float wristFlexion,
        [[maybe_unused]] float wristDeviation) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // Exoskeleton/setScaling: scale from operator motion to the commanded robot motion
    ::rapid_runtime::Result setScaling([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] double factor) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

}  // namespace

HandlerSet make_handlers() {
    HandlerSet set;
    set.exoskeleton = ::std::make_unique<Exoskeleton>();
    return set;
}

}  // namespace rapid_xarm2::bridge
