//! Scene cost limits: a scene is refused up front when one step of it would take more than
//! [`STEP_BUDGET_NS`] in the browser, or when its IGSA groups would plan more than
//! [`MAX_PLANNING_SEGMENT_CHECKS`], so no valid link can stall or crash the page.
//!
//! Per step the model is linear: every agent costs its planner's worst measured time per
//! agent-step ([`ns_per_agent_step`]). "Worst" is the densest crowd the spawn allows (bodies
//! packed at the density limit of [`crate::sim::spawn`]) heading for a goal in its middle,
//! measured natively (`cargo run --release --example step_cost`) and scaled by [`wasm_factor`].
//! Boids, whose agents park at their goal, cost far more in that scene (a jam) than in any crowd
//! that cannot jam, so a Boids group is charged the jam figure
//! ([`jam_native_ns_per_agent_step`]) only when it can jam ([`can_jam`]: packed round or next to
//! its own goal) and its other figure otherwise.
//!
//! Smaller bodies pack more of them into each agent's reach (a planner's reach is in px, or
//! its neighbour search scans grid cells sized in px), so every figure is measured at the
//! body radii [`MEASURED_RADII`], down to the smallest a scene allows, and a group is charged
//! the figure of its scene's [`crowd_radius`]: the bodies its agents can be packed among.
//! The spawn itself is O(N) and refuses regions that cannot hold their count.
//!
//! IGSA plans its path once per group (and again on edits): population × iterations objective
//! evaluations, each checking `waypoint_count + 1` segments against the obstacles. The page
//! plans in slices, so planning never blocks it; this limit keeps the total finite.
//!
//! # What these limits still protect now that the simulation runs in a worker (issue 24)
//!
//! The step budget was set so that a click waits for at most one step on the page's main
//! thread. The playground, the compare page, `<flock-path>` and the tune preview now step in a
//! Web Worker, and `tests/e2e/heavy-pause.test.mjs` shows every heavy link of the issue (steps
//! of up to 7 s) answering Pause in 20–36 ms (median of three clicks, 2026-11-27). So:
//!
//! - No longer protecting the page: [`STEP_BUDGET_NS`] and everything that only feeds the step
//!   estimate ([`wasm_factor`], [`native_ns_per_agent_step`], [`SMALL_BODY_FIGURES`],
//!   [`MEASURED_RADII`], [`crowd_radius`], the jam figure with [`can_jam`], [`JAM_FILL`] and
//!   [`JAM_REACH_DIAMETERS`]). They never bounded memory (that is per agent, bounded by
//!   `MAX_AGENTS` in `model/scene.rs`) nor the recording (the timeline's byte budget).
//! - Still depending on them before they can go: `<flock-path>` steps on the main thread where
//!   no worker can start (`www/js/flock-path.js`), and there this estimate is the only guard;
//!   a worker restart after an unanswered Pause, and a timeline seek, replay steps in the
//!   worker, so a scene of seconds per step answers again only after steps × step time (the
//!   page stays free, the scene does not); `flockpath run` refuses the same scenes as the page;
//!   `tests/fuzz_codec.rs` and `tests/world_bounds.rs` assert on the budget and
//!   [`max_agents`].
//! - [`MAX_PLANNING_SEGMENT_CHECKS`] no longer protects the page either (planning runs in
//!   slices in the worker), but it still bounds how long a scene waits before its first step:
//!   the per-group parameter maxima allow 5.4 million segment checks per group and the number
//!   of groups is bounded only by the scene's size. Its slices are one iteration, not a time,
//!   so among thousands of obstacles one slice can outlast the worker's 1 s Pause deadline.
//! - Not covered here, and a memory limit is what is left to add: each group guided by a flow
//!   field (ORCA and social force by default, Boids with `flow_field: goal`) keeps its own
//!   field of up to `MAX_CELLS` cells. Natively, 500 one-agent ORCA groups among 20 circles in a
//!   20,000 px world take 927 MB and 14.9 s to load and step twice (`flockpath run`), for an
//!   estimated step cost of 1 ms; a few
//!   thousand such groups exceed wasm32's 4 GiB.

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
        // Since its SIMD neighbour pass (2026-11-26): a step of 18,000 packed round their goal
        // took 173 ms median on the page against about 135 ms natively (1.28).
        PlannerKind::Forces => 1.3,
        PlannerKind::Igsa => 1.3,
        // The largest factor of the others. On the page (`flockpath.step(1)` timed, Chromium
        // on one core, 2026-11-26) a step of the packed crowd at the new limits took 125 ms
        // median for 85,714 ORCA agents and 132 ms for 8,000 social-force ones: 1.07 and 1.1 ×
        // the native worst windows.
        PlannerKind::Orca => 1.5,
        PlannerKind::SocialForce => 1.5,
        // Not measured in the browser yet: the largest factor of the others.
        PlannerKind::CollisionFreeSpeed => 1.5,
    }
}

