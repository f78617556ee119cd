// Handlers of asset XArm2: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the descriptor
// changes, dispatch.rs changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see dispatch.rs for
// the rules (outcomes, progress, cancellation). `rapid_xarm2_bridge --simulate` runs a simulated
// robot instead of these.
#![allow(unused_variables)]

use rapid_runtime::{Context, Outcome};

#[allow(unused_imports)]
use crate::dispatch::*;

pub struct Exoskeleton;

impl ExoskeletonHandler for Exoskeleton {
    /// Exoskeleton/enableForceFeedback: no description
    fn enable_force_feedback(&self, ctx: &Context, enabled: bool) -> Outcome {
        Outcome::NotImplemented
    }

    /// Exoskeleton/setJointTorques: torques fed back to the operator, one per joint
    fn set_joint_torques(&self, ctx: &Context, shoulder_abduction: f32, shoulder_flexion: f32, shoulder_rotation: f32, elbow_flexion: f32, forearm_rotation: f32, wrist_flexion: f32, wrist_deviation: f32) -> Outcome {
        Outcome::NotImplemented
    }

    /// Exoskeleton/setScaling: scale from operator motion to the commanded robot motion
    fn set_scaling(&self, ctx: &Context, factor: f64) -> Outcome {
        Outcome::NotImplemented
    }
}

pub fn make_handlers() -> HandlerSet {
    HandlerSet {
        exoskeleton: ::std::boxed::Box::new(Exoskeleton),
    }
}
