//! The parameters of the collision-free speed model: Tordeux, Chraibi & Seyfried, "Collision-free
//! speed model for pedestrian dynamics", Traffic and Granular Flow '15 (Springer 2016), 225–232,
//! arXiv:1512.05597. Plain data in SI units and the table the panel, the codec and validation
//! read; the planner is `crate::planners::collision_free_speed`.
//!
//! The defaults are those of JuPedSim's `CollisionFreeSpeedModel` (the reference implementation
//! by the paper's group): v⁰ 1.2 m/s, T 1 s, neighbour repulsion a = 8 over D = 0.1 m, wall
//! repulsion 5 over 0.02 m, neighbours within 3 m. The body length ℓ of the speed function is
//! not a parameter here: it is the two bodies' radii summed, from the scene's agents (the
//! diameter of equal bodies, the paper's ℓ; 0.4 m for the suite's 0.2 m radius, JuPedSim's
//! default radius).

use super::guidance::{Guidance, GUIDANCE_CHOICES};
use super::spec::ParamSpec;
use serde::{Deserialize, Serialize};

/// Collision-free speed model parameters. Lengths in m, speeds in m/s, times in s; the
/// repulsion strengths are dimensionless (they weigh unit vectors against the desired direction).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CollisionFreeSpeedParams {
    /// Desired (free) speed v⁰, the speed function's plateau (m/s, 0.1…5). Default 1.2.
    pub desired_speed: f32,
    /// Time gap T of the speed function `V(s) = min(v⁰, max(0, (s − ℓ)/T))` (s, 0.1…10):
    /// the time an agent keeps to the one ahead. Default 1.
    pub time_gap: f32,
    /// a, weight of one neighbour's repulsion `a·exp((ℓ − d)/D)` in the direction (0…50).
    /// Default 8.
    pub neighbour_strength: f32,
    /// D, decay length of the neighbour repulsion (m, 0.01…2). Default 0.1.
    pub neighbour_range: f32,
    /// Weight of a wall's repulsion `a_w·exp((r − d)/D_w)` in the direction (0…50). Default 5.
    pub wall_strength: f32,
    /// D_w, decay length of the wall repulsion (m, 0.005…2). Default 0.02.
    pub wall_range: f32,
    /// Other agents within this distance (centre to centre) are seen (m, 0.5…10). Default 3
    /// (JuPedSim's cut-off): beyond it the repulsion is below e⁻²⁶ of a and the spacing above
    /// anything that limits a walking speed.
    pub cutoff: f32,
    /// Where the desired direction `e⁰` points: the goal's flow field or straight at the goal.
    pub guidance: Guidance,
}

impl Default for CollisionFreeSpeedParams {
    fn default() -> Self {
        Self {
            desired_speed: 1.2,
            time_gap: 1.0,
            neighbour_strength: 8.0,
            neighbour_range: 0.1,
            wall_strength: 5.0,
            wall_range: 0.02,
            cutoff: 3.0,
            guidance: Guidance::FlowField,
        }
    }
}

impl CollisionFreeSpeedParams {
    /// The parameter table (sliders, range checks, docs).
    pub const SPECS: &'static [ParamSpec] = &[
        ParamSpec::number(
            "desired_speed",
            "Desired speed v⁰",
            "m/s",
            (0.1, 5.0, 0.01),
            1.2,
            "Free walking speed: the most the speed function gives (JuPedSim: 1.2 m/s).",
        ),
        ParamSpec::number(
            "time_gap",
            "Time gap T",
            "s",
            (0.1, 10.0, 0.05),
            1.0,
            "Speed = (spacing ahead − body length) / T, at most v⁰ (1 s).",
        ),
        ParamSpec::number(
            "neighbour_strength",
            "Neighbour repulsion a",
            "×",
            (0.0, 50.0, 0.1),
            8.0,
            "Weight of a neighbour's push on the walking direction (JuPedSim: 8).",
        ),
        ParamSpec::number(
            "neighbour_range",
            "Neighbour range D",
            "m",
            (0.01, 2.0, 0.01),
            0.1,
            "Decay length of the neighbour repulsion (0.1 m).",
        ),
        ParamSpec::number(
            "wall_strength",
            "Wall repulsion",
            "×",
            (0.0, 50.0, 0.1),
            5.0,
            "Weight of a wall's push on the walking direction (JuPedSim: 5).",
        ),
        ParamSpec::number(
            "wall_range",
            "Wall range",
            "m",
            (0.005, 2.0, 0.005),
            0.02,
            "Decay length of the wall repulsion (JuPedSim: 0.02 m).",
        ),
        ParamSpec::number(
            "cutoff",
            "Neighbour cut-off",
            "m",
            (0.5, 10.0, 0.1),
            3.0,
            "Other agents within this distance are seen (JuPedSim: 3 m).",
        ),
        ParamSpec::choice(
            "guidance",
            "Guidance",
            GUIDANCE_CHOICES,
            0,
            "flow_field: the desired direction follows the goal's flow field round obstacles; goal: straight at it.",
        ),
    ];
}
