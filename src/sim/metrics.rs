//! Run metrics (DESIGN §4): collisions, penetrations, arrival, path length, smoothness, speed.
//!
//! Counting rules: a collision is a pair of agents whose discs overlap at the end of a step,
//! counted once per pair per step; a penetration is an agent whose centre is inside an obstacle
//! at the end of a step, or whose centre's way during the step (the segment from where it was
//! to where it is, cut at the seam of a periodic band) passed through an obstacle it was not
//! already in: once per agent per step either way. A fast agent that jumped a thin wall
//! tunnelled through it, which the world prevents ([`crate::sim::sweep`]) and this would show.
//! Key names are a stable contract: add keys, never rename.
//!
//! Cost: recording a step is O(N) with a small constant, and so is a summary (what the page polls
//! every 250 ms); a pile of overlapping agents costs a bounded amount per agent too. Where a
//! measure would need more, it is bounded per agent (documented where it is): each agent is
//! tested against at most [`MAX_PAIR_CANDIDATES`] others for overlaps once a cell of the grid
//! is crowded (`collisions_capped_steps` counts the steps where that cut a count short), and the
//! queue order, a firefly measure, is taken for firefly groups only, on step 1 and every
//! [`QUEUE_SAMPLE_EVERY`] steps, each agent looking at no more than [`QUEUE_NEIGHBOUR_CAP`]
//! neighbours within [`QUEUE_AHEAD_RADII`] body radii.
//!
//! `fitness` holds the five measures of the GA-tuned virtual-force paper (DESIGN §3.5,
//! [`crate::sim::fitness`]) for any planner, with behaviour B1's parameters and weights (a group moving
//! at 24 px spacing towards its goal). They cost a k = 7 nearest-neighbour query per agent, so they
//! are sampled on steps 1, 1 + [`FITNESS_SAMPLE_EVERY`], 1 + 2·[`FITNESS_SAMPLE_EVERY`], … only.

use crate::model::forces_cases::Behaviour;
use crate::model::geometry::{distance, length, Aabb};
use crate::model::params::PlannerKind;
use crate::model::scene::{Scale, Scene};
use crate::sim::fitness::{FitnessMeasures, FitnessRecorder, Frame};
use crate::sim::gather::Arrival;
use crate::sim::sweep::path_enters;
use crate::spatial::{ObstacleIndex, QueryCap, SpatialGrid};
use glam::Vec2;
use serde::Serialize;
use std::ops::Range;

/// Steps without progress towards the goal after which an agent counts as stuck.
pub const STUCK_WINDOW: u32 = 300;
/// Distance from an obstacle surface (px) within which an agent is "near" it.
pub const NEAR_OBSTACLE: f32 = 30.0;
/// Below this speed (px/step) no turn is measured: a parked agent's heading jitters without
/// meaning (a twentieth of the Boids default max speed).
const MIN_TURN_SPEED: f32 = 0.1;
/// Queue order: an agent is queued when a brighter neighbour of its group (nearer the goal) is
/// this many of its body radii ahead or closer, centre to centre: 16 px for the default 4 px
/// body, a gap of one body between the two discs. Fireflies in file on `firefly-migration`
/// follow 8–16 px behind the one ahead (seed 1, step 300: 59 of the 73 not arrived; 36 within
/// 12 px); the spawn lattice leaves 0–1 of 80 that close (seeds 1–4).
pub const QUEUE_AHEAD_RADII: f32 = 4.0;
/// Queue order: largest angle (degrees) between an agent's heading and the brighter neighbour
/// for the agent to count as queued behind it.
pub const QUEUE_HALF_ANGLE_DEG: f32 = 30.0;