/// Worst native time per agent-step of each planner (ns): a crowd packed at the spawn's density
/// limit heading for a goal in its middle (a jam), world step with metrics (see the module docs).
///
/// Measured with `examples/step_cost.rs` (`taskset -c 0`, the worst 10-step window of steps
/// 0–100 and 300–400, at 2,000 and at 10,000 agents), rounded up: pso 4,146 (spread 580–840)
/// before its speed-up (below), forces 13,750 (spread 820–1,250), igsa 1,132 (spread
/// 210–280) on a quiet machine. A jam costs 4–12× a spread crowd: every agent has many more
/// neighbours within its planner's reach (the per-agent caps of [`crate::spatial::NEIGHBOUR_CAP`]
/// bound piles beyond that).
///
/// ORCA: 1,400 and social force: 15,000 (were 11,500 and 90,000, measured 2026-11-25 under
/// load 6–14, before the goal's flow field was kept between steps and the grid's neighbour
/// gathering got cheaper). Re-measured 2026-11-26 (`taskset -c 0`, load 3–4): ORCA's worst
/// window 1,319 at 10,000 and 1,368 at 85,000 (about its new limit; spread 1,192), the social
/// force's 12,591 at 2,000 and 14,982 at 10,000 (spread 1,387: it sums every neighbour within
/// 5 m, up to its cap of 512, so a packed crowd costs it 10× a spread one).
///
/// Forces: 8,000 (was 14,000). Since its neighbour pass finds the view through a fine per-step
/// index and sums four candidates at a time ([`crate::planners::forces`]), the worst window
/// measures 3,000 at 2,000 agents, 6,544 at 10,000 and 7,944 at 22,000 (about its new limit;
/// `taskset -c 0`, load 2–3, 2026-11-26); about 70% of it is now the parking pass of the jam.
/// In the browser 8,000 × 1.3 = 10,400 ns, so 180 ms hold 17,307 agents (before: 10,285).
///
/// Boids: 1,200, for a crowd that cannot jam ([`can_jam`]; the jam has its own figure,
/// [`jam_native_ns_per_agent_step`]), measured in the packed scene before Boids parked at
/// goals. Since a pile's neighbour sums test an even sample of 384 candidates instead of
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
///
/// Smaller bodies: the same scenes with bodies of radius 0.5, 1, 2 and 3 px (`step_cost N PLANNER
/// packed,late RADIUS`), see [`SMALL_BODY_FIGURES`]. The figures above are the last column.
pub fn native_ns_per_agent_step(kind: PlannerKind, crowd_radius: f32) -> f64 {
    let default_bodies = match kind {
        PlannerKind::Boids => 1_200.0,
        PlannerKind::Pso => 4_200.0,
        PlannerKind::Firefly => 1_400.0,
        PlannerKind::Forces => 8_000.0,
        PlannerKind::Igsa => 1_200.0,
        PlannerKind::Orca => 1_400.0,
        PlannerKind::SocialForce => 15_000.0,
        // `step_cost N collision_free_speed` (2026-11-27, shared 2-core machine under load
        // 11-18, release without LTO): worst windows 3,937 at 2,000 and 4,597 at 10,000.
        PlannerKind::CollisionFreeSpeed => 4_600.0,
    };
    by_radius(kind, crowd_radius, default_bodies, false)
}

