//! Scene cost limits: a scene is refused up front when one step of it would take more than
//! [`STEP_BUDGET_NS`] in the browser, or when its IGSA groups would plan more than
//! [`MAX_PLANNING_SEGMENT_CHECKS`], so no valid link can stall or crash the page.
//!
//! Per step the model is linear: every agent costs its planner's worst measured time per
//! agent-step ([`ns_per_agent_step`]). "Worst" is the densest crowd the spawn allows (bodies
//! packed at the density limit of [`crate::sim::spawn`]) heading for a goal in its middle,
//! measured natively (`cargo run --release --example step_cost`) and scaled by [`wasm_factor`].
//! The spawn itself is O(N) and refuses regions that cannot hold their count.
//!
//! IGSA plans its path once per group (and again on edits): population × iterations objective
//! evaluations, each checking `waypoint_count + 1` segments against the obstacles. The page
//! plans in slices, so planning never blocks it; this limit keeps the total finite.

use crate::model::params::{PlannerConfig, PlannerKind};
use crate::model::scene::{Group, Scene, SceneError};
use crate::spatial::ObstacleIndex;

/// Most time one step may take in the browser (ns): 180 ms. The page runs at least one step per
/// task, so a click waits for at most one step plus a frame's render: this keeps the answer to
/// input within 200 ms (issue 12).
pub const STEP_BUDGET_NS: f64 = 180e6;

/// Most path segments all IGSA groups of a scene may check while planning: population ×
/// iterations × (waypoints + 1), summed over groups. Two groups at the largest parameters
/// (200 × 3000 × 9 = 5.4 million each).
pub const MAX_PLANNING_SEGMENT_CHECKS: u64 = 10_800_000;

/// How much slower a step of each planner runs in wasm (Chromium) than natively: the browser
/// bench's per-planner table (wasm/native at 1k and 10k agents, the larger, rounded up).
pub fn wasm_factor(kind: PlannerKind) -> f64 {
    match kind {
        PlannerKind::Boids => 1.5,
        PlannerKind::Pso => 1.3,
        PlannerKind::Firefly => 1.25,
        PlannerKind::Forces => 1.25,
        PlannerKind::Igsa => 1.3,
        // Not yet measured in the browser: the largest factor of the others.
        PlannerKind::Orca => 1.5,
        PlannerKind::SocialForce => 1.5,
    }
}

