//! IGSA group path control (Liu & Liu 2022, experiments II–III, DESIGN §3.4): one path is
//! optimised for the whole group, then every agent follows it with its own lateral offset and
//! bounding-circle collision avoidance.
//!
//! * **Planning, once per group.** The path is K waypoints between the centre of the group's spawn
//!   region and its goal, optimised by IGSA (or plain GSA, to show the paper's comparison) with the
//!   fitness of [`crate::planners::igsa::path`]: length + obstacle penalty + turning penalty. It happens when
//!   the planner is built, from the scene's seed, and looks only at the scene's geometry: the same
//!   scene gives the same path for 10 agents or 1000, and planning time does not grow with the
//!   group. Moving an obstacle or a goal re-plans ([`Planner::replans_on_edit`]).
//! * **Editable paths.** A non-empty `waypoints` list (dragged in the page) replaces the optimised
//!   waypoints; nothing is optimised then. A path that crosses an obstacle is accepted and run (the
//!   world still keeps agents out of obstacles) but [`segment_crossings`] flags its segments, which
//!   the renderer shows in red and the page warns about.
//! * **Following.** Each agent keeps its progress along the path (arc length, never decreasing)
//!   and steers towards the point `look_ahead` px further on, shifted sideways by its own offset.
//!   Offsets are drawn once per agent in `[−spread, spread]` and clamped, per point of the path, to
//!   the free width on each side (precomputed at planning time), so the column narrows where the
//!   path passes close to an obstacle and widens again behind it: this is where the group slows
//!   down, the paper's "average speed at the obstacle point".
//! * **Bounding-circle collision avoidance.** Each agent's bounding circle is its body radius plus
//!   `margin / 2`. For every neighbour `j` within reach in one step (found through the spatial
//!   grid, never by scanning the group) the new velocity must satisfy
//!   `v · u_ij ≤ max(0, (d_ij − R_ij) / 2)` with `u_ij` the unit vector towards `j` and
//!   `R_ij = r_i + r_j + margin`. When both agents obey, their distance after the step is at least
//!   its projection on `u_ij`, `d + (v_j − v_i)·u_ij ≥ R_ij`: two followers never come closer than
//!   their bounding circles. The constraints are met by sliding along them (two passes of
//!   projection) and, if some are still violated, by scaling the velocity down, which always
//!   satisfies them (`v = 0` does). Overlaps that exist already (random spawn points) get a push
//!   apart. The same half-plane rule keeps agents from stepping into obstacles.
//! * **Arrival.** Agents that reach the goal take parking slots on a hexagonal lattice around it,
//!   filled from the far side towards the side the path comes in from, so no one walks through
//!   those already parked.

pub mod path;

use super::explain::{GroupPath, PathSource};
use super::planner::{GroupView, Planner, StepContext};
use crate::model::geometry::limit;
use crate::model::geometry::{unit_or, v, Aabb, Obstacle};
use crate::model::params::igsa::{IgsaParams, PathOptimizer};
use crate::model::scene::Scene;
use crate::optim::{Algorithm, Settings};
use crate::planners::igsa::path::{PathParams, PathPlanning, PathProblem, PlannedPath};
use crate::rng::Rng;
use crate::spatial::{ObstacleIndex, QueryCap};
use glam::Vec2;

/// Neighbours (and candidates of the scanned cells) one agent's bounding-circle rule looks at,
/// the first in the grid's scan order. Within its reach (about 20 px) fit about 30
/// non-overlapping 4 px discs, so only a pile reaches the cap; there it bounds the work per
/// agent (the constraint list and the feasible-velocity search grow with it).
const NEIGHBOUR_CAP: QueryCap = QueryCap { neighbours: 128, candidates: 1024 };

/// Random stream of the per-agent lateral offsets (the path planner has its own,
/// [`crate::planners::igsa::path::PATH_STREAM`]).
const OFFSET_STREAM: u32 = 0x1d5a;
/// Spacing (px) of the precomputed free widths along the path.
const WIDTH_STEP: f32 = 4.0;
/// Step (px) of the sideways march that measures the free width.
const WIDTH_MARCH: f32 = 2.0;
/// Distance (px) over which an agent slows down when it nears its parking slot.
const ARRIVE_RADIUS: f32 = 20.0;
/// Slot marker for agents that have not arrived.
const NO_SLOT: u32 = u32::MAX;

