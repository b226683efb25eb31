//! Why does an agent move as it does: picking an agent, its explanation (the terms of its step,
//! recomputed from the same state by its planner), stuck flags and the cost landscape an agent
//! sees (PSO).
//!
//! Nothing here runs during a step: an explanation is computed on demand for one selected agent,
//! so diagnosis costs nothing while no agent is selected.

use crate::planners::explain::Explanation;
use crate::sim::metrics::STUCK_WINDOW;
use crate::sim::world::World;
use glam::Vec2;

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

/// The draggable waypoint (interior point of an IGSA group's path) nearest to `p` within
/// `tolerance` px, as `(group, waypoint index among the interior points)`; later groups win
/// ties, as they are drawn on top.
pub fn pick_waypoint(world: &World, p: Vec2, tolerance: f32) -> Option<(u32, u32)> {
    let mut best: Option<(f32, u32, u32)> = None;
    for g in 0..world.scene().groups.len() {
        let Some(path) = world.planned_path(g) else { continue };
        let inner = path.points.len().saturating_sub(1);
        for (k, q) in path.points.iter().enumerate().take(inner).skip(1) {
            let d = p.distance(Vec2::from(*q));
            if d <= tolerance && best.is_none_or(|(bd, _, _)| d <= bd) {
                best = Some((d, g as u32, (k - 1) as u32));
            }
        }
    }
    best.map(|(_, g, k)| (g, k))
}

/// Ids of the agents that are stuck now (see [`crate::sim::metrics::GroupMetrics::stuck_agents`]).
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