/// Worst native time per agent-step of each planner (ns): a crowd packed at the spawn's density
/// limit heading for a goal in its middle (a jam), world step with metrics (see the module docs).
///
/// Measured with `examples/step_cost.rs` (`taskset -c 0`, the worst 10-step window of steps
/// 0–100 and 300–400, at 2,000 and at 10,000 agents), rounded up: pso 4,146 (spread 580–840)
/// before its speed-up (below), forces 13,750 (spread 820–1,250), igsa 1,132 (spread
/// 210–280) on a quiet machine; orca 11,287 (spread 5,250–6,410) and social_force 88,465
/// (spread 5,910–9,060), 2026-11-25 on the shared machine under load 6–14 (the social force sums
/// every neighbour within 5 m, up to its cap of 512, so a packed crowd costs it 10× a spread
/// one). A jam costs 4–12× a spread crowd: every agent has many more
/// neighbours within its planner's reach (the per-agent caps of [`crate::spatial::NEIGHBOUR_CAP`]
/// bound piles beyond that).
///
/// Boids: 1,200. Since a pile's neighbour sums test an even sample of 384 candidates instead of
/// the first 1,024 ([`crate::planners::boids::FLOCK_SAMPLE`]) and the fitness overlap test stops
/// at the first overlap, the worst window measures 1,044–1,131 on-CPU ns (three runs each at
/// 2,000 and 10,000 agents, 2026-11-25, on the 2-core machine shared with other builds, load
/// 9–12; the same runs of the code before gave 1,670–1,867, against 1,505 on a quiet machine,
/// so load inflates these figures if anything); spread 180–200. In the browser 1,200 × 1.5 =
/// 1,800 ns, so 180 ms hold 180e6 / 1,800 = 100,000 Boids agents (before: 1,600 × 1.5 = 2,400
/// ns, 75,000).
///
/// Firefly: 1,400. Since its survey searches a fine per-step index of the agents (cells one
/// contact reach wide) instead of the 200 px world-grid cells, and its contact cut learnt
/// which limit fails first, the worst window measures 1,179–1,330 on-CPU ns (two runs each at
/// 2,000 and 10,000 agents, steps 0–100 and 300–400, 2026-11-26, the 2-core machine shared
/// with other builds, load 8–10; the code before gave 3,400–4,243 in the same runs: the former
/// 12,000 predates its branch-free search); spread 477–528. In the browser 1,400 × 1.25 =
/// 1,750 ns, so 180 ms hold about 102,000 fireflies (before: 12,000). Bodies much smaller
/// than the default 4 px packed at the density limit are dearer: with more than 2,048 within
/// the feeler's reach (radius below about 2.2 px) the survey's caps bind and it takes the world
/// grid's query, as before this change. The step that also takes the fitness measures (one in
/// [`crate::sim::metrics::FITNESS_SAMPLE_EVERY`]) is dearer in a jam; the limit is set from the
/// worst 10-step window (every second one holds such a step), as for every planner. Re-measure when a
/// planner's cost changes.
///
/// PSO: kept at 4,200 though natively it now costs far less. Since phase 1 scans each agent's
/// surroundings once for its position and its pbest, and the candidate moves of phase 2 look up
/// a short list of possible nearest agents instead of the grid (the same floats:
/// `tests/pso_golden.rs`), the worst window measures 684–703 on-CPU ns at 10,000 agents
/// (packed, steps 0–100 and 300–400; three runs each) and 779–804 at 2,000 (two runs; that
/// clock counts in steps of about 200 ns per window there), spread 405–601, 2026-11-26 on the
/// 2-core machine shared with other builds (load 8.8–9.8); the code before, alternated with it
/// in the same runs, gave 3,579–3,748 and 3,298–3,493. But the browser gains less: the page's
/// packed 10,000 (`scripts/bench-page.mjs`: the open-field preset in a square with room for
/// 1.5 bodies per agent, no denser than `step_cost`'s) steps in 16.9 ms
/// of main-thread CPU, 1,690 ns per agent-step, which 900 × [`wasm_factor`] = 1,170 would not
/// cover. Lower this once the wasm/native ratio of the new code is measured on the same scene.
pub fn native_ns_per_agent_step(kind: PlannerKind) -> f64 {
    match kind {
        PlannerKind::Boids => 1_200.0,
        PlannerKind::Pso => 4_200.0,
        PlannerKind::Firefly => 1_400.0,
        PlannerKind::Forces => 14_000.0,
        PlannerKind::Igsa => 1_200.0,
        PlannerKind::Orca => 11_500.0,
        PlannerKind::SocialForce => 90_000.0,
    }
}

/// Worst time per agent-step of each planner in the browser (ns).
pub fn ns_per_agent_step(kind: PlannerKind) -> f64 {
    native_ns_per_agent_step(kind) * wasm_factor(kind)
}

/// The most agents of one planner a scene may hold alone under the step budget.
pub fn max_agents(kind: PlannerKind) -> u64 {
    (STEP_BUDGET_NS / ns_per_agent_step(kind)) as u64
}

fn group_step_ns(g: &Group) -> f64 {
    f64::from(g.count) * ns_per_agent_step(g.planner.kind())
}

