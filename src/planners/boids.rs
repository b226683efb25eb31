//! Reynolds steering as taught in the group-animation lecture (DESIGN §3.1).
//!
//! Each rule yields a steering force `desired − velocity` limited by `max_force` (lecture,
//! "Rule 1–3" pseudocode); the rules are combined by a weighted sum or by priority allocation
//! ("Arbitration"), then `v += a; v = limit(v, max_speed); p += v` (lecture, `Boid::update`).

use super::lanes::{self, Lanes2};
use super::planner::{GroupView, Planner, StepContext};
use crate::model::geometry::limit;
use crate::model::geometry::{length, unit_or, Aabb, Obstacle};
use crate::model::params::boids::{Arbitration, BoidsParams, FlowGuide, Leader, Role};
use crate::model::scene::PathSpec;
use crate::planners::explain::{Explanation, NamedVector};
use crate::rng::Rng;
use crate::spatial::flow_field::CachedFlowField;
use crate::spatial::{CandidateRuns, CandidateSample, Columns, Neighbour, NEIGHBOUR_CAP};
use glam::{BVec4A, Vec2, Vec4};
use std::ops::Range;

/// The Boids planner for one group.
#[derive(Clone, Debug)]
pub struct Boids {
    params: BoidsParams,
    /// The left side whisker's direction relative to the heading (computed once: `sin`/`cos`).
    side_whisker: Vec2,
    /// Scratch: the candidate neighbours being tested (reused to avoid allocating).
    candidates: CandidateRuns,
    /// Scratch: the sampled candidates of a pile ([`FLOCK_SAMPLE_ABOVE`]).
    sample: CandidateSample,
    /// Candidates tested by the last `plan` (counted, for tests of the work per agent).
    visits: Visits,
    /// Scratch: each agent's neighbour sums in this step.
    sums: Vec<FlockSums>,
    /// The flow field towards the goal and what it was built from (flow field guidance).
    flow: CachedFlowField,
    /// Per agent of the group: the path segment it has reached (path following only moves on).
    path_segment: Vec<u32>,
    /// Per agent of the group: whether it has reached the path's end. Once there, the path no
    /// longer guides it and it seeks the group's goal, however far the goal lies from the end
    /// (stepping out of the end's circle towards the goal pulled it back to the end before, so
    /// a group whose goal lay beyond the path's end circled there for ever).
    path_done: Vec<bool>,
    /// The leader's last heading while it moved (leader following).
    leader_heading: Vec2,
}

/// Segment index meaning "not placed on the path yet".
const UNPLACED: u32 = u32::MAX;
/// Weight of a follower's steering out of the leader's way.
const LEADER_EVADE_WEIGHT: f32 = 2.0;
/// Longest look into the future (steps) when predicting a chased or feared agent's position.
const MAX_PREDICTION_STEPS: f32 = 40.0;
/// A leader slower than this (px/step) keeps its last heading.
const MIN_HEADING_SPEED: f32 = 0.05;

/// Candidates tested at once by [`flock_sums`] (one 128-bit SIMD register of f32).
const LANES: usize = lanes::LANES;
const _: () = assert!(LANES == crate::spatial::CANDIDATE_LANES, "flock_sums reads whole Vec4s");
/// The lanes holding candidates when `n` of them are left in a run (index `n`, at most 4).
const RUN_MASKS: [BVec4A; LANES + 1] = [
    BVec4A::new(false, false, false, false),
    BVec4A::new(true, false, false, false),
    BVec4A::new(true, true, false, false),
    BVec4A::new(true, true, true, false),
    BVec4A::new(true, true, true, true),
];

/// What separation, alignment and cohesion need from an agent's neighbours.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct FlockSums {
    /// Σ (p − q)/|p − q|² over neighbours closer than the separation radius: exactly zero
    /// without one, and steering towards zero is no force.
    separation: Vec2,
    /// Σ velocity and Σ position over neighbours of the agent's own group.
    velocity: Vec2,
    position: Vec2,
    flocking: u32,
}

/// Side whiskers: angle from the heading (radians) and length relative to the main whisker.
const SIDE_WHISKER_ANGLE: f32 = 0.5;
const SIDE_WHISKER_SCALE: f32 = 0.6;

impl Boids {
    /// A planner with these parameters.
    pub fn new(params: BoidsParams) -> Self {
        Self {
            params,
            side_whisker: Vec2::from_angle(SIDE_WHISKER_ANGLE),
            candidates: CandidateRuns::default(),
            sample: CandidateSample::default(),
            visits: Visits::default(),
            sums: Vec::new(),
            flow: CachedFlowField::default(),
            path_segment: Vec::new(),
            path_done: Vec::new(),
            leader_heading: Vec2::ZERO,
        }
    }

    /// The planner's parameters.
    pub fn params(&self) -> &BoidsParams {
        &self.params
    }

    /// The candidates the last [`Planner::plan`] tested for its neighbour sums (counted).
    pub fn visits(&self) -> Visits {
        self.visits
    }

    /// Updates what the extensions remember between steps, from the state at the start of the
    /// step (so `agent_forces` stays a pure function of it): the flow field when the goal moved
    /// to another cell or the obstacles changed, each agent's progress along its path, the
    /// leader's heading.
    fn prepare(&mut self, ctx: &StepContext, group: &GroupView) {
        let prm = &self.params;
        if prm.flow_field == FlowGuide::Goal {
            if let Some((goal, _)) = group.goal {
                let clearance = group.agents.clone().next().map_or(0.0, |i| ctx.radii[i as usize]);
                self.flow.update(ctx.flow_fields, ctx.bounds, ctx.obstacles, goal, clearance);
            }
        }
        if prm.leader == Leader::First {
            let leader = group.agents.start as usize;
            if let Some(&v) = ctx.velocities.get(leader).filter(|_| !group.agents.is_empty()) {
                if length(v) > MIN_HEADING_SPEED {
                    self.leader_heading = unit_or(v, Vec2::X);
                } else if self.leader_heading == Vec2::ZERO {
                    let to = group.goal.map_or(Vec2::X, |(g, _)| g - ctx.positions[leader]);
                    self.leader_heading = unit_or(to, Vec2::X);
                }
            }
        }
        let n = group.agents.len();
        if self.path_segment.len() != n {
            self.path_segment = vec![UNPLACED; n];
            self.path_done = vec![false; n];
        }
        if let Some(path) = self.followed_path(ctx) {
            for (k, id) in group.agents.clone().enumerate() {
                let p = ctx.positions[id as usize];
                let seg = self.path_segment[k];
                let found = if seg == UNPLACED {
                    path.closest_point(p)
                } else {
                    // Only the next two segments are candidates: a path that loops back near
                    // itself is still walked in order.
                    path.closest_point_in(p, seg as usize..seg as usize + 3)
                };
                if let Some(q) = found {
                    self.path_segment[k] =
                        if seg == UNPLACED { q.segment as u32 } else { seg.max(q.segment as u32) };
                    self.path_done[k] |= at_path_end(path, q.along, p);
                }
            }
        }
    }

