//! Scene limits checked on load that are not a single field's range: what a scene would keep in
//! memory, and how much path planning it asks for before its first step. A scene over one is
//! refused up front with a message naming the group and the limit.
//!
//! # What is here, and why (issue 24)
//!
//! Every page steps its scene in a Web Worker, and IGSA plans in slices of a few objective
//! evaluations, so no scene can block a page however long its steps take: a slow scene shows
//! "slow scene: N steps/s" and Pause, Stop and Cancel are answered between steps or slices
//! (`tests/e2e/heavy-pause.test.mjs`). What a worker cannot survive is running out of memory:
//! wasm32 addresses at most 4 GiB, and a phone's browser gives a tab far less. So the limits
//! that remain bound memory or total work, not time per step:
//!
//! - [`MAX_FLOW_FIELD_BYTES`]: the groups' flow fields, up to 262,144 cells each, one per
//!   distinct goal and body radius (groups that would build the same field share it). Before
//!   sharing, 500 one-agent groups in a 20,000 px world kept 903 MB.
//! - [`MAX_PLANNING_SEGMENT_CHECKS`]: the total IGSA planning, which a scene must finish before
//!   its first step (the page waits with a progress bar, `flockpath run` before its first
//!   frame, and a script's `step()` plans the rest at once). It bounds that wait; slicing
//!   bounds how long the page is held at a time.
//!
//! Elsewhere, each beside what it bounds: the agent count (`MAX_AGENTS`, which bounds every
//! per-agent array), the world's size, obstacles and polygon points, names and links
//! (`crate::model::scene`), and the recording, timeline and metric series budgets
//! ([`crate::sim::limits`]).
//!
//! Gone: the step-time estimate (180 ms per step in the browser, from each planner's measured
//! worst ns per agent-step, scaled for wasm, for jammed crowds and for small bodies). It kept
//! the page answering input while it stepped on the main thread; it bounded no memory, and
//! it kept missing costs it did not model (obstacles, paths, parameters). A heavy scene now
//! runs slowly instead of being refused. `examples/step_cost.rs` still measures what a step
//! costs per planner.

use crate::model::params::PlannerConfig;
use crate::model::refusal::{Code, Message};
use crate::model::scene::{Group, Scene, SceneError};
use crate::spatial::ObstacleIndex;

/// Most path segments all IGSA groups of a scene may check while planning: population ×
/// iterations × (waypoints + 1), summed over groups. Two groups at the largest parameters
/// (200 × 3000 × 9 = 5.4 million each).
pub const MAX_PLANNING_SEGMENT_CHECKS: u64 = 10_800_000;

/// Most bytes the groups' flow fields may keep together: 1 GiB, a quarter of wasm32's 4 GiB
/// address space (the page's worker also holds the agents, the timeline and recording budgets
/// of [`crate::sim::limits`], the renderer's pixmaps, and builds a field beside the one it
/// replaces), and about what a phone's browser lets one tab have. 20,000 px worlds have fields
/// of 156,816 cells (1.9 MB), so about 570 distinct ones fit; a world of the default size
/// (1,000 × 700 px, 7,000 cells, 84 kB) about 12,800.
pub const MAX_FLOW_FIELD_BYTES: u64 = 1 << 30;

/// What the flow fields of a scene's groups would keep in memory.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FlowFieldMemory {
    /// Distinct fields: one per goal and body radius among the groups guided by a field (the
    /// world shares one field between groups that would build the same,
    /// [`crate::spatial::flow_field::FlowFieldStore`]). Two goals at the same point count twice.
    pub fields: u64,
    /// Cells of each field.
    pub cells: u64,
    /// Bytes all fields keep.
    pub bytes: u64,
    /// The group whose field first takes the total over [`MAX_FLOW_FIELD_BYTES`], if any.
    pub over_at: Option<usize>,
}

/// The memory the flow fields of `scene`'s groups would keep (see [`FlowFieldMemory`]).
pub fn flow_field_memory(scene: &Scene) -> FlowFieldMemory {
    let cells = crate::spatial::flow_field::cells_of(glam::Vec2::new(scene.width, scene.height));
    let field_bytes = cells * crate::spatial::flow_field::BYTES_PER_CELL;
    let has_obstacles = !scene.obstacles.is_empty();
    let mut distinct = std::collections::HashSet::new();
    let mut over_at = None;
    for (i, g) in scene.groups.iter().enumerate() {
        let Some(goal) = g.goal.filter(|_| g.planner.keeps_flow_field(has_obstacles)) else { continue };
        // The field's clearance is the group's body radius (none without agents).
        let clearance = if g.count == 0 { 0 } else { g.agent_radius.to_bits() };
        if !distinct.insert((goal, clearance)) {
            continue;
        }
        if over_at.is_none() && distinct.len() as u64 * field_bytes > MAX_FLOW_FIELD_BYTES {
            over_at = Some(i);
        }
    }
    let fields = distinct.len() as u64;
    FlowFieldMemory { fields, cells, bytes: fields * field_bytes, over_at }
}

