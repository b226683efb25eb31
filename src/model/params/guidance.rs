//! What the baseline planners (ORCA, social force) head for: the goal in a straight line or the
//! goal's flow field round the obstacles ([`Guidance`]). Their SI parameters are converted with
//! the scene's scale (`Scene::px_per_metre`, 20 px per metre by default).

use serde::{Deserialize, Serialize};

/// How an agent's preferred direction is chosen (its desired velocity's direction).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Guidance {
    /// Down the goal's flow field ([`crate::spatial::flow_field`]): the shortest obstacle-free
    /// way, so a wall between agent and goal is walked round. Straight at the goal when the
    /// scene has no obstacles (the field would point there too).
    FlowField,
    /// Straight at the goal, as in the papers' open-space experiments.
    Goal,
}

/// The choice row's options, in [`Guidance`] order (`flow_field` first: the default).
pub const GUIDANCE_CHOICES: &[&str] = &["flow_field", "goal"];
