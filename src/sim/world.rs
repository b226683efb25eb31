//! The running simulation: agent state as struct-of-arrays, the two-phase step, seeded spawn.

use crate::digest::Fnv1a;
use crate::model::geometry::{Aabb, Obstacle};
use crate::model::params::PlannerConfig;
use crate::model::refusal::{Code, Message};
use crate::model::scene::{OnArrival, Scene, SceneError};
use crate::planners::{GroupView, Planner, StepContext};
use crate::rng::Rng;
use crate::sim::fitness::Frame;
use crate::sim::gather::{Arrival, GoalPlaces};
use crate::sim::metrics::{Metrics, MetricsRecorder};
use crate::sim::spawn::{centre_bounds, spawn, Spawn};
use crate::sim::sweep::{path_enters, Terrain, PUSH_EPSILON};
use crate::spatial::flow_field::FlowFieldStore;
use crate::spatial::{periodic_images, ObstacleIndex, PeriodicImage, QueryCap, SpatialGrid};
use glam::Vec2;
use std::ops::Range;

/// Planners draw from this stream; each group's placement has its own ([`crate::sim::spawn`]).
const STREAM_PLAN: u32 = 1;
/// An agent whose goal is full and whose disc comes within this many of its body diameters of
/// a body at rest at that goal has reached the crowd there: it presses towards the goal's
/// centre until the crowd stops it ([`World::settle_parking`]). Boids' separation keeps a
/// stationary neighbour 14 px off centre to centre, a 6 px gap for 4 px bodies, so a gap of
/// touching discs only would leave its flock hovering round the crowd.
pub const PARK_CONTACT_DIAMETERS: f32 = 1.0;
/// Most neighbours a pressing agent steps out of.
const PRESS_NEIGHBOUR_CAP: QueryCap = QueryCap { neighbours: 16, candidates: 256 };
/// Net progress (px) towards its place that counts for a walker.
const WALK_PROGRESS: f32 = 1.0;
/// Progress below this (px per step) towards its place or the goal's centre counts as none.
const SETTLE_PROGRESS: f32 = 0.05;
/// Steps without progress after which a pressing agent comes to rest where it is.
const PRESS_STALL_STEPS: u16 = 10;
/// Steps without progress after which a walking agent gives its place back and takes the free
/// one nearest to it (another body stands in its way).
const WALK_STALL_STEPS: u16 = 60;
/// How far off the straight way to the goal's centre a pressing agent aims (rad), to one side
/// or the other by its number: a body pressing straight onto a single one at rest slides round
/// it into a pocket instead of balancing on top of it (a chain growing outward).
const PRESS_SKEW: f32 = 0.2;
/// Rounds of [`World::shoulder_through`]: one push can cause another overlap; two undo most.
const SHOULDER_ROUNDS: usize = 4;
/// Room [`World::shoulder_through`] leaves between two bodies it parts (px): with less, the
/// next push in a crowd (rounding, a neighbour's) makes them overlap again.
const SHOULDER_MARGIN: f32 = 0.1;
/// Steps in a row a walker stands wedged on another before it rests where it is.
const WEDGED_STEPS: u16 = 10;
/// Most parked neighbours examined per moving agent and round of the parking pass (the first in
/// the grid's scan order): non-overlapping bodies hold few within reach; a pile of moving
/// agents (which do not park on each other) is bounded by it.
const PARK_NEIGHBOUR_CAP: QueryCap = QueryCap { neighbours: 64, candidates: 4096 };
/// Rounds of pushing a moving agent out of parked bodies before it goes back to where its step
/// started.
const PARK_PUSH_ROUNDS: usize = 6;
/// Rings (½ body diameter apart) searched for a free place around a boxed-in body.
const PARK_SEARCH_RINGS: u32 = 20;

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
    /// Whether each agent is at rest for good (parked in its goal or waiting outside it): solid
    /// to the others, never overlapping another at rest ([`World::settle_parking`]).
    parked: Vec<bool>,
    /// Where each agent stands with its goal.
    arrival: Vec<Arrival>,
    /// Steps each settling agent has made no progress.
    stall: Vec<u16>,
    /// Steps in a row each walker overlapped another that [`World::shoulder_through`] could
    /// not part (the two stand in a hole the crowd at rest left for one).
    wedged: Vec<u16>,
    /// Nearest each walking agent has come to its place so far (px): progress is counted net,
    /// so a walker that jitters back and forth in a jam is held up all the same.
    closest: Vec<f32>,
    /// Per goal, its places once it gathers and rests (built on the first step it rests).
    goal_places: Vec<Option<GoalPlaces>>,
    /// Largest body radius and largest planner speed limit (px, px/step): the reach of the
    /// parking pass's neighbour queries.
    max_radius: f32,
    max_step: f32,
    /// Positions at the start of the step (reused buffer of the parking pass).
    previous: Vec<Vec2>,
    /// Scratch of the parking pass: per grid cell, the parked agents the grid holds in it
    /// ([`World::for_each_parked_near`] skips queries of cells without one).
    parked_in_cell: Vec<u32>,
    /// A periodic band `[start, end)` of x (px): an agent whose centre leaves it at one end
    /// re-enters at the other ([`World::set_periodic_x`]).
    periodic_x: Option<(f32, f32)>,
    /// With a periodic band, the grid the planners query: the agents plus their images across
    /// the seam ([`SpatialGrid::rebuild_with_images`]), so neighbours are seen across it.
    image_grid: Option<SpatialGrid>,
    /// Scratch: the images of the last rebuild.
    images: Vec<PeriodicImage>,
    /// Whether groups whose planner parks do park at their fixed goal ([`World::set_parking`]).
    parking: bool,
    /// The flow fields of the groups guided by one, each distinct field once
    /// ([`FlowFieldStore`]).
    flow_fields: FlowFieldStore,
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

    /// `cost_limit`: refuse scenes over the memory and planning limits of [`crate::sim::cost`];
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
                return Err(SceneError::BadReference(
                    Message::new(Code::SceneStartPositions)
                        .with("given", positions.len())
                        .with("total", total),
                ))
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
            parked: vec![false; total],
            arrival: vec![Arrival::Moving; total],
            stall: vec![0; total],
            wedged: vec![0; total],
            closest: vec![f32::INFINITY; total],
            goal_places: Vec::new(),
            max_radius,
            max_step: 0.0,
            previous: Vec::new(),
            parked_in_cell: Vec::new(),
            periodic_x: None,
            image_grid: None,
            images: Vec::new(),
            parking: true,
            flow_fields: FlowFieldStore::default(),
        };
        world.update_parking_rules();
        world.grid.rebuild(&world.pos, &world.vel);
        world.plan_now_unless_sliced();
        Ok(world)
    }

    /// [`World::new`] without the memory and planning limits of [`crate::sim::cost`] (the spawn
    /// density limit still holds): for native benchmarks and suites that run scenes bigger than
    /// the page may.
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

    /// Runs up to `evaluations` more objective evaluations of the planning (of the first group
    /// still planning; the slices do not change the result); returns
    /// [`World::planning_progress`].
    pub fn advance_planning(&mut self, evaluations: u32) -> f64 {
        if let Some(g) = self.groups.iter_mut().find(|g| g.planner.planning_progress() < 1.0) {
            g.planner.advance_planning(evaluations);
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

    /// The current state as a frame for a [`crate::sim::fitness::FitnessRecorder`], with each
    /// agent's goal position from `goals` and no per-group measures.
    pub fn fitness_frame<'a>(&'a self, goals: &'a [Option<Vec2>]) -> Frame<'a> {
        Frame {
            pos: &self.pos,
            vel: &self.vel,
            radius: &self.radius,
            goals,
            obstacles: &self.obstacles,
            group_of: &[],
        }
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
            grid: self.planning_grid(),
            obstacles: &self.obstacles,
            bounds: Vec2::new(self.scene.width, self.scene.height),
            step: self.step,
            scene: &self.scene,
            group_of: &self.group_of,
            flow_fields: &self.flow_fields,
        }
    }

    /// How many distinct flow fields the groups hold now (groups that would build the same field
    /// share one, [`FlowFieldStore`]).
    pub fn flow_field_count(&self) -> usize {
        self.flow_fields.live_fields()
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
            return Err(SceneError::no_such_item("group", g as u64 + 1));
        }
        // Checked against the scene too (a Boids group follows a path that exists), so the
        // scene's link stays loadable.
        self.scene.validate_planner(g, &config)?;
        if self.scene.groups[g].planner != config {
            // Another planner or larger IGSA settings may break a memory or planning limit: then
            // the run keeps its planner.
            // The whole scene: the flow fields' memory depends on its size and obstacles.
            let mut changed = self.scene.clone();
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
        self.update_parking_rules();
        self.plan_now_unless_sliced();
        Ok(())
    }

    /// Recomputes which groups park where after a change of planners or goals; agents parked
    /// under a rule that no longer holds (another planner, a moved goal) walk on.
    fn update_parking_rules(&mut self) {
        let goals = self.scene.goals.len();
        if self.goal_places.len() != goals {
            self.goal_places = vec![None; goals];
        }
        self.max_step = self.groups.iter().map(|g| g.planner.max_speed()).fold(0.0, f32::max);
    }

    /// Forgets the places of goal `k` (moved, resized, or the obstacles changed) and sends every
    /// agent heading there back to its planner: they find their places again.
    fn reset_goal(&mut self, k: usize) {
        if let Some(places) = self.goal_places.get_mut(k) {
            *places = None;
        }
        for i in 0..self.pos.len() {
            let heads_there =
                self.scene.groups.get(self.group_of[i] as usize).and_then(|g| g.goal) == Some(k as u32);
            if heads_there && self.arrival[i] != Arrival::Exited {
                self.arrival[i] = Arrival::Moving;
                self.parked[i] = false;
                self.stall[i] = 0;
                self.wedged[i] = 0;
            }
        }
    }

    /// Where each agent stands with its goal (walking to its place, parked, waiting, exited…).
    pub fn arrivals(&self) -> &[Arrival] {
        &self.arrival
    }

    /// How many bodies goal `k` holds, once its places are laid out (it gathers and rests).
    pub fn goal_capacity(&self, k: usize) -> Option<usize> {
        self.goal_places.get(k)?.as_ref().map(GoalPlaces::capacity)
    }

    /// Whether each agent is parked at its goal (see [`World::settle_parking`]).
    pub fn parked(&self) -> &[bool] {
        &self.parked
    }

    /// Turns parking at goals on (the default) or off. Off, arrived agents walk on as their
    /// planner steers them: the validation suite's walkers, whose goals are exits, so a crowd
    /// parked in the doorway would block the walkers behind it (in the RiMEA tests a walker at
    /// the exit has left the building). Agents parked so far walk on.
    pub fn set_parking(&mut self, on: bool) {
        self.parking = on;
        if !on {
            for k in 0..self.goal_places.len() {
                self.reset_goal(k);
            }
        }
        self.update_parking_rules();
    }

    /// Makes x periodic over `[start, end)` px (`None`: off, the default): an agent whose centre
    /// leaves the band at one end re-enters at the other, as in the periodic corridor of the
    /// validation suite's fundamental diagram. The planners see neighbours across the seam
    /// where they stand relative to them (the minimum image: the grid they query holds copies
    /// of the agents near either end beyond the other); the world's borders stay walls, so a
    /// band should lie away from them. Not part of the scene (a link cannot ask for it). An
    /// empty or non-finite band is ignored.
    pub fn set_periodic_x(&mut self, band: Option<(f32, f32)>) {
        self.periodic_x = band.filter(|(a, b)| a.is_finite() && b.is_finite() && b > a);
        self.recorder.set_periodic_x(self.periodic_x);
        self.rebuild_grid();
    }

    /// The grid the planners query: with a periodic band, the one holding the images.
    fn planning_grid(&self) -> &SpatialGrid {
        self.image_grid.as_ref().unwrap_or(&self.grid)
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
        let obstacles_changed = scene.obstacles != self.scene.obstacles;
        let changed_goals: Vec<usize> = (0..scene.goals.len().max(self.scene.goals.len()))
            .filter(|&k| obstacles_changed || scene.goals.get(k) != self.scene.goals.get(k))
            .collect();
        self.obstacles = ObstacleIndex::new(scene.obstacles.clone(), scene.width, scene.height);
        let goal_of_group: Vec<Option<u32>> = self.scene.groups.iter().map(|g| g.goal).collect();
        self.scene = scene;
        self.goal_places.resize(self.scene.goals.len(), None);
        for k in changed_goals {
            self.reset_goal(k);
        }
        // A group sent to another goal finds a place there.
        for (gi, before) in goal_of_group.iter().enumerate() {
            if self.scene.groups.get(gi).map(|g| g.goal) != Some(*before) {
                for i in self.groups[gi].agents.clone() {
                    let i = i as usize;
                    if self.arrival[i] != Arrival::Exited {
                        self.arrival[i] = Arrival::Moving;
                        self.parked[i] = false;
                    }
                }
            }
        }
        for (gi, group) in self.groups.iter_mut().enumerate() {
            if geometry_changed && group.planner.replans_on_edit() {
                group.planner =
                    crate::planners::build_for_group(&self.scene.groups[gi].planner, &self.scene, gi);
            }
        }
        self.update_parking_rules();
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
            grid: self.image_grid.as_ref().unwrap_or(&self.grid),
            obstacles: &self.obstacles,
            bounds,
            step: self.step,
            scene: &self.scene,
            group_of: &self.group_of,
            flow_fields: &self.flow_fields,
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

        self.steer_arrivals();
        let solid: Vec<bool> = self.groups.iter().map(|g| !g.planner.passes_through_obstacles()).collect();
        self.previous.clear();
        self.previous.extend_from_slice(&self.pos);
        let terrain = Terrain { obstacles: &self.obstacles, bounds, periodic_x: self.periodic_x };
        for i in 0..self.pos.len() {
            if self.parked[i] || self.arrival[i] == Arrival::Exited {
                self.vel[i] = Vec2::ZERO;
                continue;
            }
            let solid = solid[self.group_of[i] as usize];
            let (p, v) = terrain.move_agent(self.pos[i], self.next_vel[i], self.radius[i], solid);
            self.pos[i] = p;
            self.vel[i] = v;
        }
        self.step += 1;
        self.settle_parking(bounds);
        self.shoulder_through(bounds);
        self.rebuild_grid();
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
            &self.arrival,
        );
    }

    /// Arrival, after every agent moved (the grid still holds the positions before the move):
    /// a moving agent is pushed out of any body at rest (they are solid), then
    /// [`World::settle_arrival`] moves it on in its goal. So bodies at rest never overlap each
    /// other. O(N): one bounded neighbour query per moving agent, and none at all before the
    /// first agent rests.
    fn settle_parking(&mut self, bounds: Vec2) {
        let any_parked = self.parked.contains(&true);
        if !self.parking && !any_parked {
            return;
        }
        self.lay_out_places();
        let slack = self.max_radius + self.max_step + 2.0 * PARK_CONTACT_DIAMETERS * self.max_radius;
        let solid: Vec<bool> = self.groups.iter().map(|g| !g.planner.passes_through_obstacles()).collect();
        // Agents placed far from where the grid holds them in this pass (few, usually none; in
        // a jam many).
        let mut jumped = Jumped::new(slack + self.max_radius);
        // The parked agents per cell where the grid holds them, kept up to date as agents park
        // below: most moving agents have none in the cells their queries scan.
        let mut parked_in_cell = std::mem::take(&mut self.parked_in_cell);
        parked_in_cell.clear();
        parked_in_cell.resize(self.grid.cell_count(), 0);
        if any_parked {
            for (i, _) in self.parked.iter().enumerate().filter(|(_, &parked)| parked) {
                if let Some(count) = self.grid.cell_of_agent(i).and_then(|c| parked_in_cell.get_mut(c)) {
                    *count += 1;
                }
            }
        }
        for i in 0..self.pos.len() {
            if self.parked[i] || self.arrival[i] == Arrival::Exited {
                continue;
            }
            let g = self.group_of[i] as usize;
            let r = self.radius[i];
            let mut p = self.pos[i];
            let mut v = self.vel[i];
            if any_parked {
                let before = p;
                let mut free = false;
                for round in 0..=PARK_PUSH_ROUNDS {
                    // Out of every overlapping parked body at once (current positions: a body
                    // parked earlier in this pass moved this step, so the query reaches a step
                    // farther): in a notch between two bodies the pushes add up to a way out.
                    let mut push = Vec2::ZERO;
                    let mut overlapping = false;
                    let (pos, radius) = (&self.pos, &self.radius);
                    self.for_each_parked_near(p, r + slack, &jumped, &parked_in_cell, |j| {
                        let reach = r + radius[j];
                        let d = p.distance(pos[j]);
                        if d < reach {
                            overlapping = true;
                            let normal =
                                crate::model::geometry::unit_or(p - pos[j], -v.normalize_or(Vec2::X));
                            push += normal * (reach - d + PUSH_EPSILON);
                        }
                    });
                    if !overlapping {
                        free = true;
                        break;
                    }
                    if round == PARK_PUSH_ROUNDS {
                        break;
                    }
                    p += push;
                    if let Some(normal) = push.try_normalize() {
                        let into = v.dot(normal);
                        if into < 0.0 {
                            v -= normal * into;
                        }
                    }
                }
                let (lo, hi) = centre_bounds(r, bounds);
                // A place lies in the world, outside the obstacles, and is reached from where the
                // step began without passing through one.
                let from = self.previous[i];
                let placeable = |q: Vec2| {
                    q.clamp(lo, hi) == q
                        && !(solid[g]
                            && (self.obstacles.contains(q)
                                || path_enters(&self.obstacles, from, q, self.periodic_x)))
                };
                if !free || (p != before && !placeable(p)) {
                    // Boxed in between parked bodies (bodies parked onto it), or pushed out of
                    // the world or into an obstacle: the nearest free place within ten body
                    // diameters (a jump out of the crowd), else back to where the step started.
                    let towards = self.gather_centre(g);
                    p = match self.free_place_near(before, r, slack, towards, &jumped, &placeable) {
                        Some(q) => {
                            // The grid still holds it where the step started.
                            jumped.push(i, q);
                            q
                        }
                        None => self.previous[i],
                    };
                    v = Vec2::ZERO;
                }
                self.pos[i] = p;
                self.vel[i] = v;
            }
            self.settle_arrival(i, &jumped, &mut parked_in_cell, slack);
        }
        self.parked_in_cell = parked_in_cell;
    }

    /// Agents the world steers at their goals (walking to a place, pressing in) shoulder
    /// their way after the move: each overlap with an agent not at rest is undone by moving the
    /// two apart, half each (all of it for the walker when the other cannot move there: out
    /// of the world or into an obstacle). So a walker held up for long, which walks on without
    /// giving way, parts the crowd instead of walking through it, and agents queued at a goal
    /// do not pile on its walkers. Bodies at rest are left to [`World::settle_parking`].
    fn shoulder_through(&mut self, bounds: Vec2) {
        let steered = |a: Arrival| matches!(a, Arrival::Walking(_) | Arrival::Pressing);
        if !self.arrival.iter().any(|&a| steered(a)) {
            return;
        }
        let solid: Vec<bool> = self.groups.iter().map(|g| !g.planner.passes_through_obstacles()).collect();
        // The grid holds the positions before the move: a neighbour is within a step of it.
        let slack = self.max_radius + 2.0 * self.max_step;
        let mut near: Vec<usize> = Vec::new();
        // The grid holds a body that came to rest in this step within a step of where it rests.
        let (none_jumped, rest_slack) = (Jumped::new(1.0), self.max_radius + self.max_step);
        for round in 0..SHOULDER_ROUNDS {
            let last_round = round + 1 == SHOULDER_ROUNDS;
            for i in 0..self.pos.len() {
                if !steered(self.arrival[i]) {
                    continue;
                }
                let mut wedged = false;
                let bold =
                    matches!(self.arrival[i], Arrival::Walking(_)) && self.stall[i] >= WALK_STALL_STEPS;
                near.clear();
                self.grid.for_each_within_capped(
                    self.pos[i],
                    self.radius[i] + slack,
                    PRESS_NEIGHBOUR_CAP,
                    |n| {
                        near.push(n.id as usize);
                    },
                );
                for &j in &near {
                    if j == i || self.parked[j] || self.arrival[j] == Arrival::Exited {
                        continue;
                    }
                    let (pi, pj) = (self.pos[i], self.pos[j]);
                    let contact = self.radius[i] + self.radius[j];
                    let d = pi.distance(pj);
                    if d >= contact {
                        continue;
                    }
                    let away = away_from(pi, pj, d, i, j);
                    let overlap = contact - d + SHOULDER_MARGIN;
                    // Wedged for long, the two are parted into bodies at rest as well: the
                    // next step pushes whoever that leaves overlapping one out of it (or on to
                    // the nearest free place), so a hole for one never holds two for good.
                    let loose = self.wedged[i] >= WEDGED_STEPS;
                    let placeable = |k: usize, q: Vec2| {
                        let (lo, hi) = centre_bounds(self.radius[k], bounds);
                        q.clamp(lo, hi) == q
                            && !(solid[self.group_of[k] as usize]
                                && (self.obstacles.contains(q)
                                    || path_enters(&self.obstacles, self.previous[k], q, self.periodic_x)))
                            && (loose || !self.overlaps_rest(q, self.radius[k], &none_jumped, rest_slack))
                    };
                    let (qi, qj) = (pi + away * (overlap * 0.5), pj - away * (overlap * 0.5));
                    if bold {
                        // A walker held up for long is not pushed back (it would never get
                        // through): the other steps aside if it can, else they overlap a while.
                        if placeable(j, pj - away * overlap) {
                            self.pos[j] = pj - away * overlap;
                        } else {
                            wedged = true;
                        }
                    } else if placeable(i, qi) && placeable(j, qj) {
                        self.pos[i] = qi;
                        self.pos[j] = qj;
                    } else if placeable(i, pi + away * overlap) {
                        self.pos[i] = pi + away * overlap;
                    } else if placeable(j, pj - away * overlap) {
                        self.pos[j] = pj - away * overlap;
                    } else {
                        wedged = true;
                    }
                }
                if last_round {
                    self.wedged[i] = if wedged { self.wedged[i].saturating_add(1) } else { 0 };
                }
            }
        }
    }

    /// Rebuilds the neighbour grid from the agents' positions, without the agents that left
    /// the scene.
    fn rebuild_grid(&mut self) {
        let arrival = &self.arrival;
        let present = |i: usize| arrival[i] != Arrival::Exited;
        self.grid.rebuild_present(&self.pos, &self.vel, present);
        let Some(band) = self.periodic_x else {
            self.image_grid = None;
            return;
        };
        // The grid's cell is at least every planner's query radius: the images reach as far.
        let reach = self.grid.cell_size();
        periodic_images(&self.pos, present, band, reach, &mut self.images);
        let grid = match self.image_grid.take() {
            Some(g) if g.cell_size() == self.grid.cell_size() => g,
            _ => self.grid.clone(),
        };
        let grid = self.image_grid.insert(grid);
        grid.rebuild_with_images(&self.pos, &self.vel, present, &self.images);
    }

    /// The centre of the goal group `g` gathers at, once its places are laid out.
    fn gather_centre(&self, g: usize) -> Option<Vec2> {
        let k = self.scene.groups.get(g)?.goal? as usize;
        self.goal_places.get(k)?.as_ref().map(|places| places.centre)
    }

    /// Lays out the places of every goal that gathers, is headed for, and has come to rest
    /// (a fixed goal at once, a moving one at the end of its motion) and has none yet.
    fn lay_out_places(&mut self) {
        if !self.parking {
            return;
        }
        for k in 0..self.scene.goals.len() {
            if self.goal_places.get(k).is_none_or(Option::is_some) {
                continue;
            }
            let goal = &self.scene.goals[k];
            if goal.on_arrival != OnArrival::Gather || goal.rest_step().is_none_or(|rest| self.step < rest) {
                continue;
            }
            let heading: Vec<usize> = (0..self.scene.groups.len())
                .filter(|&g| {
                    self.scene.groups[g].goal == Some(k as u32)
                        && self.scene.groups[g].planner.gathers_at_goal()
                })
                .collect();
            if heading.is_empty() {
                continue;
            }
            let centre = goal.position_at(self.step);
            let body = heading.iter().map(|&g| self.scene.groups[g].agent_radius).fold(0.0, f32::max);
            let crowd: usize = heading.iter().map(|&g| self.scene.groups[g].count as usize).sum();
            let approaches: Vec<(u32, Vec2)> = heading
                .iter()
                .map(|&g| {
                    let agents = self.groups[g].agents.clone();
                    let n = agents.len().max(1) as f32;
                    let sum: Vec2 = agents.map(|i| self.pos[i as usize]).sum();
                    (g as u32, sum / n)
                })
                .collect();
            let bounds = Vec2::new(self.scene.width, self.scene.height);
            let (lo, hi) = centre_bounds(body, bounds);
            let obstacles = &self.obstacles;
            let clear = |q: Vec2| {
                let query = Aabb { min: q - Vec2::splat(body), max: q + Vec2::splat(body) };
                let mut clear = true;
                obstacles
                    .for_each_near(query, |_, o: &Obstacle| clear &= o.surface(q).signed_distance >= body);
                clear
            };
            let places = GoalPlaces::new(centre, goal.radius, body, crowd, &approaches, |q| {
                q.clamp(lo, hi) == q && clear(q)
            });
            self.goal_places[k] = Some(places);
        }
    }

    /// Moves agent `i` on in its goal after its step (it is not at rest): an agent whose centre
    /// enters a goal that gathers takes a free place there and walks to it, then rests there
    /// (arrived); when the goal is full it presses towards the goal's centre until the crowd
    /// stops it, and rests there (waiting, if outside the goal); an agent entering an exit
    /// leaves the scene.
    fn settle_arrival(&mut self, i: usize, jumped: &Jumped, parked_in_cell: &mut [u32], slack: f32) {
        let g = self.group_of[i] as usize;
        let Some(k) = self.scene.groups.get(g).and_then(|group| group.goal).map(|k| k as usize) else {
            return;
        };
        let Some(goal) = self.scene.goals.get(k) else { return };
        let (p, r) = (self.pos[i], self.radius[i]);
        let centre = goal.position_at(self.step);
        let d = p.distance(centre);
        if goal.on_arrival == OnArrival::Exit {
            if self.parking && d <= goal.radius {
                self.arrival[i] = Arrival::Exited;
                self.vel[i] = Vec2::ZERO;
            }
            return;
        }
        let goal_radius = goal.radius;
        if !self.scene.groups[g].planner.gathers_at_goal() {
            return;
        }
        let Some(places) = self.goal_places.get_mut(k).and_then(Option::as_mut) else { return };
        match self.arrival[i] {
            Arrival::Moving => {
                let full = places.is_full();
                if d <= goal_radius {
                    let claim = places.claim_for_group(g as u32, p).or_else(|| places.claim_nearest(p));
                    // No free place (all taken, some perhaps by agents still walking there): it
                    // presses in and rests where the crowd stops it.
                    self.arrival[i] = claim.map_or(Arrival::Pressing, Arrival::Walking);
                    self.stall[i] = 0;
                    self.closest[i] = f32::INFINITY;
                } else {
                    // Reached the crowd at rest in (or round) its goal? It takes the free place
                    // nearest to it (the crowd may fill the way in before the goal is full), or,
                    // the goal full, presses in and waits.
                    let gap = 2.0 * PARK_CONTACT_DIAMETERS * r;
                    let (pos, radius, group_of, groups) =
                        (&self.pos, &self.radius, &self.group_of, &self.scene.groups);
                    let mut touches = false;
                    self.for_each_parked_near(p, r + slack, jumped, parked_in_cell, |j| {
                        let same_goal =
                            groups.get(group_of[j] as usize).and_then(|h| h.goal) == Some(k as u32);
                        touches |= same_goal && p.distance(pos[j]) <= r + radius[j] + gap;
                    });
                    if touches {
                        let Some(places) = self.goal_places.get_mut(k).and_then(Option::as_mut) else {
                            return;
                        };
                        let claim = if full {
                            None
                        } else {
                            places.claim_for_group(g as u32, p).or_else(|| places.claim_nearest(p))
                        };
                        self.arrival[i] = claim.map_or(Arrival::Pressing, Arrival::Walking);
                        self.stall[i] = 0;
                        self.closest[i] = f32::INFINITY;
                    }
                }
            }
            Arrival::Walking(place) => {
                let target = places.place(place);
                let left = p.distance(target);
                if left <= SETTLE_PROGRESS && !self.overlaps_rest(target, r, jumped, slack) {
                    self.pos[i] = target;
                    if let Some(places) = self.goal_places.get_mut(k).and_then(Option::as_mut) {
                        places.fill();
                    }
                    self.rest(i, parked_in_cell);
                    return;
                }
                let progress = left < self.closest[i] - WALK_PROGRESS;
                if progress {
                    self.closest[i] = left;
                }
                if self.stall[i] < WALK_STALL_STEPS {
                    // Giving way: held up by bodies in its way, or its place is out of reach.
                    self.stall[i] = if progress { 0 } else { self.stall[i] + 1 };
                } else if !progress {
                    // Walking on without giving way ([`World::steer_arrivals`]) and still held.
                    self.stall[i] += 1;
                }
                if (self.stall[i] >= 2 * WALK_STALL_STEPS || self.wedged[i] >= WEDGED_STEPS)
                    && d <= goal_radius
                    && self.overlaps_walker(i)
                    && !self.overlaps_rest(p, r, jumped, slack)
                {
                    // Held up for good inside the goal on top of another walker (two in a hole
                    // the crowd left for one): it rests where it is and gives its place back;
                    // the other is then pushed out of it like out of any body at rest.
                    if let Some(places) = self.goal_places.get_mut(k).and_then(Option::as_mut) {
                        places.release(place);
                    }
                    self.rest(i, parked_in_cell);
                    return;
                }
                let occupied = self.overlaps_rest(target, r, jumped, slack);
                if self.stall[i] >= 4 * WALK_STALL_STEPS || occupied {
                    // Its place is out of reach (behind bodies at rest) or a body rests on it:
                    // the agent takes the next in its group's order, and gives its place back
                    // unless a body rests on it (then it stays taken, so the goal can be full).
                    let Some(places) = self.goal_places.get_mut(k).and_then(Option::as_mut) else { return };
                    let claim = places.claim_for_group(g as u32, p).or_else(|| places.claim_nearest(p));
                    if occupied {
                        // Another body fills it.
                        places.fill();
                    } else {
                        places.release(place);
                    }
                    self.arrival[i] = claim.map_or(Arrival::Pressing, Arrival::Walking);
                    self.stall[i] = 0;
                    self.closest[i] = f32::INFINITY;
                }
            }
            Arrival::Pressing => {
                // Net progress towards the centre, as for walkers: jostling in a crowd is none.
                let left = p.distance(places.centre);
                if left < self.closest[i] - SETTLE_PROGRESS {
                    self.closest[i] = left;
                    self.stall[i] = 0;
                } else {
                    self.stall[i] += 1;
                }
                if self.stall[i] >= PRESS_STALL_STEPS && !self.overlaps_rest(p, r, jumped, slack) {
                    self.rest(i, parked_in_cell);
                }
            }
            Arrival::Parked | Arrival::Waiting | Arrival::Exited => {}
        }
    }

    /// Whether agent `i` overlaps another that walks to its place.
    fn overlaps_walker(&self, i: usize) -> bool {
        let (p, r) = (self.pos[i], self.radius[i]);
        let mut overlaps = false;
        self.grid.for_each_within_capped(p, r + self.max_radius, PRESS_NEIGHBOUR_CAP, |n| {
            let j = n.id as usize;
            overlaps |= j != i
                && matches!(self.arrival[j], Arrival::Walking(_))
                && p.distance(self.pos[j]) < r + self.radius[j];
        });
        overlaps
    }

    /// Whether a body of radius `r` at `p` overlaps one at rest. Every body the grid holds
    /// near is looked at (no cap: a pile of moving agents round the place must not hide one at
    /// rest); asked only when an agent is about to come to rest.
    fn overlaps_rest(&self, p: Vec2, r: f32, jumped: &Jumped, slack: f32) -> bool {
        let mut overlaps = false;
        let (pos, radius) = (&self.pos, &self.radius);
        self.grid.for_each_within(p, r + slack, |n| {
            let j = n.id as usize;
            overlaps |= self.parked[j] && !jumped.contains(j) && p.distance(pos[j]) < r + radius[j];
        });
        jumped.for_each_near(p, r + slack, |j| {
            overlaps |= self.parked[j] && p.distance(pos[j]) < r + radius[j];
        });
        overlaps
    }

    /// Brings agent `i` to rest where it is: parked if its centre is inside its goal, else
    /// waiting outside it.
    fn rest(&mut self, i: usize, parked_in_cell: &mut [u32]) {
        let inside = self
            .goal_of_group(self.group_of[i] as usize)
            .is_some_and(|(centre, radius)| self.pos[i].distance(centre) <= radius);
        self.arrival[i] = if inside { Arrival::Parked } else { Arrival::Waiting };
        self.parked[i] = true;
        self.vel[i] = Vec2::ZERO;
        self.stall[i] = 0;
        if let Some(count) = self.grid.cell_of_agent(i).and_then(|c| parked_in_cell.get_mut(c)) {
            *count += 1;
        }
    }

    /// The velocities of the agents the world steers at its goals instead of their planners:
    /// none for those at rest or gone, straight to its place for one walking there, towards the
    /// goal's centre (a little to one side) for one pressing.
    fn steer_arrivals(&mut self) {
        for i in 0..self.pos.len() {
            let p = self.pos[i];
            let target = match self.arrival[i] {
                Arrival::Moving => continue,
                Arrival::Parked | Arrival::Waiting | Arrival::Exited => {
                    self.next_vel[i] = Vec2::ZERO;
                    continue;
                }
                Arrival::Walking(place) => {
                    let g = self.group_of[i] as usize;
                    let k = self.scene.groups.get(g).and_then(|group| group.goal);
                    match k.and_then(|k| self.goal_places.get(k as usize)).and_then(Option::as_ref) {
                        Some(places) => places.place(place),
                        None => continue,
                    }
                }
                Arrival::Pressing => {
                    let Some(centre) = self.gather_centre(self.group_of[i] as usize) else { continue };
                    let skew = if i % 2 == 0 { PRESS_SKEW } else { -PRESS_SKEW };
                    p + Vec2::from_angle(skew).rotate(centre - p)
                }
            };
            let speed = self.groups[self.group_of[i] as usize].planner.max_speed();
            let wanted = crate::model::geometry::limit(target - p, speed);
            // Held up this long, a walker walks on without giving way (two walkers that meet
            // head-on would wait for each other for ever).
            let walking = matches!(self.arrival[i], Arrival::Walking(_));
            let step =
                if walking && self.stall[i] >= WALK_STALL_STEPS { wanted } else { self.free_step(i, wanted) };
            // Within the planner's speed limit, as every move.
            self.next_vel[i] = crate::model::geometry::limit(step, speed);
        }
    }

    /// The part of the move `wanted` that agent `i` (steered by the world at its goal) can
    /// make without running into a body it gives way to where that body stands now, plus a step
    /// out of any such body it already overlaps: the world's walkers do not steer round others
    /// as planners do, so they only walk into free room (the planners' agents see them and
    /// steer round them).
    fn free_step(&self, i: usize, wanted: Vec2) -> Vec2 {
        let p = self.pos[i];
        let r = self.radius[i];
        let reach = r + self.max_radius + wanted.length();
        // The first body the move meets: the share of the move before it, and the normal there.
        let mut first = (1.0f32, Vec2::ZERO);
        let mut apart = Vec2::ZERO;
        let mut held = false;
        self.grid.for_each_within_capped(p, reach, PRESS_NEIGHBOUR_CAP, |n| {
            let j = n.id as usize;
            if j == i || self.arrival[j] == Arrival::Exited {
                return;
            }
            let q = self.pos[j];
            let contact = r + self.radius[j];
            let d = p.distance(q);
            if d < contact {
                // Already overlapping: step out of it; moving closer is not allowed.
                let away = away_from(p, q, d, i, j);
                apart += away * (contact - d) * 0.5;
                held |= wanted.dot(q - p) > 0.0;
                return;
            }
            // The first t in [0, 1] at which p + t·wanted touches q: |p − q + t·w| = contact.
            let w = wanted;
            let o = p - q;
            let a = w.length_squared();
            let b = 2.0 * o.dot(w);
            let c = o.length_squared() - contact * contact;
            if a <= 0.0 || b >= 0.0 {
                return;
            }
            let disc = b * b - 4.0 * a * c;
            if disc < 0.0 {
                return;
            }
            let t = ((-b - disc.sqrt()) / (2.0 * a)).clamp(0.0, 1.0);
            if t < first.0 {
                first = (t, (o + w * t).normalize_or_zero());
            }
        });
        if held {
            return apart;
        }
        let (t, normal) = first;
        // Up to the body, then the rest of the move along it (sliding round it, as walkers
        // slide round bodies at rest), less any part that runs back into it.
        let rest = wanted * (1.0 - t);
        let into = rest.dot(normal);
        wanted * t + rest - normal * into.min(0.0) + apart
    }

    /// Visits each parked agent the grid holds within `reach` of `p` (plus the step's slack the
    /// caller adds), bounded by [`PARK_NEIGHBOUR_CAP`], and each parked one of `jumped` (agents
    /// the grid holds at an old place) within `reach` of `p`, in the order they jumped (every
    /// caller ignores parked bodies farther than `reach`).
    ///
    /// `parked_in_cell` counts the parked agents per grid cell where the grid holds them: when
    /// the cells the query would scan hold none, the query would visit none (its caps only ever
    /// drop agents), so it is skipped. Far from the goals, that is every moving agent.
    fn for_each_parked_near(
        &self,
        p: Vec2,
        reach: f32,
        jumped: &Jumped,
        parked_in_cell: &[u32],
        mut visit: impl FnMut(usize),
    ) {
        let holds_parked =
            |cells: Range<usize>| parked_in_cell.get(cells).is_none_or(|c| c.iter().any(|&n| n > 0));
        if self.grid.query_cell_ranges(p, reach).any(holds_parked) {
            self.grid.for_each_within_capped(p, reach, PARK_NEIGHBOUR_CAP, |n| {
                let j = n.id as usize;
                if self.parked[j] && !jumped.contains(j) {
                    visit(j);
                }
            });
        }
        jumped.for_each_near(p, reach, |j| {
            if self.parked[j] {
                visit(j);
            }
        });
    }

    /// The free place (overlapping no parked body, `placeable`) nearest to `p` for a body of
    /// radius `r`: on rings ½, 1, 1½ … [`PARK_SEARCH_RINGS`]/2 diameters around `p` (8 × ring
    /// directions, at least 16); on the nearest ring with one, the one nearest `towards` (the
    /// goal). Only for a body boxed in by parked ones: rare in a crowd that parks as it arrives,
    /// but in a jam packed round its goal most bodies of its edge are boxed in every step and
    /// find no free place within the rings.
    ///
    /// A place is blocked by a parked body within `r` + its radius, among the bodies the
    /// grid holds within `r + slack` of the place and the jumped ones. Instead of one grid query
    /// per place (up to 1,688 of them for a body that finds nothing), the parked bodies round
    /// `p` are gathered once and bucketed by offset ([`PlaceBuckets`]), and each place tests
    /// the body that blocked the place before it on the ring (one body usually blocks several
    /// in a row), then the bodies of its own and the eight neighbouring buckets, stopping at the
    /// first that blocks it; the places are the same points, tested with the same expressions,
    /// so the answer is the same as testing every place against every body (a place is blocked
    /// by any body, in whatever order they are tested), except that no per-place cap applies
    /// ([`PARK_NEIGHBOUR_CAP`] bounded the old queries; non-overlapping bodies never reach it).
    /// In the frozen jam of `step_cost` packed (about 960 boxed-in bodies searching all 20
    /// rings every step at 10,000 agents) the worst 10-step window fell from 7,706 to 4,306
    /// ns per agent-step (a sort by distance and an `acosf` per body and ring before), same
    /// digests.
    fn free_place_near(
        &self,
        p: Vec2,
        r: f32,
        slack: f32,
        towards: Option<Vec2>,
        jumped: &Jumped,
        placeable: &impl Fn(Vec2) -> bool,
    ) -> Option<Vec2> {
        let query = r + slack;
        // Parked bodies that can block a place, bucketed round `p`.
        let mut bodies: Vec<NearBody> = Vec::new();
        let mut buckets = PlaceBuckets::default();
        let mut gathered_to = 0u32;
        let (mut blocked, mut places): (Vec<bool>, Vec<Vec2>) = (Vec::new(), Vec::new());
        for ring in 1..=PARK_SEARCH_RINGS {
            let distance = ring as f32 * r;
            if ring > gathered_to {
                // The rings up to 4, then all: most boxed-in bodies that find a place find it
                // on the first rings.
                gathered_to = if ring <= 4 { 4 } else { PARK_SEARCH_RINGS };
                let reach = gathered_to as f32 * r + query + 1.0;
                bodies.clear();
                self.grid.for_each_within(p, reach, |n| {
                    let j = n.id as usize;
                    if self.parked[j] && !jumped.contains(j) {
                        bodies.push(NearBody { at: self.pos[j], held: Some(n.pos), radius: self.radius[j] });
                    }
                });
                jumped.for_each_near(p, reach, |j| {
                    if self.parked[j] {
                        bodies.push(NearBody { at: self.pos[j], held: None, radius: self.radius[j] });
                    }
                });
                buckets.fill(p, r, gathered_to as f32 * r, &bodies);
            }
            let directions = 8 * ring.max(2);
            places.clear();
            places.extend(ring_directions(ring).iter().map(|&u| p + u * distance));
            blocked.clear();
            // A place is blocked by a body within `r` + its radius, among those the grid holds
            // within `query` of the place (the jumped ones wherever the grid holds them).
            let blocks = |q: Vec2, b: &NearBody| {
                b.held.is_none_or(|g| q.distance_squared(g) <= query * query)
                    && q.distance(b.at) < r + b.radius
            };
            // The body that blocked the last place first: neighbouring places of a ring are
            // about ¾ of a radius apart, so one body usually blocks several in a row.
            let mut last: Option<usize> = None;
            for &q in &places {
                let hit = match last {
                    Some(k) if blocks(q, &bodies[k]) => Some(k),
                    _ => buckets.find(p, q, |k| blocks(q, &bodies[k])),
                };
                if hit.is_some() {
                    last = hit;
                }
                blocked.push(hit.is_some());
            }
            let mut best: Option<(f32, Vec2)> = None;
            for k in 0..directions {
                if blocked[k as usize] {
                    continue;
                }
                let q = places[k as usize];
                if !placeable(q) {
                    continue;
                }
                let score = towards.map_or(0.0, |t| q.distance_squared(t));
                if best.is_none_or(|(b, _)| score < b) {
                    best = Some((score, q));
                }
            }
            if let Some((_, q)) = best {
                return Some(q);
            }
        }
        None
    }

    /// The metrics of the run so far (DESIGN §4 keys).
    pub fn metrics(&self) -> Metrics {
        let planners: Vec<&str> = self.scene.groups.iter().map(|g| g.planner.kind().name()).collect();
        self.recorder.summary(&self.scene, &planners, self.step)
    }

    /// A 64-bit FNV-1a digest of every position and velocity bit pattern: equal digests mean a
    /// bit-identical run (natively, in wasm, in any browser).
    pub fn digest(&self) -> u64 {
        let mut h = Fnv1a::new();
        for (p, v) in self.pos.iter().zip(&self.vel) {
            for x in [p.x, p.y, v.x, v.y] {
                h.f32(x);
            }
        }
        h.finish()
    }
}

