//! Group path planning as optimization (Liu & Liu 2022, experiment II): a path is K waypoints
//! between a fixed start and goal, a particle is the 2K waypoint coordinates, and the fitness
//! is `length + obstacle penalty + turning penalty`, minimised by GSA or IGSA.
//!
//! - Obstacle penalty (any [`Obstacle`] shape): every segment is sampled every `clearance / 2`
//!   px; each sample closer than `clearance` to an obstacle surface (or inside it) adds
//!   `obstacle_weight · (clearance − signed distance) · sample spacing`. On top of that every
//!   segment that exactly intersects an obstacle (or starts inside one) adds
//!   `crossing_penalty`, so a path through a wall is never cheaper than one around it.
//! - Turning penalty: `turn_weight · Σ θ_k²` over the polyline's vertices (θ in radians), after
//!   dropping waypoints that coincide with the previous one (otherwise stacking waypoints would
//!   hide a corner behind zero-length segments). The square makes one sharp turn cost more
//!   than the same total turn spread over several vertices, which is what "smooth" means.
//!
//! Measures reported per path: length, maximum deflection angle, mean turning angle (degrees),
//! exact crossings and the smallest sampled clearance.

use crate::model::geometry::{v, Aabb, Obstacle};
use crate::model::scene::Scene;
use crate::optim::{map_in_order, Algorithm, Bounds, Objective, Optimizer, Settings};
use crate::rng::Rng;
use crate::spatial::ObstacleIndex;
use glam::Vec2;
use serde::Serialize;
use std::cell::{Cell, RefCell};
use std::collections::HashMap;

/// Waypoint coordinates are searched in `[−100, 100]` and mapped linearly onto the scene: the
/// gravitational constants (G0 is an acceleration in search units) were set by Rashedi on
/// `[−100, 100]`-sized boxes, so the same G0 means the same thing on every scene size.
pub const SEARCH_HALF_RANGE: f64 = 100.0;

/// Longest piece (px) a segment is cut into when looking up the obstacles it may cross.
const PIECE_LENGTH: f32 = 32.0;

/// Random stream of the path planner (separate from the world's spawn and plan streams).
pub const PATH_STREAM: u32 = 0x9a7b;

/// Parameters of the path fitness.
#[derive(Clone, Debug, PartialEq)]
pub struct PathParams {
    /// Free waypoints between start and goal. Default 3 (more make the search much harder: with 4–6, GSA and IGSA often end on a path through an obstacle within N = 30, T = 300).
    pub waypoints: usize,
    /// Wanted distance from obstacle surfaces (px). Default 12 (agent radius 4 plus margin).
    pub clearance: f64,
    /// Penalty per px of intrusion into the clearance per px of path. Default 20.
    pub obstacle_weight: f64,
    /// Penalty per segment that intersects an obstacle (px). Default 2000.
    pub crossing_penalty: f64,
    /// Penalty per squared radian of turning (px/rad²). Default 40.
    pub turn_weight: f64,
}

impl Default for PathParams {
    fn default() -> Self {
        Self {
            waypoints: 3,
            clearance: 12.0,
            obstacle_weight: 20.0,
            crossing_penalty: 2000.0,
            turn_weight: 40.0,
        }
    }
}

/// A path-planning problem on a scene.
#[derive(Clone, Debug)]
pub struct PathProblem {
    /// Start point (px).
    pub start: [f64; 2],
    /// Goal point (px).
    pub goal: [f64; 2],
    /// Obstacles to avoid (indexed at construction: do not change them afterwards).
    pub obstacles: Vec<Obstacle>,
    /// Fitness parameters (the clearance is baked into the index boxes: do not change it).
    pub params: PathParams,
    /// Smallest waypoint coordinates (px): the scene inset by the clearance.
    pub area_min: [f64; 2],
    /// Largest waypoint coordinates (px).
    pub area_max: [f64; 2],
    bounds: Bounds,
    /// The obstacles in a grid, so a sample tests only the obstacles near it: planning time
    /// grows with the obstacles near the path, not with all of them.
    index: ObstacleIndex,
    /// Each obstacle's bounding box grown by the clearance: the samples it penalises lie in it.
    reach_boxes: Vec<Aabb>,
}

