// Handlers of asset ATHLETE: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the descriptor
// changes, dispatch.rs changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see dispatch.rs for
// the rules (outcomes, progress, cancellation). `rapid_athlete_bridge --simulate` runs a simulated
// robot instead of these.
#![allow(unused_variables)]

use rapid_runtime::{Context, Outcome};

#[allow(unused_imports)]
use crate::dispatch::*;

pub struct Mobility;

impl MobilityHandler for Mobility {
    /// Mobility/stopAllMotion: stop every motion now
    fn stop_all_motion(&self, ctx: &Context) -> Outcome {
        Outcome::NotImplemented
    }

    /// Mobility/simpleMove: drive to x, y and heading in frame
    fn simple_move(&self, ctx: &Context, frame: &str, xyt: [f64; 3]) -> Outcome {
        Outcome::NotImplemented
    }

    /// Mobility/move: drive to x, y and heading in frame, within tolerances
    fn move_(&self, ctx: &Context, frame: &str, xyt: [f64; 3], xyt_tolerance: [f64; 3]) -> Outcome {
        Outcome::NotImplemented
    }

    /// Mobility/move6DOF: move to a full pose in frame
    fn move6_dof(&self, ctx: &Context, frame: &str, xyz: [f64; 3], rot: [f32; 9]) -> Outcome {
        Outcome::NotImplemented
    }
}

pub struct Queue;

impl QueueHandler for Queue {
    /// Queue/loadMacro: queue the commands of a named macro
    fn load_macro(&self, ctx: &Context, name: &str) -> Outcome {
        Outcome::NotImplemented
    }
}

pub struct LimbController;

impl LimbControllerHandler for LimbController {
    /// LimbController/moveFoot: move one foot (wheel) to a position
    fn move_foot(&self, ctx: &Context, limb: i32, xyz: [f64; 3], frame: &str) -> Outcome {
        Outcome::NotImplemented
    }

    /// LimbController/setLimbJoints: set the six joints of one limb
    fn set_limb_joints(&self, ctx: &Context, limb: i32, hip_yaw: f32, hip_pitch: f32, knee_pitch: f32, ankle_pitch: f32, ankle_yaw: f32, ankle_roll: f32) -> Outcome {
        Outcome::NotImplemented
    }

    /// LimbController/setStance: all six limbs to a named stance
    fn set_stance(&self, ctx: &Context, stance: &str) -> Outcome {
        Outcome::NotImplemented
    }

    /// LimbController/walk: walk a distance with the current gait
    fn walk(&self, ctx: &Context, gait: &str, distance: f64, heading: f64) -> Outcome {
        Outcome::NotImplemented
    }

    /// LimbController/lockWheels: no description
    fn lock_wheels(&self, ctx: &Context, locked: bool) -> Outcome {
        Outcome::NotImplemented
    }
}

pub struct Deck;

impl DeckHandler for Deck {
    /// Deck/levelDeck: no description
    fn level_deck(&self, ctx: &Context) -> Outcome {
        Outcome::NotImplemented
    }

    /// Deck/setDeckHeight: no description
    fn set_deck_height(&self, ctx: &Context, height: f64) -> Outcome {
        Outcome::NotImplemented
    }
}

pub struct AthleteNative;

impl AthleteNativeHandler for AthleteNative {
    /// AthleteNative/athleteCommand: an ATHLETE Workbench command, handed to the ATHLETE Bridge untranslated
    fn athlete_command(&self, ctx: &Context, command: &str) -> Outcome {
        Outcome::NotImplemented
    }
}

pub fn make_handlers() -> HandlerSet {
    HandlerSet {
        mobility: ::std::boxed::Box::new(Mobility),
        queue: ::std::boxed::Box::new(Queue),
        limb_controller: ::std::boxed::Box::new(LimbController),
        deck: ::std::boxed::Box::new(Deck),
        athlete_native: ::std::boxed::Box::new(AthleteNative),
    }
}