/// Segments group `g` checks while planning its path (0 unless it is an IGSA group that plans).
pub fn planning_segment_checks(g: &Group) -> u64 {
    match &g.planner {
        PlannerConfig::Igsa(p) if p.waypoints.is_empty() && g.goal.is_some() => {
            let s = p.settings();
            s.population as u64 * u64::from(s.iterations) * (p.path_params().waypoints as u64 + 1)
        }
        _ => 0,
    }
}

/// Refuses a scene over a limit: flow fields over [`MAX_FLOW_FIELD_BYTES`] name the group whose
/// field crosses it; planning over [`MAX_PLANNING_SEGMENT_CHECKS`] names the IGSA group that
/// plans most.
pub fn check(scene: &Scene) -> Result<(), SceneError> {
    let memory = flow_field_memory(scene);
    if let Some(i) = memory.over_at {
        return Err(SceneError::FlowFieldMemory {
            path: format!("groups[{i}]"),
            fields: memory.fields,
            cells: memory.cells,
            bytes: memory.bytes,
            limit: MAX_FLOW_FIELD_BYTES,
        });
    }
    let planning: u64 = scene.groups.iter().map(planning_segment_checks).sum();
    if planning > MAX_PLANNING_SEGMENT_CHECKS {
        let most = scene.groups.iter().enumerate().max_by_key(|(_, g)| planning_segment_checks(g));
        if let Some((i, g)) = most {
            return Err(SceneError::TooCostly(
                Message::new(Code::ScenePlanningCost)
                    .with("group", i + 1)
                    .with("name", g.name.clone())
                    .with("checks", planning)
                    .with("this", planning_segment_checks(g))
                    .with("limit", MAX_PLANNING_SEGMENT_CHECKS),
            ));
        }
    }
    Ok(())
}

/// The work and memory a scene asks for, counted where it is done.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Work {
    /// Lattice places the spawn examined (counted).
    pub spawn_places: u64,
    /// Path segments IGSA planning will check (counted from the parameters).
    pub planning_segment_checks: u64,
    /// What the groups' flow fields would keep.
    pub flow_fields: FlowFieldMemory,
}

/// Validates `scene`, spawns it and checks the limits, without building planners (no IGSA
/// planning): the work it would ask for, or the refusal [`crate::World::new`] would give.
pub fn work(scene: &Scene) -> Result<Work, SceneError> {
    scene.validate()?;
    let obstacles = ObstacleIndex::new(scene.obstacles.clone(), scene.width, scene.height);
    let spawn = crate::sim::spawn::spawn(scene, &obstacles)?;
    check(scene)?;
    Ok(Work {
        spawn_places: spawn.places_examined,
        planning_segment_checks: scene.groups.iter().map(planning_segment_checks).sum(),
        flow_fields: flow_field_memory(scene),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::PlannerKind;
    use crate::model::presets;

    #[test]
    fn every_preset_is_within_the_limits() {
        for p in presets::ALL {
            let w = work(&(p.build)()).unwrap_or_else(|e| panic!("{}: {e}", p.name));
            assert!(w.planning_segment_checks <= MAX_PLANNING_SEGMENT_CHECKS);
            assert!(w.flow_fields.bytes <= MAX_FLOW_FIELD_BYTES && w.flow_fields.over_at.is_none());
        }
    }

    /// The step-time limit is gone (module docs): scenes it refused for their estimated step
    /// time load now, every planner at the most agents a scene may hold.
    #[test]
    fn crowds_once_refused_for_their_step_time_are_accepted() {
        for &kind in PlannerKind::ALL {
            let mut s = Scene::empty(20_000.0, 20_000.0);
            let mut g = presets::open_field().groups.remove(0);
            g.goal = None;
            g.spawn = crate::Region { min: [0.0, 0.0], max: [20_000.0, 20_000.0] };
            g.planner = kind.default_config();
            g.agent_radius = 0.5;
            g.count = crate::model::scene::MAX_AGENTS;
            s.groups.push(g);
            assert_eq!(check(&s), Ok(()), "{kind:?}");
        }
    }

    #[test]
    fn planning_beyond_the_limit_is_refused() {
        let mut s = presets::igsa_path_1();
        if let PlannerConfig::Igsa(p) = &mut s.groups[0].planner {
            (p.population, p.iterations, p.waypoint_count) = (200, 3000, 8);
        }
        assert_eq!(planning_segment_checks(&s.groups[0]), 5_400_000);
        s.groups.push(s.groups[0].clone());
        assert_eq!(check(&s), Ok(()));
        s.groups.push(s.groups[0].clone());
        let e = check(&s).expect_err("three groups at the largest parameters plan too much");
        assert!(e.to_string().contains("16200000 path segments"), "{e}");
    }
}
