//! The parameters of the firefly crowd (Zhang et al. 2017, DESIGN §3.3): plain data with units and the paper's defaults, and the
//! table the panel, the codec and validation read. The planner itself is in `crate::planners::firefly`.

use super::spec::ParamSpec;
use serde::{Deserialize, Serialize};

/// Firefly parameters. Lengths in px, speeds in px/step, accelerations in px/step².
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FireflyParams {
    /// Speed limit (px/step). Range 0.1…20, default 2 (paper).
    pub max_velocity: f32,
    /// α, random step, in units of r_safe. Range 0…1, default 0.2 (paper).
    pub alpha: f32,
    /// β0, attractiveness at distance 0. Range 0…2, default 1 (paper).
    pub beta0: f32,
    /// γ, light absorption per (r / r_safe)^m. Range 0…10, default 0.05 (paper).
    pub gamma: f32,
    /// m, exponent of the distance in β. Range 1…4, default 2 (paper).
    pub exponent: f32,
    /// h, feeler length (px) = body length / 2 + r_safe. Range 0…300, default 60 (paper).
    pub feeler_length: f32,
    /// r_safe, the largest safe distance (px), also the length unit of β. Range 1…300, default 50
    /// (paper).
    pub safe_distance: f32,
    /// Speed, as a share of max_velocity, of a firefly with a brighter one within r_safe of its
    /// feeler tip (and the factor on its speed while it touches a brighter one ahead). Range 0…1,
    /// default 0.55.
    pub brake: f32,
    /// Lightest firefly mass. Range 1…200, default 20 (paper).
    pub mass_min: f32,
    /// Heaviest firefly mass. Range 1…200, default 40 (paper).
    pub mass_max: f32,
    /// Brighter fireflies farther than this (px) are not seen. Range 10…1000, default 200.
    pub view_radius: f32,
    /// Sideways acceleration when an obstacle is ahead (px/step²). Range 0…10, default 1.
    pub avoid_strength: f32,
}

impl Default for FireflyParams {
    fn default() -> Self {
        Self {
            max_velocity: 2.0,
            alpha: 0.2,
            beta0: 1.0,
            gamma: 0.05,
            exponent: 2.0,
            feeler_length: 60.0,
            safe_distance: 50.0,
            brake: 0.55,
            mass_min: 20.0,
            mass_max: 40.0,
            view_radius: 200.0,
            avoid_strength: 1.0,
        }
    }
}

impl FireflyParams {
    /// The parameter table (sliders, range checks, docs).
    pub const SPECS: &'static [ParamSpec] = &[
        ParamSpec::number("max_velocity", "Max velocity", "px/step", (0.1, 20.0, 0.1), 2.0, "Speed limit."),
        ParamSpec::number(
            "alpha",
            "Random step α",
            "× r_safe",
            (0.0, 1.0, 0.01),
            0.2,
            "Size of the random part of each move.",
        ),
        ParamSpec::number("beta0", "β0", "", (0.0, 2.0, 0.05), 1.0, "Attractiveness at distance 0."),
        ParamSpec::number(
            "gamma",
            "Absorption γ",
            "",
            (0.0, 10.0, 0.01),
            0.05,
            "Light absorption: smaller γ, stronger pull from far away (distance in units of r_safe).",
        ),
        ParamSpec::number("exponent", "Exponent m", "", (1.0, 4.0, 0.1), 2.0, "Power of the distance in β."),
        ParamSpec::number(
            "feeler_length",
            "Feeler length h",
            "px",
            (0.0, 300.0, 1.0),
            60.0,
            "Length of the feeler along the velocity: body/2 + r_safe.",
        ),
        ParamSpec::number(
            "safe_distance",
            "Safe distance r_safe",
            "px",
            (1.0, 300.0, 1.0),
            50.0,
            "A brighter firefly this close to the feeler tip slows the firefly down.",
        ),
        ParamSpec::number(
            "brake",
            "Brake factor",
            "×",
            (0.0, 1.0, 0.05),
            0.55,
            "Speed (× max velocity) while a brighter firefly is at the feeler tip.",
        ),
        ParamSpec::number("mass_min", "Mass min", "", (1.0, 200.0, 1.0), 20.0, "Lightest firefly."),
        ParamSpec::number("mass_max", "Mass max", "", (1.0, 200.0, 1.0), 40.0, "Heaviest firefly."),
        ParamSpec::number(
            "view_radius",
            "View radius",
            "px",
            (10.0, 1000.0, 5.0),
            200.0,
            "Brighter fireflies farther away are not seen.",
        ),
        ParamSpec::number(
            "avoid_strength",
            "Avoidance",
            "px/step²",
            (0.0, 10.0, 0.1),
            1.0,
            "Sideways push when the feeler meets an obstacle.",
        ),
    ];
}
