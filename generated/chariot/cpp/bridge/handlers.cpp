// Handlers of asset Chariot: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the
// descriptor changes, handlers.hpp changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see handlers.hpp
// for the rules (results, progress, cancellation). `rapid_chariot_bridge --simulate` runs
// a simulated robot instead of these. To publish telemetry of your own, set
// HandlerSet::on_start and use rapid_runtime::dds::Telemetry
// (#include <rapid_runtime/dds/telemetry.hpp>).
#include "handlers.hpp"

namespace rapid_chariot::bridge {

namespace {

class Mobility final : public MobilityHandler {
public:
    // Mobility/stopAllMotion: stop every motion now
    ::rapid_runtime::Result stopAllMotion([[maybe_unused]] ::rapid_runtime::CommandContext& ctx) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // Mobility/simpleMove: drive to x, y and heading in frame
    ::rapid_runtime::Result simpleMove([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::std::string& frame,
        [[maybe_unused]] const ::rapid_runtime::Vec3d& xyt) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // Mobility/move: drive to x, y and heading in frame, within tolerances
    ::rapid_runtime::Result move([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::std::string& frame,
        [[maybe_unused]] const ::rapid_runtime::Vec3d& xyt,
        [[maybe_unused]] const ::rapid_runtime::Vec3d& xytTolerance) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // Mobility/move6DOF: move to a full pose in frame
    ::rapid_runtime::Result move6DOF([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::std::string& frame,
        [[maybe_unused]] const ::rapid_runtime::Vec3d& xyz,
        [[maybe_unused]] const ::rapid_runtime::Mat33f& rot) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

class ChariotDrive final : public ChariotDriveHandler {
public:
    // ChariotDrive/setSteeringMode: no description
    ::rapid_runtime::Result setSteeringMode([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::std::string& mode) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // ChariotDrive/setSpeedLimit: no description
    ::rapid_runtime::Result setSpeedLimit([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] float speed) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // ChariotDrive/setRideHeight: active suspension height above the ground
    ::rapid_runtime::Result setRideHeight([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] float height) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

class Turret final : public TurretHandler {
public:
    // Turret/rotateTurret: no description
    ::rapid_runtime::Result rotateTurret([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] float angle) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

class ChariotNative final : public ChariotNativeHandler {
public:
    // ChariotNative/ccmd: a CCMD command string, forwarded to the vehicle socket as-is
    ::rapid_runtime::Result ccmd([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::std::string& command) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

}  // namespace

HandlerSet make_handlers() {
    HandlerSet set;
    set.mobility = ::std::make_unique<Mobility>();
    set.chariot_drive = ::std::make_unique<ChariotDrive>();
    set.turret = ::std::make_unique<Turret>();
    set.chariot_native = ::std::make_unique<ChariotNative>();
    return set;
}

}  // namespace rapid_chariot::bridge