/// A parked body near a boxed-in one ([`World::free_place_near`]).
#[derive(Clone, Copy)]
struct NearBody {
    /// Where it is.
    at: Vec2,
    /// Where the grid holds it, or `None` if it jumped in this pass.
    held: Option<Vec2>,
    /// Its radius (px).
    radius: f32,
}

/// The bodies of [`World::free_place_near`] bucketed by their offset from the boxed-in centre
/// `p`, in square cells wider than any body's blocking reach (`r` + its radius, plus a margin
/// for rounding): a body that blocks a place lies in the place's cell or one of the eight
/// round it. Bodies outside the square are put in its edge cells (still tested, never missed);
/// the places lie at least a cell inside its edge.
#[derive(Default)]
struct PlaceBuckets {
    /// Side of a cell (px).
    cell: f32,
    /// Cells per side; cell `(0, 0)` starts at offset `−half · cell` from `p`.
    side: i32,
    half: i32,
    /// `start[c]..start[c + 1]` indexes `order` for cell `c` (row-major).
    start: Vec<u32>,
    /// Body indexes, by cell.
    order: Vec<u32>,
}

impl PlaceBuckets {
    /// Buckets `bodies` round `p` for places within `extent` of it, for a body of radius `r`.
    fn fill(&mut self, p: Vec2, r: f32, extent: f32, bodies: &[NearBody]) {
        let widest = bodies.iter().map(|b| b.radius).fold(0.0, f32::max);
        // 1 px more than the widest reach, and more than the rounding of offsets this far out.
        self.cell = r + widest + 1.0 + 1e-5 * (p.x.abs() + p.y.abs() + extent);
        self.half = (extent / self.cell).ceil() as i32 + 2;
        self.side = 2 * self.half + 1;
        let cells = (self.side * self.side) as usize;
        self.start.clear();
        self.start.resize(cells + 1, 0);
        let cell_of: Vec<u32> = bodies.iter().map(|b| self.cell_of(b.at - p)).collect();
        for &c in &cell_of {
            self.start[c as usize + 1] += 1;
        }
        for c in 0..cells {
            self.start[c + 1] += self.start[c];
        }
        let mut next = self.start.clone();
        self.order.clear();
        self.order.resize(bodies.len(), 0);
        for (k, &c) in cell_of.iter().enumerate() {
            self.order[next[c as usize] as usize] = k as u32;
            next[c as usize] += 1;
        }
    }