/// Body radii (px) at which the figures are measured, smallest first: the smallest a scene
/// allows, 1, 2, 3 and the default 4 (the figures of [`native_ns_per_agent_step`] and
/// [`jam_native_ns_per_agent_step`]). A crowd of radius r is charged the figure of the largest
/// measured radius ≤ r: a step costs less as bodies grow (fewer fit in a planner's reach), so
/// that figure bounds it.
pub const MEASURED_RADII: [f32; 5] = [0.5, 1.0, 2.0, 3.0, 4.0];

/// Worst native ns per agent-step of each planner in crowds of bodies smaller than the default,
/// at the radii 0.5, 1, 2 and 3 px of [`MEASURED_RADII`]: (planner, jam figure?, figures). The
/// jam row is Boids' [`jam_native_ns_per_agent_step`]. A planner without a row (Boids that
/// cannot jam) costs no more among small bodies than its default figure says.
///
/// Measured with `examples/step_cost.rs` like the default figures (`step_cost N PLANNER
/// packed,late RADIUS`: the worst 10-step window of steps 0–100 and 300–400, at 2,000 and
/// 10,000 agents and, where the limit this sets lies above 10,000, at about that limit too),
/// `taskset -c 0`, 2026-11-26 on the 2-core machine shared with two builds (load 2–6), rounded
/// up to 100 ns. At 0.5 px 10,000 bodies fill a 100 px square, so every agent has the whole
/// crowd within its reach and the planners' neighbour caps bind; at 3 px every figure is back
/// within a few percent of the default one. The worst windows, at 2,000 / 10,000 / more agents:
/// - Boids jam: 0.5 px 7,487 / 11,630; 1 px 3,088 / 7,509 / 20,000: 10,695; 2 px 2,119 /
///   5,458 / 20,000: 6,949; 3 px 1,743 / 4,766 / 20,000: 6,131 (the jam's cost per agent grows
///   with the crowd at every radius; the default 6,000 is set at 20,000 too). A Boids crowd that cannot jam was
///   measured packed without a goal (`step_cost`'s `free` scene, nothing parks): 400–605 at
///   every radius, below the default 1,200, so it has no row.
/// - PSO: 0.5 px 6,193 / 7,388 / 20,000: 7,684; 1 px 7,990 / 10,587 / 20,000: 11,394; 2 px
///   6,592 / 8,077 / 20,000: 8,517; 3 px 800 / 867 / 20,000: 829. Between 3 and 2 px its short
///   local candidate lists stop fitting the crowd and it falls back to the grid's queries.
/// - Firefly: 0.5 px 9,725 / 14,346; 1 px 4,849 / 14,091; 2 px 2,221 / 8,099 / 20,000:
///   11,640; 3 px 1,399 / 1,397 / 20,000: 1,416. Below about 2.2 px the survey's caps bind and
///   it takes the world grid's query.
/// - Virtual forces (its fine-index neighbour pass): 0.5 px 9,440 / 13,358; 1 px 4,196 / 9,032
///   / 16,000: 7,236; 2 px 3,379 / 8,463 / 17,000: 9,514; 3 px 3,186 / 7,010 / 20,000: 8,444.
/// - IGSA: 0.5 px 3,916 / 4,067 / 35,000: 3,913; 1 px 3,683 / 3,770 / 35,000: 4,144; 2 px
///   2,010 / 2,043 / 70,000: 2,428; 3 px 1,199 / 1,196 / 35,000: 1,220 (the default 1,200).
/// - ORCA: 0.5 px 4,798 / 5,783 / 20,000: 5,854; 1 px 3,598 / 4,449 / 40,000: 4,997; 2 px
///   2,198 / 2,515 / 46,000: 2,699; 3 px 1,613 / 1,749 / 66,000: 1,937.
/// - Social force: 0.5 px 17,367 / 18,894; 1 px 18,199 / 20,699; 2 px 19,536 / 20,046; 3 px
///   17,429 / 18,115.
pub const SMALL_BODY_FIGURES: &[(PlannerKind, bool, [f64; 4])] = &[
    (PlannerKind::Boids, true, [11_700.0, 10_700.0, 7_000.0, 6_200.0]),
    (PlannerKind::Pso, false, [7_700.0, 11_400.0, 8_600.0, 900.0]),
    (PlannerKind::Firefly, false, [14_400.0, 14_100.0, 11_700.0, 1_500.0]),
    (PlannerKind::Forces, false, [13_400.0, 9_100.0, 9_600.0, 8_500.0]),
    (PlannerKind::Igsa, false, [4_100.0, 4_200.0, 2_500.0, 1_300.0]),
    (PlannerKind::Orca, false, [5_900.0, 5_000.0, 2_700.0, 2_000.0]),
    (PlannerKind::SocialForce, false, [18_900.0, 20_700.0, 20_100.0, 18_200.0]),
    // Not measured: social force's figures as a bound. Both query the grid with the same caps
    // (512 neighbours among 4,096 candidates), and the collision-free speed model does less
    // per neighbour (one exponential, no ellipse, no contact forces).
    (PlannerKind::CollisionFreeSpeed, false, [18_900.0, 20_700.0, 20_100.0, 18_200.0]),
];