/// What IGSA parameters mean to the optimizer (the parameters themselves are plain data).
impl IgsaParams {
    /// The path fitness parameters these settings plan with.
    pub fn path_params(&self) -> PathParams {
        PathParams {
            waypoints: self.waypoint_count.clamp(1, 8) as usize,
            clearance: f64::from(self.clearance),
            ..PathParams::default()
        }
    }

    /// The optimizer settings these parameters plan with.
    pub fn settings(&self) -> Settings {
        Settings {
            population: self.population.clamp(2, 1000) as usize,
            iterations: self.iterations.clamp(1, 100_000),
            ..Settings::default()
        }
    }
}

/// The optimizer behind each choice (a planner concern: the parameters are plain data).
impl PathOptimizer {
    fn algorithm(self) -> Algorithm {
        match self {
            PathOptimizer::Igsa => Algorithm::Igsa,
            PathOptimizer::Gsa => Algorithm::Gsa,
        }
    }
}

/// Plans (or takes the edited) path of group `group` of `scene`: what the planner follows. Only
/// the scene's geometry, the group's spawn region and goal and the seed are read, never the
/// agent count. `None` when the group does not exist.
pub fn plan_group_path(scene: &Scene, group: usize, params: &IgsaParams) -> Option<GroupPath> {
    let mut job = GroupPathJob::new(scene, group, params)?;
    job.advance(u32::MAX);
    Some(job.result())
}

/// [`plan_group_path`] in slices: [`GroupPathJob::advance`] runs a few objective evaluations at
/// a time ([`PathPlanning`]), so the page can plan within its frame budget. Whatever the slices, the result is the
/// same path bit for bit.
#[derive(Clone, Debug)]
pub struct GroupPathJob {
    stage: JobStage,
}

#[derive(Clone, Debug)]
enum JobStage {
    /// The optimizer is searching.
    Searching(Box<PathPlanning>, PathSource),
    /// The path is known (edited, no goal, or planned).
    Ready(GroupPath),
}

impl GroupPathJob {
    /// Starts planning group `group` of `scene` (this evaluates the initial population); an
    /// edited path or a group without a goal is ready at once. `None` when the group does not
    /// exist.
    pub fn new(scene: &Scene, group: usize, params: &IgsaParams) -> Option<Self> {
        let g = scene.groups.get(group)?;
        let goal = g.goal.and_then(|k| scene.goals.get(k as usize));
        let s = g.spawn;
        let start = [0.5 * (s.min[0] + s.max[0]), 0.5 * (s.min[1] + s.max[1])];
        let Some(goal) = goal else {
            return Some(Self {
                stage: JobStage::Ready(GroupPath {
                    points: vec![start],
                    crossing: vec![],
                    source: PathSource::None,
                    length: 0.0,
                    max_turn_deg: 0.0,
                    mean_turn_deg: 0.0,
                    fitness: None,
                    evaluations: 0,
                }),
            });
        };
        let problem = PathProblem::new(
            to64(start),
            to64(goal.position),
            scene.obstacles.clone(),
            f64::from(scene.width),
            f64::from(scene.height),
            params.path_params(),
        );
        let stage = if params.waypoints.is_empty() {
            let source = match params.optimizer {
                PathOptimizer::Igsa => PathSource::Igsa,
                PathOptimizer::Gsa => PathSource::Gsa,
            };
            let planning =
                PathPlanning::new(problem, params.optimizer.algorithm(), &params.settings(), scene.seed);
            JobStage::Searching(Box::new(planning), source)
        } else {
            let mut pts = vec![to64(start)];
            pts.extend(params.waypoints.iter().map(|&p| to64(p)));
            pts.push(to64(goal.position));
            JobStage::Ready(group_path(&problem, pts, PathSource::Edited, None, 0))
        };
        Some(Self { stage })
    }

    /// Runs up to `evaluations` more objective evaluations (`u32::MAX`: to the end); returns the
    /// share of iterations done, 0…1.
    pub fn advance(&mut self, evaluations: u32) -> f64 {
        if let JobStage::Searching(planning, source) = &mut self.stage {
            planning.advance(evaluations);
            if planning.is_done() {
                let PlannedPath { points, fitness, evaluations, .. } = planning.result();
                let path = group_path(planning.problem(), points, *source, Some(fitness), evaluations);
                self.stage = JobStage::Ready(path);
            }
        }
        self.progress()
    }

    /// Share of the optimizer iterations done, 0…1.
    pub fn progress(&self) -> f64 {
        match &self.stage {
            JobStage::Searching(planning, _) => planning.progress().min(1.0),
            JobStage::Ready(_) => 1.0,
        }
    }

