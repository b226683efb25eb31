//! The parameters of the GA-tuned virtual forces (DESIGN §3.5): plain data with units and the paper's defaults, and the
//! table the panel, the codec and validation read. The planner itself is in `crate::planners::forces`.

use super::spec::ParamSpec;
use serde::{Deserialize, Serialize};

/// Virtual-force parameters. Lengths in px, speeds in px/step, angles in degrees.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ForcesParams {
    /// s1, weight of separation (0…1). Default 0.42 (paper, Table 14.1, B1-E1).
    pub separation_weight: f32,
    /// s2, weight of alignment (0…1). Default 0.03.
    pub alignment_weight: f32,
    /// s3, weight of cohesion (0…1). Default 0.15.
    pub cohesion_weight: f32,
    /// s4, weight of following the goal or the leader's trace (0…1). Default 0.84.
    pub following_weight: f32,
    /// s5, weight of obstacle (and border) repulsion (0…1). Default 0.44.
    pub collision_weight: f32,
    /// Full opening of the view cone. Default 330°.
    pub view_angle_deg: f32,
    /// View distance in body sizes (diameters). Default 20.
    pub view_range_sizes: f32,
    /// Translation speed limit. Default 2 px/step.
    pub max_speed: f32,
    /// Rotation speed limit: largest heading change per step. Default 10°/step.
    pub max_turn_deg: f32,
    /// Acceleration of a unit force. Default 0.2 px/step².
    pub max_force: f32,
    /// A collision with an obstacle is predicted this many steps ahead. Default 30 steps.
    pub horizon_steps: f32,
    /// Distance behind the goal (along the goal's trace) the group heads for; 0 = the goal
    /// itself. Default 0 px.
    pub follow_offset: f32,
    /// Within this distance of the followed point the following force asks for less speed.
    /// Default 40 px.
    pub slowing_distance: f32,
}

impl Default for ForcesParams {
    fn default() -> Self {
        Self {
            separation_weight: 0.42,
            alignment_weight: 0.03,
            cohesion_weight: 0.15,
            following_weight: 0.84,
            collision_weight: 0.44,
            view_angle_deg: 330.0,
            view_range_sizes: 20.0,
            max_speed: 2.0,
            max_turn_deg: 10.0,
            max_force: 0.2,
            horizon_steps: 30.0,
            follow_offset: 0.0,
            slowing_distance: 40.0,
        }
    }
}

impl ForcesParams {
    /// The parameter table (sliders, range checks, docs).
    pub const SPECS: &'static [ParamSpec] = &[
        ParamSpec::number(
            "separation_weight",
            "s1 separation",
            "×",
            (0.0, 1.0, 0.001),
            0.42,
            "Weight of the repulsion from neighbours (paper Table 14.1, B1-E1: 0.42).",
        ),
        ParamSpec::number(
            "alignment_weight",
            "s2 alignment",
            "×",
            (0.0, 1.0, 0.001),
            0.03,
            "Weight of matching the neighbours' mean velocity.",
        ),
        ParamSpec::number(
            "cohesion_weight",
            "s3 cohesion",
            "×",
            (0.0, 1.0, 0.001),
            0.15,
            "Weight of the pull towards the neighbours' centre.",
        ),
        ParamSpec::number(
            "following_weight",
            "s4 following",
            "×",
            (0.0, 1.0, 0.001),
            0.84,
            "Weight of heading for the (possibly moving) goal or a point on its trace.",
        ),
        ParamSpec::number(
            "collision_weight",
            "s5 collision",
            "×",
            (0.0, 1.0, 0.001),
            0.44,
            "Weight of the repulsion from obstacles a collision is predicted with.",
        ),
        ParamSpec::number(
            "view_angle_deg",
            "View angle",
            "°",
            (10.0, 360.0, 1.0),
            330.0,
            "Opening of the view cone; neighbours behind it are ignored.",
        ),
        ParamSpec::number(
            "view_range_sizes",
            "View range",
            "body sizes",
            (1.0, 50.0, 0.5),
            20.0,
            "How far an agent sees, in body diameters (paper: 20).",
        ),
        ParamSpec::number(
            "max_speed",
            "Max speed",
            "px/step",
            (0.1, 20.0, 0.1),
            2.0,
            "Translation speed limit; one step is 1/60 s.",
        ),
        ParamSpec::number(
            "max_turn_deg",
            "Max turn",
            "°/step",
            (0.5, 180.0, 0.5),
            10.0,
            "Rotation speed limit: largest heading change in one step.",
        ),
        ParamSpec::number(
            "max_force",
            "Force scale",
            "px/step²",
            (0.005, 2.0, 0.005),
            0.2,
            "Acceleration produced by a force of length 1.",
        ),
        ParamSpec::number(
            "horizon_steps",
            "Collision horizon",
            "steps",
            (1.0, 300.0, 1.0),
            30.0,
            "Obstacles on the course within this many steps repel the agent.",
        ),
        ParamSpec::number(
            "follow_offset",
            "Follow offset",
            "px",
            (0.0, 500.0, 1.0),
            0.0,
            "Head for a point this far behind the goal along its trace (0: the goal itself).",
        ),
        ParamSpec::number(
            "slowing_distance",
            "Slowing distance",
            "px",
            (1.0, 500.0, 1.0),
            40.0,
            "Within this distance of the followed point the agent slows down.",
        ),
    ];

    /// The five weights `[s1, s2, s3, s4, s5]`.
    pub fn weights(&self) -> [f32; 5] {
        [
            self.separation_weight,
            self.alignment_weight,
            self.cohesion_weight,
            self.following_weight,
            self.collision_weight,
        ]
    }

    /// Sets the five weights `[s1, s2, s3, s4, s5]`.
    pub fn set_weights(&mut self, s: [f32; 5]) {
        [
            self.separation_weight,
            self.alignment_weight,
            self.cohesion_weight,
            self.following_weight,
            self.collision_weight,
        ] = s;
    }
}
