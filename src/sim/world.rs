//! The running simulation: agent state as struct-of-arrays, the two-phase step, seeded spawn.

use crate::model::geometry::{v, Aabb, Obstacle};
use crate::model::params::PlannerConfig;
use crate::model::scene::{Scene, SceneError};
use crate::planners::{GroupView, Planner, StepContext};
use crate::rng::Rng;
use crate::sim::metrics::{Metrics, MetricsRecorder};
use crate::spatial::{ObstacleIndex, SpatialGrid};
use glam::Vec2;
use std::ops::Range;

/// Random stream of group `g`'s placement is `STREAM_SPAWN + g` (a group's start does not
/// depend on the draws of the groups before it); planners draw from [`STREAM_PLAN`].
const STREAM_SPAWN: u32 = 0x100;
const STREAM_PLAN: u32 = 1;
/// Most lattice places examined per group while spawning: bounds spawn time and memory for a
/// huge region mostly covered by obstacles (its finest lattice is coarsened to this many).
pub const MAX_SPAWN_PLACES: u64 = 1 << 21;
/// How far outside a surface a pushed-out agent is placed (px).
const PUSH_EPSILON: f32 = 0.01;

/// One group at run time.
#[derive(Clone)]
struct GroupRuntime {
    agents: Range<u32>,
    planner: Box<dyn Planner>,
}

/// A scene being simulated. A clone is a complete snapshot (planner state, generator, metric
/// accumulators): stepping a clone gives bit-identical results to stepping the original.
#[derive(Clone)]
pub struct World {
    scene: Scene,
    step: u32,
    /// Position of each agent (px).
    pos: Vec<Vec2>,
    /// Velocity of each agent (px/step).
    vel: Vec<Vec2>,
    /// Group index of each agent.
    group_of: Vec<u32>,
    /// Body radius of each agent (px).
    radius: Vec<f32>,
    next_vel: Vec<Vec2>,
    groups: Vec<GroupRuntime>,
    grid: SpatialGrid,
    obstacles: ObstacleIndex,
    rng: Rng,
    recorder: MetricsRecorder,
    /// Whether planning ahead (IGSA paths) is left to [`World::advance_planning`] instead of
    /// being done at once when planners are built (the page plans in slices).
    sliced_planning: bool,
}

impl World {
    /// Validates the scene, spawns its agents from the scene's seed and builds the planners
    /// (planning IGSA paths to the end).
    pub fn new(scene: Scene) -> Result<Self, SceneError> {
        Self::build(scene, true, false, None)
    }

    /// [`World::new`] leaving the planning ahead to [`World::advance_planning`], here and after
    /// edits: the page plans in slices within its frame budget. Stepping finishes it first.
    pub fn new_sliced(scene: Scene) -> Result<Self, SceneError> {
        Self::build(scene, true, true, None)
    }

    /// A world whose agents start at `positions` (in group order, heading right) instead of
    /// spawned places, without the spawn's density limit or the cost limit: piles and jams that a
    /// run can reach (a crowd converging on its goal) but that no scene spawns, for the
    /// benchmarks and the tests of bounded per-agent work. Not something a link can ask for.
    #[doc(hidden)]
    pub fn new_at(scene: Scene, positions: Vec<Vec2>) -> Result<Self, SceneError> {
        Self::build(scene, false, false, Some(positions))
    }