/// The queue order is measured at the end of step 1 and of every step that is a multiple of this
/// (the plots sample every 5th step, and then every 10th, 20th …, so each plotted value is exact).
pub const QUEUE_SAMPLE_EVERY: u32 = 5;
/// Queue order: at most this many neighbours within [`QUEUE_AHEAD_RADII`] radii (and 128 times
/// as many candidates of the scanned cells) are looked at per agent, the first in the grid's
/// scan order, so a pile costs a bounded amount per agent. Non-overlapping discs hold at most
/// about 20 others within 4 radii: only a pile reaches it.
pub const QUEUE_NEIGHBOUR_CAP: usize = 64;
/// Most agents in one cell of the world's grid for which overlaps are counted on that grid;
/// beyond it (a pile) they are counted on a grid of body-sized cells instead.
const CROWDED_CELL: usize = 64;
/// Overlap counting on the body-sized grid tests each agent against at most this many others
/// (the first in the grid's scan order): a cell there holds one or two non-overlapping bodies,
/// so only a pile reaches it, and then the step's count is a lower bound.
pub const MAX_PAIR_CANDIDATES: usize = 128;

/// The fitness measures are taken every this many steps (on steps 1, 1 + this, …; 3 samples per
/// simulated second). One sample costs about 2.2 Boids steps at 10k agents (`cargo run --release
/// --example fitness_cost`: 744 against 236 on-CPU ns per agent-step with every step sampled), so
/// sampling every step would triple a step; every 20th adds about 11 %.
pub const FITNESS_SAMPLE_EVERY: u32 = 20;

/// The five fitness measures (each 0…1) and their weighted sum, averaged over the sampled steps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct FitnessMetrics {
    /// Gm, inter-agent distance (mean distance to the 7 nearest vs 24 px, quantum 4 px).
    pub gm: f64,
    /// Gg, distance to the goal (quantum 40 px; 0 for a group without a goal).
    pub gg: f64,
    /// Gc, share of agents overlapping no other agent and no obstacle.
    pub gc: f64,
    /// Ga, orientation consistency with the 7 nearest.
    pub ga: f64,
    /// Gd, distance consistency (deviation of the 7 distances, quantum 4 px).
    pub gd: f64,
    /// `Gsum` with B1's weights S (35, 20, 20, 15, 10): a score out of 100.
    pub gsum: f64,
    /// Steps sampled so far.
    pub sampled_steps: u64,
}

impl FitnessMetrics {
    fn new(m: FitnessMeasures, sampled_steps: u64) -> Self {
        Self {
            gm: m.gm,
            gg: m.gg,
            gc: m.gc,
            ga: m.ga,
            gd: m.gd,
            gsum: m.gsum(&Behaviour::GroupMoving.weights()),
            sampled_steps,
        }
    }
}

/// Metrics of one group, or of the whole run.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct GroupMetrics {
    /// Group name (empty for the whole run).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Planner name (only per group).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub planner: Option<String>,
    /// Number of agents.
    pub agents: u32,
    /// Share of agents that have arrived (0…1): whose centre is inside their goal's disc now (a
    /// moving goal: where it is now), or that left the scene through an exit. Agents without a
    /// goal count as not arrived.
    pub arrived_share: f64,
    /// Agents at rest outside their full goal, waiting for room (DESIGN §4).
    pub waiting_agents: u32,
    /// `waiting_agents` as a share of the agents (0…1).
    pub waiting_share: f64,
    /// Agents that left the scene through an exit goal.
    pub exited_agents: u32,
    /// Mean steps from the start to first reaching the goal, over arrived agents (null if none).
    pub mean_time_to_goal: Option<f64>,
    /// The same in seconds (steps × DT).
    pub mean_time_to_goal_s: Option<f64>,
    /// Overlapping agent pairs, summed over steps (a pair across two groups counts in both groups
    /// and once overall).
    pub collisions_agent_agent: u64,
    /// The overlapping pairs of `collisions_agent_agent` in which at least one agent had not
    /// arrived (it was moving): without the pile-up of agents at their goal.
    pub collisions_moving: u64,
    /// Agents whose centre is inside an obstacle at the end of a step or passed through one
    /// during it, summed over steps.
    pub penetrations_agent_obstacle: u64,
    /// Mean speed over agents and steps (px/step).
    pub mean_speed: f64,
    /// `mean_speed` in m/s (the scene's `px_per_metre`, one step = DT s).
    pub mean_speed_m_s: f64,
    /// Mean speed of agents within 30 px of an obstacle surface (px/step; null if none came near).
    pub mean_speed_near_obstacles: Option<f64>,
    /// `mean_speed_near_obstacles` in m/s.
    pub mean_speed_near_obstacles_m_s: Option<f64>,
    /// Mean distance travelled per agent (px).
    pub mean_path_length: f64,
    /// `mean_path_length` in metres.
    pub mean_path_length_m: f64,
    /// Mean turning angle per step (degrees), over moving agents.
    pub mean_turn_deg: f64,
    /// Largest turning angle in one step (degrees).
    pub max_turn_deg: f64,
    /// Agents with a goal that have not arrived and made no progress in the last 300 steps.
    pub stuck_agents: u32,
    /// Queue order (firefly groups only, DESIGN §3.3) at step `queue_order_step`: among agents
    /// that have a goal and have not arrived, the share with a neighbour of their group nearer
    /// the goal (brighter) close ahead: within 4 body radii (16 px for 4 px bodies), centre to
    /// centre, and within ±30° of their heading (0…1; null if no agent qualifies or the group is
    /// not a firefly group). A crowd spread out at the spawn reads near 0; single files, where
    /// everyone but each file's head follows close behind a brighter one, approach 1.
    pub queue_order: Option<f64>,
    /// The step `queue_order` was measured at: step 1, then every [`QUEUE_SAMPLE_EVERY`]th step
    /// (the current step before the first sample); null with `queue_order`.
    pub queue_order_step: Option<u32>,
    /// The five fitness measures and Gsum (DESIGN §3.5), sampled every
    /// [`FITNESS_SAMPLE_EVERY`] steps; null before the first sample (step 0). A group's measures
    /// average its own agents, whose nearest neighbours may belong to any group.
    pub fitness: Option<FitnessMetrics>,
}