/// Quality measures of a path.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PathMeasures {
    /// Total length (px).
    pub length: f64,
    /// Largest turning (deflection) angle at a vertex (degrees).
    pub max_turn_deg: f64,
    /// Mean turning angle over the vertices (degrees).
    pub mean_turn_deg: f64,
    /// Segments that intersect an obstacle (0 for a valid path).
    pub crossings: u32,
    /// Smallest distance from a sampled path point to an obstacle surface (px; negative inside).
    pub min_clearance: f64,
}

/// The result of planning.
#[derive(Clone, Debug, PartialEq)]
pub struct PlannedPath {
    /// Start, the waypoints, goal.
    pub points: Vec<[f64; 2]>,
    /// Fitness of the path.
    pub fitness: f64,
    /// Its measures.
    pub measures: PathMeasures,
    /// Objective evaluations used.
    pub evaluations: u64,
}

impl PathProblem {
    /// A problem in a `width × height` world.
    pub fn new(
        start: [f64; 2],
        goal: [f64; 2],
        obstacles: Vec<Obstacle>,
        width: f64,
        height: f64,
        params: PathParams,
    ) -> Self {
        let k = params.waypoints.max(1);
        let m = params.clearance.min(0.25 * width.min(height)).max(0.0);
        let bounds = Bounds::uniform(2 * k, -SEARCH_HALF_RANGE, SEARCH_HALF_RANGE);
        let reach_boxes = obstacles.iter().map(|o| o.aabb().inflate(params.clearance as f32)).collect();
        // Cells of a few clearances: a sample's query box meets one to four of them.
        let cell = (4.0 * params.clearance as f32).clamp(16.0, 64.0);
        let index = ObstacleIndex::with_cell_size(obstacles.clone(), width as f32, height as f32, cell);
        Self {
            start,
            goal,
            obstacles,
            params: PathParams { waypoints: k, ..params },
            area_min: [m, m],
            area_max: [width - m, height - m],
            bounds,
            index,
            reach_boxes,
        }
    }

    /// The problem for group `group` of `scene`: from the centre of its spawn region to its goal.
    /// `None` when the group does not exist or has no goal.
    pub fn from_scene(scene: &Scene, group: usize, params: PathParams) -> Option<Self> {
        let g = scene.groups.get(group)?;
        let goal = scene.goals.get(g.goal? as usize)?;
        let s = g.spawn;
        let start = [0.5 * f64::from(s.min[0] + s.max[0]), 0.5 * f64::from(s.min[1] + s.max[1])];
        let goal = [f64::from(goal.position[0]), f64::from(goal.position[1])];
        Some(Self::new(
            start,
            goal,
            scene.obstacles.clone(),
            f64::from(scene.width),
            f64::from(scene.height),
            params,
        ))
    }

    /// Start, waypoints from the particle `x` (search coordinates mapped onto the scene), goal.
    pub fn points(&self, x: &[f64]) -> Vec<[f64; 2]> {
        let mut pts = Vec::with_capacity(x.len() / 2 + 2);
        pts.push(self.start);
        let map = |u: f64, d: usize| {
            let s = (u + SEARCH_HALF_RANGE) / (2.0 * SEARCH_HALF_RANGE);
            self.area_min[d] + s * (self.area_max[d] - self.area_min[d])
        };
        pts.extend(x.chunks_exact(2).map(|c| [map(c[0], 0), map(c[1], 1)]));
        pts.push(self.goal);
        pts
    }