    /// `cost_limit`: refuse scenes over the step-cost limit of [`crate::sim::cost`];
    /// `sliced_planning`: leave IGSA planning to [`World::advance_planning`];
    /// `start`: the agents' positions instead of the spawn's.
    fn build(
        scene: Scene,
        cost_limit: bool,
        sliced_planning: bool,
        start: Option<Vec<Vec2>>,
    ) -> Result<Self, SceneError> {
        scene.validate()?;
        let obstacles = ObstacleIndex::new(scene.obstacles.clone(), scene.width, scene.height);
        let total = scene.agent_count() as usize;
        // Placement first: a scene too dense to spawn is refused before any planning.
        let (pos, mut vel) = match start {
            None => {
                let Spawn { positions, directions, .. } = spawn(&scene, &obstacles)?;
                (positions, directions)
            }
            Some(positions) if positions.len() == total => (positions, vec![Vec2::X; total]),
            Some(positions) => {
                return Err(SceneError::BadReference(format!(
                    "{} start positions for {total} agents",
                    positions.len()
                )))
            }
        };
        if cost_limit {
            crate::sim::cost::check(&scene)?;
        }
        let planners: Vec<Box<dyn Planner>> = (0..scene.groups.len())
            .map(|gi| crate::planners::build_for_group(&scene.groups[gi].planner, &scene, gi))
            .collect();
        let mut group_of = Vec::with_capacity(total);
        let mut radius = Vec::with_capacity(total);
        let mut groups = Vec::with_capacity(scene.groups.len());
        let mut interaction = 0.0f32;
        let mut max_radius = 0.0f32;
        for ((gi, g), planner) in scene.groups.iter().enumerate().zip(planners) {
            let start = group_of.len() as u32;
            let speed = planner.max_speed() * 0.25;
            for v in &mut vel[start as usize..start as usize + g.count as usize] {
                *v *= speed;
            }
            group_of.resize(group_of.len() + g.count as usize, gi as u32);
            radius.resize(radius.len() + g.count as usize, g.agent_radius);
            interaction = interaction.max(planner.interaction_radius());
            max_radius = max_radius.max(g.agent_radius);
            groups.push(GroupRuntime { agents: start..group_of.len() as u32, planner });
        }
        let cell = interaction.max(2.0 * max_radius).max(1.0);
        let grid = SpatialGrid::new(scene.width, scene.height, cell, total);
        let recorder = MetricsRecorder::new(&scene, &pos);
        let rng = Rng::new(scene.seed, STREAM_PLAN);
        let next_vel = vec![Vec2::ZERO; total];
        let mut world = Self {
            scene,
            step: 0,
            pos,
            vel,
            group_of,
            radius,
            next_vel,
            groups,
            grid,
            obstacles,
            rng,
            recorder,
            sliced_planning,
        };
        world.grid.rebuild(&world.pos, &world.vel);
        world.plan_now_unless_sliced();
        Ok(world)
    }

    /// [`World::new`] without the step-cost limit of [`crate::sim::cost`] (the spawn density limit
    /// still holds): for native benchmarks that time scenes bigger than the page may run.
    #[doc(hidden)]
    pub fn new_beyond_cost_limit(scene: Scene) -> Result<Self, SceneError> {
        Self::build(scene, false, false, None)
    }

    /// Share of the planning ahead done (IGSA paths), 0…1: the mean over the groups that plan
    /// ahead; 1 when nothing is left to plan.
    pub fn planning_progress(&self) -> f64 {
        let shares: Vec<f64> = self
            .groups
            .iter()
            .filter(|g| g.planner.replans_on_edit())
            .map(|g| g.planner.planning_progress())
            .collect();
        if shares.iter().all(|&s| s >= 1.0) {
            1.0
        } else {
            shares.iter().sum::<f64>() / shares.len() as f64
        }
    }

    /// Runs up to `iterations` planning iterations (of the first group still planning; the
    /// slices do not change the result); returns [`World::planning_progress`].
    pub fn advance_planning(&mut self, iterations: u32) -> f64 {
        if let Some(g) = self.groups.iter_mut().find(|g| g.planner.planning_progress() < 1.0) {
            g.planner.advance_planning(iterations);
        }
        self.planning_progress()
    }

    /// Plans everything left to plan, at once.
    pub fn finish_planning(&mut self) {
        for g in &mut self.groups {
            if g.planner.planning_progress() < 1.0 {
                g.planner.advance_planning(u32::MAX);
            }
        }
    }

    fn plan_now_unless_sliced(&mut self) {
        if !self.sliced_planning {
            self.finish_planning();
        }
    }

    /// The scene this world was built from.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Steps simulated since the start.
    pub fn step_count(&self) -> u32 {
        self.step
    }

    /// Number of agents.
    pub fn agent_count(&self) -> usize {
        self.pos.len()
    }

    /// Agent positions (px).
    pub fn positions(&self) -> &[Vec2] {
        &self.pos
    }

    /// Agent velocities (px/step).
    pub fn velocities(&self) -> &[Vec2] {
        &self.vel
    }

    /// Group index of each agent.
    pub fn group_of(&self) -> &[u32] {
        &self.group_of
    }

