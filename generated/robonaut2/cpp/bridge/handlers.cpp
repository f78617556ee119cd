// Handlers of asset Robonaut2: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the
// descriptor changes, handlers.hpp changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see handlers.hpp
// for the rules (results, progress, cancellation). `rapid_robonaut2_bridge --simulate` runs
// a simulated robot instead of these. To publish telemetry of your own, set
// HandlerSet::on_start and use rapid_runtime::dds::Telemetry
// (#include <rapid_runtime/dds/telemetry.hpp>).
#include "handlers.hpp"

namespace rapid_robonaut2::bridge {

namespace {

class Arm final : public ArmHandler {
public:
    // Arm/Setpoint for Tool: move the tool (hand) to a cartesian pose
    ::rapid_runtime::Result Setpoint_for_Tool([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::rapid_runtime::Vec3d& xyz,
        [[maybe_unused]] const ::rapid_runtime::Vec3d& rpy,
        [[maybe_unused]] const ::std::string& frame) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // Arm/Setpoint for single joint: set every joint of the arm
    ::rapid_runtime::Result Setpoint_for_single_joint([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] float abduction,
        [[maybe_unused]] float extension,
        [[maybe_unused]] float upperArmOuterRotation,
        [[maybe_unused]] float elbowFlexion,
        [[maybe_unused]] float forearmOuterRotation,
        [[maybe_unused]] float wristFlexion,
        [[maybe_unused]] float wristUlnarFlexion) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

class Neck final : public NeckHandler {
public:
    // Neck/Setpoint for single joint: set every joint of the neck
    ::rapid_runtime::Result Setpoint_for_single_joint([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] float lowerPitch,
        [[maybe_unused]] float yaw,
        [[maybe_unused]] float upperPitch) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

class Hand final : public HandHandler {
public:
    // Hand/Open the Hand: open all fingers
    ::rapid_runtime::Result Open_the_Hand([[maybe_unused]] ::rapid_runtime::CommandContext& ctx) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // Hand/Close the Hand: close all fingers (power grasp)
    ::rapid_runtime::Result Close_the_Hand([[maybe_unused]] ::rapid_runtime::CommandContext& ctx) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

class SetpointStreams final : public Streams {
public:
    // handPose: rapid::PositionSample on 'rapid_position_sample-handPose' from XArm2, 500 Hz, deadline 10 ms, lease 100 ms, on loss: stop
    void handPose([[maybe_unused]] const ::rapid::PositionSample& sample) override {
        // the new setpoint: hand it to your control loop (no locks, no allocation here)
    }

    void on_state([[maybe_unused]] const ::rapid_runtime::StreamSpec& stream,
                  [[maybe_unused]] ::rapid_runtime::StreamState state) override {
        // lost with on_loss stop: bring the joints the stream drives to rest
    }
};

}  // namespace

HandlerSet make_handlers() {
    HandlerSet set;
    set.arm = ::std::make_unique<Arm>();
    set.neck = ::std::make_unique<Neck>();
    set.hand = ::std::make_unique<Hand>();
    set.streams = ::std::make_unique<SetpointStreams>();
    return set;
}

}  // namespace rapid_robonaut2::bridge