    /// Whether the path is known.
    pub fn is_done(&self) -> bool {
        matches!(self.stage, JobStage::Ready(_))
    }

    /// The path: the planned one once [`GroupPathJob::is_done`], the best so far before.
    pub fn result(&self) -> GroupPath {
        match &self.stage {
            JobStage::Ready(path) => path.clone(),
            JobStage::Searching(planning, source) => {
                let PlannedPath { points, fitness, evaluations, .. } = planning.result();
                group_path(planning.problem(), points, *source, Some(fitness), evaluations)
            }
        }
    }
}

fn to64(p: [f32; 2]) -> [f64; 2] {
    [f64::from(p[0]), f64::from(p[1])]
}

/// The report of the path through `points` on `problem`.
fn group_path(
    problem: &PathProblem,
    points: Vec<[f64; 2]>,
    source: PathSource,
    fitness: Option<f64>,
    evaluations: u64,
) -> GroupPath {
    let measures = problem.measure(&points);
    let crossing = points.windows(2).map(|w| problem.segment_crosses(w[0], w[1])).collect();
    GroupPath {
        points: points.iter().map(|p| [p[0] as f32, p[1] as f32]).collect(),
        crossing,
        source,
        length: measures.length,
        max_turn_deg: measures.max_turn_deg,
        mean_turn_deg: measures.mean_turn_deg,
        fitness,
        evaluations,
    }
}

/// Per segment of the polyline `points`, whether it crosses (or starts or ends inside) an
/// obstacle: the check the page's path editor warns with.
pub fn segment_crossings(points: &[Vec2], obstacles: &ObstacleIndex) -> Vec<bool> {
    points
        .windows(2)
        .map(|w| {
            let (a, b) = (w[0], w[1]);
            let query = Aabb { min: a.min(b), max: a.max(b) };
            let mut hit = false;
            obstacles.for_each_near(query, |_, o: &Obstacle| {
                hit = hit || o.contains(a) || o.contains(b) || o.ray_cast(a, b - a).is_some();
            });
            hit
        })
        .collect()
}

/// A polyline with its cumulative arc length.
#[derive(Clone, Debug, Default)]
struct Polyline {
    points: Vec<Vec2>,
    /// `arc[i]` = length from the start to `points[i]`.
    arc: Vec<f32>,
}

impl Polyline {
    fn new(points: Vec<Vec2>) -> Self {
        let mut arc = Vec::with_capacity(points.len());
        let mut total = 0.0;
        for (i, p) in points.iter().enumerate() {
            if i > 0 {
                total += p.distance(points[i - 1]);
            }
            arc.push(total);
        }
        Self { points, arc }
    }

    fn length(&self) -> f32 {
        self.arc.last().copied().unwrap_or(0.0)
    }

    /// Point and unit tangent at arc length `s` (clamped to the path).
    fn at(&self, s: f32) -> (Vec2, Vec2) {
        let n = self.points.len();
        if n == 0 {
            return (Vec2::ZERO, Vec2::X);
        }
        if n == 1 {
            return (self.points[0], Vec2::X);
        }
        let s = s.clamp(0.0, self.length());
        let mut i = self.arc.partition_point(|&a| a <= s).clamp(1, n - 1);
        // Skip zero-length segments so the tangent is defined.
        while i < n - 1 && self.arc[i] - self.arc[i - 1] <= 1e-6 {
            i += 1;
        }
        let (a, b) = (self.points[i - 1], self.points[i]);
        let len = self.arc[i] - self.arc[i - 1];
        let t = if len > 1e-6 { ((s - self.arc[i - 1]) / len).clamp(0.0, 1.0) } else { 0.0 };
        (a + (b - a) * t, unit_or(b - a, Vec2::X))
    }

    /// Arc length of the point nearest to `p` on the segments overlapping `[from, to]`.
    fn project(&self, p: Vec2, from: f32, to: f32) -> f32 {
        let mut best = (f32::INFINITY, from);
        for i in 1..self.points.len() {
            if self.arc[i] < from || self.arc[i - 1] > to {
                continue;
            }
            let (a, b) = (self.points[i - 1], self.points[i]);
            let ab = b - a;
            let len2 = ab.length_squared();
            let t = if len2 > 1e-12 { ((p - a).dot(ab) / len2).clamp(0.0, 1.0) } else { 0.0 };
            let d2 = p.distance_squared(a + ab * t);
            if d2 < best.0 {
                best = (d2, self.arc[i - 1] + t * (self.arc[i] - self.arc[i - 1]));
            }
        }
        best.1
    }
}

