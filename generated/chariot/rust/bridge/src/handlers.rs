// Handlers of asset Chariot: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the descriptor
// changes, dispatch.rs changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see dispatch.rs for
// the rules (outcomes, progress, cancellation). `rapid_chariot_bridge --simulate` runs a simulated
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

pub struct ChariotDrive;

impl ChariotDriveHandler for ChariotDrive {
    /// ChariotDrive/setSteeringMode: no description
    fn set_steering_mode(&self, ctx: &Context, mode: &str) -> Outcome {
        Outcome::NotImplemented
    }

    /// ChariotDrive/setSpeedLimit: no description
    fn set_speed_limit(&self, ctx: &Context, speed: f32) -> Outcome {
        Outcome::NotImplemented
    }

    /// ChariotDrive/setRideHeight: active suspension height above the ground
    fn set_ride_height(&self, ctx: &Context, height: f32) -> Outcome {
        Outcome::NotImplemented
    }
}

pub struct Turret;

impl TurretHandler for Turret {
    /// Turret/rotateTurret: no description
    fn rotate_turret(&self, ctx: &Context, angle: f32) -> Outcome {
        Outcome::NotImplemented
    }
}

pub struct ChariotNative;

impl ChariotNativeHandler for ChariotNative {
    /// ChariotNative/ccmd: a CCMD command string, forwarded to the vehicle socket as-is
    fn ccmd(&self, ctx: &Context, command: &str) -> Outcome {
        Outcome::NotImplemented
    }
}

pub fn make_handlers() -> HandlerSet {
    HandlerSet {
        mobility: ::std::boxed::Box::new(Mobility),
        chariot_drive: ::std::boxed::Box::new(ChariotDrive),
        turret: ::std::boxed::Box::new(Turret),
        chariot_native: ::std::boxed::Box::new(ChariotNative),
    }
}