    /// The scene path this group follows, if any.
    fn followed_path<'s>(&self, ctx: &StepContext<'s>) -> Option<&'s PathSpec> {
        let index = self.params.path.checked_sub(1)?;
        ctx.scene.paths.get(index as usize)
    }

    /// Seek with arrival towards a goal of radius `goal_radius` at up to `top_speed`: the
    /// steering force, the way to the goal, and whether the agent is parked inside it.
    fn seek_goal(&self, goal: Option<(Vec2, f32)>, p: Vec2, vel: Vec2, top_speed: f32) -> (Vec2, Vec2, bool) {
        let prm = &self.params;
        match goal {
            Some((goal, goal_radius)) => {
                let to = goal - p;
                let d = length(to);
                // Inside the goal the agent parks: it brakes and only keeps its distance, so
                // an arrived group spreads over the goal instead of piling onto its centre.
                let parked = d <= goal_radius;
                // Arrival: slow down over `arrival_radius` before the goal's edge, and creep
                // (a tenth of max speed) the rest of the way so the group keeps filling in.
                let ramp = ((d - goal_radius) / prm.arrival_radius).clamp(0.1, 1.0);
                let speed = if parked { 0.0 } else { top_speed * ramp };
                let desired = if d > 1e-6 { to * (speed / d) } else { Vec2::ZERO };
                (limit(desired - vel, prm.max_force), to, parked)
            }
            None => (Vec2::ZERO, Vec2::X, false),
        }
    }

    /// The top-down or leader guidance that replaces seeking the goal, if a feature gives one.
    fn guide(
        &self,
        ctx: &StepContext,
        group: &GroupView,
        k: usize,
        id: u32,
        p: Vec2,
        vel: Vec2,
    ) -> Option<Guide> {
        let prm = &self.params;
        if prm.role == Role::Predator {
            if let Some(prey) = nearest_of_role(ctx, p, prm.chase_radius, Role::Prey, id) {
                // Pursuit: aim where the prey will be when reached at top speed.
                let t = (prey.d2.sqrt() / prm.max_speed).min(MAX_PREDICTION_STEPS);
                let aim = prey.pos + prey.vel * t - p;
                return Some(Guide::new("pursue prey", self.steer_towards(aim, vel), aim));
            }
        }
        if prm.leader == Leader::First && !group.agents.is_empty() {
            let leader = group.agents.start;
            if id == leader {
                let (seek, to, parked) = self.seek_goal(group.goal, p, vel, prm.max_speed * prm.leader_speed);
                return Some(Guide {
                    name: "lead to goal",
                    steer: seek,
                    to_goal: to,
                    parked,
                    flock: false,
                    evade: None,
                });
            }
            return Some(self.follow_leader(ctx, leader, p, vel));
        }
        if let Some(path) = self.followed_path(ctx) {
            if let Some(g) = self.follow_path(path, group, k, p, vel) {
                return Some(g);
            }
        }
        if prm.flow_field == FlowGuide::Goal {
            if let (Some((goal, goal_radius)), Some(field)) = (group.goal, self.flow.get()) {
                let direction = field.direction_at(p);
                if direction != Vec2::ZERO {
                    let parked = p.distance(goal) <= goal_radius;
                    let way = field.distance_at(p);
                    let way = if way.is_finite() { way } else { p.distance(goal) };
                    let ramp = ((way - goal_radius) / prm.arrival_radius).clamp(0.1, 1.0);
                    let speed = if parked { 0.0 } else { prm.max_speed * ramp };
                    let steer = limit(direction * speed - vel, prm.max_force);
                    return Some(Guide {
                        name: "flow field",
                        steer,
                        to_goal: direction,
                        parked,
                        flock: true,
                        evade: None,
                    });
                }
            }
        }
        None
    }

    /// Reynolds' leader following: arrive at a point `leader_distance` behind the leader; when in
    /// front of it (within its path's width), steer sideways out of its way and brake.
    fn follow_leader(&self, ctx: &StepContext, leader: u32, p: Vec2, vel: Vec2) -> Guide {
        let prm = &self.params;
        let l = ctx.positions[leader as usize];
        let heading = self.leader_heading;
        let behind = l - heading * prm.leader_distance;
        let to = behind - p;
        // Arrival at a moving point: the leader's velocity plus a pull that fades over the
        // arrival radius, so a follower at the point walks with the leader instead of stopping.
        let desired =
            limit(ctx.velocities[leader as usize] + to * (prm.max_speed / prm.arrival_radius), prm.max_speed);
        let steer = limit(desired - vel, prm.max_force);
        let rel = p - l;
        let ahead = rel.dot(heading);
        let lateral = rel - heading * ahead;
        let in_the_way = ahead > -ctx.radii[leader as usize]
            && ahead < 2.0 * prm.leader_distance
            && lateral.length() < prm.leader_distance;
        let evade = in_the_way.then(|| {
            let side = unit_or(lateral, heading.perp());
            self.steer_towards(side - heading * 0.5, vel) * LEADER_EVADE_WEIGHT
        });
        Guide { name: "follow leader", steer, to_goal: to, parked: false, flock: true, evade }
    }

    /// Reynolds' path following: predict the position `path_lookahead` ahead; inside the
    /// corridor, steer along the path; outside it, seek the path point `path_lookahead` beyond
    /// the predicted position's projection. `None` once the agent has reached the end (the
    /// group's goal takes over for good); without a goal, it stays at the end.
    fn follow_path(&self, path: &PathSpec, group: &GroupView, k: usize, p: Vec2, vel: Vec2) -> Option<Guide> {
        let prm = &self.params;
        let seg = self.path_segment.get(k).copied().filter(|&s| s != UNPLACED).unwrap_or(0) as usize;
        let here = path.closest_point_in(p, seg..seg + 3)?;
        let done = self.path_done.get(k).copied().unwrap_or(false);
        if done || at_path_end(path, here.along, p) {
            return if group.goal.is_some() {
                None
            } else {
                let end = path.point_at(path.length());
                let (steer, to, parked) = self.seek_goal(Some((end, path.radius)), p, vel, prm.max_speed);
                Some(Guide { name: "path end", steer, to_goal: to, parked, flock: !parked, evade: None })
            };
        }
        let ahead = unit_or(vel, here.direction);
        let future = p + ahead * prm.path_lookahead;
        let projected = path.closest_point_in(future, seg..seg + 3)?;
        let along = projected.along.max(here.along);
        let target = path.point_at(along + prm.path_lookahead);
        let direction =
            if future.distance(projected.point) > path.radius || p.distance(here.point) > path.radius {
                target - p
            } else {
                target - here.point
            };
        Some(Guide::new("follow path", self.steer_towards(direction, vel), direction))
    }

    /// Evasion of predators in sight: away from their predicted positions, nearer ones more.
    fn flee(&self, ctx: &StepContext, p: Vec2, vel: Vec2, id: u32) -> Option<Vec2> {
        let prm = &self.params;
        let mut away = Vec2::ZERO;
        let mut seen = false;
        ctx.grid.for_each_within_capped(p, prm.flee_radius, NEIGHBOUR_CAP, |n| {
            if n.id != id && role_of(ctx, n.id) == Role::Predator {
                // Until they would meet head-on: the predicted point stays between the two, so
                // fleeing never turns the prey towards a fast predator.
                let t = (n.d2.sqrt() / (n.vel.length() + prm.max_speed)).min(MAX_PREDICTION_STEPS);
                let from = p - (n.pos + n.vel * t);
                let d2 = from.length_squared().max(1.0);
                away += from / d2;
                seen = true;
            }
        });
        seen.then(|| self.steer_towards(away, vel))
    }

    /// `desired − velocity` with the desired velocity along `direction` at max speed, limited.
    #[inline]
    fn steer_towards(&self, direction: Vec2, velocity: Vec2) -> Vec2 {
        let len = length(direction);
        if len <= 1e-9 {
            return Vec2::ZERO;
        }
        limit(direction * (self.params.max_speed / len) - velocity, self.params.max_force)
    }

    /// Whisker obstacle avoidance: a forward probe and two shorter side probes; a touching
    /// probe yields a force along the surface normal plus a sideways push (lecture, "Obstacle
    /// Avoidance"), stronger the nearer the hit.
    ///
    /// The whiskers' length is `whisker_length` at top speed and shrinks with the speed: they
    /// look as many steps ahead at any speed (Reynolds' look-ahead is a time, not a distance).
    /// With a fixed length, a crowd waiting at a door a few bodies wide never went through:
    /// the barely moving agents at its mouth, heading wherever the crowd's jostling turned
    /// them, had whiskers touching the wall round the door and were pushed back from it, and
    /// under priority arbitration that push took the whole force budget before seeking had
    /// any. An agent that has (almost) stopped has whiskers of about its own radius, pointing
    /// along `to_goal`.
    fn avoid_obstacles(&self, ctx: &StepContext, p: Vec2, vel: Vec2, radius: f32, to_goal: Vec2) -> Vec2 {
        if ctx.obstacles.is_empty() || self.params.whisker_length <= 0.0 {
            return Vec2::ZERO;
        }
        let ahead = self.params.whisker_length * (length(vel) / self.params.max_speed).min(1.0);
        let heading = unit_or(vel, unit_or(to_goal, Vec2::X));
        let side = self.side_whisker;
        let whiskers = [
            heading * (ahead + radius),
            side.rotate(heading) * (ahead * SIDE_WHISKER_SCALE + radius),
            Vec2::new(side.x, -side.y).rotate(heading) * (ahead * SIDE_WHISKER_SCALE + radius),
        ];
        let reach = ahead + radius;
        let query = Aabb { min: p - Vec2::splat(reach), max: p + Vec2::splat(reach) };
        let mut force = Vec2::ZERO;
        for (w, whisker) in whiskers.iter().enumerate() {
            let mut nearest: Option<(f32, Vec2)> = None;
            ctx.obstacles.for_each_near(query, |_, o: &Obstacle| {
                if let Some(hit) = o.ray_cast(p, *whisker) {
                    if nearest.is_none_or(|(t, _)| hit.t < t) {
                        nearest = Some((hit.t, hit.normal));
                    }
                }
            });
            let Some((t, normal)) = nearest else { continue };
            // Sideways component of the normal; a head-on hit turns left (whisker 0) so the
            // agent never brakes straight into the surface.
            let mut lateral = normal - heading * normal.dot(heading);
            if lateral.length_squared() < 1e-4 {
                lateral = if w == 2 { -heading.perp() } else { heading.perp() };
            }
            let desired = normal + unit_or(lateral, heading.perp());
            force += self.steer_towards(desired, vel) * (1.5 - t);
        }
        limit(force, self.params.max_force)
    }

    /// Reynolds' "stay within walls": near a border, desire a velocity pointing back inside.
    fn contain(&self, ctx: &StepContext, p: Vec2, vel: Vec2) -> Vec2 {
        let margin = self.params.perception_radius.min(0.25 * ctx.bounds.x.min(ctx.bounds.y));
        let s = self.params.max_speed;
        let mut desired = vel;
        let mut near = false;
        if p.x < margin {
            desired.x = s;
            near = true;
        } else if p.x > ctx.bounds.x - margin {
            desired.x = -s;
            near = true;
        }
        if p.y < margin {
            desired.y = s;
            near = true;
        } else if p.y > ctx.bounds.y - margin {
            desired.y = -s;
            near = true;
        }
        if near {
            self.steer_towards(desired, vel)
        } else {
            Vec2::ZERO
        }
    }
}