    /// Whether segment a→b intersects an obstacle (or starts or ends inside one).
    pub fn segment_crosses(&self, a: [f64; 2], b: [f64; 2]) -> bool {
        let (pa, pb) = (to_vec2(a), to_vec2(b));
        // An obstacle the segment touches overlaps the box of one of its pieces (a long diagonal
        // segment's own box would hold most of the scene); the 1 px margin covers rounding.
        let pieces = (pa.distance(pb) / PIECE_LENGTH).ceil().clamp(1.0, 4096.0) as u32;
        let mut hit = false;
        for k in 0..pieces {
            let (p0, p1) =
                (pa.lerp(pb, k as f32 / pieces as f32), pa.lerp(pb, (k + 1) as f32 / pieces as f32));
            let query = Aabb { min: p0.min(p1), max: p0.max(p1) }.inflate(1.0);
            self.index.for_each_near(query, |_, o| {
                hit = hit || o.contains(pa) || o.contains(pb) || o.ray_cast(pa, pb - pa).is_some();
            });
            if hit {
                break;
            }
        }
        hit
    }

    /// Scene-order indices of the obstacles whose clearance box holds `p`, into `near`: the
    /// only ones that add a penalty at `p` (the index returns a superset, filtered here by the
    /// same box test the full loop makes).
    fn obstacles_reaching(&self, p: Vec2, near: &mut Vec<u32>) {
        near.clear();
        let query = Aabb { min: p, max: p }.inflate(self.params.clearance as f32 + 1.0);
        self.index.for_each_near(query, |i, _| {
            if self.reach_boxes[i as usize].contains(p) {
                near.push(i);
            }
        });
        // Scene order, so the penalties add up in the same order as over the full list.
        near.sort_unstable();
    }

    /// Sum of the obstacle penalties along the polyline and the smallest sampled clearance.
    fn obstacle_terms(&self, pts: &[[f64; 2]]) -> (f64, f64, u32) {
        let c = self.params.clearance;
        let spacing = (0.5 * c).max(1.0);
        let mut penalty = 0.0;
        let mut min_clear = f64::INFINITY;
        let mut crossings = 0u32;
        let mut near = Vec::new();
        for w in pts.windows(2) {
            let (a, b) = (w[0], w[1]);
            if self.segment_crosses(a, b) {
                crossings += 1;
            }
            let (ds, points) = segment_samples(a, b, spacing);
            for p in points {
                self.obstacles_reaching(p, &mut near);
                if near.len() < self.obstacles.len() {
                    // Some obstacle is farther than the clearance.
                    min_clear = min_clear.min(c);
                }
                for &i in &near {
                    let sd = f64::from(self.obstacles[i as usize].surface(p).signed_distance);
                    min_clear = min_clear.min(sd);
                    if sd < c {
                        penalty += (c - sd) * ds.max(1.0);
                    }
                }
            }
        }
        (penalty, min_clear, crossings)
    }

    /// Length, max and mean turning angle (radians) and Σθ² of the polyline, ignoring
    /// coincident points.
    fn shape_terms(pts: &[[f64; 2]]) -> (f64, f64, f64, f64) {
        let mut kept: Vec<[f64; 2]> = Vec::with_capacity(pts.len());
        for &p in pts {
            if kept.last().is_none_or(|&q| dist(p, q) > 1e-6) {
                kept.push(p);
            }
        }
        let length: f64 = kept.windows(2).map(|w| dist(w[0], w[1])).sum();
        let (mut max, mut sum, mut sum2) = (0.0f64, 0.0, 0.0);
        let vertices = kept.len().saturating_sub(2);
        for w in kept.windows(3) {
            let (ux, uy) = (w[1][0] - w[0][0], w[1][1] - w[0][1]);
            let (vx, vy) = (w[2][0] - w[1][0], w[2][1] - w[1][1]);
            let theta = libm::atan2((ux * vy - uy * vx).abs(), ux * vx + uy * vy);
            max = max.max(theta);
            sum += theta;
            sum2 += theta * theta;
        }
        let mean = if vertices > 0 { sum / vertices as f64 } else { 0.0 };
        (length, max, mean, sum2)
    }