/// The figure of a crowd of `crowd_radius`: `default_bodies` from 4 px up, else the largest
/// figure measured at the radii from the largest measured radius ≤ `crowd_radius` up (the
/// [`SMALL_BODY_FIGURES`] row and `default_bodies`). The cost is not always monotone in the
/// radius (PSO's worst is at 1 px, where the crowd still moves, not at 0.5 px, where it
/// freezes), so a radius is never charged less than any larger one.
fn by_radius(kind: PlannerKind, crowd_radius: f32, default_bodies: f64, jam: bool) -> f64 {
    let class = MEASURED_RADII.iter().rposition(|&r| crowd_radius >= r).unwrap_or(0);
    let small = SMALL_BODY_FIGURES.iter().find(|(k, j, _)| *k == kind && *j == jam);
    let figures = small.map_or(&[][..], |(_, _, f)| &f[..]);
    figures.iter().skip(class).fold(default_bodies, |worst, &f| worst.max(f))
}

/// Least number of agents whose bodies set a scene's [`crowd_radius`].
pub const CROWDING_AGENTS: u32 = 100;

/// The radius of the bodies a scene's agents can be packed among (px): the smallest radius r
/// such that the groups of radius ≤ r hold at least [`CROWDING_AGENTS`] agents (a handful of
/// small bodies adds only a handful of neighbours), or the smallest radius of a scene with
/// fewer agents in all. Every group is charged for it, whatever its own radius: any crowd can
/// end up packed among the smallest bodies.
pub fn crowd_radius(scene: &Scene) -> f32 {
    let mut groups: Vec<(f32, u32)> = scene.groups.iter().map(|g| (g.agent_radius, g.count)).collect();
    groups.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut held = 0u32;
    for &(radius, count) in &groups {
        held = held.saturating_add(count);
        if held >= CROWDING_AGENTS {
            return radius;
        }
    }
    groups.first().map_or(DEFAULT_BODY_RADIUS, |g| g.0)
}

/// The default body radius (px): the figures without a radius are measured with it.
pub const DEFAULT_BODY_RADIUS: f32 = 4.0;