/// Distance from `p` to the nearest obstacle surface (negative inside), `f32::INFINITY` if none
/// lies within `reach`.
fn clearance_at(obstacles: &ObstacleIndex, p: Vec2, reach: f32) -> (f32, Vec2) {
    let mut best = (f32::INFINITY, Vec2::ZERO);
    let query = Aabb { min: p - Vec2::splat(reach), max: p + Vec2::splat(reach) };
    obstacles.for_each_near(query, |_, o: &Obstacle| {
        let s = o.surface(p);
        if s.signed_distance < best.0 {
            best = (s.signed_distance, s.normal);
        }
    });
    best
}

/// The IGSA path-following planner of one group.
#[derive(Clone)]
pub struct IgsaPlanner {
    params: IgsaParams,
    /// The group's path as planned or edited (what the page shows).
    report: Option<GroupPath>,
    path: Polyline,
    /// Free width on the left and the right of the path, every [`WIDTH_STEP`] px of arc.
    widths: Vec<(f32, f32)>,
    /// Lateral offset of each agent of the group, in `[−1, 1]` (× spread).
    offsets: Vec<f32>,
    /// Arc length reached by each agent; `NAN` until the first step places it.
    progress: Vec<f32>,
    /// Parking slot of each agent ([`NO_SLOT`] until it arrives).
    slot_of: Vec<u32>,
    /// Parking slots relative to the goal centre, in filling order.
    slots: Vec<Vec2>,
    next_slot: u32,
    /// Scratch for one agent's constraints: (unit direction, largest approach speed).
    constraints: Vec<(Vec2, f32)>,
    /// The path still being planned, with the scene and group it is for; `None` once the
    /// planner follows its path.
    planning: Option<Box<PendingPath>>,
}

#[derive(Clone)]
struct PendingPath {
    job: GroupPathJob,
    scene: Scene,
    group: usize,
}

impl IgsaPlanner {
    /// A planner for group `group` of `scene`: plans its path now (see [`plan_group_path`]),
    /// measures the free width along it, draws the agents' offsets and lays out the parking
    /// slots. A missing group gives a planner that holds every agent still.
    pub fn new(params: IgsaParams, scene: &Scene, group: usize) -> Self {
        let mut planner = Self::planning(params, scene, group);
        planner.advance_planning(u32::MAX);
        planner
    }

    /// The same planner with its path still to plan: [`Planner::advance_planning`] plans it in
    /// slices (the page spreads them over frames) and then sets the planner up as
    /// [`IgsaPlanner::new`] does. Until then no path is shown and agents are not planned for.
    pub fn planning(params: IgsaParams, scene: &Scene, group: usize) -> Self {
        let mut planner = Self {
            params,
            report: None,
            path: Polyline::default(),
            widths: Vec::new(),
            offsets: Vec::new(),
            progress: Vec::new(),
            slot_of: Vec::new(),
            slots: Vec::new(),
            next_slot: 0,
            constraints: Vec::new(),
            planning: None,
        };
        match GroupPathJob::new(scene, group, &planner.params) {
            Some(job) if !job.is_done() => {
                planner.planning = Some(Box::new(PendingPath { job, scene: scene.clone(), group }))
            }
            job => planner.follow(job.map(|j| j.result()), scene, group),
        }
        planner
    }

    /// Sets up following `report` (the planned or edited path): free widths, offsets, slots.
    fn follow(&mut self, report: Option<GroupPath>, scene: &Scene, group: usize) {
        let params = &self.params;
        let g = scene.groups.get(group);
        let count = g.map_or(0, |g| g.count as usize);
        let radius = g.map_or(4.0, |g| g.agent_radius);
        let obstacles = ObstacleIndex::new(scene.obstacles.clone(), scene.width, scene.height);
        let bounds = Vec2::new(scene.width, scene.height);
        let points: Vec<Vec2> = report
            .as_ref()
            .filter(|r| r.source != PathSource::None)
            .map(|r| r.points.iter().map(|&p| v(p)).collect())
            .unwrap_or_default();
        let path = Polyline::new(points);
        let widths = free_widths(&path, &obstacles, bounds, radius + 0.5 * params.margin, params.spread);
        let mut rng = Rng::new(scene.seed, OFFSET_STREAM + group as u32);
        let offsets = (0..count).map(|_| rng.range(-1.0, 1.0)).collect();
        let goal = g.and_then(|g| g.goal).and_then(|k| scene.goals.get(k as usize));
        let slots = match goal {
            Some(goal) if path.points.len() >= 2 => {
                let n = path.points.len();
                let entry = unit_or(path.points[n - 2] - path.points[n - 1], -Vec2::X);
                parking_slots(
                    v(goal.position),
                    entry,
                    count,
                    2.0 * radius + params.margin,
                    &obstacles,
                    bounds,
                    radius,
                )
            }
            _ => Vec::new(),
        };
        *self = Self {
            params: self.params.clone(),
            report,
            path,
            widths,
            offsets,
            progress: vec![f32::NAN; count],
            slot_of: vec![NO_SLOT; count],
            slots,
            next_slot: 0,
            constraints: Vec::new(),
            planning: None,
        };
    }