    /// The cell column (or row) of offset `x`: `x / cell + half` truncated, which is its floor
    /// where it matters (inside the square, where it is positive) without a `floorf` call;
    /// offsets `cell − 1` apart or less land at most one cell apart.
    fn coord(&self, x: f32) -> i32 {
        ((x / self.cell + self.half as f32) as i32).clamp(0, self.side - 1)
    }

    fn cell_of(&self, w: Vec2) -> u32 {
        (self.coord(w.y) * self.side + self.coord(w.x)) as u32
    }

    /// The first body (by index) among those of the cells round place `q` for which `hit`
    /// holds: its own cell first, then the eight round it.
    fn find(&self, p: Vec2, q: Vec2, mut hit: impl FnMut(usize) -> bool) -> Option<usize> {
        let w = q - p;
        let (cx, cy) = (self.coord(w.x), self.coord(w.y));
        let mut scan = |x: i32, y: i32| -> Option<usize> {
            if x < 0 || y < 0 || x >= self.side || y >= self.side {
                return None;
            }
            let c = (y * self.side + x) as usize;
            let range = self.start[c] as usize..self.start[c + 1] as usize;
            self.order[range].iter().map(|&k| k as usize).find(|&k| hit(k))
        };
        if let Some(k) = scan(cx, cy) {
            return Some(k);
        }
        for (dx, dy) in [(-1, -1), (0, -1), (1, -1), (-1, 0), (1, 0), (-1, 1), (0, 1), (1, 1)] {
            if let Some(k) = scan(cx + dx, cy + dy) {
                return Some(k);
            }
        }
        None
    }
}

