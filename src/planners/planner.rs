//! The contract every planner keeps: the read-only [`StepContext`] of a step, the
//! [`GroupView`] of the group it steers, and the [`Planner`] trait. The bottom of the planners
//! layer: planner files import this, never the folder's `mod.rs` that builds them.

use crate::model::scene::Scene;
use crate::planners::explain::{Explanation, GroupPath};
use crate::rng::Rng;
use crate::spatial::flow_field::FlowFieldStore;
use crate::spatial::{ObstacleIndex, SpatialGrid};
use glam::Vec2;
use std::ops::Range;

/// Read-only view of the world at the start of a step: planners read it, never write it,
/// so the new velocities do not depend on the order agents are planned in.
pub struct StepContext<'a> {
    /// Positions of all agents (px).
    pub positions: &'a [Vec2],
    /// Velocities of all agents (px/step).
    pub velocities: &'a [Vec2],
    /// Body radius of every agent (px).
    pub radii: &'a [f32],
    /// All agents bucketed for neighbour queries.
    pub grid: &'a SpatialGrid,
    /// Static obstacles with a spatial index.
    pub obstacles: &'a ObstacleIndex,
    /// World size (px).
    pub bounds: Vec2,
    /// Steps simulated so far.
    pub step: u32,
    /// The scene being run: its paths, hills and every group's planner settings (roles).
    pub scene: &'a Scene,
    /// Group index of every agent.
    pub group_of: &'a [u32],
    /// The world's flow fields, shared by the groups that would build the same one.
    pub flow_fields: &'a FlowFieldStore,
}

/// What a planner knows about the group it steers.
#[derive(Clone, Debug)]
pub struct GroupView {
    /// Global ids of the group's agents (groups own contiguous id ranges).
    pub agents: Range<u32>,
    /// Current goal position and arrival radius, if the group has a goal.
    pub goal: Option<(Vec2, f32)>,
}

/// Copies a boxed planner with all its internal state (replay checkpoints clone the world).
/// Implemented for every `Clone` planner, so a planner only has to derive `Clone`.
pub trait PlannerClone {
    /// A boxed deep copy of this planner.
    fn clone_box(&self) -> Box<dyn Planner>;
}

impl<T: Planner + Clone + 'static> PlannerClone for T {
    fn clone_box(&self) -> Box<dyn Planner> {
        Box::new(self.clone())
    }
}

impl Clone for Box<dyn Planner> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}

/// A crowd planner: computes every new velocity of its group from the old state.
pub trait Planner: PlannerClone {
    /// Largest radius (px) the planner queries neighbours in; sizes the spatial grid.
    fn interaction_radius(&self) -> f32;
    /// Speed limit (px/step); the world checks it after every step.
    fn max_speed(&self) -> f32;
    /// Writes the new velocity of agent `group.agents.start + k` to `new_velocities[k]`.
    fn plan(&mut self, ctx: &StepContext, group: GroupView, rng: &mut Rng, new_velocities: &mut [Vec2]);
    /// Whether the world should let this group's agents move into obstacles instead of pushing
    /// them out. Only for showing a planner's own failure (the original PSO penetrating).
    fn passes_through_obstacles(&self) -> bool {
        false
    }
    /// The path the group follows, for planners that plan one (IGSA group path control).
    fn planned_path(&self) -> Option<&GroupPath> {
        None
    }
    /// Whether the world must rebuild this planner when obstacles or goals are edited during a
    /// run (a planner that planned on the old geometry).
    fn replans_on_edit(&self) -> bool {
        false
    }
    /// Share of the planning ahead done, 0…1 (IGSA plans its path in slices); 1 for planners
    /// that plan nothing ahead. The world does not step a group before it reaches 1.
    fn planning_progress(&self) -> f64 {
        1.0
    }
    /// Runs up to `evaluations` more objective evaluations of the planning ahead (`u32::MAX`:
    /// all of it); returns the share done. Slices of any size give the same result.
    fn advance_planning(&mut self, evaluations: u32) -> f64 {
        let _ = evaluations;
        1.0
    }
    /// Why `agent` would move as it does at the next step: the terms of its step recomputed from
    /// `ctx` (forces per component, points looked at, neighbours). Called only for a selected
    /// agent, so it costs nothing per step. The default explains nothing.
    fn explain(&self, ctx: &StepContext, group: &GroupView, agent: u32) -> Explanation {
        let _ = (ctx, group, agent);
        Explanation::default()
    }
    /// The objective `agent` minimises at point `p`, for planners that have one (PSO's cost
    /// landscape); `None` otherwise.
    fn cost_at(&self, ctx: &StepContext, group: &GroupView, agent: u32, p: Vec2) -> Option<f32> {
        let _ = (ctx, group, agent, p);
        None
    }
}