impl Planner for Boids {
    fn interaction_radius(&self) -> f32 {
        self.params.perception_radius.max(self.params.separation_radius)
    }

    fn max_speed(&self) -> f32 {
        self.params.max_speed
    }

    /// Prey must still flee once at their goal: they are not gathered.
    fn plan(&mut self, ctx: &StepContext, group: GroupView, _rng: &mut Rng, new_velocities: &mut [Vec2]) {
        self.prepare(ctx, &group);
        // Pass 1: the neighbour sums of every agent. Pass 2: the rule forces from them, in id
        // order. Apart, each loop is small enough for the CPU to overlap consecutive agents
        // (pass 2 is chains of square roots and divisions).
        let mut sums = std::mem::take(&mut self.sums);
        sums.clear();
        sums.resize(group.agents.len(), FlockSums::default());
        let mut block = std::mem::take(&mut self.candidates);
        let mut sample = std::mem::take(&mut self.sample);
        let reach = self.interaction_radius();
        let everyone_is_own = group.agents.start == 0 && group.agents.end as usize >= ctx.positions.len();
        let sep_r = self.params.separation_radius;
        let columns = ctx.grid.columns();
        let mut visits = Visits::default();
        let mut sum_one = |id: u32, p: Vec2, (from, runs): (Columns, &[Range<usize>])| {
            if let Some(out) = sums.get_mut((id - group.agents.start) as usize) {
                let tested: usize = runs.iter().map(ExactSizeIterator::len).sum();
                visits.count(tested);
                *out = flock_sums(from, runs, p, reach, sep_r, &group.agents, everyone_is_own);
            }
        };
        let grid_agents = ctx.grid.ids_in_cell_order().len();
        if grid_agents == ctx.positions.len() && group.agents.len() * 4 >= grid_agents {
            // Cell by cell: the agents of a cell share their candidates (sampled once per cell
            // in a pile), and the cells they read stay in the cache.
            ctx.grid.for_each_candidate_block(reach, &mut block, |slots, runs| {
                let tested = flock_candidates(columns, runs, &mut sample);
                for k in slots {
                    let id = columns.ids[k];
                    if group.agents.contains(&id) {
                        sum_one(id, Vec2::new(columns.x[k], columns.y[k]), tested);
                    }
                }
            });
        } else {
            // A small group among many agents: gather for its own agents only.
            for id in group.agents.clone() {
                let p = ctx.positions[id as usize];
                ctx.grid.candidate_runs(p, reach, &mut block);
                sum_one(id, p, flock_candidates(columns, &block, &mut sample));
            }
        }
        self.visits = visits;
        // Plain rules four agents at a time (the same arithmetic lane by lane), the rest and
        // every extension one at a time.
        let four_at_a_time = if self.is_plain(ctx) { sums.len() / LANES * LANES } else { 0 };
        for k in (0..four_at_a_time).step_by(LANES) {
            if let (Some(out), Some(neighbours)) =
                (new_velocities.get_mut(k..k + LANES), sums.get(k..k + LANES))
            {
                out.copy_from_slice(&self.plan_four(ctx, &group, k, neighbours));
            }
        }
        for ((k, id), (out, &neighbours)) in
            group.agents.clone().enumerate().zip(new_velocities.iter_mut().zip(&sums)).skip(four_at_a_time)
        {
            let forces = self.agent_forces(ctx, &group, k, id, neighbours);
            *out = limit(ctx.velocities[id as usize] + forces.acceleration, self.params.max_speed);
        }
        self.candidates = block;
        self.sample = sample;
        self.sums = sums;
    }