/// The agents the parking pass placed far from where the grid holds them (see
/// [`World::free_place_near`]), in the order they jumped, bucketed by place: a jam can make
/// thousands jump in one pass, and every query of the pass asks which lie near it.
struct Jumped {
    /// Whether each agent jumped.
    flag: Vec<bool>,
    /// Side of a bucket (px): the largest reach of a query of the pass.
    cell: f32,
    /// Per bucket `(x, y)`, the jumped agents in it as `(order of jumping, agent)`.
    buckets: std::collections::HashMap<(i32, i32), Vec<(u32, u32)>>,
    /// How many jumped.
    count: u32,
}

impl Jumped {
    /// None yet; buckets of `cell` px. The flags are allocated on the first jump.
    fn new(cell: f32) -> Self {
        Self { flag: Vec::new(), cell: cell.max(1.0), buckets: Default::default(), count: 0 }
    }

    fn bucket(&self, p: Vec2) -> (i32, i32) {
        ((p.x / self.cell).floor() as i32, (p.y / self.cell).floor() as i32)
    }

    fn push(&mut self, i: usize, at: Vec2) {
        if self.flag.len() <= i {
            self.flag.resize(i + 1, false);
        }
        self.flag[i] = true;
        let key = self.bucket(at);
        self.buckets.entry(key).or_default().push((self.count, i as u32));
        self.count += 1;
    }

