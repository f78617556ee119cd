// Handlers of asset Oddity: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the
// descriptor changes, handlers.hpp changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see handlers.hpp
// for the rules (results, progress, cancellation). `rapid_oddity_bridge --simulate` runs
// a simulated robot instead of these. To publish telemetry of your own, set
// HandlerSet::on_start and use rapid_runtime::dds::Telemetry
// (#include <rapid_runtime/dds/telemetry.hpp>).
#include "handlers.hpp"

namespace rapid_oddity::bridge {

namespace {

class Queue final : public QueueHandler {
public:
    // Queue/loadMacro: queue the commands of a named macro
    ::rapid_runtime::Result loadMacro([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::std::string& name) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

class Winch final : public WinchHandler {
public:
    // Winch/reelOut: no description
    ::rapid_runtime::Result reelOut([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] float length) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // Winch/setTension: no description
    ::rapid_runtime::Result setTension([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] ::std::int32_t tension) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // Winch/setOffset: no description
    ::rapid_runtime::Result setOffset([[maybe_unused]] ::rapid_runtime::CommandContext& ctx,
        [[maybe_unused]] const ::rapid_runtime::Vec3d& offset) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }

    // Winch/cancelAll: lets go of the winch's own pending moves (not the command queue's cancelAll)
    ::rapid_runtime::Result cancelAll([[maybe_unused]] ::rapid_runtime::CommandContext& ctx) override {
        return ::rapid_runtime::Result::failed("not implemented");
    }
};

}  // namespace

HandlerSet make_handlers() {
    HandlerSet set;
    set.queue = ::std::make_unique<Queue>();
    set.winch = ::std::make_unique<Winch>();
    return set;
}

}  // namespace rapid_oddity::bridge
