//! Reynolds steering as taught in the group-animation lecture (DESIGN §3.1).
//!
//! Each rule yields a steering force `desired − velocity` limited by `max_force` (lecture,
//! "Rule 1–3" pseudocode); the rules are combined by a weighted sum or by priority allocation
//! ("Arbitration"), then `v += a; v = limit(v, max_speed); p += v` (lecture, `Boid::update`).

use super::{limit, GroupView, ParamSpec, Planner, StepContext};
use crate::diagnose::{Explanation, NamedVector};
use crate::flow_field::{self, FlowField};
use crate::geometry::{unit_or, Aabb, Obstacle};
use crate::rng::Rng;
use crate::scene::PathSpec;
use crate::spatial::Neighbour;
use glam::Vec2;
use serde::{Deserialize, Serialize};

/// How the rules' forces are combined into one acceleration.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Arbitration {
    /// `a = limit(Σ wᵢ Fᵢ, max_force)`: the lecture's weighted summation.
    Weighted,
    /// Reynolds' prioritised allocation: obstacle avoidance, containment, separation, seek,
    /// alignment, cohesion, each weighted force added while the `max_force` budget remains.
    Priority,
}

/// Boids parameters. Lengths in px, speeds in px/step, forces in px/step².
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BoidsParams {
    /// Neighbours within this distance are seen (alignment, cohesion). Default 50 px.
    pub perception_radius: f32,
    /// Neighbours closer than this push away (separation). Default 14 px: 3.5 body radii, so a
    /// group fits a goal of 60 px radius without piling up.
    pub separation_radius: f32,
    /// Speed limit. Default 2 px/step (120 px/s at 60 steps/s).
    pub max_speed: f32,
    /// Steering force (acceleration) limit. Default 0.15 px/step².
    pub max_force: f32,
    /// Separation weight; the lecture's 1.5.
    pub separation_weight: f32,
    /// Alignment weight; the lecture's 1.0.
    pub alignment_weight: f32,
    /// Cohesion weight; the lecture's 1.0.
    pub cohesion_weight: f32,
    /// Weight of seeking the group's goal. Default 1.0.
    pub seek_weight: f32,
    /// Weight of obstacle avoidance and boundary containment. Default 3.0.
    pub avoid_weight: f32,
    /// Length of the forward whisker that probes for obstacles. Default 50 px.
    pub whisker_length: f32,
    /// Over this distance before the goal's edge the desired speed ramps down (arrival); inside
    /// the goal agents park (brake, keep their distance). Default 60 px.
    pub arrival_radius: f32,
    /// How the forces are combined.
    pub arbitration: Arbitration,
    /// Followers aim at the point this far behind the leader (px). Default 30.
    pub leader_distance: f32,
    /// The leader's speed as a share of max speed, so followers can keep up. Default 0.75.
    pub leader_speed: f32,
    /// Leader following: `first` makes the group's first agent the leader; the others follow it.
    pub leader: Leader,
    /// Path following looks this far ahead of the agent (px) for its predicted position. Default 30.
    pub path_lookahead: f32,
    /// The scene path this group follows, 1-based; 0 (the default) follows none, and so does a
    /// number beyond the scene's paths (a documented no-op: deleting a path never breaks a scene).
    pub path: u32,
    /// Flow field guidance: `goal` replaces straight seeking by the goal-derived flow field.
    pub flow_field: FlowGuide,
    /// Predators see prey within this distance (px). Default 400.
    pub chase_radius: f32,
    /// Prey see predators within this distance (px). Default 100.
    pub flee_radius: f32,
    /// Weight of fleeing from predators. Default 3.
    pub flee_weight: f32,
    /// Separation weight while fleeing (replaces `separation_weight`). Default 0.8: a threatened
    /// school closes up.
    pub fleeing_separation_weight: f32,
    /// Alignment weight while fleeing. Default 2.
    pub fleeing_alignment_weight: f32,
    /// Cohesion weight while fleeing. Default 2.
    pub fleeing_cohesion_weight: f32,
    /// Predator/prey role of the group's agents.
    pub role: Role,
}

/// Leader following (lecture, "Leader Following").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Leader {
    /// Every agent steers for itself.
    None,
    /// The group's first agent seeks the goal; the others arrive at a point behind it, leave its
    /// path when in front of it, and never overtake it.
    First,
}