    /// The measures of the polyline through `pts`.
    pub fn measure(&self, pts: &[[f64; 2]]) -> PathMeasures {
        let (length, max, mean, _) = Self::shape_terms(pts);
        let (_, min_clearance, crossings) = self.obstacle_terms(pts);
        PathMeasures {
            length,
            max_turn_deg: max.to_degrees(),
            mean_turn_deg: mean.to_degrees(),
            crossings,
            min_clearance: if min_clearance.is_finite() { min_clearance } else { self.params.clearance },
        }
    }

    /// The fitness of the polyline through `pts`.
    pub fn fitness_of(&self, pts: &[[f64; 2]]) -> f64 {
        let (length, _, _, turn2) = Self::shape_terms(pts);
        let (penalty, _, crossings) = self.obstacle_terms(pts);
        length
            + self.params.obstacle_weight * penalty
            + self.params.crossing_penalty * f64::from(crossings)
            + self.params.turn_weight * turn2
    }

    /// Optimises the path with `algorithm` (GSA or IGSA in the paper; any works) for
    /// `settings.iterations` iterations from `seed`.
    pub fn plan(&self, algorithm: Algorithm, settings: &Settings, seed: u32) -> PlannedPath {
        let mut planning = PathPlanning::new(self.clone(), algorithm, settings, seed);
        planning.advance(u32::MAX);
        planning.result()
    }
}

/// A path being planned a slice at a time ([`PathPlanning::advance`]), so a caller with a time
/// budget (the page's worker) can spread the work over frames. A slice is bounded by objective
/// evaluations, not iterations: one iteration at the largest settings evaluates up to three
/// times the population (the move, IGSA's neighbourhood move, a restart), and among thousands
/// of obstacles that took seconds. The evaluations are the same whatever the slices, so the
/// result is bit-identical to [`PathProblem::plan`].
///
/// How a slice can stop inside an iteration without the optimizers knowing: an iteration (or
/// the build, which evaluates the initial population) runs on a copy of the optimizer against
/// `Metered`, which answers from the values computed by earlier slices, computes new ones
/// while the budget lasts, and after that answers a stand-in value and notes that it starved.
/// A starved copy is thrown away; the next slice runs the iteration again on a fresh copy,
/// which asks for the same points in the same order (the optimizer's state and random stream
/// are the same and every value it was given is the true one), so the values kept answer them
/// and the budget goes to the points after. Only a copy that never starved is kept. The
/// objective is a pure function of the point, so a kept value is the value.
pub struct PathPlanning {
    problem: PathProblem,
    algorithm: Algorithm,
    settings: Settings,
    seed: u32,
    /// Built (the initial population evaluated) by the first slice, so starting is instant.
    optimizer: Option<Box<dyn Optimizer + Send>>,
    /// Iterations done so far.
    done: u32,
    /// Values computed for the unfinished build or iteration, by the point's bits.
    kept: HashMap<Vec<u64>, f64>,
}

/// The path problem seen through a slice's evaluation budget (see [`PathPlanning`]).
struct Metered<'a> {
    problem: &'a PathProblem,
    kept: RefCell<&'a mut HashMap<Vec<u64>, f64>>,
    /// New evaluations this slice may still compute.
    budget: Cell<u64>,
    /// Whether a value was asked for after the budget ran out.
    starved: Cell<bool>,
}

impl Objective for Metered<'_> {
    fn bounds(&self) -> &Bounds {
        self.problem.bounds()
    }

    fn evaluate(&self, x: &[f64]) -> f64 {
        let key: Vec<u64> = x.iter().map(|v| v.to_bits()).collect();
        if let Some(&f) = self.kept.borrow().get(&key) {
            return f;
        }
        if self.starved.get() || self.budget.get() == 0 {
            // The copy asking is thrown away: any value will do.
            self.starved.set(true);
            return f64::MAX;
        }
        self.budget.set(self.budget.get() - 1);
        let f = self.problem.evaluate(x);
        self.kept.borrow_mut().insert(key, f);
        f
    }
}