    /// Body radius of each agent (px).
    pub fn radii(&self) -> &[f32] {
        &self.radius
    }

    /// The obstacle index (for renderers and tools that query obstacles).
    pub fn obstacles(&self) -> &ObstacleIndex {
        &self.obstacles
    }

    /// The neighbour grid as of the end of the last step (for picking and diagnosis).
    pub fn grid(&self) -> &SpatialGrid {
        &self.grid
    }

    /// The read-only context the planners see at the start of the next step: diagnosis
    /// ([`crate::sim::diagnose`]) recomputes a planner's terms from it.
    pub fn step_context(&self) -> StepContext<'_> {
        StepContext {
            positions: &self.pos,
            velocities: &self.vel,
            radii: &self.radius,
            grid: &self.grid,
            obstacles: &self.obstacles,
            bounds: Vec2::new(self.scene.width, self.scene.height),
            step: self.step,
            scene: &self.scene,
            group_of: &self.group_of,
        }
    }

    /// The planner steering group `g`.
    pub fn planner_of_group(&self, g: usize) -> Option<&dyn Planner> {
        self.groups.get(g).map(|r| r.planner.as_ref())
    }

    /// What the planner of group `g` is told about its group at the next step.
    pub fn group_view(&self, g: usize) -> Option<GroupView> {
        let agents = self.groups.get(g)?.agents.clone();
        Some(GroupView { agents, goal: self.goal_of_group(g) })
    }

    /// The per-agent metrics accumulators (stuck flags for diagnosis).
    pub fn metrics_recorder(&self) -> &MetricsRecorder {
        &self.recorder
    }

    /// Current goal position of group `g`, if it has one.
    pub fn goal_of_group(&self, g: usize) -> Option<(Vec2, f32)> {
        let goal = self.scene.groups.get(g)?.goal?;
        let goal = self.scene.goals.get(goal as usize)?;
        Some((goal.position_at(self.step), goal.radius))
    }

    /// The path group `g` follows, if its planner plans one (IGSA group path control).
    pub fn planned_path(&self, g: usize) -> Option<&crate::planners::GroupPath> {
        self.groups.get(g)?.planner.planned_path()
    }

    /// Replaces the planner parameters of group `g` without restarting the run.
    pub fn set_group_planner(&mut self, g: usize, config: PlannerConfig) -> Result<(), SceneError> {
        if g >= self.scene.groups.len() {
            return Err(SceneError::BadReference(format!("there is no group {}", g + 1)));
        }
        // Checked against the scene too (a Boids group follows a path that exists), so the
        // scene's link stays loadable.
        self.scene.validate_planner(g, &config)?;
        if self.scene.groups[g].planner != config {
            // Another planner or larger IGSA settings may break a cost limit: then the run keeps
            // its planner.
            let mut changed = Scene { groups: self.scene.groups.clone(), ..Scene::empty(10.0, 10.0) };
            changed.groups[g].planner = config.clone();
            crate::sim::cost::check(&changed)?;
        }
        self.scene.groups[g].planner = config;
        let planner = crate::planners::build_for_group(&self.scene.groups[g].planner, &self.scene, g);
        let cell = planner.interaction_radius().max(self.grid.cell_size());
        if cell > self.grid.cell_size() {
            self.grid = SpatialGrid::new(self.scene.width, self.scene.height, cell, self.pos.len());
            self.grid.rebuild(&self.pos, &self.vel);
        }
        self.groups[g].planner = planner;
        self.plan_now_unless_sliced();
        Ok(())
    }

    /// Takes the fitness measures of the metrics every `every` steps from now on (0 = never;
    /// default [`crate::sim::metrics::FITNESS_SAMPLE_EVERY`]): benchmarks compare their cost.
    #[doc(hidden)]
    pub fn set_fitness_sample_every(&mut self, every: u32) {
        self.recorder.set_fitness_sample_every(every);
    }

    /// Replaces the neighbour grid by one cell, so every query scans every agent: the O(N²)
    /// baseline of `flockpath bench`. Same neighbours, only the float summation order differs.
    #[doc(hidden)]
    pub fn use_brute_force_neighbours(&mut self) {
        self.grid = SpatialGrid::single_cell(self.scene.width, self.scene.height);
        self.grid.rebuild(&self.pos, &self.vel);
    }

    /// Switches to an edited scene. When only obstacles and goals changed, the run goes on with
    /// the agents where they are (a wall dropped in front of a moving flock); any change to the
    /// groups or the seed restarts the run.
    pub fn edit_scene(&mut self, scene: Scene) -> Result<(), SceneError> {
        scene.validate()?;
        let same_agents = scene.seed == self.scene.seed
            && scene.width == self.scene.width
            && scene.height == self.scene.height
            && scene.groups.len() == self.scene.groups.len()
            && scene.groups.iter().zip(&self.scene.groups).all(|(a, b)| {
                a.count == b.count
                    && a.spawn == b.spawn
                    && a.agent_radius == b.agent_radius
                    && a.planner == b.planner
            });
        if !same_agents {
            *self = World::build(scene, true, self.sliced_planning, None)?;
            return Ok(());
        }
        let geometry_changed = scene.obstacles != self.scene.obstacles || scene.goals != self.scene.goals;
        self.obstacles = ObstacleIndex::new(scene.obstacles.clone(), scene.width, scene.height);
        self.scene = scene;
        for (gi, group) in self.groups.iter_mut().enumerate() {
            if geometry_changed && group.planner.replans_on_edit() {
                group.planner =
                    crate::planners::build_for_group(&self.scene.groups[gi].planner, &self.scene, gi);
            }
        }
        self.plan_now_unless_sliced();
        Ok(())
    }

    /// Advances `n` steps.
    pub fn step_n(&mut self, n: u32) {
        for _ in 0..n {
            self.step();
        }
    }

    /// One fixed step: every planner computes new velocities from the old state (phase 1),
    /// then all agents move, are kept out of obstacles and inside the bounds (phase 2).
    pub fn step(&mut self) {
        // A group cannot move before its path is known (a no-op once planned).
        self.finish_planning();
        let bounds = Vec2::new(self.scene.width, self.scene.height);
        let ctx = StepContext {
            positions: &self.pos,
            velocities: &self.vel,
            radii: &self.radius,
            grid: &self.grid,
            obstacles: &self.obstacles,
            bounds,
            step: self.step,
            scene: &self.scene,
            group_of: &self.group_of,
        };
        let step = self.step;
        for (gi, group) in self.groups.iter_mut().enumerate() {
            let goal = self
                .scene
                .groups
                .get(gi)
                .and_then(|g| g.goal)
                .and_then(|k| self.scene.goals.get(k as usize))
                .map(|goal| (goal.position_at(step), goal.radius));
            let view = GroupView { agents: group.agents.clone(), goal };
            let out = &mut self.next_vel[group.agents.start as usize..group.agents.end as usize];
            group.planner.plan(&ctx, view, &mut self.rng, out);
            let max_speed = group.planner.max_speed();
            for v in out.iter_mut() {
                // A planner bug must not poison the run: non-finite → stop, overspeed → clamp.
                *v = if v.is_finite() { crate::model::geometry::limit(*v, max_speed) } else { Vec2::ZERO };
            }
        }

        let solid: Vec<bool> = self.groups.iter().map(|g| !g.planner.passes_through_obstacles()).collect();
        for i in 0..self.pos.len() {
            let previous = self.pos[i];
            let mut v = self.next_vel[i];
            let mut p = previous + v;
            let solid = solid[self.group_of[i] as usize];
            if solid {
                resolve_obstacles(&self.obstacles, &mut p, &mut v, self.radius[i]);
            }
            // The centre always ends inside the world (a world narrower than the body holds
            // it on the middle line), also when an obstacle touches the border.
            let (lo, hi) = centre_bounds(self.radius[i], bounds);
            let clamped = p.clamp(lo, hi);
            if clamped.x != p.x {
                v.x = 0.0;
            }
            if clamped.y != p.y {
                v.y = 0.0;
            }
            p = clamped;
            if solid && self.obstacles.contains(p) {
                // Pushing out failed (overlapping obstacles, or the border pushed it back in):
                // stay where it was, inside the world and outside the obstacles.
                p = previous;
                v = Vec2::ZERO;
            }
            self.pos[i] = p;
            self.vel[i] = v;
        }
        self.step += 1;
        self.grid.rebuild(&self.pos, &self.vel);
        let goals: Vec<Option<(Vec2, f32)>> = (0..self.groups.len()).map(|g| self.goal_of_group(g)).collect();
        self.recorder.record(
            self.step,
            &self.pos,
            &self.vel,
            &self.group_of,
            &self.radius,
            &goals,
            &self.grid,
            &self.obstacles,
        );
    }

    /// The metrics of the run so far (DESIGN §4 keys).
    pub fn metrics(&self) -> Metrics {
        let planners: Vec<&str> = self.scene.groups.iter().map(|g| g.planner.kind().name()).collect();
        self.recorder.summary(&self.scene, &planners, self.step)
    }

    /// A 64-bit FNV-1a digest of every position and velocity bit pattern: equal digests mean a
    /// bit-identical run (natively, in wasm, in any browser).
    pub fn digest(&self) -> u64 {
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        let mut eat = |x: f32| {
            for b in x.to_bits().to_le_bytes() {
                h ^= u64::from(b);
                h = h.wrapping_mul(0x0000_0100_0000_01b3);
            }
        };
        for (p, v) in self.pos.iter().zip(&self.vel) {
            eat(p.x);
            eat(p.y);
            eat(v.x);
            eat(v.y);
        }
        h
    }
}

