//! What a planner shows about itself, as plain data: one agent's step as named force vectors and
//! points (recomputed on demand; `sim::diagnose` picks the agent) and a group's planned path.

use glam::Vec2;
use serde::Serialize;
use serde_json::json;

/// A named vector drawn as an arrow from the agent (a force, a desired velocity, a feeler).
#[derive(Clone, Debug, PartialEq)]
pub struct NamedVector {
    /// What it is ("separation", "feeler", …).
    pub name: String,
    /// The vector: a force or direction drawn × [`Explanation::scale`], or a length in scene
    /// px (feelers) when `in_px`.
    pub vector: Vec2,
    /// Whether `vector` is a length in scene px, drawn as it is.
    pub in_px: bool,
}

impl NamedVector {
    /// A force or direction with a name (drawn scaled).
    pub fn new(name: &str, vector: Vec2) -> Self {
        Self { name: name.to_string(), vector, in_px: false }
    }

    /// A length in scene px with a name (a feeler), drawn as it is.
    pub fn px(name: &str, vector: Vec2) -> Self {
        Self { name: name.to_string(), vector, in_px: true }
    }
}

/// A named point of the scene (PSO's pbest and gbest, a followed firefly, a rejected candidate).
#[derive(Clone, Debug, PartialEq)]
pub struct NamedPoint {
    /// What it is.
    pub name: String,
    /// Where (scene px).
    pub point: Vec2,
}

impl NamedPoint {
    /// A point with a name.
    pub fn new(name: &str, point: Vec2) -> Self {
        Self { name: name.to_string(), point }
    }
}

/// The terms of one agent's next step, as its planner computes them from the current state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Explanation {
    /// Global agent id.
    pub agent: u32,
    /// Group index.
    pub group: u32,
    /// Planner name.
    pub planner: String,
    /// Position (px).
    pub position: Vec2,
    /// Velocity (px/step).
    pub velocity: Vec2,
    /// A short description of what the agent is doing ("queued behind a brighter firefly").
    pub state: String,
    /// Whether the agent is stuck (no progress towards its goal for [`STUCK_WINDOW`] steps).
    pub stuck: bool,
    /// Agents the planner took into account.
    pub neighbours: Vec<u32>,
    /// Arrows from the agent: per-component forces (their sum is [`Explanation::applied`] for
    /// force planners), feelers, directions.
    pub vectors: Vec<NamedVector>,
    /// Points the planner looks at.
    pub points: Vec<NamedPoint>,
    /// What the step applies: the acceleration (Boids, forces, firefly) or the chosen velocity
    /// (PSO).
    pub applied: Vec2,
    /// Scene px per unit of the force arrows, chosen by the planner so its arrows are visible
    /// (forces of 0.15 px/step² drawn as 30 px arrows need 200); 0 lets [`explain`] choose one
    /// that draws the longest arrow [`AUTO_ARROW_LENGTH`] px long.
    pub scale: f32,
    /// Extra named numbers (brightness, cost, mass, …).
    pub values: Vec<(String, f32)>,
}

impl Explanation {
    /// The explanation as JSON for the inspector.
    pub fn to_json(&self) -> serde_json::Value {
        let xy = |v: Vec2| json!([v.x, v.y]);
        json!({
            "agent": self.agent,
            "group": self.group,
            "planner": self.planner,
            "position": xy(self.position),
            "velocity": xy(self.velocity),
            "speed": self.velocity.length(),
            "state": self.state,
            "stuck": self.stuck,
            "neighbours": self.neighbours,
            "vectors": self.vectors.iter().map(|v| json!({"name": v.name, "vector": xy(v.vector),
                "length": v.vector.length(), "in_px": v.in_px})).collect::<Vec<_>>(),
            "points": self.points.iter().map(|p| json!({"name": p.name, "point": xy(p.point)}))
                .collect::<Vec<_>>(),
            "applied": xy(self.applied),
            "values": self.values.iter().map(|(k, v)| json!({"name": k, "value": v})).collect::<Vec<_>>(),
        })
    }
}

/// Where a group's path came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PathSource {
    /// Planned by IGSA.
    Igsa,
    /// Planned by GSA.
    Gsa,
    /// The user's edited waypoints.
    Edited,
    /// The group has no goal: there is nothing to follow.
    None,
}

/// A group's path as planned (or edited), with what the page shows about it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GroupPath {
    /// Start, waypoints, goal (scene px).
    pub points: Vec<[f32; 2]>,
    /// Per segment, whether it crosses an obstacle.
    pub crossing: Vec<bool>,
    /// Where the waypoints came from.
    pub source: PathSource,
    /// Length (px), maximum and mean turning angle (degrees) of the polyline.
    pub length: f64,
    /// Largest deflection at a waypoint (degrees).
    pub max_turn_deg: f64,
    /// Mean deflection over the waypoints (degrees).
    pub mean_turn_deg: f64,
    /// Fitness the optimizer reached (`None` for an edited path).
    pub fitness: Option<f64>,
    /// Objective evaluations the planning spent (0 for an edited path).
    pub evaluations: u64,
}
