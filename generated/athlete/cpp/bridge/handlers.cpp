// Handlers of asset ATHLETE: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the
// descriptor changes, handlers.hpp changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see handlers.hpp
// for the rules (results, progress, cancellation). `rapid_athlete_bridge --simulate` runs
// a simulated robot instead of these. To publish telemetry of your own, set
// HandlerSet::on_start and use rapid_runtime::dds::Telemetry
// (#include <rapid_runtime/dds/telemetry.hpp>).
#include "handlers.hpp"

namespace rapid_athlete::bridge {

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

class LimbController final : public LimbControllerHandler {
public:
    // LimbController/moveFoot: move one foot (wheel) to a position
    ::rapid_runtime::Result moveFoot([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] ::std::int32_t limb,
        [[maybe_unused]] const ::rapid_runtime::Vec3d& xyz,
        [[maybe_unused]] const ::std::string& frame) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // LimbController/setLimbJoints: set the six joints of one limb
    ::rapid_runtime::Result setLimbJoints([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] ::std::int32_t limb,
        [[maybe_unused]] float hipYaw,
        [[maybe_unused]] float hipPitch,
        [[maybe_unused]] float kneePitch,
        [[maybe_unused]] float anklePitch,
        [[maybe_unused]] float ankleYaw,
        [[maybe_unused]] float ankleRoll) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // LimbController/setStance: all six limbs to a named stance
    ::rapid_runtime::Result setStance([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::std::string& stance) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // LimbController/walk: walk a distance with the current gait
    ::rapid_runtime::Result walk([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::std::string& gait,
        [[maybe_unused]] double distance,
        [[maybe_unused]] double heading) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // LimbController/lockWheels: no description
    ::rapid_runtime::Result lockWheels([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] bool locked) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

class Deck final : public DeckHandler {
public:
    // Deck/levelDeck: no description
    ::rapid_runtime::Result levelDeck([[maybe_unused]] ::rapid_runtime::CommandContext& ctx) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // Deck/setDeckHeight: no description
    ::rapid_runtime::Result setDeckHeight([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] double height) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

class AthleteNative final : public AthleteNativeHandler {
public:
    // AthleteNative/athleteCommand: an ATHLETE Workbench command, handed to the ATHLETE Bridge untranslated
    ::rapid_runtime::Result athleteCommand([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::std::string& command) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

}  // namespace

HandlerSet make_handlers() {
    HandlerSet set;
    set.mobility = ::std::make_unique<Mobility>();
    set.queue = ::std::make_unique<Queue>();
    set.limb_controller = ::std::make_unique<LimbController>();
    set.deck = ::std::make_unique<Deck>();
    set.athlete_native = ::std::make_unique<AthleteNative>();
    return set;
}

}  // namespace rapid_athlete::bridge
