// Handlers of asset K10Red: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the
// descriptor changes, handlers.hpp changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see handlers.hpp
// for the rules (results, progress, cancellation). `rapid_k10red_bridge --simulate` runs
// a simulated robot instead of these. To publish telemetry of your own, set
// HandlerSet::on_start and use rapid_runtime::dds::Telemetry
// (#include <rapid_runtime/dds/telemetry.hpp>).
#include "handlers.hpp"

namespace rapid_k10red::bridge {

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

class Queue final : public QueueHandler {
public:
    // Queue/loadMacro: queue the commands of a named macro
    ::rapid_runtime::Result loadMacro([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::std::string& name) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

class PanTiltCamera final : public PanTiltCameraHandler {
public:
    // PanTiltCamera/pointCamera: point the pan-tilt unit
    ::rapid_runtime::Result pointCamera([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] float pan,
        [[maybe_unused]] float tilt) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // PanTiltCamera/takePicture: acquire an image; it arrives on the camera's image topics
    ::rapid_runtime::Result takePicture([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::std::string& mode,
        [[maybe_unused]] float exposure) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // PanTiltCamera/takePanorama: a tiled panorama between two pan angles
    ::rapid_runtime::Result takePanorama([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] float panStart,
        [[maybe_unused]] float panEnd,
        [[maybe_unused]] float tilt,
        [[maybe_unused]] ::std::int32_t tiles) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

class K10Native final : public K10NativeHandler {
public:
    // K10Native/nativeCommand: a K10 command line, passed to the rover executive as-is
    ::rapid_runtime::Result nativeCommand([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::std::string& text) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

}  // namespace

HandlerSet make_handlers() {
    HandlerSet set;
    set.mobility = ::std::make_unique<Mobility>();
    set.queue = ::std::make_unique<Queue>();
    set.pan_tilt_camera = ::std::make_unique<PanTiltCamera>();
    set.k10_native = ::std::make_unique<K10Native>();
    return set;
}

}  // namespace rapid_k10red::bridge