    fn explain(&self, ctx: &StepContext, group: &GroupView, agent: u32) -> Explanation {
        let k = agent.saturating_sub(group.agents.start) as usize;
        let mut sums = FlockSums::default();
        if let Some(&p) = ctx.positions.get(agent as usize) {
            let mut runs = CandidateRuns::default();
            ctx.grid.candidate_runs(p, self.interaction_radius(), &mut runs);
            let everyone_is_own = group.agents.start == 0 && group.agents.end as usize >= ctx.positions.len();
            let sep_r = self.params.separation_radius;
            let mut sample = CandidateSample::default();
            let (columns, runs) = flock_candidates(ctx.grid.columns(), &runs, &mut sample);
            sums = flock_sums(
                columns,
                runs,
                p,
                self.interaction_radius(),
                sep_r,
                &group.agents,
                everyone_is_own,
            );
        }
        let forces = self.agent_forces(ctx, group, k, agent, sums);
        let mut e = Explanation::default();
        for &(name, force) in &forces.weighted[..forces.used] {
            e.vectors.push(NamedVector::new(name, force));
        }
        e.applied = forces.acceleration;
        if let Some(&p) = ctx.positions.get(agent as usize) {
            // The agents flock_sums counts: within reach, not at the agent's own position.
            ctx.grid.for_each_within(p, self.interaction_radius(), |n| {
                if n.id != agent && n.d2 > 0.0 {
                    e.neighbours.push(n.id);
                }
            });
        }
        e.state = match (forces.parked, forces.fleeing) {
            (_, true) => "fleeing a predator".into(),
            (true, false) => "parked in the goal".into(),
            (false, false) => "steering".into(),
        };
        e
    }
}