impl PathPlanning {
    /// Starts planning `problem`; nothing is computed yet.
    pub fn new(problem: PathProblem, algorithm: Algorithm, settings: &Settings, seed: u32) -> Self {
        Self {
            problem,
            algorithm,
            settings: settings.clone(),
            seed,
            optimizer: None,
            done: 0,
            kept: HashMap::new(),
        }
    }

    /// Runs up to `evaluations` more objective evaluations (`u32::MAX`: to the end); returns the
    /// share of iterations done, 0…1. The first evaluations build the initial population. A
    /// slice of at least one evaluation always makes progress.
    pub fn advance(&mut self, evaluations: u32) -> f64 {
        if evaluations == u32::MAX {
            self.run_to_the_end();
            return self.progress();
        }
        let mut budget = u64::from(evaluations);
        while budget > 0 && !self.is_done() {
            let metered = Metered {
                problem: &self.problem,
                kept: RefCell::new(&mut self.kept),
                budget: Cell::new(budget),
                starved: Cell::new(false),
            };
            let attempt = match &self.optimizer {
                Some(optimizer) => {
                    let mut copy = optimizer.clone_box();
                    copy.step(&metered);
                    copy
                }
                None => self.algorithm.build(&metered, &self.settings, Rng::new(self.seed, PATH_STREAM)),
            };
            budget = metered.budget.get();
            if metered.starved.get() {
                break;
            }
            if self.optimizer.is_some() {
                self.done += 1;
            }
            self.optimizer = Some(attempt);
            self.kept.clear();
        }
        self.progress()
    }

    /// Every iteration left at once, on the optimizer itself (nothing to keep between slices).
    fn run_to_the_end(&mut self) {
        let optimizer = match &mut self.optimizer {
            Some(optimizer) => optimizer,
            None => {
                let rng = Rng::new(self.seed, PATH_STREAM);
                self.optimizer.insert(self.algorithm.build(&self.problem, &self.settings, rng))
            }
        };
        // Values an earlier slice kept for the unfinished iteration are computed again: cheaper
        // than looking every point up.
        self.kept.clear();
        while self.done < self.settings.iterations {
            optimizer.step(&self.problem);
            self.done += 1;
        }
    }

    /// Share of the iterations done, 0…1 (1 when there are none to do).
    pub fn progress(&self) -> f64 {
        if self.settings.iterations == 0 {
            1.0
        } else {
            f64::from(self.done) / f64::from(self.settings.iterations)
        }
    }

    /// Whether every iteration has run.
    pub fn is_done(&self) -> bool {
        self.optimizer.is_some() && self.done >= self.settings.iterations
    }

    /// The problem being solved.
    pub fn problem(&self) -> &PathProblem {
        &self.problem
    }

    /// The best path so far (the planned path once [`PathPlanning::is_done`]).
    pub fn result(&self) -> PlannedPath {
        let built;
        let optimizer = match &self.optimizer {
            Some(optimizer) => optimizer,
            None => {
                built = self.algorithm.build(&self.problem, &self.settings, Rng::new(self.seed, PATH_STREAM));
                &built
            }
        };
        let points = self.problem.points(optimizer.best_position());
        PlannedPath {
            measures: self.problem.measure(&points),
            fitness: optimizer.best_value(),
            points,
            evaluations: optimizer.evaluations(),
        }
    }
}

impl Clone for PathPlanning {
    fn clone(&self) -> Self {
        Self {
            problem: self.problem.clone(),
            algorithm: self.algorithm,
            settings: self.settings.clone(),
            seed: self.seed,
            optimizer: self.optimizer.as_ref().map(|o| o.clone_box()),
            done: self.done,
            kept: self.kept.clone(),
        }
    }
}

impl std::fmt::Debug for PathPlanning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PathPlanning")
            .field("algorithm", &self.algorithm)
            .field("done", &self.done)
            .field("iterations", &self.settings.iterations)
            .finish()
    }
}

impl Objective for PathProblem {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }

    fn evaluate(&self, x: &[f64]) -> f64 {
        self.fitness_of(&self.points(x))
    }
}