/// Worst native time per agent-step of a planner whose agents park at their goal, in a crowd
/// that can jam (see [`can_jam`]): `step_cost`'s `packed` scene, a square crowd at the density
/// limit round its own goal, where the parking pass searches every step for a free place for
/// each agent boxed in by parked bodies ([`crate::sim::world`]). `None` for a planner whose
/// [`native_ns_per_agent_step`] already is that figure (every planner that does not park, and
/// virtual forces, measured in that scene).
///
/// Boids: 6,000. That scene freezes within about 10 steps into a jam (at 10,000 agents about
/// 9,000 parked bodies and 960 boxed in by them, each searching for a free place every step),
/// and its cost per agent grows with the crowd: worst 10-step window (steps 0–100 and
/// 300–400) 1,861 on-CPU ns at 2,000 agents, 4,434 at 10,000 and 5,725 at 20,000
/// (2026-11-26, `taskset -c 1` on the 2-core machine shared with other builds, load 4–7;
/// before the free-place search tested places from buckets, 7,706 at 10,000 and about 19,600
/// at 20,000). In the browser 6,000 × 1.5 = 9,000 ns, so 180 ms hold 20,000 Boids in a jam:
/// the limit is the largest size measured, so the worst of the three sizes is the honest
/// figure up to it (the 2,000 / 10,000 rule of the other planners would have let in a crowd
/// dearer per agent than measured). Spread and open-field crowds (the page bench, whose goal lies far from
/// the packed crowd) cannot jam and keep [`native_ns_per_agent_step`].
pub fn jam_native_ns_per_agent_step(kind: PlannerKind, crowd_radius: f32) -> Option<f64> {
    match kind {
        PlannerKind::Boids => Some(by_radius(kind, crowd_radius, 6_000.0, true)),
        _ => None,
    }
}

/// Least fill of a spawn region (bodies × (2r)² over the region's area including a body's
/// margin, 1 at the density limit) at which a parking group round its goal is charged as a jam.
/// A quarter of the density limit, well below the measured jam (1) and well above the page
/// bench's 100,000 Boids spread over the field (about 0.07).
pub const JAM_FILL: f64 = 0.25;

/// How near its spawn region a group's goal must come for the group to be charged as a jam: the
/// goal's disc within this many body diameters of the region (the parking pass's free-place
/// search reaches 10).
pub const JAM_REACH_DIAMETERS: f32 = 10.0;

/// Whether group `g` of `scene` can freeze into the jam of [`jam_native_ns_per_agent_step`]: its
/// planner parks at goals (Boids, virtual forces), its goal is fixed, its spawn region is
/// filled to at least [`JAM_FILL`] of the density limit, and the goal's disc lies within
/// [`JAM_REACH_DIAMETERS`] body diameters of the region (it contains or touches the goal).
pub fn can_jam(scene: &Scene, g: &Group) -> bool {
    if !matches!(g.planner.kind(), PlannerKind::Boids | PlannerKind::Forces) {
        return false;
    }
    let Some(goal) = g.goal.and_then(|k| scene.goals.get(k as usize)) else {
        return false;
    };
    if goal.motion.is_some() {
        return false;
    }
    let (lo, hi) = (g.spawn.min, g.spawn.max);
    let diameter = 2.0 * f64::from(g.agent_radius);
    let area =
        (f64::from(hi[0] - lo[0]).max(0.0) + diameter) * (f64::from(hi[1] - lo[1]).max(0.0) + diameter);
    let fill = f64::from(g.count) * diameter * diameter / area.max(f64::MIN_POSITIVE);
    let [x, y] = goal.position;
    let dx = (lo[0] - x).max(x - hi[0]).max(0.0);
    let dy = (lo[1] - y).max(y - hi[1]).max(0.0);
    let reach = goal.radius + JAM_REACH_DIAMETERS * 2.0 * g.agent_radius;
    fill >= JAM_FILL && f64::from(dx).hypot(f64::from(dy)) <= f64::from(reach)
}

/// Worst time per agent-step of each planner in the browser (ns), among bodies of
/// `crowd_radius` (px).
pub fn ns_per_agent_step(kind: PlannerKind, crowd_radius: f32) -> f64 {
    native_ns_per_agent_step(kind, crowd_radius) * wasm_factor(kind)
}