/// Metrics of a run: overall keys at the top level, per-group under `groups`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Metrics {
    /// Steps simulated.
    pub steps: u32,
    /// Seconds simulated (steps × DT).
    pub time_s: f64,
    /// The scene's scale (px per metre) behind the `_m` and `_m_s` keys.
    pub px_per_metre: f64,
    /// Overall metrics.
    #[serde(flatten)]
    pub overall: GroupMetrics,
    /// Overlapping pairs at the end of the last step.
    pub collisions_last_step: u32,
    /// Steps whose overlap count was cut short by the per-agent cap ([`MAX_PAIR_CANDIDATES`]):
    /// only a pile of overlapping agents reaches it; then the collision counts are lower bounds.
    pub collisions_capped_steps: u32,
    /// Per-group metrics, in scene order.
    pub groups: Vec<GroupMetrics>,
}

/// Per-agent and per-group accumulators, updated at the end of every step.
#[derive(Clone, Debug)]
pub struct MetricsRecorder {
    prev_pos: Vec<Vec2>,
    prev_vel: Vec<Vec2>,
    /// `prev_vel[i].length()`, kept so it is not taken twice.
    prev_speed: Vec<f32>,
    path_length: Vec<f32>,
    arrived_step: Vec<u32>,
    /// Whether each agent has arrived as of the last recorded step (inside its goal, or exited).
    arrived_now: Vec<bool>,
    /// Where each agent stood with its goal at the last recorded step.
    arrival: Vec<Arrival>,
    best_goal_distance: Vec<f32>,
    last_progress_step: Vec<u32>,
    groups: Vec<GroupAcc>,
    collisions_last_step: u32,
    collisions_total: u64,
    collisions_moving_total: u64,
    collisions_capped_steps: u32,
    /// Body-sized grid for counting overlaps in a pile (built the first time one is met).
    contact_grid: Option<SpatialGrid>,
    /// World size (px), for the contact grid.
    world_size: (f32, f32),
    /// Each group's agent ids (groups own contiguous ranges).
    group_agents: Vec<Range<u32>>,
    /// Groups whose queue order `record` samples (the firefly groups at the start).
    queue_groups: Vec<bool>,
    /// Each group's body radius (px): the queue order's reach is a multiple of it.
    group_radius: Vec<f32>,
    /// The world's periodic band in x, if any: a centre that wrapped did not cross the world.
    periodic_x: Option<(f32, f32)>,
    /// Per group `(queued, candidates)` at the last sample, and the step of that sample.
    queue: Vec<(u32, u32)>,
    queue_step: Option<u32>,
    fitness: FitnessRecorder,
    /// Steps between fitness samples (0 = none).
    fitness_every: u32,
    /// Each agent's goal position at the sampled step (reused buffer).
    fitness_goals: Vec<Option<Vec2>>,
}