/// One algorithm on one scene over several seeds: the mean measures of its planned paths.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PathRow {
    /// Scene name.
    pub scene: String,
    /// Algorithm name.
    pub algorithm: &'static str,
    /// Seeds run.
    pub runs: u32,
    /// Mean path length (px).
    pub length: f64,
    /// Mean of the maximum deflection angle (degrees).
    pub max_turn_deg: f64,
    /// Mean of the mean turning angle (degrees).
    pub mean_turn_deg: f64,
    /// Mean fitness.
    pub fitness: f64,
    /// Runs whose path intersects an obstacle.
    pub crossing_runs: u32,
    /// Every run's measures, in seed order.
    #[serde(skip)]
    pub per_run: Vec<PathMeasures>,
}

/// Plans every scene's first group with every algorithm for seeds `0..runs` (in parallel
/// natively) and averages the measures. `progress(done, total)` counts plans.
pub fn compare_paths(
    scenes: &[Scene],
    algorithms: &[Algorithm],
    runs: u32,
    settings: &Settings,
    params: &PathParams,
    progress: &mut dyn FnMut(usize, usize),
) -> Vec<PathRow> {
    let problems: Vec<(String, PathProblem)> = scenes
        .iter()
        .filter_map(|s| PathProblem::from_scene(s, 0, params.clone()).map(|p| (s.name.clone(), p)))
        .collect();
    let mut jobs = Vec::new();
    for p in 0..problems.len() {
        for &a in algorithms {
            for seed in 0..runs {
                jobs.push((p, a, seed));
            }
        }
    }
    let plans = map_in_order(&jobs, &|&(p, a, seed)| problems[p].1.plan(a, settings, seed), progress);
    let mut rows = Vec::new();
    for (k, chunk) in plans.chunks(runs.max(1) as usize).enumerate() {
        let (p, a, _) = jobs[k * runs.max(1) as usize];
        let n = chunk.len() as f64;
        let mean = |f: &dyn Fn(&PlannedPath) -> f64| chunk.iter().map(f).sum::<f64>() / n;
        rows.push(PathRow {
            scene: problems[p].0.clone(),
            algorithm: a.name(),
            runs,
            length: mean(&|c| c.measures.length),
            max_turn_deg: mean(&|c| c.measures.max_turn_deg),
            mean_turn_deg: mean(&|c| c.measures.mean_turn_deg),
            fitness: mean(&|c| c.fitness),
            crossing_runs: chunk.iter().filter(|c| c.measures.crossings > 0).count() as u32,
            per_run: chunk.iter().map(|c| c.measures.clone()).collect(),
        });
    }
    rows
}

/// The rows as a text table, plus, per scene, on how many seeds the second algorithm's path
/// has a smaller maximum deflection than the first's.
pub fn path_table_text(rows: &[PathRow]) -> String {
    let mut s = format!(
        "{:<14}{:<9}{:>6}{:>11}{:>13}{:>14}{:>12}{:>11}\n",
        "scene", "planner", "runs", "length", "max turn °", "mean turn °", "fitness", "crossing"
    );
    for r in rows {
        s.push_str(&format!(
            "{:<14}{:<9}{:>6}{:>11.1}{:>13.1}{:>14.1}{:>12.1}{:>11}\n",
            r.scene,
            r.algorithm,
            r.runs,
            r.length,
            r.max_turn_deg,
            r.mean_turn_deg,
            r.fitness,
            r.crossing_runs
        ));
    }
    for pair in rows.chunks(2) {
        if let [a, b] = pair {
            if a.scene == b.scene {
                let smoother =
                    a.per_run.iter().zip(&b.per_run).filter(|(x, y)| y.max_turn_deg < x.max_turn_deg).count();
                let shorter = a.per_run.iter().zip(&b.per_run).filter(|(x, y)| y.length < x.length).count();
                s.push_str(&format!(
                    "{}: {} has the smaller max turn on {smoother}/{} seeds and the shorter path on {shorter}/{}\n",
                    a.scene,
                    b.algorithm,
                    a.per_run.len(),
                    a.per_run.len()
                ));
            }
        }
    }
    s
}

