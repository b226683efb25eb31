//! The parameters of the PSO crowd (Chen & Lin 2009, DESIGN §3.2): plain data with units and the paper's defaults, and the
//! table the panel, the codec and validation read. The planner itself is in `crate::planners::pso`.

use super::spec::ParamSpec;
use serde::{Deserialize, Serialize};

/// PSO crowd parameters. Lengths in px, speeds in px/step.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PsoParams {
    /// ω, weight of the previous direction. Range 0…2, default 1.0 (paper).
    pub inertia: f32,
    /// c1, pull towards the agent's own best position. Range 0…3, default 0.5 (paper).
    pub cognitive: f32,
    /// c2, pull towards the group's best position. Range 0…3, default 0.5 (paper).
    pub social: f32,
    /// k of the acceptance probability `1 − f/e^{−k}`: the no-go boundary lies at σ-scaled distance
    /// √k. Range 0.1…5, default 1 (paper): the boundary is the σ-ellipse itself.
    pub k: f32,
    /// c_obs, weight of the obstacle term against the target term. Range 0…50, default 5: at the
    /// no-go boundary an agent walks at about a third of the speed it has in the open.
    pub obstacle_weight: f32,
    /// Vmax, the speed limit (px/step). Range 0.1…20, default 2 (120 px/s).
    pub max_speed: f32,
    /// σ of every agent in both axes (px). Range 1…50, default 5 (paper): two agents keep at
    /// least 2σ = 10 px apart.
    pub agent_sigma: f32,
    /// Rotated candidates tried after a refusal. Range 0…32, default 8.
    pub retries: u32,
    /// Largest rotation of a retried candidate (degrees). Range 1…90, default 20 (paper).
    pub retry_angle_deg: f32,
    /// Distance (px) of each agent's sight point towards the target, a gbest candidate. Range
    /// 0…500, default 50; 0 is the literal swarm best.
    pub sight: f32,
    /// The acceptance step (local search). Default on; off is the original PSO, which lets agents
    /// walk through obstacles.
    #[serde(with = "on_off")]
    pub acceptance: bool,
    /// Ground height (px) at which the terrain cost of the scene's hills equals an obstacle's
    /// at its no-go boundary: higher ground is never accepted, lower ground costs in proportion
    /// to its height. Range 1…1000, default 60.
    pub climb_limit: f32,
}

impl Default for PsoParams {
    fn default() -> Self {
        Self {
            inertia: 1.0,
            cognitive: 0.5,
            social: 0.5,
            k: 1.0,
            obstacle_weight: 5.0,
            max_speed: 2.0,
            agent_sigma: 5.0,
            retries: 8,
            retry_angle_deg: 20.0,
            sight: 50.0,
            acceptance: true,
            climb_limit: 60.0,
        }
    }
}

impl PsoParams {
    /// The parameter table (sliders, range checks, docs).
    pub const SPECS: &'static [ParamSpec] = &[
        ParamSpec::number("inertia", "Inertia ω", "×", (0.0, 2.0, 0.05), 1.0, "Weight of the previous direction."),
        ParamSpec::number(
            "cognitive",
            "Cognitive c1",
            "×",
            (0.0, 3.0, 0.05),
            0.5,
            "Pull towards the agent's own best position.",
        ),
        ParamSpec::number(
            "social",
            "Social c2",
            "×",
            (0.0, 3.0, 0.05),
            0.5,
            "Pull towards the group's best position.",
        ),
        ParamSpec::number(
            "k",
            "Acceptance k",
            "",
            (0.1, 5.0, 0.1),
            1.0,
            "Moves closer than σ-scaled distance √k to an obstacle or agent are never accepted.",
        ),
        ParamSpec::number(
            "obstacle_weight",
            "Obstacle weight c_obs",
            "×",
            (0.0, 50.0, 0.5),
            5.0,
            "Weight of the obstacle cost against the target cost; slows agents near obstacles.",
        ),
        ParamSpec::number("max_speed", "Max speed Vmax", "px/step", (0.1, 20.0, 0.1), 2.0, "Speed limit."),
        ParamSpec::number(
            "agent_sigma",
            "Agent σ",
            "px",
            (1.0, 50.0, 0.5),
            5.0,
            "Scope of each person in the cost model; agents keep 2σ apart.",
        ),
        ParamSpec::number(
            "retries",
            "Retries",
            "",
            (0.0, 32.0, 1.0),
            8.0,
            "Rotated candidates tried when a move is refused.",
        ),
        ParamSpec::number(
            "retry_angle_deg",
            "Retry angle",
            "°",
            (1.0, 90.0, 1.0),
            20.0,
            "Largest rotation of a retried candidate.",
        ),
        ParamSpec::number(
            "sight",
            "Sight",
            "px",
            (0.0, 500.0, 5.0),
            50.0,
            "Each agent offers the point this far towards the target as a group-best candidate; 0 = pure PSO.",
        ),
        ParamSpec::choice(
            "acceptance",
            "Acceptance step",
            &["on", "off"],
            0,
            "Off is the original PSO: agents may walk through obstacles.",
        ),
        ParamSpec::number(
            "climb_limit",
            "Climb limit",
            "px",
            (1.0, 1000.0, 1.0),
            60.0,
            "Hills: ground this high is never walked on; lower ground costs in proportion to its height.",
        ),
    ];
}

/// Serialises a bool as `"on"`/`"off"` (a choice in the parameter table); reads either form.
mod on_off {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(value: &bool, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(if *value { "on" } else { "off" })
    }

    #[derive(Deserialize)]
    #[serde(untagged)]
    enum OnOff {
        Bool(bool),
        Text(String),
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<bool, D::Error> {
        match OnOff::deserialize(d)? {
            OnOff::Bool(b) => Ok(b),
            OnOff::Text(t) if t == "on" => Ok(true),
            OnOff::Text(t) if t == "off" => Ok(false),
            OnOff::Text(t) => Err(serde::de::Error::custom(format!("expected \"on\" or \"off\", got {t:?}"))),
        }
    }
}