#[derive(Clone, Debug, Default)]
struct GroupAcc {
    collisions: u64,
    collisions_moving: u64,
    penetrations: u64,
    speed_sum: f64,
    speed_samples: u64,
    near_speed_sum: f64,
    near_samples: u64,
    turn_sum: f64,
    turn_samples: u64,
    max_turn: f64,
}

const NOT_ARRIVED: u32 = u32::MAX;

impl MetricsRecorder {
    /// Starts recording a run whose agents start at `positions`.
    pub fn new(scene: &Scene, positions: &[Vec2]) -> Self {
        let n = positions.len();
        Self {
            prev_pos: positions.to_vec(),
            prev_vel: vec![Vec2::ZERO; n],
            prev_speed: vec![0.0; n],
            path_length: vec![0.0; n],
            arrived_step: vec![NOT_ARRIVED; n],
            arrived_now: vec![false; n],
            arrival: vec![Arrival::Moving; n],
            best_goal_distance: vec![f32::INFINITY; n],
            last_progress_step: vec![0; n],
            groups: vec![GroupAcc::default(); scene.groups.len()],
            collisions_last_step: 0,
            collisions_total: 0,
            collisions_moving_total: 0,
            collisions_capped_steps: 0,
            contact_grid: None,
            world_size: (scene.width, scene.height),
            group_agents: {
                let mut start = 0u32;
                scene
                    .groups
                    .iter()
                    .map(|g| {
                        start += g.count;
                        start - g.count..start
                    })
                    .collect()
            },
            queue_groups: scene.groups.iter().map(|g| g.planner.kind() == PlannerKind::Firefly).collect(),
            group_radius: scene.groups.iter().map(|g| g.agent_radius).collect(),
            periodic_x: None,
            queue: vec![(0, 0); scene.groups.len()],
            queue_step: None,
            fitness: FitnessRecorder::new(
                Behaviour::GroupMoving.fitness_params(),
                scene.width,
                scene.height,
                n,
            ),
            fitness_every: FITNESS_SAMPLE_EVERY,
            fitness_goals: vec![None; n],
        }
    }

    /// Takes the fitness measures on steps 1, 1 + `every`, … from now on (0 = never).
    pub fn set_fitness_sample_every(&mut self, every: u32) {
        self.fitness_every = every;
    }

    /// Takes a centre that leaves the band `[start, end)` at one end and re-enters at the other
    /// as one that wrapped (`World::set_periodic_x`), not one that crossed the world.
    pub fn set_periodic_x(&mut self, band: Option<(f32, f32)>) {
        self.periodic_x = band;
    }

