//! The parameters of Reynolds steering (DESIGN §3.1): plain data with units and the paper's defaults, and the
//! table the panel, the codec and validation read. The planner itself is in `crate::planners::boids`.

use super::spec::ParamSpec;
use serde::{Deserialize, Serialize};

/// How the rules' forces are combined into one acceleration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Arbitration {
    /// `a = limit(Σ wᵢ Fᵢ, max_force)`: the lecture's weighted summation.
    Weighted,
    /// Reynolds' prioritised allocation: obstacle avoidance, containment, separation, seek,
    /// alignment, cohesion, each weighted force added while the `max_force` budget remains.
    Priority,
}

/// Boids parameters. Lengths in px, speeds in px/step, forces in px/step².
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BoidsParams {
    /// Neighbours within this distance are seen (alignment, cohesion). Default 50 px.
    pub perception_radius: f32,
    /// Neighbours closer than this push away (separation). Default 14 px: 3.5 body radii, so a
    /// group fits a goal of 60 px radius without piling up.
    pub separation_radius: f32,
    /// Speed limit. Default 2 px/step (120 px/s at 60 steps/s).
    pub max_speed: f32,
    /// Steering force (acceleration) limit. Default 0.15 px/step².
    pub max_force: f32,
    /// Separation weight; the lecture's 1.5.
    pub separation_weight: f32,
    /// Alignment weight; the lecture's 1.0.
    pub alignment_weight: f32,
    /// Cohesion weight; the lecture's 1.0.
    pub cohesion_weight: f32,
    /// Weight of seeking the group's goal. Default 1.0.
    pub seek_weight: f32,
    /// Weight of obstacle avoidance and boundary containment. Default 3.0.
    pub avoid_weight: f32,
    /// Length of the forward whisker that probes for obstacles. Default 50 px.
    pub whisker_length: f32,
    /// Over this distance before the goal's edge the desired speed ramps down (arrival); inside
    /// the goal agents park (brake, keep their distance). Default 60 px.
    pub arrival_radius: f32,
    /// How the forces are combined.
    pub arbitration: Arbitration,
    /// Followers aim at the point this far behind the leader (px). Default 30.
    pub leader_distance: f32,
    /// The leader's speed as a share of max speed, so followers can keep up. Default 0.75.
    pub leader_speed: f32,
    /// Leader following: `first` makes the group's first agent the leader; the others follow it.
    pub leader: Leader,
    /// Path following looks this far ahead of the agent (px) for its predicted position. Default 30.
    pub path_lookahead: f32,
    /// The scene path this group follows, 1-based; 0 (the default) follows none. A scene naming a
    /// path it lacks is refused; deleting a path renumbers its followers (`edit.rs`).
    pub path: u32,
    /// Flow field guidance: `goal` replaces straight seeking by the goal-derived flow field.
    pub flow_field: FlowGuide,
    /// Predators see prey within this distance (px). Default 400.
    pub chase_radius: f32,
    /// Prey see predators within this distance (px). Default 100.
    pub flee_radius: f32,
    /// Weight of fleeing from predators. Default 3.
    pub flee_weight: f32,
    /// Separation weight while fleeing (replaces `separation_weight`). Default 0.8: a threatened
    /// school closes up.
    pub fleeing_separation_weight: f32,
    /// Alignment weight while fleeing. Default 2.
    pub fleeing_alignment_weight: f32,
    /// Cohesion weight while fleeing. Default 2.
    pub fleeing_cohesion_weight: f32,
    /// Predator/prey role of the group's agents.
    pub role: Role,
}

/// Leader following (lecture, "Leader Following").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Leader {
    /// Every agent steers for itself.
    None,
    /// The group's first agent seeks the goal; the others arrive at a point behind it, leave its
    /// path when in front of it, and never overtake it.
    First,
}

/// Top-down guidance (lecture, "Flow Field").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FlowGuide {
    /// Seek the goal in a straight line.
    Off,
    /// Follow the flow field of the shortest obstacle-free ways to the goal
    /// ([`crate::spatial::flow_field`]), combined with the local rules.
    Goal,
}

/// Predator/prey role (lecture, "more complex behaviours").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// Neither chases nor flees.
    None,
    /// Pursues the nearest prey within `chase_radius`, aiming at its predicted position.
    Predator,
    /// Flees predators within `flee_radius` (evading their predicted positions), with the
    /// fleeing weights of separation, alignment and cohesion while it sees one.
    Prey,
}

impl Default for BoidsParams {
    fn default() -> Self {
        Self {
            perception_radius: 50.0,
            separation_radius: 14.0,
            max_speed: 2.0,
            max_force: 0.15,
            separation_weight: 1.5,
            alignment_weight: 1.0,
            cohesion_weight: 1.0,
            seek_weight: 1.0,
            avoid_weight: 3.0,
            whisker_length: 50.0,
            arrival_radius: 60.0,
            arbitration: Arbitration::Weighted,
            leader_distance: 30.0,
            leader_speed: 0.75,
            leader: Leader::None,
            path_lookahead: 30.0,
            path: 0,
            flow_field: FlowGuide::Off,
            chase_radius: 400.0,
            flee_radius: 100.0,
            flee_weight: 3.0,
            fleeing_separation_weight: 0.8,
            fleeing_alignment_weight: 2.0,
            fleeing_cohesion_weight: 2.0,
            role: Role::None,
        }
    }
}

