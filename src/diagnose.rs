//! Why does an agent move as it does: picking an agent, its explanation (the terms of its step,
//! recomputed from the same state by its planner), stuck flags and the cost landscape an agent
//! sees (PSO).
//!
//! Nothing here runs during a step: an explanation is computed on demand for one selected agent,
//! so diagnosis costs nothing while no agent is selected.

use crate::metrics::STUCK_WINDOW;
use crate::world::World;
use glam::Vec2;
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

/// Length (scene px) of the longest force arrow when the planner sets no scale.
pub const AUTO_ARROW_LENGTH: f32 = 40.0;

/// The agent nearest to `p` whose body lies within `tolerance` px of it, ties broken by the
/// smaller id; `None` when there is none (or for a non-finite point). Uses the world's grid.
pub fn agent_at(world: &World, p: Vec2, tolerance: f32) -> Option<u32> {
    if !p.is_finite() {
        return None;
    }
    let tolerance = if tolerance.is_finite() { tolerance.max(0.0) } else { 0.0 };
    let radii = world.radii();
    let reach = radii.iter().copied().fold(0.0f32, f32::max) + tolerance;
    let mut best: Option<(f32, u32)> = None;
    world.grid().for_each_within(p, reach, |n| {
        let r = radii.get(n.id as usize).copied().unwrap_or(0.0) + tolerance;
        if n.d2 <= r * r && best.is_none_or(|b| (n.d2, n.id) < b) {
            best = Some((n.d2, n.id));
        }
    });
    best.map(|(_, id)| id)
}

/// Why agent `agent` moves as it does; `None` for an id that does not exist.
pub fn explain(world: &World, agent: u32) -> Option<Explanation> {
    let i = agent as usize;
    let group = *world.group_of().get(i)?;
    let planner = world.planner_of_group(group as usize)?;
    let view = world.group_view(group as usize)?;
    let ctx = world.step_context();
    let mut e = planner.explain(&ctx, &view, agent);
    e.agent = agent;
    e.group = group;
    e.planner = world.scene().groups.get(group as usize).map(|g| g.planner.kind().name().to_string())?;
    e.position = world.positions()[i];
    e.velocity = world.velocities()[i];
    e.stuck = world.metrics_recorder().is_stuck(i, view.goal.is_some(), world.step_count());
    if e.scale <= 0.0 {
        // No scale from the planner: the longest force arrow is drawn 40 px long.
        let longest = e
            .vectors
            .iter()
            .filter(|v| !v.in_px)
            .map(|v| v.vector.length())
            .chain([e.applied.length()])
            .filter(|l| l.is_finite())
            .fold(0.0f32, f32::max);
        e.scale = if longest > 1e-9 { AUTO_ARROW_LENGTH / longest } else { 1.0 };
    }
    if e.stuck {
        e.state = format!("stuck: no progress towards the goal for {STUCK_WINDOW}+ steps; {}", e.state);
    }
    Some(e)
}

/// Ids of the agents that are stuck now (see [`crate::metrics::GroupMetrics::stuck_agents`]).
pub fn stuck_agents(world: &World) -> Vec<u32> {
    let steps = world.step_count();
    if steps < STUCK_WINDOW {
        return Vec::new();
    }
    let recorder = world.metrics_recorder();
    let mut out = Vec::new();
    for g in 0..world.scene().groups.len() {
        let Some(view) = world.group_view(g) else { continue };
        let has_goal = view.goal.is_some();
        out.extend(view.agents.filter(|&id| recorder.is_stuck(id as usize, has_goal, steps)));
    }
    out
}

/// The cost landscape one agent sees, sampled on a square grid centred on it.
#[derive(Clone, Debug, PartialEq)]
pub struct CostGrid {
    /// Scene point of the grid's top-left corner (px).
    pub origin: Vec2,
    /// Side of one cell (px).
    pub cell: f32,
    /// Cells per side.
    pub cells: u32,
    /// `costs[row * cells + col]`: the planner's objective at the cell's centre.
    pub costs: Vec<f32>,
}

/// Largest grid side [`cost_grid`] fills (cells), so a request cannot take long.
pub const MAX_COST_GRID_CELLS: u32 = 96;

/// The objective agent `agent`'s planner minimises, sampled on `cells × cells` cells spanning
/// `2 · half_size` px around the agent; `None` if its planner has no cost landscape (only PSO
/// has one) or the id does not exist.
pub fn cost_grid(world: &World, agent: u32, half_size: f32, cells: u32) -> Option<CostGrid> {
    let i = agent as usize;
    let group = *world.group_of().get(i)? as usize;
    let planner = world.planner_of_group(group)?;
    let view = world.group_view(group)?;
    let ctx = world.step_context();
    let cells = cells.clamp(1, MAX_COST_GRID_CELLS);
    let half_size = if half_size.is_finite() { half_size.clamp(1.0, 10_000.0) } else { 100.0 };
    let cell = 2.0 * half_size / cells as f32;
    let origin = world.positions()[i] - Vec2::splat(half_size);
    let mut costs = Vec::with_capacity((cells * cells) as usize);
    for row in 0..cells {
        for col in 0..cells {
            let p = origin + Vec2::new((col as f32 + 0.5) * cell, (row as f32 + 0.5) * cell);
            costs.push(planner.cost_at(&ctx, &view, agent, p)?);
        }
    }
    Some(CostGrid { origin, cell, cells, costs })
}
