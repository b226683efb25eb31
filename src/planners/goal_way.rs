//! The way to the goal shared by the baseline planners (ORCA, social force): the preferred
//! direction at a point, straight at the goal or down the goal's flow field round the obstacles
//! ([`Guidance`]), and whether the agent has arrived (inside the goal it parks: preferred
//! speed zero, so an arrived crowd stops instead of piling onto the goal's centre).

use crate::model::geometry::{distance, unit_or};
use crate::model::params::guidance::Guidance;
use crate::model::scene::Scene;
use crate::planners::planner::{GroupView, StepContext};
use crate::spatial::flow_field::CachedFlowField;
use glam::Vec2;

/// Pixels per metre of `scene`: the baselines' SI parameters are converted with it.
pub fn px_per_metre(scene: &Scene) -> f32 {
    scene.px_per_metre
}

/// Where one agent wants to go at this step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Way {
    /// Unit preferred direction; zero without a goal, inside it, or where no way is known.
    pub direction: Vec2,
    /// Whether the agent's centre is inside its goal (it parks).
    pub arrived: bool,
}

/// The preferred directions of one group's agents: a cached flow field when guided by one.
#[derive(Clone, Debug, Default)]
pub struct GoalWay {
    field: CachedFlowField,
}

impl GoalWay {
    /// Builds (or keeps) the flow field this step needs, from the state at its start: rebuilt
    /// when the goal moved to another cell or the obstacles changed; none without obstacles
    /// (the way is then straight) or with straight guidance.
    pub fn prepare(&mut self, ctx: &StepContext, group: &GroupView, guidance: Guidance) {
        let Some((goal, _)) = group.goal else { return };
        if guidance != Guidance::FlowField || ctx.obstacles.is_empty() {
            self.field.clear();
            return;
        }
        let clearance = group.agents.clone().next().map_or(0.0, |i| ctx.radii[i as usize]);
        self.field.update(ctx.flow_fields, ctx.bounds, ctx.obstacles, goal, clearance);
    }

    /// The way from `p` for a group heading for `goal` (position, radius).
    pub fn at(&self, p: Vec2, goal: Option<(Vec2, f32)>) -> Way {
        let Some((goal, radius)) = goal else { return Way { direction: Vec2::ZERO, arrived: false } };
        if distance(p, goal) <= radius {
            return Way { direction: Vec2::ZERO, arrived: true };
        }
        let straight = unit_or(goal - p, Vec2::ZERO);
        let direction = match self.field.get() {
            Some(field) => {
                let d = field.direction_at(p);
                if d == Vec2::ZERO {
                    straight
                } else {
                    d
                }
            }
            None => straight,
        };
        Way { direction, arrived: false }
    }
}