    /// Records the state at the end of step `step`.
    #[allow(clippy::too_many_arguments, reason = "one call per step with the world's parallel arrays")]
    pub fn record(
        &mut self,
        step: u32,
        pos: &[Vec2],
        vel: &[Vec2],
        group_of: &[u32],
        radius: &[f32],
        goals: &[Option<(Vec2, f32)>],
        grid: &SpatialGrid,
        obstacles: &ObstacleIndex,
        arrival: &[Arrival],
    ) {
        self.arrival.clear();
        self.arrival.extend_from_slice(arrival);
        self.arrival.resize(pos.len(), Arrival::Moving);
        for i in 0..pos.len() {
            let g = group_of[i] as usize;
            if self.arrival[i] == Arrival::Exited {
                // Gone: it neither moves nor meets anyone; it arrived when it left.
                if self.arrived_step[i] == NOT_ARRIVED {
                    self.arrived_step[i] = step;
                }
                self.arrived_now[i] = true;
                self.prev_pos[i] = pos[i];
                self.prev_vel[i] = Vec2::ZERO;
                self.prev_speed[i] = 0.0;
                continue;
            }
            let acc = &mut self.groups[g];
            let p = pos[i];
            let v = vel[i];
            let moved = distance(p, self.prev_pos[i]);
            self.path_length[i] += moved;
            let speed = length(v);
            acc.speed_sum += f64::from(speed);
            acc.speed_samples += 1;

            let prev_v = self.prev_vel[i];
            let prev_speed = self.prev_speed[i];
            if speed > MIN_TURN_SPEED && prev_speed > MIN_TURN_SPEED {
                let cos = (v.dot(prev_v) / (speed * prev_speed)).clamp(-1.0, 1.0);
                let turn = f64::from(libm::acosf(cos)).to_degrees();
                acc.turn_sum += turn;
                acc.turn_samples += 1;
                acc.max_turn = acc.max_turn.max(turn);
            }

            if !obstacles.is_empty() {
                let query = Aabb { min: p, max: p }.inflate(NEAR_OBSTACLE);
                let (mut inside, mut near, mut nearest) = (false, false, f32::INFINITY);
                obstacles.for_each_near(query, |_, o| {
                    let s = o.surface(p);
                    inside |= s.signed_distance < 0.0;
                    near |= s.signed_distance < NEAR_OBSTACLE;
                    nearest = nearest.min(s.signed_distance);
                });
                // The way lies within `moved` of where it ends: a move shorter than the query's
                // reach crosses only an obstacle it found nearer than that (usually none).
                let crossed = !inside
                    && (moved > NEAR_OBSTACLE || nearest < moved)
                    && path_enters(obstacles, self.prev_pos[i], p, self.periodic_x);
                if inside || crossed {
                    acc.penetrations += 1;
                }
                if near {
                    acc.near_speed_sum += f64::from(speed);
                    acc.near_samples += 1;
                }
            }

            if let Some((goal, goal_radius)) = goals.get(g).copied().flatten() {
                let d = distance(p, goal);
                self.arrived_now[i] = d <= goal_radius;
                if self.arrived_step[i] == NOT_ARRIVED && d <= goal_radius {
                    self.arrived_step[i] = step;
                }
                if d < self.best_goal_distance[i] - radius[i] {
                    self.best_goal_distance[i] = d;
                    self.last_progress_step[i] = step;
                }
            }
            self.prev_pos[i] = p;
            self.prev_vel[i] = v;
            self.prev_speed[i] = speed;
        }

        // Collisions after arrivals (a pair with an agent not yet arrived is a moving one).
        let max_radius = radius.iter().copied().fold(0.0f32, f32::max);
        // Collisions: pairs closer than the sum of radii, each once, counted as they are found.
        let pair_radius = 2.0 * max_radius;
        let (pair_grid, cap) = if grid.max_cell_occupancy() <= CROWDED_CELL || pos.is_empty() {
            (grid, usize::MAX)
        } else {
            // A pile: the world's cells hold too many agents to test every pair of a cell.
            let contact = self.contact_grid.get_or_insert_with(|| {
                let (w, h) = self.world_size;
                SpatialGrid::new(w, h, pair_radius.max(1.0), pos.len())
            });
            contact.rebuild(pos, &[]);
            (&*contact, MAX_PAIR_CANDIDATES)
        };
        let groups = &mut self.groups;
        let arrived = &self.arrived_step;
        let gone = &self.arrival;
        let (mut count, mut moving_count) = (0u32, 0u32);
        let capped = pair_grid.for_each_pair_within_capped(pair_radius, cap, |a, b| {
            let d2 = pos[a as usize].distance_squared(pos[b as usize]);
            let r = radius[a as usize] + radius[b as usize];
            let present = gone[a as usize] != Arrival::Exited && gone[b as usize] != Arrival::Exited;
            if present && d2 < r * r {
                count += 1;
                let moving = arrived[a as usize] == NOT_ARRIVED || arrived[b as usize] == NOT_ARRIVED;
                moving_count += u32::from(moving);
                let (ga, gb) = (group_of[a as usize] as usize, group_of[b as usize] as usize);
                groups[ga].collisions += 1;
                groups[ga].collisions_moving += u64::from(moving);
                if gb != ga {
                    groups[gb].collisions += 1;
                    groups[gb].collisions_moving += u64::from(moving);
                }
            }
        });
        self.collisions_last_step = count;
        self.collisions_total += u64::from(count);
        self.collisions_moving_total += u64::from(moving_count);
        self.collisions_capped_steps += u32::from(capped);

        if self.fitness_every > 0 && step % self.fitness_every == 1 % self.fitness_every {
            self.fitness_goals.clear();
            self.fitness_goals
                .extend(group_of.iter().map(|&g| goals.get(g as usize).copied().flatten().map(|(p, _)| p)));
            self.fitness.record(Frame { pos, vel, radius, goals: &self.fitness_goals, obstacles, group_of });
        }

        if self.queue_groups.contains(&true) && (step == 1 || step.is_multiple_of(QUEUE_SAMPLE_EVERY)) {
            let mut queue = std::mem::take(&mut self.queue);
            let sampled = &self.queue_groups;
            let target = |g: usize| goals.get(g).copied().flatten().map(|(t, _)| t);
            self.queue_order_into(grid, target, |g| sampled.get(g).copied().unwrap_or(false), &mut queue);
            self.queue = queue;
            self.queue_step = Some(step);
        }
    }