/// Pushes a disc of `radius` at `p` out of any obstacle it overlaps and removes the velocity
/// component into the surface (agents slide along walls). A few rounds handle corners.
fn resolve_obstacles(obstacles: &ObstacleIndex, p: &mut Vec2, v: &mut Vec2, radius: f32) {
    if obstacles.is_empty() {
        return;
    }
    for _ in 0..3 {
        let mut moved = false;
        let query = Aabb { min: *p - Vec2::splat(radius), max: *p + Vec2::splat(radius) };
        let here = *p;
        let mut push = None;
        obstacles.for_each_near(query, |_, o: &Obstacle| {
            if push.is_some() {
                return;
            }
            let s = o.surface(here);
            if s.signed_distance < radius {
                push = Some(s);
            }
        });
        if let Some(s) = push {
            *p = s.point + s.normal * (radius + PUSH_EPSILON);
            let into = v.dot(s.normal);
            if into < 0.0 {
                *v -= s.normal * into;
            }
            moved = true;
        }
        if !moved {
            break;
        }
    }
}

/// The corners of the rectangle of centres that keeps a body of `radius` inside a world of
/// size `bounds`. Along a side shorter than the body the range is the middle point: the body
/// stays centred there, overhanging both borders equally.
pub fn centre_bounds(radius: f32, bounds: Vec2) -> (Vec2, Vec2) {
    let r = Vec2::splat(radius).min(0.5 * bounds);
    (r, bounds - r)
}