    /// The group's path with its crossings and measures.
    pub fn report(&self) -> Option<&GroupPath> {
        self.report.as_ref()
    }

    /// Free width (left, right) at arc length `s`.
    fn width_at(&self, s: f32) -> (f32, f32) {
        if self.widths.is_empty() {
            return (0.0, 0.0);
        }
        let k = ((s / WIDTH_STEP).round().max(0.0) as usize).min(self.widths.len() - 1);
        self.widths[k]
    }

    /// The point agent `k` at `p` heads for: along the path with its offset, or its parking slot.
    fn target(
        &mut self,
        k: usize,
        p: Vec2,
        goal: Option<(Vec2, f32)>,
        obstacles: &ObstacleIndex,
    ) -> Option<(Vec2, bool)> {
        if self.path.points.len() < 2 {
            return None;
        }
        let total = self.path.length();
        let look = self.params.look_ahead;
        let s = match self.progress[k] {
            s if s.is_nan() => self.path.project(p, 0.0, total),
            s => s.max(self.path.project(p, s - WIDTH_STEP, s + 2.0 * look + 40.0)),
        };
        self.progress[k] = s;
        if self.slot_of[k] == NO_SLOT {
            let inside = goal.is_some_and(|(c, r)| p.distance(c) < r);
            if inside || s >= total - 1.0 {
                self.slot_of[k] = self.next_slot.min(self.slots.len().saturating_sub(1) as u32);
                self.next_slot = self.next_slot.saturating_add(1);
            }
        }
        if self.slot_of[k] != NO_SLOT {
            let centre = goal.map_or(self.path.points[self.path.points.len() - 1], |(c, _)| c);
            let offset = self.slots.get(self.slot_of[k] as usize).copied().unwrap_or(Vec2::ZERO);
            return Some((centre + offset, true));
        }
        // The carrot: the first offset point at least `look` px from the agent, searched along the
        // path from `s + look`. Inside a sharp turn the offset point `look` px ahead can sit on
        // the agent itself, which would leave it nothing to walk towards.
        let want = self.offsets.get(k).copied().unwrap_or(0.0) * self.params.spread;
        let mut ahead = (s + look).min(total);
        loop {
            let (c, tangent) = self.path.at(ahead);
            let normal = Vec2::new(-tangent.y, tangent.x);
            let (left, right) = self.width_at(ahead);
            let target = c + normal * want.clamp(-left, right);
            if ahead >= total || target.distance_squared(p) >= look * look {
                if !line_blocked(obstacles, p, target) {
                    return Some((target, false));
                }
                // The straight way to the carrot cuts an obstacle's corner (an offset agent on the
                // inside of a turn): head back to the path where the agent is instead.
                let (c, tangent) = self.path.at(s + WIDTH_STEP);
                let normal = Vec2::new(-tangent.y, tangent.x);
                let (left, right) = self.width_at(s + WIDTH_STEP);
                let beside = c + normal * want.clamp(-left, right);
                let back = if line_blocked(obstacles, p, beside) { c } else { beside };
                return Some((back, false));
            }
            ahead = (ahead + WIDTH_STEP).min(total);
        }
    }
}

/// Rotations (degrees) of the wanted velocity tried when the constraints block it.
const DETOURS_DEG: [f32; 8] = [25.0, -25.0, 50.0, -50.0, 75.0, -75.0, 100.0, -100.0];

