//! The parameters of IGSA path control (Liu & Liu 2022, DESIGN §3.4): plain data with units and the paper's defaults, and the
//! table the panel, the codec and validation read. The planner itself is in `crate::planners::igsa`.

use super::spec::ParamSpec;
use crate::model::refusal::{Code, Message, Refusal};
use serde::{Deserialize, Serialize};

/// Most waypoints an edited path may hold.
pub const MAX_EDITED_WAYPOINTS: usize = 64;

/// Which optimizer plans the path.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PathOptimizer {
    /// Improved gravitational search (the paper's method).
    Igsa,
    /// Plain gravitational search (the paper's baseline).
    Gsa,
}

/// IGSA group path control parameters. Lengths in px, speeds in px/step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct IgsaParams {
    /// The path optimizer: `igsa` (default, the paper's) or `gsa` (its baseline).
    pub optimizer: PathOptimizer,
    /// Population N of the path optimizer. Range 5…200, default 30 (the paper uses 50; 30 plans
    /// in about 50 ms natively, so a reset in the page does not stall).
    pub population: u32,
    /// Iterations T of the path optimizer. Range 10…3000, default 300 (paper: 1000).
    pub iterations: u32,
    /// Free waypoints K between start and goal. Range 1…8, default 3 (see `optim::path`).
    pub waypoint_count: u32,
    /// Clearance the path keeps from obstacle surfaces (px). Range 0…60, default 12.
    pub clearance: f32,
    /// Speed limit (px/step). Range 0.1…10, default 1.5.
    pub max_speed: f32,
    /// Largest change of velocity per step (px/step²). Range 0.01…5, default 0.2.
    pub max_accel: f32,
    /// Half-width of the column: offsets are drawn in ±spread px. Range 0…200, default 30.
    pub spread: f32,
    /// How far ahead along the path an agent aims (px). Range 5…200, default 30.
    pub look_ahead: f32,
    /// Gap kept between two bodies: the bounding circles are the bodies grown by half of it
    /// (px). Range 0…20, default 2.
    pub margin: f32,
    /// Edited waypoints (scene px) between start and goal; empty (the default) plans them.
    /// Not a slider: the page sets it by dragging the path's handles.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub waypoints: Vec<[f32; 2]>,
}

impl Default for IgsaParams {
    fn default() -> Self {
        Self {
            optimizer: PathOptimizer::Igsa,
            population: 30,
            iterations: 300,
            waypoint_count: 3,
            clearance: 12.0,
            max_speed: 1.5,
            max_accel: 0.2,
            spread: 30.0,
            look_ahead: 30.0,
            margin: 2.0,
            waypoints: Vec::new(),
        }
    }
}

impl IgsaParams {
    /// The parameter table (sliders, range checks, docs). Append only: links store values by
    /// position. `waypoints` is not in it (a list, not a slider); the codec carries it after
    /// the table's values.
    pub const SPECS: &'static [ParamSpec] = &[
        ParamSpec::choice(
            "optimizer",
            "Path optimizer",
            &["igsa", "gsa"],
            0,
            "IGSA (Liu & Liu 2022) or plain GSA, to compare the paths they plan.",
        ),
        ParamSpec::number(
            "population",
            "Population N",
            "",
            (5.0, 200.0, 1.0),
            30.0,
            "Particles of the path optimizer.",
        ),
        ParamSpec::number(
            "iterations",
            "Iterations T",
            "",
            (10.0, 3000.0, 10.0),
            300.0,
            "Iterations of the path optimizer.",
        ),
        ParamSpec::number(
            "waypoint_count",
            "Waypoints K",
            "",
            (1.0, 8.0, 1.0),
            3.0,
            "Free waypoints between start and goal.",
        ),
        ParamSpec::number(
            "clearance",
            "Path clearance",
            "px",
            (0.0, 60.0, 1.0),
            12.0,
            "Distance the path keeps from obstacles.",
        ),
        ParamSpec::number("max_speed", "Max speed", "px/step", (0.1, 10.0, 0.1), 1.5, "Speed limit."),
        ParamSpec::number(
            "max_accel",
            "Max acceleration",
            "px/step²",
            (0.01, 5.0, 0.01),
            0.2,
            "Largest change of velocity per step.",
        ),
        ParamSpec::number(
            "spread",
            "Column half-width",
            "px",
            (0.0, 200.0, 1.0),
            30.0,
            "Agents follow the path offset sideways by up to this much.",
        ),
        ParamSpec::number(
            "look_ahead",
            "Look-ahead",
            "px",
            (5.0, 200.0, 1.0),
            30.0,
            "How far along the path an agent aims.",
        ),
        ParamSpec::number(
            "margin",
            "Body gap",
            "px",
            (0.0, 20.0, 0.5),
            2.0,
            "Gap kept between bodies (bounding circles = body + gap/2).",
        ),
    ];

    /// Checks what the table cannot: the edited waypoints.
    pub fn check_waypoints(&self) -> Result<(), WaypointError> {
        if self.waypoints.len() > MAX_EDITED_WAYPOINTS {
            return Err(WaypointError::TooMany(self.waypoints.len()));
        }
        if let Some(k) = self.waypoints.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
            return Err(WaypointError::NotFinite(k + 1));
        }
        Ok(())
    }
}

/// Why an IGSA group's edited waypoints were refused.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum WaypointError {
    /// More than [`MAX_EDITED_WAYPOINTS`] waypoints (holds the count).
    #[error("an edited path holds at most {MAX_EDITED_WAYPOINTS} waypoints, this one {0}")]
    TooMany(usize),
    /// Waypoint number `k` (from 1) has a NaN or infinite coordinate.
    #[error("waypoint {0} is not a finite point")]
    NotFinite(usize),
}

impl Refusal for WaypointError {
    fn message(&self) -> Message {
        match *self {
            WaypointError::TooMany(n) => {
                Message::new(Code::WaypointsTooMany).with("most", MAX_EDITED_WAYPOINTS).with("count", n)
            }
            WaypointError::NotFinite(k) => Message::new(Code::WaypointNotFinite).with("number", k),
        }
    }
}
