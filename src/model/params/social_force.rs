//! The parameters of the social force model: Helbing & Molnár, "Social force model for
//! pedestrian dynamics", Phys. Rev. E 51, 4282 (1995) for the driving term, the exponential
//! agent–agent and agent–wall repulsion and the field of view; Helbing, Farkas & Vicsek,
//! "Simulating dynamical features of escape panic", Nature 407, 487 (2000) for the mass and the
//! body and sliding-friction forces of touching bodies. Plain data in SI units and the table the
//! panel, the codec and validation read; the planner is `crate::planners::social_force`.
//!
//! The elliptical potential comes in two specifications ([`Ellipse`]): HM's (spec I, the
//! ellipse stretched along the other's own step) and, the default, Johansson, Helbing & Shukla, "Specification
//! of the social force pedestrian model by evolutionary adjustment to video tracking data",
//! Advances in Complex Systems 10, 271 (2007) (spec II, stretched along the relative step).

use super::guidance::{Guidance, GUIDANCE_CHOICES};
use super::spec::ParamSpec;
use serde::{Deserialize, Serialize};

/// Social force parameters. Lengths in m, speeds in m/s, times in s, masses in kg; the 1995
/// potentials per unit mass (m²/s²), the 2000 body constants in N per m (k) and kg/(m·s) (κ).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SocialForceParams {
    /// Desired speed `v⁰` (m/s). Default 1.34 (1995: the mean of the Gaussian desired speeds).
    pub desired_speed: f32,
    /// Largest speed as a multiple of `v⁰` (1995: `v_max = 1.3 v⁰`). Default 1.3.
    pub max_speed_factor: f32,
    /// Relaxation time τ of the driving term (s). Default 0.5 (both papers).
    pub relaxation_time: f32,
    /// `V⁰_αβ`, strength of the agent–agent potential (m²/s²). Default 2.1 (1995).
    pub agent_strength: f32,
    /// σ, range of the agent–agent potential (m). Default 0.3 (1995).
    pub agent_range: f32,
    /// Δt of the elliptical potential: how far ahead (in seconds of the other's walk) the
    /// ellipse reaches (s). Default 2 (1995).
    pub step_time: f32,
    /// `U⁰_αB`, strength of the wall potential (m²/s²). Default 10 (1995).
    pub wall_strength: f32,
    /// R, range of the wall potential (m). Default 0.2 (1995).
    pub wall_range: f32,
    /// 2φ, the field of view (degrees). Default 200 (1995: φ = 100°).
    pub view_angle_deg: f32,
    /// c, weight of forces from outside the field of view (0…1). Default 0.5 (1995).
    pub out_of_view_weight: f32,
    /// Mass m of a pedestrian (kg). Default 80 (2000).
    pub mass: f32,
    /// k, body compression constant (kg/s², N per m of overlap). Default 1.2·10⁵ (2000).
    pub body_force: f32,
    /// κ, sliding friction constant (kg/(m·s)). Default 2.4·10⁵ (2000).
    pub friction: f32,
    /// Other agents within this distance exert forces (m); beyond it the 1995 potential is
    /// below 1% of the driving term. Default 5.
    pub interaction_range: f32,
    /// Where the desired direction `e⁰` points: the goal's flow field or straight at the goal.
    pub guidance: Guidance,
    /// Which step stretches the elliptical potential: β's own (spec I, 1995) or the relative
    /// one (spec II, 2007). Default spec II: it passes 9 of the validation suite's 12 tests
    /// where spec I passes 5 (issue 25, docs/validation.md). A scene or link that does not name
    /// it (all written before issue 25) runs spec II too.
    pub ellipse: Ellipse,
}

/// The specification of the elliptical agent–agent potential: `2b = √((‖r‖ + ‖r − y‖)² − ‖y‖²)`
/// with `r = r_α − r_β` and the step `y` that stretches the ellipse.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Ellipse {
    /// Spec I (Helbing & Molnár 1995): `y = v_β Δt`, the other's own step; a pedestrian
    /// standing still is a circle.
    SpecI,
    /// Spec II (Johansson, Helbing & Shukla 2007): `y = (v_β − v_α) Δt`, the relative step; two
    /// walking side by side at one velocity are circles to each other, one approached head-on
    /// is stretched by the closing speed.
    #[default]
    SpecIi,
}

/// The choice row's options, in [`Ellipse`] order (spec II, the second, is the default).
pub const ELLIPSE_CHOICES: &[&str] = &["spec_i", "spec_ii"];