/// Top-down guidance (lecture, "Flow Field").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FlowGuide {
    /// Seek the goal in a straight line.
    Off,
    /// Follow the flow field of the shortest obstacle-free ways to the goal
    /// ([`crate::flow_field`]), combined with the local rules.
    Goal,
}

/// Predator/prey role (lecture, "more complex behaviours").
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// Neither chases nor flees.
    None,
    /// Pursues the nearest prey within `chase_radius`, aiming at its predicted position.
    Predator,
    /// Flees predators within `flee_radius` (evading their predicted positions), with the
    /// fleeing weights of separation, alignment and cohesion while it sees one.
    Prey,
}

impl Default for BoidsParams {
    fn default() -> Self {
        Self {
            perception_radius: 50.0,
            separation_radius: 14.0,
            max_speed: 2.0,
            max_force: 0.15,
            separation_weight: 1.5,
            alignment_weight: 1.0,
            cohesion_weight: 1.0,
            seek_weight: 1.0,
            avoid_weight: 3.0,
            whisker_length: 50.0,
            arrival_radius: 60.0,
            arbitration: Arbitration::Weighted,
            leader_distance: 30.0,
            leader_speed: 0.75,
            leader: Leader::None,
            path_lookahead: 30.0,
            path: 0,
            flow_field: FlowGuide::Off,
            chase_radius: 400.0,
            flee_radius: 100.0,
            flee_weight: 3.0,
            fleeing_separation_weight: 0.8,
            fleeing_alignment_weight: 2.0,
            fleeing_cohesion_weight: 2.0,
            role: Role::None,
        }
    }
}

impl BoidsParams {
    /// The parameter table (sliders, range checks, docs).
    pub const SPECS: &'static [ParamSpec] = &[
        ParamSpec::number(
            "perception_radius",
            "Perception radius",
            "px",
            (5.0, 300.0, 1.0),
            50.0,
            "Neighbours closer than this are seen (alignment, cohesion).",
        ),
        ParamSpec::number(
            "separation_radius",
            "Separation radius",
            "px",
            (1.0, 200.0, 1.0),
            14.0,
            "Neighbours closer than this push the agent away.",
        ),
        ParamSpec::number(
            "max_speed",
            "Max speed",
            "px/step",
            (0.1, 20.0, 0.1),
            2.0,
            "Speed limit; one step is 1/60 s.",
        ),
        ParamSpec::number(
            "max_force",
            "Max force",
            "px/step²",
            (0.005, 2.0, 0.005),
            0.15,
            "Limit of the steering acceleration.",
        ),
        ParamSpec::number(
            "separation_weight",
            "Separation",
            "×",
            (0.0, 5.0, 0.1),
            1.5,
            "Weight of separation (lecture: 1.5).",
        ),
        ParamSpec::number(
            "alignment_weight",
            "Alignment",
            "×",
            (0.0, 5.0, 0.1),
            1.0,
            "Weight of alignment (lecture: 1.0).",
        ),
        ParamSpec::number(
            "cohesion_weight",
            "Cohesion",
            "×",
            (0.0, 5.0, 0.1),
            1.0,
            "Weight of cohesion (lecture: 1.0).",
        ),
        ParamSpec::number(
            "seek_weight",
            "Seek goal",
            "×",
            (0.0, 5.0, 0.1),
            1.0,
            "Weight of steering towards the group's goal.",
        ),
        ParamSpec::number(
            "avoid_weight",
            "Avoid obstacles",
            "×",
            (0.0, 10.0, 0.1),
            3.0,
            "Weight of whisker obstacle avoidance and boundary containment.",
        ),
        ParamSpec::number(
            "whisker_length",
            "Whisker length",
            "px",
            (0.0, 300.0, 1.0),
            50.0,
            "Length of the forward probe that detects obstacles.",
        ),
        ParamSpec::number(
            "arrival_radius",
            "Arrival radius",
            "px",
            (1.0, 500.0, 1.0),
            60.0,
            "Over this distance before the goal the agent slows down; inside it parks.",
        ),
        ParamSpec::choice(
            "arbitration",
            "Arbitration",
            &["weighted", "priority"],
            0,
            "Weighted sum of all rules, or priority allocation of the force budget.",
        ),
        // Extensions, appended (links store parameters by position); each feature's settings
        // come before its switch, see `ParamSpec::omitted_at_default`.
        ParamSpec::number(
            "leader_distance",
            "Follow distance",
            "px",
            (5.0, 200.0, 1.0),
            30.0,
            "Leader following: followers aim this far behind the leader.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "leader_speed",
            "Leader speed",
            "× max",
            (0.1, 1.0, 0.05),
            0.75,
            "Leader following: the leader walks at this share of max speed so followers keep up.",
        )
        .omitted_at_default(),
        ParamSpec::choice(
            "leader",
            "Leader",
            &["none", "first"],
            0,
            "first: the group's first agent leads to the goal; the others follow behind it.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "path_lookahead",
            "Path look-ahead",
            "px",
            (0.0, 200.0, 1.0),
            30.0,
            "Path following: how far ahead the agent predicts its position.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "path",
            "Follow path",
            "#",
            (0.0, 64.0, 1.0),
            0.0,
            "Number of the scene path the group follows (0 = none).",
        )
        .omitted_at_default(),
        ParamSpec::choice(
            "flow_field",
            "Flow field",
            &["off", "goal"],
            0,
            "goal: follow the shortest obstacle-free way to the goal instead of a straight line.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "chase_radius",
            "Chase radius",
            "px",
            (10.0, 2000.0, 10.0),
            400.0,
            "Predators see prey within this distance.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "flee_radius",
            "Flee radius",
            "px",
            (10.0, 1000.0, 5.0),
            100.0,
            "Prey see predators within this distance.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "flee_weight",
            "Flee",
            "×",
            (0.0, 10.0, 0.1),
            3.0,
            "Weight of fleeing from predators.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "fleeing_separation_weight",
            "Separation (fleeing)",
            "×",
            (0.0, 5.0, 0.1),
            0.8,
            "Separation weight while a predator is in sight.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "fleeing_alignment_weight",
            "Alignment (fleeing)",
            "×",
            (0.0, 5.0, 0.1),
            2.0,
            "Alignment weight while a predator is in sight.",
        )
        .omitted_at_default(),
        ParamSpec::number(
            "fleeing_cohesion_weight",
            "Cohesion (fleeing)",
            "×",
            (0.0, 5.0, 0.1),
            2.0,
            "Cohesion weight while a predator is in sight.",
        )
        .omitted_at_default(),
        ParamSpec::choice(
            "role",
            "Role",
            &["none", "predator", "prey"],
            0,
            "predator: chase the nearest prey; prey: flee predators in sight.",
        )
        .omitted_at_default(),
    ];
}