    /// The metrics so far; `planners` names each group's planner.
    /// The queue order is reported for firefly groups only (see [`Self::summary_with_queue`]).
    pub fn summary(&self, scene: &Scene, planners: &[&str], steps: u32) -> Metrics {
        let firefly = PlannerKind::Firefly.name();
        self.summary_with_queue(scene, planners, steps, |g| planners.get(g).is_some_and(|&p| p == firefly))
    }

    /// [`Self::summary`] with the queue order reported only for the groups `queue_for(g)` picks
    /// (the others get null). A group sampled by `record` (a firefly group from the start) costs
    /// nothing here; any other picked group is measured now, before the first sample too: a
    /// bounded neighbour query of 4 body radii per agent on a grid built for it.
    pub fn summary_with_queue(
        &self,
        scene: &Scene,
        planners: &[&str],
        steps: u32,
        queue_for: impl Fn(usize) -> bool,
    ) -> Metrics {
        let dt = f64::from(crate::model::scene::DT);
        let scale = scene.scale();
        let mut overall = GroupAcc::default();
        let mut groups = Vec::with_capacity(scene.groups.len());
        let mut start = 0usize;
        let mut all = Stats::default();
        let queue = self.queue_now(scene, steps, &queue_for);
        let (mut queued, mut queue_candidates) = (0u32, 0u32);
        let mut queue_step = None;
        for (gi, g) in scene.groups.iter().enumerate() {
            let agents = start..start + g.count as usize;
            start = agents.end;
            let acc = &self.groups[gi];
            let stats = self.agent_stats(agents, g.goal.is_some(), steps);
            all.add(&stats);
            overall.penetrations += acc.penetrations;
            overall.speed_sum += acc.speed_sum;
            overall.speed_samples += acc.speed_samples;
            overall.near_speed_sum += acc.near_speed_sum;
            overall.near_samples += acc.near_samples;
            overall.turn_sum += acc.turn_sum;
            overall.turn_samples += acc.turn_samples;
            overall.max_turn = overall.max_turn.max(acc.max_turn);
            let mut m = to_metrics(acc, &stats, (acc.collisions, acc.collisions_moving), dt, scale);
            m.name = Some(g.name.clone());
            m.planner = planners.get(gi).map(|s| s.to_string());
            let (q, c, at) = queue.get(gi).copied().unwrap_or_default();
            m.queue_order = (c > 0).then(|| f64::from(q) / f64::from(c));
            m.queue_order_step = m.queue_order.map(|_| at);
            if m.queue_order.is_some() {
                queue_step = Some(queue_step.map_or(at, |s: u32| s.min(at)));
            }
            m.fitness =
                self.fitness.group_measures(gi).map(|f| FitnessMetrics::new(f, self.fitness.frames()));
            (queued, queue_candidates) = (queued + q, queue_candidates + c);
            groups.push(m);
        }
        let mut overall =
            to_metrics(&overall, &all, (self.collisions_total, self.collisions_moving_total), dt, scale);
        overall.queue_order = (queue_candidates > 0).then(|| f64::from(queued) / f64::from(queue_candidates));
        overall.queue_order_step = overall.queue_order.and(queue_step);
        let sampled = self.fitness.frames();
        overall.fitness = (sampled > 0).then(|| FitnessMetrics::new(self.fitness.measures(), sampled));
        Metrics {
            steps,
            time_s: f64::from(steps) * dt,
            px_per_metre: scale.px_per_metre(),
            overall,
            collisions_last_step: self.collisions_last_step,
            collisions_capped_steps: self.collisions_capped_steps,
            groups,
        }
    }