/// The rule forces of one agent in one step.
struct AgentForces {
    /// Named weighted forces in arbitration order: obstacle avoidance, (fleeing or leaving the
    /// leader's way, when active), separation, seek (or the guidance replacing it), alignment,
    /// cohesion. Only the first `used` entries are forces.
    weighted: [(&'static str, Vec2); 6],
    /// How many entries of `weighted` hold forces.
    used: usize,
    /// The acceleration the arbitration makes of them.
    acceleration: Vec2,
    /// Inside the goal: braking, only keeping its distance.
    parked: bool,
    /// A predator is in sight (prey only).
    fleeing: bool,
}

/// Guidance that replaces seeking the goal (pursuit, leader, path, flow field).
struct Guide {
    /// Name of the force in explanations.
    name: &'static str,
    /// Its steering force (unweighted).
    steer: Vec2,
    /// The way the agent wants to go (fallback heading of the whiskers).
    to_goal: Vec2,
    /// Parked: braking inside its goal.
    parked: bool,
    /// Whether alignment and cohesion apply (a leader ignores its followers).
    flock: bool,
    /// An urgent force that comes right after obstacle avoidance (leaving the leader's way).
    evade: Option<Vec2>,
}

impl Guide {
    fn new(name: &'static str, steer: Vec2, to_goal: Vec2) -> Self {
        Self { name, steer, to_goal, parked: false, flock: true, evade: None }
    }
}

/// Whether an agent at `p`, whose closest path point lies `along` the path, has reached the
/// path's end: within the corridor's half-width of the last point, on its last stretch.
fn at_path_end(path: &PathSpec, along: f32, p: Vec2) -> bool {
    let length = path.length();
    along >= length - path.radius && p.distance(path.point_at(length)) <= path.radius
}

/// A planner's role read from another group's settings (only Boids groups have one).
fn role_of(ctx: &StepContext, agent: u32) -> Role {
    let group = ctx.group_of.get(agent as usize).and_then(|&g| ctx.scene.groups.get(g as usize));
    match group.map(|g| &g.planner) {
        Some(crate::model::params::PlannerConfig::Boids(p)) => p.role,
        _ => Role::None,
    }
}

/// The nearest agent of `role` within `radius` of `p` (not `me`), ties by id.
fn nearest_of_role(ctx: &StepContext, p: Vec2, radius: f32, role: Role, me: u32) -> Option<Neighbour> {
    let mut best: Option<Neighbour> = None;
    ctx.grid.for_each_within_capped(p, radius, NEIGHBOUR_CAP, |n| {
        if n.id != me && best.is_none_or(|b| (n.d2, n.id) < (b.d2, b.id)) && role_of(ctx, n.id) == role {
            best = Some(n);
        }
    });
    best
}

impl Boids {
    /// Every rule force of agent `id` from the step's state and its neighbour sums.
    /// `plan` and `explain` both call it, so an explanation is exactly what the step applies.
    #[inline(always)]
    fn agent_forces(
        &self,
        ctx: &StepContext,
        group: &GroupView,
        k: usize,
        id: u32,
        sums: FlockSums,
    ) -> AgentForces {
        let prm = &self.params;
        let i = id as usize;
        let p = ctx.positions[i];
        let vel = ctx.velocities[i];
        let (sep, sum_vel, sum_pos, n_flock) = (sums.separation, sums.velocity, sums.position, sums.flocking);

        let separation = self.steer_towards(sep, vel);
        let (alignment, cohesion) = if n_flock > 0 {
            let inv = 1.0 / n_flock as f32;
            (self.steer_towards(sum_vel * inv, vel), self.steer_towards(sum_pos * inv - p, vel))
        } else {
            (Vec2::ZERO, Vec2::ZERO)
        };
        // Without an extension this is plain seeking, computed exactly as it always was.
        let (seek_name, seek, to_goal, mut parked, flock, evade) = match self.guide(ctx, group, k, id, p, vel)
        {
            Some(g) => (g.name, g.steer, g.to_goal, g.parked, g.flock, g.evade),
            None => {
                let (seek, to, parked) = self.seek_goal(group.goal, p, vel, prm.max_speed);
                ("seek", seek, to, parked, true, None)
            }
        };
        let flee = if prm.role == Role::Prey { self.flee(ctx, p, vel, id) } else { None };
        let fleeing = flee.is_some();
        // A threatened prey leaves its parking spot; its flocking weights change (lecture).
        parked &= !fleeing;
        let (w_sep, w_align, w_coh) = if fleeing {
            (prm.fleeing_separation_weight, prm.fleeing_alignment_weight, prm.fleeing_cohesion_weight)
        } else {
            (prm.separation_weight, prm.alignment_weight, prm.cohesion_weight)
        };
        let (alignment, cohesion) =
            if parked || !flock { (Vec2::ZERO, Vec2::ZERO) } else { (alignment, cohesion) };
        let avoid = self.avoid_obstacles(ctx, p, vel, ctx.radii[i], to_goal) + self.contain(ctx, p, vel);

        let mut weighted = [("", Vec2::ZERO); 6];
        let mut used = 0;
        let mut push = |name: &'static str, force: Vec2| {
            weighted[used] = (name, force);
            used += 1;
        };
        push("obstacle avoidance", avoid * prm.avoid_weight);
        if let Some(f) = flee {
            push("flee predator", f * prm.flee_weight);
        } else if let Some(f) = evade {
            push("leave leader's way", f);
        }
        push("separation", separation * w_sep);
        push(seek_name, seek * prm.seek_weight);
        push("alignment", alignment * w_align);
        push("cohesion", cohesion * w_coh);
        let forces = weighted.iter().take(used).map(|&(_, f)| f);
        let acceleration = match prm.arbitration {
            Arbitration::Weighted => limit(forces.sum(), prm.max_force),
            Arbitration::Priority => {
                let mut acc = Vec2::ZERO;
                let mut budget = prm.max_force;
                for f in forces {
                    let len = length(f);
                    if len <= budget {
                        acc += f;
                        budget -= len;
                    } else {
                        acc += f * (budget / len);
                        break;
                    }
                }
                acc
            }
        };
        AgentForces { weighted, used, acceleration, parked, fleeing }
    }
}

impl Boids {
    /// Whether the group steers by the plain rules [`Self::plan_four`] computes: no predator or
    /// prey role, no leader, no path, no flow field.
    fn is_plain(&self, ctx: &StepContext) -> bool {
        let prm = &self.params;
        prm.role == Role::None
            && prm.leader == Leader::None
            && prm.flow_field != FlowGuide::Goal
            && self.followed_path(ctx).is_none()
    }