/// Body radii grouped by powers of two: class `k` holds radii below `2^k` px (k = 0 for radii
/// under 1 px), bucketed in cells of `2^(k+1)` px, so a body touches at most 3×3 cells of its
/// class and any class above it: the check of a new body costs a bounded number of cells.
const SIZE_CLASSES: usize = 8;

fn size_class(radius: f32) -> usize {
    let mut k = 0;
    while k + 1 < SIZE_CLASSES && radius >= (1u32 << k) as f32 {
        k += 1;
    }
    k
}

/// Bodies placed so far, for the overlap check of the next ones.
struct PlacedBodies {
    /// First body of each `(class, cell)` bucket; `next` chains the rest.
    head: std::collections::HashMap<u64, u32>,
    next: Vec<u32>,
    pos: Vec<Vec2>,
    radius: Vec<f32>,
    in_class: [u32; SIZE_CLASSES],
}

impl PlacedBodies {
    fn new() -> Self {
        Self {
            head: std::collections::HashMap::new(),
            next: Vec::new(),
            pos: Vec::new(),
            radius: Vec::new(),
            in_class: [0; SIZE_CLASSES],
        }
    }

    fn key(class: usize, p: Vec2) -> u64 {
        let cell = (2u32 << class) as f32;
        let (cx, cy) = ((p.x / cell).max(0.0) as u64, (p.y / cell).max(0.0) as u64);
        ((class as u64) << 48) | (cx << 24) | cy
    }

    fn insert(&mut self, p: Vec2, radius: f32) {
        let class = size_class(radius);
        let id = self.pos.len() as u32;
        let previous = self.head.insert(Self::key(class, p), id).unwrap_or(u32::MAX);
        self.next.push(previous);
        self.pos.push(p);
        self.radius.push(radius);
        self.in_class[class] += 1;
    }