    /// Per group `(queued, candidates, step measured)` for the groups `queue_for` picks: the
    /// last sample of a sampled group, else measured now on a grid built over the last state.
    fn queue_now(
        &self,
        scene: &Scene,
        steps: u32,
        queue_for: &impl Fn(usize) -> bool,
    ) -> Vec<(u32, u32, u32)> {
        let sampled =
            |g: usize| self.queue_step.is_some() && self.queue_groups.get(g).copied().unwrap_or(false);
        let mut out = vec![(0, 0, steps); scene.groups.len()];
        let reach = scene.groups.iter().map(|g| g.agent_radius).fold(0.0f32, f32::max) * QUEUE_AHEAD_RADII;
        for (g, slot) in out.iter_mut().enumerate() {
            if let (true, true, Some(step)) = (queue_for(g), sampled(g), self.queue_step) {
                let (q, c) = self.queue.get(g).copied().unwrap_or_default();
                *slot = (q, c, step);
            }
        }
        let measure = |g: usize| queue_for(g) && !sampled(g);
        if (0..scene.groups.len()).any(measure) {
            let mut grid = SpatialGrid::new(scene.width, scene.height, reach.max(1.0), self.prev_pos.len());
            grid.rebuild(&self.prev_pos, &self.prev_vel);
            let target = |g: usize| {
                let goal = scene.groups.get(g)?.goal?;
                Some(scene.goals.get(goal as usize)?.position_at(steps))
            };
            let mut counts = vec![(0, 0); scene.groups.len()];
            self.queue_order_into(&grid, target, measure, &mut counts);
            for (g, (q, c)) in counts.into_iter().enumerate() {
                if measure(g) {
                    out[g] = (q, c, steps);
                }
            }
        }
        out
    }

    /// Per group `(queued, candidates)` for [`GroupMetrics::queue_order`] into `counts`, for the
    /// groups `pick` selects, from the last recorded state; `grid` holds the agents at their
    /// last positions, `target(g)` is group `g`'s goal then. Each agent looks at no more than
    /// [`QUEUE_NEIGHBOUR_CAP`] neighbours within [`QUEUE_AHEAD_RADII`] of its radii: O(N), never
    /// O(N²).
    fn queue_order_into(
        &self,
        grid: &SpatialGrid,
        target: impl Fn(usize) -> Option<Vec2>,
        pick: impl Fn(usize) -> bool,
        counts: &mut Vec<(u32, u32)>,
    ) {
        counts.clear();
        counts.resize(self.group_agents.len(), (0, 0));
        let pos = &self.prev_pos;
        let cos_limit = libm::cosf(QUEUE_HALF_ANGLE_DEG.to_radians());
        let cap = QueryCap { neighbours: QUEUE_NEIGHBOUR_CAP, candidates: 128 * QUEUE_NEIGHBOUR_CAP };
        for (gi, agents) in self.group_agents.iter().enumerate() {
            if !pick(gi) {
                continue;
            }
            let Some(target) = target(gi) else { continue };
            let reach = self.group_radius.get(gi).copied().unwrap_or(0.0) * QUEUE_AHEAD_RADII;
            for id in agents.clone() {
                let i = id as usize;
                if self.arrived_step.get(i).is_none_or(|&s| s != NOT_ARRIVED) {
                    continue;
                }
                counts[gi].1 += 1;
                let v = self.prev_vel[i];
                let speed = v.length();
                if speed <= MIN_TURN_SPEED {
                    continue;
                }
                let p = pos[i];
                let mine = p.distance_squared(target);
                let mut queued = false;
                grid.for_each_within_capped(p, reach, cap, |n| {
                    queued = queued
                        || (n.id != id
                            && agents.contains(&n.id)
                            && n.d2 > 0.0
                            && n.pos.distance_squared(target) < mine
                            && v.dot(n.pos - p) >= cos_limit * speed * n.d2.sqrt());
                });
                counts[gi].0 += u32::from(queued);
            }
        }
    }

