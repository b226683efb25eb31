//! Reynolds steering as taught in the group-animation lecture (DESIGN §3.1).
//!
//! Each rule yields a steering force `desired − velocity` limited by `max_force` (lecture,
//! "Rule 1–3" pseudocode); the rules are combined by a weighted sum or by priority allocation
//! ("Arbitration"), then `v += a; v = limit(v, max_speed); p += v` (lecture, `Boid::update`).

use super::{limit, GroupView, ParamSpec, Planner, StepContext};
use crate::diagnose::{Explanation, NamedVector};
use crate::geometry::{unit_or, Aabb, Obstacle};
use crate::rng::Rng;
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
    ];
}

/// The Boids planner for one group.
#[derive(Clone, Debug)]
pub struct Boids {
    params: BoidsParams,
    /// Scratch: the neighbours of the agent being planned (reused to avoid allocating).
    near: Vec<NearAgent>,
}

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
        Self { params, near: Vec::new() }
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
        let mut near = std::mem::take(&mut self.near);
        for (k, id) in group.agents.clone().enumerate() {
            let forces = self.agent_forces(ctx, &group, id, &mut near);
            new_velocities[k] =
                limit(ctx.velocities[id as usize] + forces.acceleration, self.params.max_speed);
        }
        self.near = near;
    }

    fn explain(&self, ctx: &StepContext, group: &GroupView, agent: u32) -> Explanation {
        let mut near = Vec::new();
        let forces = self.agent_forces(ctx, group, agent, &mut near);
        let mut e = Explanation::default();
        for (name, force) in RULE_NAMES.iter().zip(forces.weighted) {
            e.vectors.push(NamedVector::new(name, force));
        }
        e.applied = forces.acceleration;
        e.neighbours =
            near[..forces.neighbours].iter().filter(|n| n.id != agent && n.d2 > 0.0).map(|n| n.id).collect();
        e.state = if forces.parked { "parked in the goal".into() } else { "steering".into() };
        e
    }
}

/// The rule forces of one agent in one step.
struct AgentForces {
    /// Weighted forces in [`RULE_NAMES`] order.
    weighted: [Vec2; 5],
    /// The acceleration the arbitration makes of them.
    acceleration: Vec2,
    /// Inside the goal: braking, only keeping its distance.
    parked: bool,
    /// How many entries of the scratch list are the agent's neighbours (itself included).
    neighbours: usize,
}

/// Names of the weighted rule forces, in arbitration order (the explanation's arrows).
const RULE_NAMES: [&str; 5] = ["obstacle avoidance", "separation", "seek", "alignment", "cohesion"];

impl Boids {
    /// Every rule force of agent `id` from the step's state; `near` is scratch for its neighbours.
    /// `plan` and `explain` both call it, so an explanation is exactly what the step applies.
    fn agent_forces(
        &self,
        ctx: &StepContext,
        group: &GroupView,
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
        let mut parked = false;
        let (seek, to_goal) = match group.goal {
            Some((goal, goal_radius)) => {
                let to = goal - p;
                let d = to.length();
                // Inside the goal the agent parks: it brakes and only keeps its distance, so
                // an arrived group spreads over the goal instead of piling onto its centre.
                parked = d <= goal_radius;
                // Arrival: slow down over `arrival_radius` before the goal's edge, and creep
                // (a tenth of max speed) the rest of the way so the group keeps filling in.
                let ramp = ((d - goal_radius) / prm.arrival_radius).clamp(0.1, 1.0);
                let speed = if parked { 0.0 } else { prm.max_speed * ramp };
                let desired = if d > 1e-6 { to * (speed / d) } else { Vec2::ZERO };
                (limit(desired - vel, prm.max_force), to)
            }
            None => (Vec2::ZERO, Vec2::X),
        };
        let (alignment, cohesion) = if parked { (Vec2::ZERO, Vec2::ZERO) } else { (alignment, cohesion) };
        let avoid = self.avoid_obstacles(ctx, p, vel, ctx.radii[i], unit_or(to_goal, Vec2::X))
            + self.contain(ctx, p, vel);

        let weighted = [
            avoid * prm.avoid_weight,
            separation * prm.separation_weight,
            seek * prm.seek_weight,
            alignment * prm.alignment_weight,
            cohesion * prm.cohesion_weight,
        ];
        let acceleration = match prm.arbitration {
            Arbitration::Weighted => limit(weighted.iter().sum(), prm.max_force),
            Arbitration::Priority => {
                let mut acc = Vec2::ZERO;
                let mut budget = prm.max_force;
                for f in weighted {
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
        AgentForces { weighted, acceleration, parked, neighbours: count }
    }
}

/// `v` if `keep`, else `+0` in both lanes, without a branch (a NaN from a skipped `0/0` is
/// masked out too). Sums start at `+0`, so adding the `+0` is exact.
#[inline(always)]
fn keep_if(keep: bool, v: Vec2) -> Vec2 {
    let mask = 0u32.wrapping_sub(u32::from(keep));
    Vec2::new(f32::from_bits(v.x.to_bits() & mask), f32::from_bits(v.y.to_bits() & mask))
}