    /// [`Self::steer_towards`] per lane.
    #[inline]
    fn steer_four(&self, direction: Lanes2, velocity: Lanes2) -> Lanes2 {
        let len = direction.length();
        let steer = (direction.scale(Vec4::splat(self.params.max_speed) / len) - velocity)
            .limit(self.params.max_force);
        Lanes2::select(len.cmple(Vec4::splat(1e-9)), Lanes2::ZERO, steer)
    }

    /// The new velocities of the four agents `group.agents.start + k ..` with neighbour sums
    /// `sums`, for plain rules ([`Self::is_plain`]): what [`Self::agent_forces`] and `plan` give
    /// one agent at a time, bit for bit, with the square roots and divisions of four agents in
    /// one go instead of four chains of them.
    fn plan_four(&self, ctx: &StepContext, group: &GroupView, k: usize, sums: &[FlockSums]) -> [Vec2; LANES] {
        let prm = &self.params;
        let id = |j: usize| group.agents.start as usize + k + j;
        let p = Lanes2::from_fn(|j| ctx.positions[id(j)]);
        let vel = Lanes2::from_fn(|j| ctx.velocities[id(j)]);
        let count = Vec4::new(
            sums[0].flocking as f32,
            sums[1].flocking as f32,
            sums[2].flocking as f32,
            sums[3].flocking as f32,
        );
        let flocking = count.cmpgt(Vec4::ZERO);

        let separation = self.steer_four(Lanes2::from_fn(|j| sums[j].separation), vel);
        let inv = Vec4::ONE / count;
        let alignment = self.steer_four(Lanes2::from_fn(|j| sums[j].velocity).scale(inv), vel);
        let cohesion = self.steer_four(Lanes2::from_fn(|j| sums[j].position).scale(inv) - p, vel);
        // Seek with arrival, as `seek_goal`.
        let (seek, to_goal, parked) = match group.goal {
            Some((goal, goal_radius)) => {
                let to = Lanes2::splat(goal) - p;
                let d = to.length();
                let parked = d.cmple(Vec4::splat(goal_radius));
                let ramp =
                    lanes::clamp((d - Vec4::splat(goal_radius)) / Vec4::splat(prm.arrival_radius), 0.1, 1.0);
                let speed = Vec4::select(parked, Vec4::ZERO, Vec4::splat(prm.max_speed) * ramp);
                let desired = Lanes2::select(d.cmpgt(Vec4::splat(1e-6)), to.scale(speed / d), Lanes2::ZERO);
                ((desired - vel).limit(prm.max_force), to, parked)
            }
            None => (Lanes2::ZERO, Lanes2::splat(Vec2::X), BVec4A::FALSE),
        };
        let flock = flocking & !parked;
        let alignment = Lanes2::select(flock, alignment, Lanes2::ZERO);
        let cohesion = Lanes2::select(flock, cohesion, Lanes2::ZERO);
        // Obstacles and borders: per agent (whisker queries), as `agent_forces`.
        let avoid = Lanes2::from_fn(|j| {
            let (pj, vj) = (p.lane(j), vel.lane(j));
            self.avoid_obstacles(ctx, pj, vj, ctx.radii[id(j)], to_goal.lane(j)) + self.contain(ctx, pj, vj)
        });
        let weighted = [
            avoid.scale(Vec4::splat(prm.avoid_weight)),
            separation.scale(Vec4::splat(prm.separation_weight)),
            seek.scale(Vec4::splat(prm.seek_weight)),
            alignment.scale(Vec4::splat(prm.alignment_weight)),
            cohesion.scale(Vec4::splat(prm.cohesion_weight)),
        ];
        let acceleration = match prm.arbitration {
            Arbitration::Weighted => {
                weighted.iter().fold(Lanes2::ZERO, |acc, &f| acc + f).limit(prm.max_force)
            }
            Arbitration::Priority => {
                let (mut acc, mut budget, mut done) =
                    (Lanes2::ZERO, Vec4::splat(prm.max_force), BVec4A::FALSE);
                for f in weighted {
                    let len = f.length();
                    let fits = len.cmple(budget);
                    let share = Lanes2::select(fits, f, f.scale(budget / len));
                    acc = Lanes2::select(done, acc, acc + share);
                    budget = Vec4::select(done | !fits, budget, budget - len);
                    done |= !fits;
                }
                acc
            }
        };
        let new_velocity = (vel + acceleration).limit(prm.max_speed);
        std::array::from_fn(|j| new_velocity.lane(j))
    }
}

/// Most candidates (agents of the cells round an agent, within reach or not) [`flock_sums`]
/// tests one by one. The 3 × 3 cells of perception size round an agent (150 × 150 px with the
/// default 50 px) hold at most 361 bodies of the default 4 px radius on the spawn's lattice
/// (one per 8 × 8 px) and 418 touching in the densest (hexagonal) packing, so only a crowd
/// pressed into overlapping or a pile has more; then [`FLOCK_SAMPLE`] of them, evenly spaced,
/// stand for all ([`flock_candidates`]), which bounds an agent's work however dense the pile.
pub const FLOCK_SAMPLE_ABOVE: usize = 448;

/// Candidates sampled from cells holding more than [`FLOCK_SAMPLE_ABOVE`]. Alignment and
/// cohesion are means over the flockmates found, and separation steers along the direction of
/// its sum: an even sample of the neighbourhood estimates all three without scaling.
pub const FLOCK_SAMPLE: usize = 384;

/// The candidates [`flock_sums`] tests for the candidate runs `runs` of `columns`: the runs
/// themselves, or in a pile (more than [`FLOCK_SAMPLE_ABOVE`]) [`FLOCK_SAMPLE`] of them,
/// evenly spaced, copied into `sample` ([`CandidateSample`]).
fn flock_candidates<'a>(
    columns: Columns<'a>,
    runs: &'a CandidateRuns,
    sample: &'a mut CandidateSample,
) -> (Columns<'a>, &'a [Range<usize>]) {
    if runs.len() <= FLOCK_SAMPLE_ABOVE {
        (columns, runs.runs())
    } else {
        sample.fill(columns, runs.runs(), FLOCK_SAMPLE);
        (sample.columns(), sample.runs())
    }
}