    /// Whether agent `i` (of a group with a goal if `has_goal`) is stuck after `steps` steps: not
    /// arrived and no progress towards the goal in the last [`STUCK_WINDOW`] steps. False for an
    /// id out of range.
    pub fn is_stuck(&self, i: usize, has_goal: bool, steps: u32) -> bool {
        let (Some(&arrived), Some(&progress)) = (self.arrived_step.get(i), self.last_progress_step.get(i))
        else {
            return false;
        };
        arrived == NOT_ARRIVED
            && !self.arrival.get(i).is_some_and(|a| *a == Arrival::Waiting)
            && has_goal
            && steps >= STUCK_WINDOW
            && steps.saturating_sub(progress) >= STUCK_WINDOW
    }

    fn agent_stats(&self, agents: std::ops::Range<usize>, has_goal: bool, steps: u32) -> Stats {
        let mut s = Stats::default();
        for i in agents {
            s.agents += 1;
            s.path_sum += f64::from(self.path_length[i]);
            let waiting = self.arrival[i] == Arrival::Waiting;
            s.waiting += u32::from(waiting);
            s.exited += u32::from(self.arrival[i] == Arrival::Exited);
            if self.arrived_now[i] {
                s.arrived += 1;
                s.arrival_steps_sum += f64::from(self.arrived_step[i]);
            } else if !waiting && self.is_stuck(i, has_goal, steps) {
                s.stuck += 1;
            }
        }
        s
    }
}

#[derive(Default)]
struct Stats {
    agents: u32,
    arrived: u32,
    waiting: u32,
    exited: u32,
    arrival_steps_sum: f64,
    path_sum: f64,
    stuck: u32,
}

impl Stats {
    fn add(&mut self, o: &Stats) {
        self.agents += o.agents;
        self.arrived += o.arrived;
        self.waiting += o.waiting;
        self.exited += o.exited;
        self.arrival_steps_sum += o.arrival_steps_sum;
        self.path_sum += o.path_sum;
        self.stuck += o.stuck;
    }
}

fn ratio(num: f64, den: u64) -> f64 {
    if den == 0 {
        0.0
    } else {
        num / den as f64
    }
}

fn to_metrics(acc: &GroupAcc, s: &Stats, collisions: (u64, u64), dt: f64, scale: Scale) -> GroupMetrics {
    let (collisions, collisions_moving) = collisions;
    let mean_time = (s.arrived > 0).then(|| s.arrival_steps_sum / f64::from(s.arrived));
    let mean_speed = ratio(acc.speed_sum, acc.speed_samples);
    let near_speed = (acc.near_samples > 0).then(|| acc.near_speed_sum / acc.near_samples as f64);
    let path_length = ratio(s.path_sum, u64::from(s.agents));
    GroupMetrics {
        name: None,
        planner: None,
        agents: s.agents,
        arrived_share: ratio(f64::from(s.arrived), u64::from(s.agents)),
        waiting_agents: s.waiting,
        waiting_share: ratio(f64::from(s.waiting), u64::from(s.agents)),
        exited_agents: s.exited,
        mean_time_to_goal: mean_time,
        mean_time_to_goal_s: mean_time.map(|t| t * dt),
        collisions_agent_agent: collisions,
        collisions_moving,
        penetrations_agent_obstacle: acc.penetrations,
        mean_speed,
        mean_speed_m_s: scale.m_s(mean_speed),
        mean_speed_near_obstacles: near_speed,
        mean_speed_near_obstacles_m_s: near_speed.map(|v| scale.m_s(v)),
        mean_path_length: path_length,
        mean_path_length_m: scale.metres(path_length),
        mean_turn_deg: ratio(acc.turn_sum, acc.turn_samples),
        max_turn_deg: acc.max_turn,
        stuck_agents: s.stuck,
        queue_order: None,
        queue_order_step: None,
        fitness: None,
    }
}