/// Worst time per agent-step in the browser of a group of `kind` that can jam (ns), among bodies
/// of `crowd_radius` (px).
pub fn jam_ns_per_agent_step(kind: PlannerKind, crowd_radius: f32) -> f64 {
    jam_native_ns_per_agent_step(kind, crowd_radius)
        .unwrap_or_else(|| native_ns_per_agent_step(kind, crowd_radius))
        * wasm_factor(kind)
}

/// The most agents of one planner a scene may hold alone under the step budget, among bodies of
/// `crowd_radius` (px; [`DEFAULT_BODY_RADIUS`] for the default bodies).
pub fn max_agents(kind: PlannerKind, crowd_radius: f32) -> u64 {
    (STEP_BUDGET_NS / ns_per_agent_step(kind, crowd_radius)) as u64
}

/// The most agents of one planner a scene may hold alone under the step budget when they can
/// jam ([`can_jam`]), among bodies of `crowd_radius` (px).
pub fn max_jam_agents(kind: PlannerKind, crowd_radius: f32) -> u64 {
    (STEP_BUDGET_NS / jam_ns_per_agent_step(kind, crowd_radius)) as u64
}

/// Worst browser time per agent-step of group `g` of `scene` among bodies of `crowd` px (ns).
fn group_ns_per_agent_step(scene: &Scene, g: &Group, crowd: f32) -> f64 {
    if can_jam(scene, g) {
        jam_ns_per_agent_step(g.planner.kind(), crowd)
    } else {
        ns_per_agent_step(g.planner.kind(), crowd)
    }
}

fn group_step_ns(scene: &Scene, g: &Group, crowd: f32) -> f64 {
    f64::from(g.count) * group_ns_per_agent_step(scene, g, crowd)
}