/// How many candidates a [`Boids`] step tested for its neighbour sums, counted per agent.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Visits {
    /// Agents whose sums were computed.
    pub agents: u64,
    /// Candidates tested, all agents together.
    pub total: u64,
    /// The most candidates one agent tested.
    pub max_per_agent: u64,
}

impl Visits {
    fn count(&mut self, tested: usize) {
        self.agents += 1;
        self.total += tested as u64;
        self.max_per_agent = self.max_per_agent.max(tested as u64);
    }
}

/// The neighbour sums of the agent at `p` over the candidates `runs` of `columns`: every agent
/// within `reach` of it except those at exactly its position (itself), the separation terms of
/// those closer than `separation_radius`, velocity and position sums of those in `own_group`.
///
/// The candidates are tested four at a time (one SIMD register natively and in wasm) without a
/// branch: whether a candidate is within reach is a coin flip the CPU cannot predict. Each lane
/// keeps its own partial sums, added up in a fixed order at the end; every lane operation is
/// one correctly rounded IEEE operation, so the result is the same with or without SIMD,
/// natively and in wasm.
#[inline]
fn flock_sums(
    columns: Columns<'_>,
    runs: &[Range<usize>],
    p: Vec2,
    reach: f32,
    separation_radius: f32,
    own_group: &Range<u32>,
    everyone_is_own: bool,
) -> FlockSums {
    let (px, py) = (Vec4::splat(p.x), Vec4::splat(p.y));
    let (reach2, sep2) = (Vec4::splat(reach * reach), Vec4::splat(separation_radius * separation_radius));
    let [mut sep_x, mut sep_y, mut vel_x, mut vel_y, mut pos_x, mut pos_y] = [Vec4::ZERO; 6];
    // The flocking count as floats (exact up to 2^24): a lane add, where a population count
    // is a dozen instructions on the x86-64 baseline.
    let mut flocking = Vec4::ZERO;
    // Adds the block of four candidates from storage slot `at` on (positions and velocities
    // `x`, `y`, `vx`, `vy`) whose lanes `in_run` belong to the run.
    let mut add = |at: usize, [x, y, vx, vy]: [Vec4; 4], in_run: BVec4A| {
        let (dx, dy) = (px - x, py - y);
        let d2 = dx * dx + dy * dy;
        let within = d2.cmple(reach2) & d2.cmpgt(Vec4::ZERO) & in_run;
        let close = within & d2.cmplt(sep2);
        let own = if everyone_is_own {
            within
        } else {
            let is_own = |j: usize| columns.ids.get(at + j).is_some_and(|id| own_group.contains(id));
            within & BVec4A::new(is_own(0), is_own(1), is_own(2), is_own(3))
        };
        // One division for both axes (division is the slowest lane operation).
        let inv_d2 = d2.recip();
        sep_x += Vec4::select(close, dx * inv_d2, Vec4::ZERO);
        sep_y += Vec4::select(close, dy * inv_d2, Vec4::ZERO);
        vel_x += Vec4::select(own, vx, Vec4::ZERO);
        vel_y += Vec4::select(own, vy, Vec4::ZERO);
        pos_x += Vec4::select(own, x, Vec4::ZERO);
        pos_y += Vec4::select(own, y, Vec4::ZERO);
        flocking += Vec4::select(own, Vec4::ONE, Vec4::ZERO);
    };
    for run in runs {
        // The run's whole blocks of four as exact chunks (no bounds test, no mask per block),
        // then its last, partial block, masked: the same blocks in the same order as reading
        // four at a time from the run's start, so the same lanes add the same terms.
        let whole = run.start..run.start + run.len() / LANES * LANES;
        let [x, y, vx, vy] =
            [columns.x, columns.y, columns.vx, columns.vy].map(|s| s.get(whole.clone()).unwrap_or_default());
        let blocks = x
            .chunks_exact(LANES)
            .zip(y.chunks_exact(LANES))
            .zip(vx.chunks_exact(LANES))
            .zip(vy.chunks_exact(LANES));
        let mut done = whole.start;
        for (((x, y), vx), vy) in blocks {
            let lanes = [x, y, vx, vy].map(Vec4::from_slice);
            add(done, lanes, RUN_MASKS[LANES]);
            done += LANES;
        }
        // A column shorter than the run (never: the grid pads them) falls back to reading
        // block by block, NaN past the end (no lane within reach).
        for at in (done..run.end).step_by(LANES) {
            let load = |s: &[f32]| s.get(at..at + LANES).map_or(Vec4::NAN, Vec4::from_slice);
            let lanes = [columns.x, columns.y, columns.vx, columns.vy].map(load);
            // Lanes past the run's end hold the next cells' agents or padding.
            add(at, lanes, RUN_MASKS[(run.end - at).min(LANES)]);
        }
    }
    let total = |l: Vec4| (l.x + l.y) + (l.z + l.w);
    FlockSums {
        separation: Vec2::new(total(sep_x), total(sep_y)),
        velocity: Vec2::new(total(vel_x), total(vel_y)),
        position: Vec2::new(total(pos_x), total(pos_y)),
        flocking: total(flocking) as u32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{presets, PlannerConfig, World};

    /// `plan` (plain rules four agents at a time) gives every agent the velocity that the
    /// one-at-a-time forces (`explain`, hence `agent_forces`) give, bit for bit: both
    /// arbitrations, with a goal, obstacles and borders.
    #[test]
    fn four_at_a_time_equals_one_at_a_time() {
        for arbitration in [Arbitration::Priority, Arbitration::Weighted] {
            let mut scene = presets::pillars();
            for g in &mut scene.groups {
                if let PlannerConfig::Boids(p) = &mut g.planner {
                    p.arbitration = arbitration;
                }
                g.count = 203; // not a multiple of four: the tail goes one at a time
            }
            let mut world = World::new(scene).expect("valid");
            let mut checked = 0;
            for _ in 0..6 {
                world.step_n(40);
                let ctx = world.step_context();
                for g in 0..world.scene().groups.len() {
                    let PlannerConfig::Boids(params) = world.scene().groups[g].planner.clone() else {
                        continue;
                    };
                    let view = world.group_view(g).expect("group");
                    let mut planner = Boids::new(params);
                    assert!(planner.is_plain(&ctx));
                    let mut planned = vec![Vec2::ZERO; view.agents.len()];
                    planner.plan(&ctx, view.clone(), &mut Rng::new(1, 1), &mut planned);
                    for (k, id) in view.agents.clone().enumerate() {
                        let e = planner.explain(&ctx, &view, id);
                        let one = limit(ctx.velocities[id as usize] + e.applied, planner.params.max_speed);
                        assert_eq!(
                            planned[k].to_array().map(f32::to_bits),
                            one.to_array().map(f32::to_bits),
                            "{arbitration:?} agent {id}: {:?} vs {one:?}",
                            planned[k]
                        );
                        checked += 1;
                    }
                }
            }
            assert!(checked >= 6 * 200, "{checked} agents checked");
        }
    }

    /// `count` Boids agents at the positions of a fixed low-discrepancy pattern over a `side` px
    /// square at (100, 100), heading for a goal on the right: a jam no spawn makes (the spawn
    /// keeps bodies apart) but a converging crowd can reach.
    fn pile(count: u32, side: f32) -> World {
        let mut scene = presets::constant_density(count, 9.0);
        scene.groups[0].spawn = crate::Region { min: [100.0, 100.0], max: [100.0 + side, 100.0 + side] };
        let positions = (0..count)
            .map(|i| {
                let u = (f64::from(i) + 0.5) / f64::from(count);
                let v = (f64::from(i) * 0.618_033_988_749_894_9).fract();
                Vec2::new(100.0 + side * u as f32, 100.0 + side * v as f32)
            })
            .collect();
        World::new_at(scene, positions).expect("valid scene")
    }

    /// Plans one step of group 0 of `world` as the world would: the planner and what it visited.
    fn plan_group_0(world: &World) -> (Boids, Vec<Vec2>) {
        let ctx = world.step_context();
        let PlannerConfig::Boids(params) = world.scene().groups[0].planner.clone() else {
            panic!("a Boids group");
        };
        let view = world.group_view(0).expect("group");
        let mut planner = Boids::new(params);
        let mut planned = vec![Vec2::ZERO; view.agents.len()];
        planner.plan(&ctx, view, &mut Rng::new(1, 1), &mut planned);
        (planner, planned)
    }

    /// In a pile of 5,000 agents within 40 × 40 px, the cells round every agent hold all 5,000:
    /// each agent's neighbour sums test exactly [`FLOCK_SAMPLE`] of them (counted), not 5,000
    /// (or the 1,024 of the former cap), and `explain` sees the same sample as `plan`.
    #[test]
    fn a_jammed_step_tests_at_most_the_sample_per_agent() {
        let n = 5_000;
        let world = pile(n, 40.0);
        let ctx = world.step_context();
        let mut runs = CandidateRuns::default();
        let reach = BoidsParams::default().perception_radius;
        ctx.grid.candidate_runs(world.positions()[0], reach, &mut runs);
        assert_eq!(runs.len(), n as usize, "every agent of the pile is a candidate of every other");
        let (planner, planned) = plan_group_0(&world);
        let visits = planner.visits();
        assert_eq!(visits.agents, u64::from(n));
        assert_eq!(visits.max_per_agent, FLOCK_SAMPLE as u64);
        assert_eq!(visits.total, u64::from(n) * FLOCK_SAMPLE as u64);
        assert!(planned.iter().all(|v| v.is_finite()));
        let view = world.group_view(0).expect("group");
        for id in (0..n).step_by(97) {
            let e = planner.explain(&ctx, &view, id);
            let one = limit(ctx.velocities[id as usize] + e.applied, planner.params.max_speed);
            assert_eq!(planned[id as usize].to_array().map(f32::to_bits), one.to_array().map(f32::to_bits));
        }
        // Separation still pushes the pile apart: the sampled sums are not zero.
        assert!(planned.iter().filter(|v| v.length() > 0.1).count() > n as usize / 2);
    }

    /// Crowds of 4 px bodies side by side never reach the sampling threshold, so every agent
    /// tests all its candidates as before sampling existed: the spawn at its density limit (one
    /// body per 8 × 8 px) and bodies touching in hexagonal packing, the densest there is.
    #[test]
    fn crowds_without_overlap_test_every_candidate() {
        let mut lattice = presets::constant_density(6_400, 9.0);
        lattice.groups[0].spawn = crate::Region { min: [100.0, 100.0], max: [740.0, 740.0] };
        lattice.groups[0].agent_radius = 4.0;
        let lattice = World::new(lattice).expect("valid scene at the density limit");
        let mut hex = presets::constant_density(6_400, 9.0);
        hex.groups[0].agent_radius = 4.0;
        let rows = 3.0_f32.sqrt() * 4.0;
        let positions = (0..6_400)
            .map(|i| {
                Vec2::new(
                    100.0 + 8.0 * (i % 80) as f32 + 4.0 * ((i / 80) % 2) as f32,
                    100.0 + rows * (i / 80) as f32,
                )
            })
            .collect();
        let hex = World::new_at(hex, positions).expect("valid hexagonal crowd");
        for (name, world) in [("lattice", lattice), ("hexagonal", hex)] {
            let (planner, _) = plan_group_0(&world);
            let ctx = world.step_context();
            let reach = planner.interaction_radius();
            let mut runs = CandidateRuns::default();
            let all: usize = world
                .positions()
                .iter()
                .map(|&p| {
                    ctx.grid.candidate_runs(p, reach, &mut runs);
                    runs.len()
                })
                .sum();
            let visits = planner.visits();
            assert_eq!(visits.total, all as u64, "{name}: no agent was sampled");
            assert!(visits.max_per_agent <= FLOCK_SAMPLE_ABOVE as u64, "{name}: {visits:?}");
            assert!(visits.max_per_agent >= 300, "{name}: the crowd is dense: {visits:?}");
        }
    }
}
