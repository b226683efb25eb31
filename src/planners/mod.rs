//! Crowd planners: one file each behind the [`Planner`] trait (in `planner.rs`, the bottom of
//! this layer), and [`build`], which turns a group's [`PlannerConfig`] into a running planner.
//!
//! Layer: planners. Uses `model`, `spatial`, `optim` (IGSA plans its path with it) and `rng`.

pub mod boids;
pub mod collision_free_speed;
pub mod explain;
pub mod firefly;
pub mod forces;
pub mod goal_way;
pub mod igsa;
mod lanes;
pub mod orca;
pub mod planner;
pub mod pso;
pub mod social_force;

use crate::model::geometry::Obstacle;
use crate::model::params::PlannerConfig;
use crate::model::scene::Scene;

pub use boids::Boids;
pub use collision_free_speed::CollisionFreeSpeed;
pub use explain::GroupPath;
pub use firefly::Firefly;
pub use forces::Forces;
pub use igsa::IgsaPlanner;
pub use orca::Orca;
pub use planner::{GroupView, Planner, PlannerClone, StepContext};
pub use pso::Pso;
pub use social_force::SocialForce;

/// A fresh planner for a group of `count` agents.
pub fn build(config: &PlannerConfig, count: usize, obstacles: &[Obstacle]) -> Box<dyn Planner> {
    let _ = count;
    match config {
        PlannerConfig::Boids(p) => Box::new(Boids::new(p.clone())),
        PlannerConfig::Pso(p) => Box::new(Pso::new(p.clone(), obstacles)),
        PlannerConfig::Firefly(p) => Box::new(Firefly::new(p.clone())),
        PlannerConfig::Forces(p) => Box::new(Forces::new(p.clone())),
        // Without its scene the IGSA planner has no path to plan: use `build_for_group`.
        PlannerConfig::Igsa(p) => Box::new(IgsaPlanner::new(p.clone(), &Scene::empty(10.0, 10.0), 0)),
        PlannerConfig::Orca(p) => Box::new(Orca::new(p.clone())),
        PlannerConfig::SocialForce(p) => Box::new(SocialForce::new(p.clone())),
        PlannerConfig::CollisionFreeSpeed(p) => Box::new(CollisionFreeSpeed::new(p.clone())),
    }
}

/// A fresh planner for group `group` of `scene`. Planners that plan ahead (IGSA) read the
/// scene's geometry and seed here and plan when [`Planner::advance_planning`] is called
/// (the world does); the others are [`PlannerConfig::build`].
pub fn build_for_group(config: &PlannerConfig, scene: &Scene, group: usize) -> Box<dyn Planner> {
    match config {
        PlannerConfig::Igsa(p) => Box::new(IgsaPlanner::planning(p.clone(), scene, group)),
        PlannerConfig::Orca(p) => Box::new(orca::for_scene(p.clone(), scene)),
        PlannerConfig::SocialForce(p) => Box::new(social_force::for_scene(p.clone(), scene)),
        PlannerConfig::CollisionFreeSpeed(p) => Box::new(collision_free_speed::for_scene(p.clone(), scene)),
        _ => {
            let count = scene.groups.get(group).map_or(0, |g| g.count as usize);
            build(config, count, &scene.obstacles)
        }
    }
}