/// The velocity that meets every half-plane `v · u ≤ allowed` and makes the most progress along
/// `wanted`: the wanted velocity slid along the constraints (two passes of projection), and the
/// wanted velocity turned by each of [`DETOURS_DEG`], each scaled down until it is feasible
/// (scaling works because every `allowed` is ≥ 0). Ties keep the earlier candidate, so the
/// choice is the same on every platform; with no progress possible the agent keeps right (a
/// side shared by everyone, so two agents meeting head-on pass each other).
fn best_feasible(wanted: Vec2, constraints: &[(Vec2, f32)]) -> Vec2 {
    let feasible = |mut v: Vec2| {
        let mut scale = 1.0f32;
        for &(u, allowed) in constraints {
            let along = v.dot(u);
            if along > allowed {
                scale = scale.min(allowed / along);
            }
        }
        v *= scale.max(0.0);
        v
    };
    let mut slid = wanted;
    for _ in 0..2 {
        for &(u, allowed) in constraints {
            let along = slid.dot(u);
            if along > allowed {
                slid -= u * (along - allowed);
            }
        }
    }
    let mut best = feasible(slid);
    let mut best_score = best.dot(wanted);
    let (speed2, tolerance) = (wanted.length_squared(), 0.9);
    if best_score >= tolerance * speed2 || speed2 <= 1e-12 {
        return best;
    }
    for deg in DETOURS_DEG {
        let candidate = feasible(Vec2::from_angle(deg.to_radians()).rotate(wanted));
        let score = candidate.dot(wanted);
        if score > best_score {
            best = candidate;
            best_score = score;
        }
    }
    if best_score <= 1e-3 * speed2 {
        best = feasible(Vec2::new(-wanted.y, wanted.x) * 0.5);
    }
    best
}

/// Whether the segment a→b crosses an obstacle.
fn line_blocked(obstacles: &ObstacleIndex, a: Vec2, b: Vec2) -> bool {
    let query = Aabb { min: a.min(b), max: a.max(b) };
    let mut hit = false;
    obstacles.for_each_near(query, |_, o: &Obstacle| hit = hit || o.ray_cast(a, b - a).is_some());
    hit
}

/// Free width on each side of the path every [`WIDTH_STEP`] px: the largest sideways distance
/// (≤ `spread`) over which a body of bounding radius `body` stays clear of obstacles and inside
/// the world. Positive offsets are on the side of the normal `(−t.y, t.x)`.
fn free_widths(
    path: &Polyline,
    obstacles: &ObstacleIndex,
    bounds: Vec2,
    body: f32,
    spread: f32,
) -> Vec<(f32, f32)> {
    if path.points.len() < 2 {
        return Vec::new();
    }
    let samples = (path.length() / WIDTH_STEP).ceil() as usize + 1;
    let reach = spread + body + WIDTH_MARCH;
    (0..samples)
        .map(|i| {
            let (c, t) = path.at(i as f32 * WIDTH_STEP);
            let normal = Vec2::new(-t.y, t.x);
            let free = |dir: f32| {
                let mut d = 0.0;
                while d + WIDTH_MARCH <= spread {
                    let q = c + normal * (dir * (d + WIDTH_MARCH));
                    let inside =
                        q.x >= body && q.y >= body && q.x <= bounds.x - body && q.y <= bounds.y - body;
                    if !inside || clearance_at(obstacles, q, reach).0 < body {
                        break;
                    }
                    d += WIDTH_MARCH;
                }
                d
            };
            (free(-1.0), free(1.0))
        })
        .collect()
}

/// Parking slots around a goal for `count` agents: a hexagonal lattice of pitch `pitch` (px)
/// clipped to the world and clear of obstacles, grown until it holds them all, ordered from the
/// far side to the side the path comes in from (`entry`, a unit vector from the goal).
fn parking_slots(
    goal: Vec2,
    entry: Vec2,
    count: usize,
    pitch: f32,
    obstacles: &ObstacleIndex,
    bounds: Vec2,
    radius: f32,
) -> Vec<Vec2> {
    if count == 0 {
        return Vec::new();
    }
    let pitch = pitch.max(0.5);
    let row = pitch * 0.866_025_4;
    // A hexagonal cell holds pitch × row px²; start with a disc of that many cells.
    let mut reach = (count as f32 * pitch * row / std::f32::consts::PI).sqrt() + pitch;
    let mut slots = Vec::new();
    for _ in 0..12 {
        slots.clear();
        let rows = (reach / row).ceil() as i32;
        let cols = (reach / pitch).ceil() as i32 + 1;
        for j in -rows..=rows {
            let shift = if j.rem_euclid(2) == 1 { 0.5 * pitch } else { 0.0 };
            for i in -cols..=cols {
                let o = Vec2::new(i as f32 * pitch + shift, j as f32 * row);
                let q = goal + o;
                let inside =
                    q.x >= radius && q.y >= radius && q.x <= bounds.x - radius && q.y <= bounds.y - radius;
                if o.length() <= reach && inside && clearance_at(obstacles, q, radius + 1.0).0 >= radius {
                    slots.push(o);
                }
            }
        }
        if slots.len() >= count {
            break;
        }
        reach *= 1.25;
    }
    // The `count` slots nearest the goal (ties by lattice order: the sorts are stable), then
    // farthest from the entry first.
    slots.sort_by(|a, b| a.length_squared().total_cmp(&b.length_squared()));
    slots.truncate(count.max(1));
    let far = entry * reach;
    slots.sort_by(|a, b| b.distance_squared(far).total_cmp(&a.distance_squared(far)));
    slots
}

