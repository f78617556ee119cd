// Handlers of asset EvaSuitA: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the
// descriptor changes, handlers.hpp changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see handlers.hpp
// for the rules (results, progress, cancellation). `rapid_evasuita_bridge --simulate` runs
// a simulated robot instead of these. To publish telemetry of your own, set
// HandlerSet::on_start and use rapid_runtime::dds::Telemetry
// (#include <rapid_runtime/dds/telemetry.hpp>).
#include "handlers.hpp"

namespace rapid_evasuita::bridge {

HandlerSet make_handlers() {
    HandlerSet set;
    // (the asset takes no commands of its own: no handler to make)
    return set;
}

}  // namespace rapid_evasuita::bridge
