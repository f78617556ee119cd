// Handlers of asset EvaSuitA: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the descriptor
// changes, dispatch.rs changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see dispatch.rs for
// the rules (outcomes, progress, cancellation). `rapid_evasuita_bridge --simulate` runs a simulated
// robot instead of these.
#![allow(unused_variables)]

#[allow(unused_imports)]
use crate::dispatch::*;

pub fn make_handlers() -> HandlerSet {
    HandlerSet {
    }
}