/// Estimated time of one step of `scene` in the browser (ns).
pub fn step_cost_ns(scene: &Scene) -> f64 {
    scene.groups.iter().map(group_step_ns).sum()
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

/// Refuses a scene over a limit: a step over [`STEP_BUDGET_NS`] names the group that costs
/// the most, its planner, its count and how many agents of that planner would fit beside the
/// others; planning over [`MAX_PLANNING_SEGMENT_CHECKS`] names the IGSA group that plans most.
pub fn check(scene: &Scene) -> Result<(), SceneError> {
    let total = step_cost_ns(scene);
    let costliest = |cost: &dyn Fn(&Group) -> f64| {
        scene.groups.iter().enumerate().max_by(|a, b| cost(a.1).total_cmp(&cost(b.1)))
    };
    if total > STEP_BUDGET_NS {
        if let Some((i, g)) = costliest(&group_step_ns) {
            let kind = g.planner.kind().name();
            let fit = ((STEP_BUDGET_NS - (total - group_step_ns(g))).max(0.0)
                / ns_per_agent_step(g.planner.kind())) as u64;
            return Err(SceneError::TooCostly(format!(
                "group {} ({}): {} {kind} agents would make a step take about {:.0} ms in the \
                 browser, over the {:.0} ms limit; at most {fit} {kind} agents fit beside the \
                 other groups ({} alone)",
                i + 1,
                g.name,
                g.count,
                total / 1e6,
                STEP_BUDGET_NS / 1e6,
                max_agents(g.planner.kind()),
            )));
        }
    }
    let planning: u64 = scene.groups.iter().map(planning_segment_checks).sum();
    if planning > MAX_PLANNING_SEGMENT_CHECKS {
        if let Some((i, g)) = costliest(&|g| planning_segment_checks(g) as f64) {
            return Err(SceneError::TooCostly(format!(
                "group {} ({}): igsa path planning of all groups would check {planning} path \
                 segments (population × iterations × (waypoints + 1), this group {}), over the \
                 limit of {MAX_PLANNING_SEGMENT_CHECKS}: lower the population or the iterations",
                i + 1,
                g.name,
                planning_segment_checks(g),
            )));
        }
    }
    Ok(())
}

/// The work a scene asks for, counted where it is done and estimated where it is timed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Work {
    /// Lattice places the spawn examined (counted).
    pub spawn_places: u64,
    /// Estimated time of one step in the browser (ns).
    pub step_ns: f64,
    /// Path segments IGSA planning will check (counted from the parameters).
    pub planning_segment_checks: u64,
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
        step_ns: step_cost_ns(scene),
        planning_segment_checks: scene.groups.iter().map(planning_segment_checks).sum(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::presets;

    #[test]
    fn every_preset_is_within_the_limits() {
        for p in presets::ALL {
            let w = work(&(p.build)()).unwrap_or_else(|e| panic!("{}: {e}", p.name));
            assert!(w.step_ns <= STEP_BUDGET_NS && w.planning_segment_checks <= MAX_PLANNING_SEGMENT_CHECKS);
        }
    }

    #[test]
    fn too_many_fireflies_are_refused_naming_group_planner_count_and_limit() {
        let mut s = Scene::empty(20_000.0, 20_000.0);
        let mut g = presets::open_field().groups.remove(0);
        g.goal = None;
        g.spawn = crate::Region { min: [0.0, 0.0], max: [20_000.0, 20_000.0] };
        g.planner = PlannerKind::Firefly.default_config();
        g.count = max_agents(PlannerKind::Firefly) as u32;
        s.groups.push(g);
        assert_eq!(check(&s), Ok(()), "exactly the limit is accepted");
        s.groups[0].count += 1;
        let e = check(&s).expect_err("one more is refused");
        let text = e.to_string();
        assert!(matches!(e, SceneError::TooCostly(_)));
        let count = format!("{} firefly agents", s.groups[0].count);
        let limit = format!("at most {} firefly agents", max_agents(PlannerKind::Firefly));
        for part in ["group 1 (flock)", count.as_str(), "180 ms limit", limit.as_str()] {
            assert!(text.contains(part), "{part:?} missing from {text:?}");
        }
    }

    #[test]
    fn a_hundred_thousand_boids_fit_and_one_more_does_not() {
        assert_eq!(max_agents(PlannerKind::Boids), 100_000);
        let mut s = Scene::empty(20_000.0, 20_000.0);
        let mut g = presets::open_field().groups.remove(0);
        g.spawn = crate::Region { min: [0.0, 0.0], max: [20_000.0, 20_000.0] };
        g.planner = PlannerKind::Boids.default_config();
        g.count = 100_000;
        s.groups.push(g);
        assert_eq!(check(&s), Ok(()));
        s.groups[0].count += 1;
        assert!(matches!(check(&s), Err(SceneError::TooCostly(_))));
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