impl Default for SocialForceParams {
    fn default() -> Self {
        Self {
            desired_speed: 1.34,
            max_speed_factor: 1.3,
            relaxation_time: 0.5,
            agent_strength: 2.1,
            agent_range: 0.3,
            step_time: 2.0,
            wall_strength: 10.0,
            wall_range: 0.2,
            view_angle_deg: 200.0,
            out_of_view_weight: 0.5,
            mass: 80.0,
            body_force: 1.2e5,
            friction: 2.4e5,
            interaction_range: 5.0,
            guidance: Guidance::FlowField,
            ellipse: Ellipse::SpecIi,
        }
    }
}

impl SocialForceParams {
    /// The parameter table (sliders, range checks, docs).
    pub const SPECS: &'static [ParamSpec] = &[
        ParamSpec::number(
            "desired_speed",
            "Desired speed v⁰",
            "m/s",
            (0.1, 5.0, 0.01),
            1.34,
            "Speed the driving term relaxes to (1995: mean 1.34 m/s).",
        ),
        ParamSpec::number(
            "max_speed_factor",
            "Max speed",
            "× v⁰",
            (1.0, 3.0, 0.05),
            1.3,
            "Speed limit as a multiple of the desired speed (1995: 1.3).",
        ),
        ParamSpec::number(
            "relaxation_time",
            "Relaxation time τ",
            "s",
            (0.05, 5.0, 0.01),
            0.5,
            "How fast the velocity relaxes to the desired one (both papers: 0.5 s).",
        ),
        ParamSpec::number(
            "agent_strength",
            "Agent repulsion V⁰",
            "m²/s²",
            (0.0, 50.0, 0.1),
            2.1,
            "Strength of the elliptical agent–agent potential (1995: 2.1).",
        ),
        ParamSpec::number(
            "agent_range",
            "Agent range σ",
            "m",
            (0.01, 3.0, 0.01),
            0.3,
            "Decay length of the agent–agent potential (1995: 0.3 m).",
        ),
        ParamSpec::number(
            "step_time",
            "Step time Δt",
            "s",
            (0.0, 10.0, 0.1),
            2.0,
            "The ellipse round another agent reaches its next Δt of walking (1995: 2 s).",
        ),
        ParamSpec::number(
            "wall_strength",
            "Wall repulsion U⁰",
            "m²/s²",
            (0.0, 100.0, 0.5),
            10.0,
            "Strength of the wall potential (1995: 10).",
        ),
        ParamSpec::number(
            "wall_range",
            "Wall range R",
            "m",
            (0.01, 3.0, 0.01),
            0.2,
            "Decay length of the wall potential (1995: 0.2 m).",
        ),
        ParamSpec::number(
            "view_angle_deg",
            "Field of view 2φ",
            "°",
            (0.0, 360.0, 1.0),
            200.0,
            "Others within this cone ahead push with full weight (1995: 200°).",
        ),
        ParamSpec::number(
            "out_of_view_weight",
            "Out-of-view weight c",
            "×",
            (0.0, 1.0, 0.01),
            0.5,
            "Weight of forces from agents outside the field of view (1995: 0.5).",
        ),
        ParamSpec::number(
            "mass",
            "Mass m",
            "kg",
            (10.0, 200.0, 1.0),
            80.0,
            "Mass of a pedestrian; divides the body and friction forces (2000: 80 kg).",
        ),
        ParamSpec::number(
            "body_force",
            "Body force k",
            "kg/s²",
            (0.0, 1.0e6, 1000.0),
            1.2e5,
            "Compression of touching bodies, per m of overlap (2000: 1.2·10⁵).",
        ),
        ParamSpec::number(
            "friction",
            "Sliding friction κ",
            "kg/(m·s)",
            (0.0, 1.0e6, 1000.0),
            2.4e5,
            "Friction of touching bodies sliding past each other (2000: 2.4·10⁵).",
        ),
        ParamSpec::number(
            "interaction_range",
            "Interaction range",
            "m",
            (0.5, 20.0, 0.1),
            5.0,
            "Other agents within this distance exert forces.",
        ),
        ParamSpec::choice(
            "guidance",
            "Guidance",
            GUIDANCE_CHOICES,
            0,
            "flow_field: the desired direction follows the goal's flow field round obstacles; goal: straight at it.",
        ),
        // Appended after links existed: left out of links while spec II, the default (issue 25).
        ParamSpec::choice(
            "ellipse",
            "Elliptical potential",
            ELLIPSE_CHOICES,
            1,
            "spec_i: stretched along the other's step v_β Δt (1995); spec_ii: along the relative step (v_β − v_α) Δt (2007).",
        )
        .omitted_at_default(),
    ];

    /// Largest speed `v_max = factor · v⁰` (m/s).
    pub fn max_speed(&self) -> f32 {
        self.desired_speed * self.max_speed_factor
    }
}