/// The Boids planner for one group.
#[derive(Clone, Debug)]
pub struct Boids {
    params: BoidsParams,
    /// Scratch: the neighbours of the agent being planned (reused to avoid allocating).
    near: Vec<NearAgent>,
    /// The flow field towards the goal and what it was built from (flow field guidance).
    flow: Option<(FlowKey, FlowField)>,
    /// Per agent of the group: the path segment it has reached (path following only moves on).
    path_segment: Vec<u32>,
    /// The leader's last heading while it moved (leader following).
    leader_heading: Vec2,
}

/// What a cached flow field depends on.
#[derive(Clone, Copy, Debug, PartialEq)]
struct FlowKey {
    goal_cell: (i32, i32),
    obstacles: u64,
    bounds: Vec2,
    clearance: f32,
}

/// Segment index meaning "not placed on the path yet".
const UNPLACED: u32 = u32::MAX;
/// Weight of a follower's steering out of the leader's way.
const LEADER_EVADE_WEIGHT: f32 = 2.0;
/// Longest look into the future (steps) when predicting a chased or feared agent's position.
const MAX_PREDICTION_STEPS: f32 = 40.0;
/// A leader slower than this (px/step) keeps its last heading.
const MIN_HEADING_SPEED: f32 = 0.05;

/// A neighbour found within the perception radius.
#[derive(Clone, Copy, Debug, Default)]
struct NearAgent {
    id: u32,
    d2: f32,
    pos: Vec2,
    vel: Vec2,
}

/// Side whiskers: angle from the heading (radians) and length relative to the main whisker.
const SIDE_WHISKER_ANGLE: f32 = 0.5;
const SIDE_WHISKER_SCALE: f32 = 0.6;

impl Boids {
    /// A planner with these parameters.
    pub fn new(params: BoidsParams) -> Self {
        Self { params, near: Vec::new(), flow: None, path_segment: Vec::new(), leader_heading: Vec2::ZERO }
    }