/// Estimated time of one step of `scene` in the browser (ns).
pub fn step_cost_ns(scene: &Scene) -> f64 {
    let crowd = crowd_radius(scene);
    scene.groups.iter().map(|g| group_step_ns(scene, g, crowd)).sum()
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
    let crowd = crowd_radius(scene);
    let costliest = |cost: &dyn Fn(&Group) -> f64| {
        scene.groups.iter().enumerate().max_by(|a, b| cost(a.1).total_cmp(&cost(b.1)))
    };
    if total > STEP_BUDGET_NS {
        if let Some((i, g)) = costliest(&|g| group_step_ns(scene, g, crowd)) {
            let kind = g.planner.kind().name();
            let fit = ((STEP_BUDGET_NS - (total - group_step_ns(scene, g, crowd))).max(0.0)
                / group_ns_per_agent_step(scene, g, crowd)) as u64;
            let (jam, alone) = if can_jam(scene, g) {
                (" packed round their own goal (the jam limit)", max_jam_agents(g.planner.kind(), crowd))
            } else {
                ("", max_agents(g.planner.kind(), crowd))
            };
            // Named only when it costs more than the default bodies would.
            let small = if crowd < DEFAULT_BODY_RADIUS
                && group_ns_per_agent_step(scene, g, crowd)
                    > group_ns_per_agent_step(scene, g, DEFAULT_BODY_RADIUS)
            {
                format!(" among bodies of radius {crowd} px (small bodies crowd into each agent's reach)")
            } else {
                String::new()
            };
            return Err(SceneError::TooCostly(format!(
                "group {} ({}): {} {kind} agents{jam}{small} would make a step take about {:.0} ms \
                 in the browser, over the {:.0} ms limit; at most {fit} {kind} agents fit beside \
                 the other groups ({alone} alone)",
                i + 1,
                g.name,
                g.count,
                total / 1e6,
                STEP_BUDGET_NS / 1e6,
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
        g.count = max_agents(PlannerKind::Firefly, DEFAULT_BODY_RADIUS) as u32;
        s.groups.push(g);
        assert_eq!(check(&s), Ok(()), "exactly the limit is accepted");
        s.groups[0].count += 1;
        let e = check(&s).expect_err("one more is refused");
        let text = e.to_string();
        assert!(matches!(e, SceneError::TooCostly(_)));
        let count = format!("{} firefly agents", s.groups[0].count);
        let limit =
            format!("at most {} firefly agents", max_agents(PlannerKind::Firefly, DEFAULT_BODY_RADIUS));
        for part in ["group 1 (flock)", count.as_str(), "180 ms limit", limit.as_str()] {
            assert!(text.contains(part), "{part:?} missing from {text:?}");
        }
    }

    #[test]
    fn a_hundred_thousand_boids_fit_and_one_more_does_not() {
        assert_eq!(max_agents(PlannerKind::Boids, DEFAULT_BODY_RADIUS), 100_000);
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

    /// `examples/step_cost.rs`'s `packed` scene: `n` Boids at the density limit round their goal.
    fn jam(n: u32) -> Scene {
        let radius = 4.0;
        let side = (f64::from(n).sqrt().ceil() as f32) * 2.0 * radius;
        let world = side + 200.0;
        let mut s = Scene::empty(world, world);
        let (lo, hi) = (100.0 + radius, 100.0 + side - radius);
        s.goals.push(crate::Goal::fixed([0.5 * world, 0.5 * world], 20.0));
        let mut g = presets::constant_density(1, 1.0).groups.remove(0);
        g.count = n;
        g.spawn = crate::Region { min: [lo, lo], max: [hi, hi] };
        g.goal = Some(0);
        g.agent_radius = radius;
        g.planner = PlannerKind::Boids.default_config();
        s.groups.push(g);
        s
    }

    /// The page bench's scene (scripts/bench-page.mjs `loadScene`): the `open-field` preset
    /// scaled to `n` agents, spread over the field or packed in a square at its left.
    fn bench(n: u32, packed: bool) -> Scene {
        let mut s = presets::open_field();
        let density = 9.0 / (std::f32::consts::PI * 50.0 * 50.0);
        let width = (n as f32 / density * 1.6).sqrt();
        let height = width / 1.6;
        let (sx, sy) = (width / s.width, height / s.height);
        (s.width, s.height) = (width, height);
        for goal in &mut s.goals {
            goal.position = [goal.position[0] * sx, goal.position[1] * sy];
            goal.radius *= (sx * sy).sqrt();
        }
        let g = &mut s.groups[0];
        g.count = n;
        g.planner = PlannerKind::Boids.default_config();
        let side = (n as f32 * 1.5).sqrt() * 2.0 * g.agent_radius;
        g.spawn = if packed {
            crate::Region {
                min: [40.0, height / 2.0 - side / 2.0],
                max: [40.0 + side, height / 2.0 + side / 2.0],
            }
        } else {
            crate::Region { min: [10.0, 10.0], max: [width - 10.0, height - 10.0] }
        };
        s
    }

    #[test]
    fn a_jam_of_boids_is_charged_its_own_figure_and_the_bench_crowds_are_not() {
        let s = jam(100_000);
        assert!(can_jam(&s, &s.groups[0]));
        let text = check(&s).expect_err("100,000 Boids jammed round their goal are refused").to_string();
        let alone = format!("({} alone)", max_jam_agents(PlannerKind::Boids, DEFAULT_BODY_RADIUS));
        for part in
            ["group 1", "100000 boids agents packed round their own goal (the jam limit)", alone.as_str()]
        {
            assert!(text.contains(part), "{part:?} missing from {text:?}");
        }
        let limit = max_jam_agents(PlannerKind::Boids, DEFAULT_BODY_RADIUS) as u32;
        assert_eq!(check(&jam(limit)), Ok(()), "exactly the jam limit is accepted");
        assert!(check(&jam(limit + 1)).is_err(), "one more is refused");
        for packed in [false, true] {
            let s = bench(100_000, packed);
            assert!(!can_jam(&s, &s.groups[0]), "bench packed={packed} counted as a jam");
            assert_eq!(work(&s).map(|_| ()), Ok(()), "bench packed={packed}");
        }
        // A crowd filled to the jam fill whose goal lies just outside its region still jams.
        let mut s = jam(10_000);
        s.goals[0].position = [s.groups[0].spawn.max[0] + 60.0, s.goals[0].position[1]];
        assert!(can_jam(&s, &s.groups[0]));
        s.goals[0].position[0] += 100.0;
        assert!(!can_jam(&s, &s.groups[0]));
    }

    #[test]
    fn the_crowd_radius_is_set_by_a_hundred_agents_or_more() {
        let mut s = jam(10_000);
        assert_eq!(crowd_radius(&s), 4.0);
        let mut dots = s.groups[0].clone();
        (dots.agent_radius, dots.count) = (0.5, CROWDING_AGENTS - 1);
        s.groups.push(dots);
        assert_eq!(crowd_radius(&s), 4.0, "99 dots add only 99 neighbours");
        s.groups[1].count = CROWDING_AGENTS;
        assert_eq!(crowd_radius(&s), 0.5);
        s.groups[0].count = 0;
        s.groups[1].count = 3;
        assert_eq!(crowd_radius(&s), 0.5, "a scene of a few agents: its smallest bodies");
    }

    #[test]
    fn every_figure_grows_as_bodies_shrink() {
        for &kind in PlannerKind::ALL.iter() {
            let mut last = 0.0;
            for &r in MEASURED_RADII.iter().rev() {
                let figure = native_ns_per_agent_step(kind, r);
                assert!(figure >= last && figure > 0.0, "{kind:?} at {r} px: {figure} < {last}");
                last = figure;
                if let Some(jam) = jam_native_ns_per_agent_step(kind, r) {
                    assert!(jam >= figure, "{kind:?} jam at {r} px");
                }
            }
            // Between the measured radii the smaller radius's figure is charged.
            assert_eq!(native_ns_per_agent_step(kind, 0.7), native_ns_per_agent_step(kind, 0.5));
            assert_eq!(native_ns_per_agent_step(kind, 3.9), native_ns_per_agent_step(kind, 3.0));
            assert_eq!(native_ns_per_agent_step(kind, 40.0), native_ns_per_agent_step(kind, 4.0));
        }
        assert!(
            native_ns_per_agent_step(PlannerKind::Firefly, 0.5)
                > 5.0 * native_ns_per_agent_step(PlannerKind::Firefly, 4.0)
        );
    }

    #[test]
    fn small_fireflies_are_refused_at_their_own_limit_naming_the_body_size() {
        let mut s = Scene::empty(20_000.0, 20_000.0);
        let mut g = presets::open_field().groups.remove(0);
        g.goal = None;
        g.spawn = crate::Region { min: [0.0, 0.0], max: [20_000.0, 20_000.0] };
        g.planner = PlannerKind::Firefly.default_config();
        g.agent_radius = 0.5;
        let limit = max_agents(PlannerKind::Firefly, 0.5);
        assert!(limit * 5 < max_agents(PlannerKind::Firefly, DEFAULT_BODY_RADIUS));
        g.count = limit as u32;
        s.groups.push(g);
        assert_eq!(check(&s), Ok(()), "exactly the limit is accepted");
        s.groups[0].count += 1;
        let text = check(&s).expect_err("one more is refused").to_string();
        let alone = format!("({limit} alone)");
        for part in ["firefly agents among bodies of radius 0.5 px", alone.as_str()] {
            assert!(text.contains(part), "{part:?} missing from {text:?}");
        }
        // 100 small bodies among 4 px ones make every group pay for small bodies.
        s.groups[0].agent_radius = 4.0;
        s.groups[0].count = max_agents(PlannerKind::Firefly, DEFAULT_BODY_RADIUS) as u32;
        assert_eq!(check(&s), Ok(()));
        let mut dots = s.groups[0].clone();
        (dots.agent_radius, dots.count, dots.planner) =
            (1.0, CROWDING_AGENTS, PlannerKind::Orca.default_config());
        s.groups.push(dots);
        assert!(check(&s).is_err(), "the fireflies now crowd among 1 px bodies");
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