    /// Whether a body of `radius` at `p` stays clear of every placed body. Groups are placed
    /// largest radius first, so every placed body is in `p`'s class or above: 3×3 cells each.
    fn clear(&self, p: Vec2, radius: f32) -> bool {
        for class in 0..SIZE_CLASSES {
            if self.in_class[class] == 0 {
                continue;
            }
            let cell = (2u32 << class) as f32;
            let reach = ((radius + (1u32 << class) as f32) / cell).ceil() as i64;
            let (cx, cy) = ((p.x / cell).max(0.0) as i64, (p.y / cell).max(0.0) as i64);
            for y in (cy - reach).max(0)..=cy + reach {
                for x in (cx - reach).max(0)..=cx + reach {
                    let key = ((class as u64) << 48) | ((x as u64) << 24) | y as u64;
                    let mut id = self.head.get(&key).copied().unwrap_or(u32::MAX);
                    while id != u32::MAX {
                        let gap = radius + self.radius[id as usize];
                        if p.distance_squared(self.pos[id as usize]) < gap * gap {
                            return false;
                        }
                        id = self.next[id as usize];
                    }
                }
            }
        }
        true
    }
}

/// Whether a body of `radius` at `p` keeps clear of every obstacle.
fn clear_of_obstacles(obstacles: &ObstacleIndex, p: Vec2, radius: f32) -> bool {
    let mut clear = true;
    let query = Aabb { min: p - Vec2::splat(radius), max: p + Vec2::splat(radius) };
    obstacles.for_each_near(query, |_, o| clear &= o.surface(p).signed_distance >= radius);
    clear
}

/// A lattice of `cols × rows` places tiling a rectangle: one body per place, its centre drawn
/// in the place shrunk by the body radius, so bodies of two places never overlap.
struct Lattice {
    origin: Vec2,
    place: Vec2,
    cols: u32,
    rows: u32,
}

impl Lattice {
    /// Places of side at least `spacing` (≥ 2 × radius) over `size`.
    fn new(origin: Vec2, size: Vec2, spacing: f32) -> Self {
        let cols = ((size.x / spacing) as u32).max(1);
        let rows = ((size.y / spacing) as u32).max(1);
        Self { origin, place: Vec2::new(size.x / cols as f32, size.y / rows as f32), cols, rows }
    }

    fn corner(&self, place: u32) -> Vec2 {
        let (i, j) = (place % self.cols, place / self.cols);
        self.origin + Vec2::new(i as f32 * self.place.x, j as f32 * self.place.y)
    }

    fn centre(&self, place: u32) -> Vec2 {
        self.corner(place) + 0.5 * self.place
    }
}

/// Spawns every group without overlap, in O(N): each group is laid on a jittered lattice over
/// its spawn region whose places are at least a body diameter apart, coarse enough to spread
/// the group over the whole region and refined until enough places are clear of obstacles and
/// of the groups placed before (largest bodies first). Returns the positions and the unit
/// start directions, agent by agent; refuses a group its region cannot hold (the density
/// limit), naming the group, its count and the most the region holds.
///
/// Work: the lattice places examined, each a constant number of cell lookups. Without
/// obstacles the first lattice has at most about as many places as agents; obstacles refine it,
/// by at least 0.9 in spacing a time, up to [`MAX_SPAWN_PLACES`] places per group.
pub fn spawn(scene: &Scene, obstacles: &ObstacleIndex) -> Result<Spawn, SceneError> {
    let mut offsets = Vec::with_capacity(scene.groups.len());
    let mut total = 0usize;
    for g in &scene.groups {
        offsets.push(total);
        total += g.count as usize;
    }
    let mut pos = vec![Vec2::ZERO; total];
    let mut dir = vec![Vec2::ZERO; total];
    let mut order: Vec<usize> = (0..scene.groups.len()).collect();
    order.sort_by(|&a, &b| scene.groups[b].agent_radius.total_cmp(&scene.groups[a].agent_radius));
    let mut placed = PlacedBodies::new();
    let mut places_examined = 0u64;
    for gi in order {
        let g = &scene.groups[gi];
        if g.count == 0 {
            continue;
        }
        let mut rng = Rng::new(scene.seed, STREAM_SPAWN.wrapping_add(gi as u32));
        let start = offsets[gi];
        let out = start..start + g.count as usize;
        places_examined += place_group(scene, obstacles, &placed, gi, &mut rng, &mut pos[out.clone()])?;
        for (p, d) in pos[out.clone()].iter().zip(&mut dir[out]) {
            placed.insert(*p, g.agent_radius);
            *d = Vec2::from_angle(rng.range(-std::f32::consts::PI, std::f32::consts::PI));
        }
    }
    Ok(Spawn { positions: pos, directions: dir, places_examined })
}