impl Planner for IgsaPlanner {
    fn interaction_radius(&self) -> f32 {
        // Neighbours farther than this cannot touch the bounding circle within one step.
        8.0 + self.params.margin + 2.0 * self.params.max_speed + 1.0
    }

    fn max_speed(&self) -> f32 {
        self.params.max_speed
    }

    fn plan(&mut self, ctx: &StepContext, group: GroupView, _rng: &mut Rng, new_velocities: &mut [Vec2]) {
        let start = group.agents.start as usize;
        let n = new_velocities.len();
        if self.progress.len() != n {
            self.progress = vec![f32::NAN; n];
            self.slot_of = vec![NO_SLOT; n];
        }
        let max_speed = self.params.max_speed;
        let margin = self.params.margin;
        for (k, out) in new_velocities.iter_mut().enumerate() {
            let i = start + k;
            let (p, old_v, r) = (ctx.positions[i], ctx.velocities[i], ctx.radii[i]);
            let desired = match self.target(k, p, group.goal, ctx.obstacles) {
                Some((target, parking)) => {
                    let to = target - p;
                    let d = to.length();
                    let speed = if parking { max_speed * (d / ARRIVE_RADIUS).min(1.0) } else { max_speed };
                    if d > 0.25 {
                        to * (speed / d)
                    } else {
                        Vec2::ZERO
                    }
                }
                None => Vec2::ZERO,
            };
            let mut vel = old_v + limit(desired - old_v, self.params.max_accel);

            // Bounding circles: one half-plane per neighbour that can be reached in a step.
            self.constraints.clear();
            let reach = r + 8.0_f32.max(r) + margin + 2.0 * max_speed + 1.0;
            let mut push = Vec2::ZERO;
            let constraints = &mut self.constraints;
            ctx.grid.for_each_within_capped(p, reach, NEIGHBOUR_CAP, |nb| {
                if nb.id as usize == i {
                    return;
                }
                let d = nb.d2.sqrt();
                let rr = r + ctx.radii[nb.id as usize] + margin;
                let u = unit_or(nb.pos - p, Vec2::from_angle(i as f32));
                if d < rr {
                    // Already inside each other's bounding circles: step apart.
                    push -= u * (rr - d).min(max_speed);
                }
                constraints.push((u, (0.5 * (d - rr)).max(0.0)));
            });
            let (sd, normal) = clearance_at(ctx.obstacles, p, r + 2.0 * max_speed + 1.0);
            if sd.is_finite() {
                constraints.push((-normal, (sd - r - 0.05).max(0.0)));
            }
            vel = limit(vel + push, max_speed);
            *out = best_feasible(vel, constraints);
        }
    }

    fn planned_path(&self) -> Option<&GroupPath> {
        self.report.as_ref().filter(|r| r.source != PathSource::None)
    }

    fn replans_on_edit(&self) -> bool {
        true
    }

    fn planning_progress(&self) -> f64 {
        self.planning.as_ref().map_or(1.0, |p| p.job.progress())
    }

