// Handlers of asset Robonaut2: written once by rapidgen, yours to edit.
// Regeneration never touches this file (delete it to get fresh stubs). When the descriptor
// changes, dispatch.rs changes with it and the compiler says what to update.
//
// Every method answers EXEC_FAILED "not implemented" until you write it; see dispatch.rs for
// the rules (outcomes, progress, cancellation). `rapid_robonaut2_bridge --simulate` runs a simulated
// robot instead of these.
#![allow(unused_variables)]

use rapid_runtime::{Context, Outcome};

#[allow(unused_imports)]
use crate::dispatch::*;

pub struct Arm;

impl ArmHandler for Arm {
    /// Arm/Setpoint for Tool: move the tool (hand) to a cartesian pose
    fn setpoint_for_tool(&self, ctx: &Context, xyz: [f64; 3], rpy: [f64; 3], frame: &str) -> Outcome {
        Outcome::NotImplemented
    }

    /// Arm/Setpoint for single joint: set every joint of the arm
    fn setpoint_for_single_joint(&self, ctx: &Context, abduction: f32, extension: f32, upper_arm_outer_rotation: f32, elbow_flexion: f32, forearm_outer_rotation: f32, wrist_flexion: f32, wrist_ulnar_flexion: f32) -> Outcome {
        Outcome::NotImplemented
    }
}

pub struct Neck;

impl NeckHandler for Neck {
    /// Neck/Setpoint for single joint: set every joint of the neck
    fn setpoint_for_single_joint(&self, ctx: &Context, lower_pitch: f32, yaw: f32, upper_pitch: f32) -> Outcome {
        Outcome::NotImplemented
    }
}

pub struct Hand;

impl HandHandler for Hand {
    /// Hand/Open the Hand: open all fingers
    fn open_the_hand(&self, ctx: &Context) -> Outcome {
        Outcome::NotImplemented
    }

    /// Hand/Close the Hand: close all fingers (power grasp)
    fn close_the_hand(&self, ctx: &Context) -> Outcome {
        Outcome::NotImplemented
    }
}

pub fn make_handlers() -> HandlerSet {
    HandlerSet {
        arm: ::std::boxed::Box::new(Arm),
        neck: ::std::boxed::Box::new(Neck),
        hand: ::std::boxed::Box::new(Hand),
    }
}
