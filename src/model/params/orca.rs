//! The parameters of ORCA, optimal reciprocal collision avoidance (van den Berg, Guy, Lin &
//! Manocha, "Reciprocal n-body collision avoidance", Robotics Research 2011): plain data in SI
//! units and the table the panel, the codec and validation read. The planner itself is in
//! `crate::planners::orca`; lengths and speeds are converted to px and px/step with the scene's
//! scale (`Scene::px_per_metre`) and the step ([`crate::DT`]).
//!
//! The paper fixes no values (its experiments are in its robots' units): the counts follow its
//! reference implementation's examples (10 neighbours), the speeds and horizons are a walking
//! pedestrian's (1.34 m/s preferred, Weidmann's free walking speed; 2 s to react to others).

use super::guidance::{Guidance, GUIDANCE_CHOICES};
use super::spec::ParamSpec;
use serde::{Deserialize, Serialize};

/// ORCA parameters. Lengths in m, speeds in m/s, times in s.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OrcaParams {
    /// Preferred speed `|v_pref|` towards the goal (m/s, 0.1…5). Default 1.34.
    pub pref_speed: f32,
    /// Largest speed `v_max`, the radius of the disc `D(0, v_max)` of allowed velocities
    /// (m/s, 0.1…6). Default 2.
    pub max_speed: f32,
    /// Other agents within this distance are considered (m, 0.5…20). Default 5.
    pub neighbour_dist: f32,
    /// At most this many of them, the nearest (1…50). Default 10.
    pub max_neighbours: u32,
    /// Time horizon τ of the velocity obstacles of other agents (s, 0.1…20): a velocity is
    /// avoided if it collides within τ. Default 2.
    pub time_horizon: f32,
    /// Time horizon of the static obstacles and the world's borders (s, 0.05…20). Default 1.
    pub time_horizon_obstacles: f32,
    /// Where the preferred velocity points: the goal's flow field or straight at the goal.
    pub guidance: Guidance,
}

impl Default for OrcaParams {
    fn default() -> Self {
        Self {
            pref_speed: 1.34,
            max_speed: 2.0,
            neighbour_dist: 5.0,
            max_neighbours: 10,
            time_horizon: 2.0,
            time_horizon_obstacles: 1.0,
            guidance: Guidance::FlowField,
        }
    }
}

impl OrcaParams {
    /// The parameter table (sliders, range checks, docs).
    pub const SPECS: &'static [ParamSpec] = &[
        ParamSpec::number(
            "pref_speed",
            "Preferred speed",
            "m/s",
            (0.1, 5.0, 0.01),
            1.34,
            "Speed of the preferred velocity v_pref towards the goal (1.34 m/s: free walking).",
        ),
        ParamSpec::number(
            "max_speed",
            "Max speed",
            "m/s",
            (0.1, 6.0, 0.01),
            2.0,
            "Radius of the disc of allowed velocities; the chosen velocity never exceeds it.",
        ),
        ParamSpec::number(
            "neighbour_dist",
            "Neighbour distance",
            "m",
            (0.5, 20.0, 0.1),
            5.0,
            "Other agents within this distance are considered.",
        ),
        ParamSpec::number(
            "max_neighbours",
            "Max neighbours",
            "#",
            (1.0, 50.0, 1.0),
            10.0,
            "At most this many of them, the nearest (by distance, then id).",
        ),
        ParamSpec::number(
            "time_horizon",
            "Time horizon",
            "s",
            (0.1, 20.0, 0.1),
            2.0,
            "τ: velocities that would collide with another agent within τ are avoided.",
        ),
        ParamSpec::number(
            "time_horizon_obstacles",
            "Obstacle horizon",
            "s",
            (0.05, 20.0, 0.05),
            1.0,
            "τ for obstacles and borders: the speed towards a wall is at most gap / τ.",
        ),
        ParamSpec::choice(
            "guidance",
            "Guidance",
            GUIDANCE_CHOICES,
            0,
            "flow_field: the preferred velocity follows the goal's flow field round obstacles; goal: straight at it.",
        ),
    ];
}