    fn contains(&self, i: usize) -> bool {
        self.flag.get(i).copied().unwrap_or(false)
    }

    /// Calls `visit` with each jumped agent whose bucket meets the square of `reach` round `p`
    /// (a superset of those within `reach` of it), in the order they jumped.
    fn for_each_near(&self, p: Vec2, reach: f32, mut visit: impl FnMut(usize)) {
        if self.count == 0 {
            return;
        }
        let (lo, hi) = (self.bucket(p - Vec2::splat(reach)), self.bucket(p + Vec2::splat(reach)));
        let mut near: Vec<(u32, u32)> = Vec::new();
        for x in lo.0..=hi.0 {
            for y in lo.1..=hi.1 {
                if let Some(list) = self.buckets.get(&(x, y)) {
                    near.extend_from_slice(list);
                }
            }
        }
        near.sort_unstable();
        for (_, j) in near {
            visit(j as usize);
        }
    }
}

/// The unit directions of the places on ring `ring` of [`World::free_place_near`]
/// (`8 × max(ring, 2)` of them, the `k`-th at `k · τ / count` rad), computed once: a jam asks
/// for them for many bodies every step, and the sines and cosines were most of that cost. The
/// same `libm` calls on the same angles, so the same floats.
fn ring_directions(ring: u32) -> &'static [Vec2] {
    static TABLE: std::sync::OnceLock<Vec<Vec<Vec2>>> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| {
        (0..=PARK_SEARCH_RINGS)
            .map(|ring| {
                let directions = 8 * ring.max(2);
                let step = std::f32::consts::TAU / directions as f32;
                (0..directions)
                    .map(|k| {
                        let angle = k as f32 * step;
                        Vec2::new(libm::cosf(angle), libm::sinf(angle))
                    })
                    .collect()
            })
            .collect()
    });
    table.get(ring as usize).map_or(&[], Vec::as_slice)
}

/// The unit direction from `q` (agent `j`) to `p` (agent `i`), `d` apart: agents on the same
/// point part along x, the lower id to the left, so the two choose opposite ways.
fn away_from(p: Vec2, q: Vec2, d: f32, i: usize, j: usize) -> Vec2 {
    if d > 0.0 {
        (p - q) / d
    } else if i < j {
        Vec2::NEG_X
    } else {
        Vec2::X
    }
}