/// The samples of segment a→b at most `spacing` px apart, both ends included, and the length
/// each stands for.
fn segment_samples(a: [f64; 2], b: [f64; 2], spacing: f64) -> (f64, impl Iterator<Item = Vec2>) {
    let len = dist(a, b);
    let samples = (len / spacing).ceil().max(1.0) as usize;
    let points = (0..=samples).map(move |s| {
        let t = s as f64 / samples as f64;
        Vec2::new((a[0] + t * (b[0] - a[0])) as f32, (a[1] + t * (b[1] - a[1])) as f32)
    });
    (len / samples as f64, points)
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    libm::sqrt(dx * dx + dy * dy)
}

fn to_vec2(p: [f64; 2]) -> Vec2 {
    v([p[0] as f32, p[1] as f32])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wall_problem() -> PathProblem {
        let wall = Obstacle::Rect { min: [180.0, 0.0], max: [220.0, 160.0] };
        PathProblem::new([40.0, 100.0], [360.0, 100.0], vec![wall], 400.0, 240.0, PathParams::default())
    }

    #[test]
    fn straight_path_measures() {
        let p = PathProblem::new([0.0, 0.0], [30.0, 40.0], vec![], 100.0, 100.0, PathParams::default());
        let m = p.measure(&[[0.0, 0.0], [30.0, 40.0]]);
        assert!((m.length - 50.0).abs() < 1e-12);
        assert_eq!((m.max_turn_deg, m.mean_turn_deg, m.crossings), (0.0, 0.0, 0));
        let right_angle = p.measure(&[[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [10.0, 10.0]]);
        assert!((right_angle.max_turn_deg - 90.0).abs() < 1e-9);
    }

    #[test]
    fn crossing_a_wall_costs_more_than_going_around() {
        let p = wall_problem();
        let through = p.fitness_of(&[[40.0, 100.0], [200.0, 100.0], [360.0, 100.0]]);
        let around = p.fitness_of(&[[40.0, 100.0], [200.0, 190.0], [360.0, 100.0]]);
        assert!(p.measure(&[[40.0, 100.0], [360.0, 100.0]]).crossings == 1);
        assert!(around < through, "{around} vs {through}");
    }

    /// The obstacle terms as they were before the index: every obstacle tested at every sample.
    fn full_scan_terms(p: &PathProblem, pts: &[[f64; 2]]) -> (f64, f64, u32) {
        let c = p.params.clearance;
        let spacing = (0.5 * c).max(1.0);
        let (mut penalty, mut min_clear, mut crossings) = (0.0, f64::INFINITY, 0u32);
        for w in pts.windows(2) {
            let (a, b) = (w[0], w[1]);
            let (pa, pb) = (to_vec2(a), to_vec2(b));
            if p.obstacles
                .iter()
                .any(|o| o.contains(pa) || o.contains(pb) || o.ray_cast(pa, pb - pa).is_some())
            {
                crossings += 1;
            }
            let (ds, points) = segment_samples(a, b, spacing);
            for q in points {
                for o in &p.obstacles {
                    if !o.aabb().inflate(c as f32).contains(q) {
                        min_clear = min_clear.min(c);
                        continue;
                    }
                    let sd = f64::from(o.surface(q).signed_distance);
                    min_clear = min_clear.min(sd);
                    if sd < c {
                        penalty += (c - sd) * ds.max(1.0);
                    }
                }
            }
        }
        (penalty, min_clear, crossings)
    }

    #[test]
    fn the_obstacle_index_gives_the_full_scan_values_bit_for_bit() {
        let mut rng = Rng::new(3, 0);
        let mut obstacles = Vec::new();
        for k in 0..600 {
            let (x, y) = (rng.range(-20.0, 820.0), rng.range(-20.0, 520.0));
            obstacles.push(match k % 3 {
                0 => Obstacle::Circle { center: [x, y], radius: rng.range(1.0, 6.0) },
                1 => Obstacle::Rect { min: [x, y], max: [x + rng.range(1.0, 40.0), y + rng.range(1.0, 8.0)] },
                _ => Obstacle::Polygon { points: vec![[x, y], [x + 9.0, y + 2.0], [x + 3.0, y + 7.0]] },
            });
        }
        // One long wall over index cell borders, and obstacles on exact cell corners.
        obstacles.push(Obstacle::Rect { min: [64.0, 128.0], max: [700.0, 140.0] });
        obstacles.push(Obstacle::Circle { center: [128.0, 192.0], radius: 4.0 });
        for clearance in [0.0, 5.0, 12.0, 40.0] {
            let params = PathParams { clearance, waypoints: 4, ..PathParams::default() };
            let p = PathProblem::new([30.0, 250.0], [770.0, 250.0], obstacles.clone(), 800.0, 500.0, params);
            let mut evaluated = 0;
            for _ in 0..150 {
                let x: Vec<f64> = (0..8).map(|_| rng.unit_f64() * 200.0 - 100.0).collect();
                let pts = p.points(&x);
                let (penalty, min_clear, crossings) = full_scan_terms(&p, &pts);
                let indexed = p.obstacle_terms(&pts);
                assert_eq!(indexed.0.to_bits(), penalty.to_bits(), "penalty at clearance {clearance}");
                assert_eq!(indexed.1.to_bits(), min_clear.to_bits(), "min clearance at {clearance}");
                assert_eq!(indexed.2, crossings, "crossings at clearance {clearance}");
                evaluated += usize::from(penalty > 0.0 && crossings > 0);
            }
            if clearance > 0.0 {
                assert!(evaluated > 50, "the random paths must meet obstacles ({evaluated})");
            }
        }
    }

    #[test]
    fn sliced_planning_equals_planning_in_one_go() {
        let p = wall_problem();
        let settings = Settings { population: 12, iterations: 40, ..Settings::default() };
        for algorithm in [Algorithm::Igsa, Algorithm::Gsa] {
            let whole = p.plan(algorithm, &settings, 9);
            let mut calls_of_budget = Vec::new();
            for budget in [1, 7, u32::MAX] {
                let mut sliced = PathPlanning::new(p.clone(), algorithm, &settings, 9);
                let mut last = sliced.progress();
                assert_eq!(last, 0.0);
                let mut calls = 0u64;
                while !sliced.is_done() {
                    // A copy taken mid-way (a timeline checkpoint) carries on identically.
                    if calls == 100 {
                        sliced = sliced.clone();
                    }
                    let now = sliced.advance(budget);
                    assert!(now >= last, "progress never falls: {last} → {now}");
                    last = now;
                    calls += 1;
                }
                assert_eq!(last, 1.0);
                assert_eq!(sliced.advance(5), 1.0, "nothing left to do");
                let r = sliced.result();
                assert_eq!(
                    (r.fitness.to_bits(), &r.points, r.evaluations),
                    (whole.fitness.to_bits(), &whole.points, whole.evaluations),
                    "{algorithm:?} in slices of {budget} evaluations"
                );
                calls_of_budget.push(calls);
            }
            // A slice computes at most its budget of evaluations (a point asked twice in one
            // iteration is computed once, hence the margin).
            let evaluations = whole.evaluations;
            assert!(
                calls_of_budget[0] >= evaluations - evaluations / 50,
                "{calls_of_budget:?} vs {evaluations}"
            );
            assert!(calls_of_budget[1] >= evaluations / 7, "{calls_of_budget:?}");
            assert!(calls_of_budget[1] <= calls_of_budget[0] / 5, "{calls_of_budget:?}");
            assert_eq!(calls_of_budget[2], 1);
        }
    }

    #[test]
    fn stacked_waypoints_do_not_hide_a_corner() {
        let p = wall_problem();
        let m = p.measure(&[[0.0, 0.0], [10.0, 0.0], [10.0, 0.0], [10.0, 0.0], [10.0, 10.0]]);
        assert!((m.max_turn_deg - 90.0).abs() < 1e-9);
    }
}