/// Where [`spawn`] put the agents, and the work it did.
#[derive(Clone, Debug)]
pub struct Spawn {
    /// Start position of every agent, in agent order (px).
    pub positions: Vec<Vec2>,
    /// Unit start heading of every agent (the world scales it by a quarter of the speed limit).
    pub directions: Vec<Vec2>,
    /// Lattice places examined over all groups and refinements (the spawn's work).
    pub places_examined: u64,
}

/// Places the agents of group `gi` (see [`spawn`]) into `out`; returns the places examined.
fn place_group(
    scene: &Scene,
    obstacles: &ObstacleIndex,
    placed: &PlacedBodies,
    gi: usize,
    rng: &mut Rng,
    out: &mut [Vec2],
) -> Result<u64, SceneError> {
    let g = &scene.groups[gi];
    let r = g.agent_radius;
    // Centres lie in the spawn region, moved in where it reaches closer to a border than a
    // radius (see `centre_bounds`).
    let (lo, hi) = centre_bounds(r, Vec2::new(scene.width, scene.height));
    let first = v(g.spawn.min).clamp(lo, hi);
    let last = v(g.spawn.max).clamp(lo, hi);
    // The lattice tiles the centres' rectangle grown by a radius: its first and last places put
    // centres on the rectangle's sides, and a single place fits a side shorter than a body.
    let origin = first - Vec2::splat(r);
    let size = last - first + Vec2::splat(2.0 * r);
    let wanted = out.len();
    let area = f64::from(size.x) * f64::from(size.y);
    let finest = (2.0 * r).max((area / MAX_SPAWN_PLACES as f64).sqrt() as f32);
    let mut spacing = finest.max((area / wanted as f64).sqrt() as f32);
    let mut examined = 0u64;
    let (lattice, mut free) = loop {
        let lattice = Lattice::new(origin, size, spacing);
        examined += u64::from(lattice.cols) * u64::from(lattice.rows);
        let free: Vec<u32> = (0..lattice.cols * lattice.rows)
            .filter(|&k| {
                let c = lattice.centre(k);
                clear_of_obstacles(obstacles, c, r) && placed.clear(c, r)
            })
            .collect();
        if free.len() >= wanted {
            break (lattice, free);
        }
        if spacing <= finest {
            return Err(SceneError::Blocked(format!(
                "group {} ({}): {} agents of radius {r} px do not fit in its spawn region \
                 ({}×{} px): it holds at most {} apart from each other, the obstacles and the \
                 other groups (the density limit)",
                gi + 1,
                g.name,
                g.count,
                g.spawn.max[0] - g.spawn.min[0],
                g.spawn.max[1] - g.spawn.min[1],
                free.len()
            )));
        }
        // Refine towards the spacing the free share suggests, at least a little each time.
        let ratio = (free.len() as f32 / (1.1 * wanted as f32)).sqrt().clamp(0.25, 0.9);
        spacing = finest.max(spacing * ratio);
    };
    // A seeded partial shuffle picks which free places get an agent.
    for a in 0..wanted {
        let j = a + rng.below((free.len() - a) as u32) as usize;
        free.swap(a, j);
    }
    let room = lattice.place - Vec2::splat(2.0 * r);
    for (p, &k) in out.iter_mut().zip(&free) {
        let jittered =
            lattice.corner(k) + Vec2::splat(r) + room.max(Vec2::ZERO) * Vec2::new(rng.unit(), rng.unit());
        *p = if clear_of_obstacles(obstacles, jittered, r) && placed.clear(jittered, r) {
            jittered
        } else {
            lattice.centre(k)
        };
    }
    Ok(examined)
}
