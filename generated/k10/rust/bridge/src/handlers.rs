// Handlers of asset K10Red: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the descriptor
// changes, dispatch.rs changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see dispatch.rs for
// the rules (outcomes, progress, cancellation). `rapid_k10red_bridge --simulate` runs a simulated
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

pub struct PanTiltCamera;

impl PanTiltCameraHandler for PanTiltCamera {
    /// PanTiltCamera/pointCamera: point the pan-tilt unit
    fn point_camera(&self, ctx: &Context, pan: f32, tilt: f32) -> Outcome {
        Outcome::NotImplemented
    }

    /// PanTiltCamera/takePicture: acquire an image; it arrives on the camera's image topics
    fn take_picture(&self, ctx: &Context, mode: &str, exposure: f32) -> Outcome {
        Outcome::NotImplemented
    }

    /// PanTiltCamera/takePanorama: a tiled panorama between two pan angles
    fn take_panorama(&self, ctx: &Context, pan_start: f32, pan_end: f32, tilt: f32, tiles: i32) -> Outcome {
        Outcome::NotImplemented
    }
}

pub struct K10Native;

impl K10NativeHandler for K10Native {
    /// K10Native/nativeCommand: a K10 command line, passed to the rover executive as-is
    fn native_command(&self, ctx: &Context, text: &str) -> Outcome {
        Outcome::NotImplemented
    }
}

pub fn make_handlers() -> HandlerSet {
    HandlerSet {
        mobility: ::std::boxed::Box::new(Mobility),
        queue: ::std::boxed::Box::new(Queue),
        pan_tilt_camera: ::std::boxed::Box::new(PanTiltCamera),
        k10_native: ::std::boxed::Box::new(K10Native),
    }
}