    fn advance_planning(&mut self, evaluations: u32) -> f64 {
        let Some(pending) = &mut self.planning else { return 1.0 };
        pending.job.advance(evaluations);
        if !pending.job.is_done() {
            return pending.job.progress();
        }
        if let Some(done) = self.planning.take() {
            self.follow(Some(done.job.result()), &done.scene, done.group);
        }
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::igsa::MAX_EDITED_WAYPOINTS;
    use crate::model::params::WaypointError;

    #[test]
    fn polyline_points_and_projection() {
        let line = Polyline::new(vec![Vec2::ZERO, Vec2::new(10.0, 0.0), Vec2::new(10.0, 10.0)]);
        assert_eq!(line.length(), 20.0);
        assert_eq!(line.at(15.0), (Vec2::new(10.0, 5.0), Vec2::Y));
        assert_eq!(line.project(Vec2::new(12.0, 4.0), 0.0, 20.0), 14.0);
        assert_eq!(line.project(Vec2::new(3.0, -2.0), 0.0, 20.0), 3.0);
    }

    #[test]
    fn slots_fill_from_the_far_side_and_stay_clear() {
        let obstacles =
            ObstacleIndex::new(vec![Obstacle::Circle { center: [100.0, 60.0], radius: 20.0 }], 400.0, 400.0);
        let slots =
            parking_slots(Vec2::new(100.0, 100.0), Vec2::X, 50, 10.0, &obstacles, Vec2::splat(400.0), 4.0);
        assert_eq!(slots.len(), 50);
        assert!(slots[0].x < slots[49].x, "{:?} then {:?}", slots[0], slots[49]);
        for s in &slots {
            assert!(clearance_at(&obstacles, Vec2::new(100.0, 100.0) + *s, 30.0).0 >= 4.0);
        }
        for (a, s) in slots.iter().enumerate() {
            for t in &slots[a + 1..] {
                assert!(s.distance(*t) > 9.9);
            }
        }
    }

    #[test]
    fn a_world_planning_in_slices_runs_as_one_planned_at_once() {
        let mut scene = (crate::model::presets::find("igsa-path-2").expect("preset").build)();
        let params = IgsaParams { iterations: 60, population: 12, ..IgsaParams::default() };
        scene.groups[0].planner = crate::model::params::PlannerConfig::Igsa(params.clone());
        let mut at_once = crate::World::new(scene.clone()).expect("valid");
        assert_eq!(at_once.planning_progress(), 1.0);
        let mut sliced = crate::World::new_sliced(scene.clone()).expect("valid");
        assert_eq!(sliced.planning_progress(), 0.0);
        assert!(sliced.planned_path(0).is_none(), "no path before it is planned");
        let mut copy = None;
        let mut last = 0.0;
        while sliced.planning_progress() < 1.0 {
            // Seven evaluations: an iteration evaluates the population (12) and more, so most
            // slices end inside an iteration and progress only every second or third.
            let now = sliced.advance_planning(7);
            assert!(now >= last, "progress never falls: {last} → {now}");
            last = now;
            if copy.is_none() && now > 0.3 {
                copy = Some(sliced.clone());
            }
        }
        assert_eq!(sliced.planned_path(0), at_once.planned_path(0));
        assert_eq!(sliced.planned_path(0), plan_group_path(&scene, 0, &params).as_ref());
        // A copy taken mid-way finishes with the same path when it steps.
        let mut copy = copy.expect("planning took several slices");
        for w in [&mut at_once, &mut sliced, &mut copy] {
            w.step_n(80);
        }
        assert_eq!(sliced.digest(), at_once.digest());
        assert_eq!(copy.digest(), at_once.digest());
        // An edit of the geometry re-plans in slices too, with the path planned at once.
        let mut edited = scene.clone();
        edited.obstacles.pop();
        at_once.edit_scene(edited.clone()).expect("valid edit");
        sliced.edit_scene(edited).expect("valid edit");
        assert!(sliced.planning_progress() < 1.0);
        while sliced.advance_planning(25) < 1.0 {}
        assert_eq!(sliced.planned_path(0), at_once.planned_path(0));
    }

    #[test]
    fn edited_waypoints_are_checked() {
        let mut p = IgsaParams { waypoints: vec![[1.0, 2.0]], ..IgsaParams::default() };
        assert_eq!(p.check_waypoints(), Ok(()));
        p.waypoints.push([f32::NAN, 0.0]);
        assert_eq!(p.check_waypoints(), Err(WaypointError::NotFinite(2)));
        assert_eq!(
            p.check_waypoints().map_err(|e| e.to_string()),
            Err("waypoint 2 is not a finite point".into())
        );
        p.waypoints = vec![[0.0, 0.0]; MAX_EDITED_WAYPOINTS + 1];
        assert_eq!(p.check_waypoints(), Err(WaypointError::TooMany(MAX_EDITED_WAYPOINTS + 1)));
    }
}