    /// The planner's parameters.
    pub fn params(&self) -> &BoidsParams {
        &self.params
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
                let key = FlowKey {
                    goal_cell: ((goal.x / flow_field::CELL) as i32, (goal.y / flow_field::CELL) as i32),
                    obstacles: flow_field::obstacles_fingerprint(ctx.obstacles.obstacles()),
                    bounds: ctx.bounds,
                    clearance,
                };
                if self.flow.as_ref().is_none_or(|(k, _)| *k != key) {
                    let field = FlowField::new(ctx.bounds, ctx.obstacles, goal, clearance);
                    self.flow = Some((key, field));
                }
            }
        }
        if prm.leader == Leader::First {
            let leader = group.agents.start as usize;
            if let Some(&v) = ctx.velocities.get(leader).filter(|_| !group.agents.is_empty()) {
                if v.length() > MIN_HEADING_SPEED {
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
                let d = to.length();
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
            if let (Some((goal, goal_radius)), Some((_, field))) = (group.goal, &self.flow) {
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
    /// the predicted position's projection. `None` once the end is reached (the goal takes over).
    fn follow_path(&self, path: &PathSpec, group: &GroupView, k: usize, p: Vec2, vel: Vec2) -> Option<Guide> {
        let prm = &self.params;
        let seg = self.path_segment.get(k).copied().filter(|&s| s != UNPLACED).unwrap_or(0) as usize;
        let here = path.closest_point_in(p, seg..seg + 3)?;
        let length = path.length();
        let end = path.point_at(length);
        if here.along >= length - path.radius && p.distance(end) <= path.radius {
            return if group.goal.is_some() {
                None
            } else {
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
        ctx.grid.for_each_within(p, prm.flee_radius, |n| {
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
        let len = direction.length();
        if len <= 1e-9 {
            return Vec2::ZERO;
        }
        limit(direction * (self.params.max_speed / len) - velocity, self.params.max_force)
    }

    /// Whisker obstacle avoidance: a forward probe and two shorter side probes; a touching
    /// probe yields a force along the surface normal plus a sideways push (lecture, "Obstacle
    /// Avoidance"), stronger the nearer the hit.
    fn avoid_obstacles(&self, ctx: &StepContext, p: Vec2, vel: Vec2, radius: f32, fallback: Vec2) -> Vec2 {
        let length = self.params.whisker_length;
        if ctx.obstacles.is_empty() || length <= 0.0 {
            return Vec2::ZERO;
        }
        let heading = unit_or(vel, fallback);
        let side = Vec2::from_angle(SIDE_WHISKER_ANGLE);
        let whiskers = [
            heading * (length + radius),
            side.rotate(heading) * (length * SIDE_WHISKER_SCALE + radius),
            Vec2::new(side.x, -side.y).rotate(heading) * (length * SIDE_WHISKER_SCALE + radius),
        ];
        let reach = length + radius;
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

    fn plan(&mut self, ctx: &StepContext, group: GroupView, _rng: &mut Rng, new_velocities: &mut [Vec2]) {
        self.prepare(ctx, &group);
        let mut near = std::mem::take(&mut self.near);
        let mut plan_one = |id: u32| {
            let k = (id - group.agents.start) as usize;
            let forces = self.agent_forces(ctx, &group, k, id, &mut near);
            if let Some(out) = new_velocities.get_mut(k) {
                *out = limit(ctx.velocities[id as usize] + forces.acceleration, self.params.max_speed);
            }
        };
        let in_cell_order = ctx.grid.ids_in_cell_order();
        if in_cell_order.len() == ctx.positions.len() && group.agents.len() * 4 >= in_cell_order.len() {
            // Agents one after another in the grid's order query the same cells: at 100,000
            // agents that keeps them in the cache. Each agent's forces depend only on the state
            // at the start of the step, so the order changes no result.
            for &id in in_cell_order {
                if group.agents.contains(&id) {
                    plan_one(id);
                }
            }
        } else {
            group.agents.clone().for_each(plan_one);
        }
        self.near = near;
    }

    fn explain(&self, ctx: &StepContext, group: &GroupView, agent: u32) -> Explanation {
        let mut near = Vec::new();
        let k = agent.saturating_sub(group.agents.start) as usize;
        let forces = self.agent_forces(ctx, group, k, agent, &mut near);
        let mut e = Explanation::default();
        for &(name, force) in &forces.weighted[..forces.used] {
            e.vectors.push(NamedVector::new(name, force));
        }
        e.applied = forces.acceleration;
        e.neighbours =
            near[..forces.neighbours].iter().filter(|n| n.id != agent && n.d2 > 0.0).map(|n| n.id).collect();
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
    /// How many entries of the scratch list are the agent's neighbours (itself included).
    neighbours: usize,
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

/// A planner's role read from another group's settings (only Boids groups have one).
fn role_of(ctx: &StepContext, agent: u32) -> Role {
    let group = ctx.group_of.get(agent as usize).and_then(|&g| ctx.scene.groups.get(g as usize));
    match group.map(|g| &g.planner) {
        Some(super::PlannerConfig::Boids(p)) => p.role,
        _ => Role::None,
    }
}

/// The nearest agent of `role` within `radius` of `p` (not `me`), ties by id.
fn nearest_of_role(ctx: &StepContext, p: Vec2, radius: f32, role: Role, me: u32) -> Option<Neighbour> {
    let mut best: Option<Neighbour> = None;
    ctx.grid.for_each_within(p, radius, |n| {
        if n.id != me && best.is_none_or(|b| (n.d2, n.id) < (b.d2, b.id)) && role_of(ctx, n.id) == role {
            best = Some(n);
        }
    });
    best
}

impl Boids {
    /// Every rule force of agent `id` from the step's state; `near` is scratch for its neighbours.
    /// `plan` and `explain` both call it, so an explanation is exactly what the step applies.
    fn agent_forces(
        &self,
        ctx: &StepContext,
        group: &GroupView,
        k: usize,
        id: u32,
        near: &mut Vec<NearAgent>,
    ) -> AgentForces {
        let prm = &self.params;
        let sep_r2 = prm.separation_radius * prm.separation_radius;
        let look = self.interaction_radius();
        let look2 = look * look;
        let (first, end) = (group.agents.start, group.agents.end);
        let i = id as usize;
        let p = ctx.positions[i];
        let vel = ctx.velocities[i];

        let (mut sep, mut n_sep) = (Vec2::ZERO, 0u32);
        let (mut sum_vel, mut sum_pos, mut n_flock) = (Vec2::ZERO, Vec2::ZERO, 0u32);
        // Pass 1 gathers the neighbours without a branch per candidate (whether a candidate of
        // the nearby cells is within reach is a coin flip the CPU cannot predict); pass 2 sums
        // over them in the same order, so the sums are those of a plain loop, bit for bit.
        // `near` only grows; `count` is how much of it holds this agent's neighbours.
        let mut count = 0usize;
        ctx.grid.for_each_candidate_run(p, look, |ids, positions, velocities| {
            if near.len() <= count + ids.len() {
                near.resize(count + ids.len() + 1, NearAgent::default());
            }
            for ((&nid, &q), &nv) in ids.iter().zip(positions).zip(velocities) {
                let d2 = p.distance_squared(q);
                if let Some(slot) = near.get_mut(count) {
                    *slot = NearAgent { id: nid, d2, pos: q, vel: nv };
                }
                count += usize::from(d2 <= look2);
            }
        });
        for n in &near[..count] {
            if n.id == id || n.d2 <= 0.0 {
                continue;
            }
            // (p − q)/|p − q|²: the lecture's normalised difference over the distance. Masked,
            // not branched: the test is unpredictable, and adding +0 leaves the sum exact.
            let close = n.d2 < sep_r2;
            sep += keep_if(close, (p - n.pos) / n.d2);
            n_sep += u32::from(close);
            // Alignment and cohesion only with the agent's own group.
            if n.id >= first && n.id < end {
                sum_vel += n.vel;
                sum_pos += n.pos;
                n_flock += 1;
            }
        }

        let separation = if n_sep > 0 { self.steer_towards(sep, vel) } else { Vec2::ZERO };
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
        let avoid = self.avoid_obstacles(ctx, p, vel, ctx.radii[i], unit_or(to_goal, Vec2::X))
            + self.contain(ctx, p, vel);

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
                    let len = f.length();
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
        AgentForces { weighted, used, acceleration, parked, fleeing, neighbours: count }
    }
}

/// `v` if `keep`, else `+0` in both lanes, without a branch (a NaN from a skipped `0/0` is
/// masked out too). Sums start at `+0`, so adding the `+0` is exact.
#[inline(always)]
fn keep_if(keep: bool, v: Vec2) -> Vec2 {
    let mask = 0u32.wrapping_sub(u32::from(keep));
    Vec2::new(f32::from_bits(v.x.to_bits() & mask), f32::from_bits(v.y.to_bits() & mask))
}