impl BoidsParams {
    /// The parameter table (sliders, range checks, docs).
    pub const SPECS: &'static [ParamSpec] = &[
        ParamSpec::number(
            "perception_radius",
            "Perception radius",
            "px",
            (5.0, 300.0, 1.0),
            50.0,
            "Neighbours closer than this are seen (alignment, cohesion).",
        ),
        ParamSpec::number(
            "separation_radius",
            "Separation radius",
            "px",
            (1.0, 200.0, 1.0),
            14.0,
            "Neighbours closer than this push the agent away.",
        ),
        ParamSpec::number(
            "max_speed",
            "Max speed",
            "px/step",
            (0.1, 20.0, 0.1),
            2.0,
            "Speed limit; one step is 1/60 s.",
        ),
        ParamSpec::number(
            "max_force",
            "Max force",
            "px/step²",
            (0.005, 2.0, 0.005),
            0.15,
            "Limit of the steering acceleration.",
        ),
        ParamSpec::number(
            "separation_weight",
            "Separation",
            "×",
            (0.0, 5.0, 0.1),
            1.5,
            "Weight of separation (lecture: 1.5).",
        ),
        ParamSpec::number(
            "alignment_weight",
            "Alignment",
            "×",
            (0.0, 5.0, 0.1),
            1.0,
            "Weight of alignment (lecture: 1.0).",
        ),
        ParamSpec::number(
            "cohesion_weight",
            "Cohesion",
            "×",
            (0.0, 5.0, 0.1),
            1.0,
            "Weight of cohesion (lecture: 1.0).",
        ),
        ParamSpec::number(
            "seek_weight",
            "Seek goal",
            "×",
            (0.0, 5.0, 0.1),
            1.0,
            "Weight of steering towards the group's goal.",
        ),
        ParamSpec::number(
            "avoid_weight",
            "Avoid obstacles",
            "×",
            (0.0, 10.0, 0.1),
            3.0,
            "Weight of whisker obstacle avoidance and boundary containment.",
        ),
        ParamSpec::number(
            "whisker_length",
            "Whisker length",
            "px",
            (0.0, 300.0, 1.0),
            50.0,
            "Length of the forward probe that detects obstacles.",
        ),
        ParamSpec::number(
            "arrival_radius",
            "Arrival radius",
            "px",
            (1.0, 500.0, 1.0),
            60.0,
            "Over this distance before the goal the agent slows down; inside it parks.",
        ),
        ParamSpec::choice(
            "arbitration",
            "Arbitration",
            &["weighted", "priority"],
            0,
            "Weighted sum of all rules, or priority allocation of the force budget.",
        ),
        // Extensions, appended (links store parameters by position); each feature's settings
        // come before its switch, see `ParamSpec::omitted_at_default`.
        ParamSpec::number(
            "leader_distance",
            "Follow distance",
            "px",
            (5.0, 200.0, 1.0),
            30.0,
            "Leader following: followers aim this far behind the leader.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "leader_speed",
            "Leader speed",
            "× max",
            (0.1, 1.0, 0.05),
            0.75,
            "Leader following: the leader walks at this share of max speed so followers keep up.",
        )
        .omitted_at_default(),
        ParamSpec::choice(
            "leader",
            "Leader",
            &["none", "first"],
            0,
            "first: the group's first agent leads to the goal; the others follow behind it.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "path_lookahead",
            "Path look-ahead",
            "px",
            (0.0, 200.0, 1.0),
            30.0,
            "Path following: how far ahead the agent predicts its position.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "path",
            "Follow path",
            "#",
            (0.0, 64.0, 1.0),
            0.0,
            "Number of the scene path the group follows (0 = none).",
        )
        .omitted_at_default(),
        ParamSpec::choice(
            "flow_field",
            "Flow field",
            &["off", "goal"],
            0,
            "goal: follow the shortest obstacle-free way to the goal instead of a straight line.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "chase_radius",
            "Chase radius",
            "px",
            (10.0, 2000.0, 10.0),
            400.0,
            "Predators see prey within this distance.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "flee_radius",
            "Flee radius",
            "px",
            (10.0, 1000.0, 5.0),
            100.0,
            "Prey see predators within this distance.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "flee_weight",
            "Flee",
            "×",
            (0.0, 10.0, 0.1),
            3.0,
            "Weight of fleeing from predators.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "fleeing_separation_weight",
            "Separation (fleeing)",
            "×",
            (0.0, 5.0, 0.1),
            0.8,
            "Separation weight while a predator is in sight.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "fleeing_alignment_weight",
            "Alignment (fleeing)",
            "×",
            (0.0, 5.0, 0.1),
            2.0,
            "Alignment weight while a predator is in sight.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "fleeing_cohesion_weight",
            "Cohesion (fleeing)",
            "×",
            (0.0, 5.0, 0.1),
            2.0,
            "Cohesion weight while a predator is in sight.",
        )
        .omitted_at_default(),
        ParamSpec::choice(
            "role",
            "Role",
            &["none", "predator", "prey"],
            0,
            "predator: chase the nearest prey; prey: flee predators in sight.",
        )
        .omitted_at_default(),
    ];
}
