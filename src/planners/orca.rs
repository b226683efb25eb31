//! ORCA, optimal reciprocal collision avoidance (van den Berg, Guy, Lin & Manocha, "Reciprocal
//! n-body collision avoidance", Robotics Research, STAR 70, 2011), written from the paper.
//!
//! Per agent A and step, from the state at the start of the step:
//! 1. Preferred velocity `v_pref`: towards the goal (or down its flow field) at the preferred
//!    speed; zero inside the goal.
//! 2. For each of the `max_neighbours` nearest agents B (by distance², then id) within the
//!    neighbour distance, the half-plane `ORCA^τ_{A|B} = {v | (v − (v_A + ½u)) · n ≥ 0}` (the
//!    paper's definition of ORCA): `u` is the vector from the relative velocity `v_A − v_B` to
//!    the closest point of the boundary of the truncated velocity obstacle
//!    `VO^τ_{A|B} = {v | ∃t ∈ [0, τ] : t v ∈ D(p_B − p_A, r_A + r_B)}`, `n` the boundary's
//!    outward normal there; the current velocities stand for `v^opt` (the paper's choice for
//!    crowds). Each
//!    agent takes half the responsibility (the ½), so the pair avoids reciprocally. Agents
//!    already overlapping use a cutoff of one step instead of τ (they separate in the next step).
//! 3. For each obstacle and world border near A, one half-plane with full responsibility and
//!    `v^opt = 0` (the paper's static obstacles): the obstacle is linearised at its point nearest to A (a supporting
//!    line, so for a convex obstacle every velocity allowed is collision-free within the
//!    obstacle horizon): the speed towards it is at most `gap / τ_obs`.
//! 4. The new velocity `v_new = argmin_{v ∈ ORCA^τ_A} ‖v − v_pref‖` with `ORCA^τ_A = D(0, v_max)
//!    ∩ ⋂_B ORCA^τ_{A|B}`, by the paper's incremental 2-D linear program (constraints added in a
//!    fixed order, obstacles first, instead of a random one: the same result on every
//!    platform). When the half-planes leave no room (the paper's densely packed conditions),
//!    the velocity that minimises the largest violation of the agents' half-planes while keeping
//!    the obstacles' is taken: the paper's 3-D linear program, solved as 2-D programs on the
//!    lines of equal violation.
//!
//! All geometry is in px and px/step (τ in steps): ORCA is scale-free, only the parameters are
//! converted from m, m/s and s. Only +, −, ×, ÷ and √: bit-identical natively and in wasm.

use super::goal_way::{px_per_metre, GoalWay};
use super::planner::{GroupView, Planner, StepContext};
use crate::model::geometry::{length, unit_or, Aabb, Obstacle};
use crate::model::params::OrcaParams;
use crate::model::scene::{DEFAULT_PX_PER_METRE, DT};
use crate::planners::explain::{Explanation, NamedVector};
use crate::rng::Rng;
use crate::spatial::QueryCap;
use glam::Vec2;

/// Neighbour queries visit at most this many agents within reach, among at most this many
/// agents of the scanned cells (the first in the grid's scan order): a pile costs a bounded
/// amount of work per agent. The nearest `max_neighbours` are taken from them.
const NEIGHBOUR_CAP: QueryCap = QueryCap { neighbours: 1024, candidates: 4096 };
/// Below this (px/step) two normals or a direction count as parallel or zero.
const EPS: f32 = 1e-6;
/// Added to the sum of two radii (px): ORCA's velocities lie on the boundary of the allowed set,
/// where rounding, the neighbour limit and the densely packed fallback left bodies overlapping
/// by up to 0.02 px in `orca-crossing` (nine pair-steps in 2,400 steps), which the metrics count
/// as collisions. With a quarter pixel (2.5% of a 5 px radius) there are none.
const CONTACT_MARGIN: f32 = 0.25;

/// One ORCA half-plane of allowed velocities `{v | (v − point) · normal ≥ 0}` (px/step).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HalfPlane {
    /// A point on the boundary line.
    pub point: Vec2,
    /// Unit normal pointing into the allowed side.
    pub normal: Vec2,
}

impl HalfPlane {
    /// How far `v` lies outside the half-plane (negative inside).
    pub fn violation(&self, v: Vec2) -> f32 {
        -(v - self.point).dot(self.normal)
    }

    /// The boundary's direction (the normal turned a quarter).
    fn direction(&self) -> Vec2 {
        self.normal.perp()
    }
}

/// The half-plane `ORCA^τ_{A|B}` of agent A against agent B.
///
/// `rel_pos = p_B − p_A`, `rel_vel = v_A − v_B`, `own_vel = v_A`, `radius_sum = r_A + r_B`,
/// `tau` in steps (> 0). `apart` is the direction A gives way in when the two centres coincide
/// (callers pass opposite ones to the two agents, so they part).
pub fn agent_half_plane(
    rel_pos: Vec2,
    rel_vel: Vec2,
    own_vel: Vec2,
    radius_sum: f32,
    tau: f32,
    apart: Vec2,
) -> HalfPlane {
    let dist2 = rel_pos.length_squared();
    let r2 = radius_sum * radius_sum;
    let (u, normal) = if dist2 > r2 {
        // The truncated cone: a disc D(rel_pos/τ, r/τ) (its cutoff) and two legs from the
        // origin tangent to D(rel_pos, r).
        let w = rel_vel - rel_pos / tau;
        let w2 = w.length_squared();
        let along = w.dot(rel_pos);
        if along < 0.0 && along * along > r2 * w2 {
            // Nearest the cutoff arc: project onto the small circle.
            let wl = w2.sqrt();
            let n = w / wl;
            (n * (radius_sum / tau - wl), n)
        } else {
            // Nearest a leg: the one on w's side of rel_pos. The leg direction is rel_pos turned
            // by ±β, cos β = leg / |rel_pos|, sin β = r / |rel_pos|.
            let leg = (dist2 - r2).sqrt();
            let side = if rel_pos.perp_dot(w) > 0.0 { 1.0 } else { -1.0 };
            let d = Vec2::new(
                rel_pos.x * leg - side * rel_pos.y * radius_sum,
                side * rel_pos.x * radius_sum + rel_pos.y * leg,
            ) / dist2;
            let u = d * rel_vel.dot(d) - rel_vel;
            // The outward normal points away from the cone's inside (where rel_pos lies).
            let mut n = d.perp();
            if n.dot(rel_pos) > 0.0 {
                n = -n;
            }
            (u, n)
        }
    } else {
        // Overlapping: the velocity obstacle of one step, D(rel_pos, r) (cutoff at Δt = 1).
        let w = rel_vel - rel_pos;
        let wl = length(w);
        let n = if wl > EPS { w / wl } else { unit_or(-rel_pos, apart) };
        (n * (radius_sum - wl), n)
    };
    HalfPlane { point: own_vel + u * 0.5, normal }
}

/// The half-plane of a static surface (obstacle or border) at `gap` px from the body's edge
/// with unit `normal` pointing from the surface to the agent (`v^opt = 0`, full responsibility): the speed towards the surface is at most `gap / tau`; an overlapping body
/// (`gap < 0`) must leave within one step.
pub fn surface_half_plane(normal: Vec2, gap: f32, tau: f32) -> HalfPlane {
    let allowed = if gap >= 0.0 { gap / tau } else { gap };
    HalfPlane { point: -normal * allowed, normal }
}

/// The best point on the boundary of `lines[k]` that keeps `lines[..k]` and `|v| ≤ radius`:
/// nearest to `target`, or furthest along `target` when `direction` (the 3-D program's step).
/// `None` when no such point exists.
fn on_line(lines: &[HalfPlane], k: usize, radius: f32, target: Vec2, direction: bool) -> Option<Vec2> {
    let line = lines[k];
    let d = line.direction();
    // The disc cuts the line where |point + t d|² = radius².
    let b = line.point.dot(d);
    let disc = b * b - line.point.length_squared() + radius * radius;
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    let (mut lo, mut hi) = (-b - s, -b + s);
    for other in &lines[..k] {
        // (point + t d − other.point) · other.normal ≥ 0  ⇔  t (d · n) ≥ (other.point − point) · n
        let denom = d.dot(other.normal);
        let num = (other.point - line.point).dot(other.normal);
        if denom.abs() <= EPS {
            if num > EPS {
                return None;
            }
            continue;
        }
        let t = num / denom;
        if denom > 0.0 {
            lo = lo.max(t);
        } else {
            hi = hi.min(t);
        }
        if lo > hi {
            return None;
        }
    }
    let t = if direction {
        if target.dot(d) > 0.0 {
            hi
        } else {
            lo
        }
    } else {
        (target - line.point).dot(d).clamp(lo, hi)
    };
    Some(line.point + d * t)
}

/// The paper's 2-D linear program: the velocity in the disc of `radius` and every half-plane
/// nearest to `target` (or furthest along the unit `target` when `direction`), adding the
/// half-planes in order. Returns the index of the first half-plane that left no room
/// (`lines.len()` on success); `result` then holds the solution of the ones before it.
fn solve_2d(lines: &[HalfPlane], radius: f32, target: Vec2, direction: bool, result: &mut Vec2) -> usize {
    *result = if direction {
        target * radius
    } else if target.length_squared() > radius * radius {
        unit_or(target, Vec2::ZERO) * radius
    } else {
        target
    };
    for k in 0..lines.len() {
        if lines[k].violation(*result) > 0.0 {
            match on_line(lines, k, radius, target, direction) {
                Some(v) => *result = v,
                None => return k,
            }
        }
    }
    lines.len()
}

/// The paper's 3-D linear program (densely packed conditions): from the first infeasible half-plane
/// `start` on, the velocity minimising the largest violation of the soft half-planes
/// `lines[hard..]` while keeping the hard ones `lines[..hard]`, as a sequence of 2-D programs on
/// the lines where two half-planes are violated equally.
fn solve_3d(
    lines: &[HalfPlane],
    hard: usize,
    start: usize,
    radius: f32,
    result: &mut Vec2,
    scratch: &mut Vec<HalfPlane>,
) {
    let mut worst = 0.0f32;
    for i in start.max(hard)..lines.len() {
        if lines[i].violation(*result) <= worst {
            continue;
        }
        scratch.clear();
        scratch.extend_from_slice(&lines[..hard]);
        let (ni, ci) = (lines[i].normal, lines[i].point.dot(lines[i].normal));
        for j in &lines[hard..i] {
            // Where j is violated no more than i: v · (n_j − n_i) ≥ p_j·n_j − p_i·n_i.
            let m = j.normal - ni;
            let len = length(m);
            if len <= EPS {
                // Same direction: one of the two is always the more violated.
                continue;
            }
            let n = m / len;
            scratch.push(HalfPlane { point: n * ((j.point.dot(j.normal) - ci) / len), normal: n });
        }
        let before = *result;
        if solve_2d(scratch, radius, ni, true, result) < scratch.len() {
            // Only rounding can make this program infeasible: keep the last solution.
            *result = before;
        }
        worst = lines[i].violation(*result);
    }
}

/// ORCA's velocity: `argmin ‖v − v_pref‖` over the disc of `max_speed` and `lines`, the first
/// `hard` of which (obstacles) are never given up. When the hard half-planes alone
/// leave no room every half-plane is treated as soft.
pub fn solve(
    lines: &[HalfPlane],
    hard: usize,
    v_pref: Vec2,
    max_speed: f32,
    scratch: &mut Vec<HalfPlane>,
) -> Vec2 {
    let mut v = Vec2::ZERO;
    let failed = solve_2d(lines, max_speed, v_pref, false, &mut v);
    if failed < lines.len() {
        let hard = if failed < hard { 0 } else { hard };
        solve_3d(lines, hard, failed, max_speed, &mut v, scratch);
    }
    v
}

/// The ORCA planner for one group.
#[derive(Clone, Debug)]
pub struct Orca {
    params: OrcaParams,
    way: GoalWay,
    /// Parameters in px, px/step and steps.
    pref_speed: f32,
    max_speed: f32,
    neighbour_dist: f32,
    tau: f32,
    tau_obstacles: f32,
    /// Scratch: one agent's half-planes, the 3-D program's lines, the nearest neighbours.
    lines: Vec<HalfPlane>,
    scratch: Vec<HalfPlane>,
    nearest: Vec<Near>,
    /// Grid slots of the agents within a query's radius.
    slots: Vec<u32>,
}

/// A neighbour kept by the nearest-neighbour selection.
#[derive(Clone, Copy, Debug)]
struct Near {
    d2: f32,
    id: u32,
    pos: Vec2,
    vel: Vec2,
}

impl Orca {
    /// A planner with these parameters at the default scene scale.
    pub fn new(params: OrcaParams) -> Self {
        Self::with_scale(params, DEFAULT_PX_PER_METRE)
    }

    /// A planner with these parameters for a scene of `px_per_metre`.
    pub fn with_scale(params: OrcaParams, px_per_metre: f32) -> Self {
        let speed = px_per_metre * DT;
        Self {
            pref_speed: params.pref_speed * speed,
            max_speed: params.max_speed * speed,
            neighbour_dist: params.neighbour_dist * px_per_metre,
            tau: params.time_horizon / DT,
            tau_obstacles: params.time_horizon_obstacles / DT,
            params,
            way: GoalWay::default(),
            lines: Vec::new(),
            scratch: Vec::new(),
            nearest: Vec::new(),
            slots: Vec::new(),
        }
    }

    /// The parameters.
    pub fn params(&self) -> &OrcaParams {
        &self.params
    }

    /// The `max_neighbours` agents nearest to agent `id` within the neighbour distance, by
    /// (distance², id), into `self.nearest`. A first query within a quarter of the distance
    /// usually finds them all (then they are the nearest overall); otherwise the whole distance.
    fn gather_nearest(&mut self, ctx: &StepContext, id: u32, p: Vec2) {
        let k = self.params.max_neighbours as usize;
        let (nearest, slots) = (&mut self.nearest, &mut self.slots);
        // The agents within `radius` first (a branch-free pass, the same agents in the same
        // order as a capped visit), then the k nearest of them by `(distance², id)` as keys:
        // squared distances are finite and non-negative, so their bits order like them.
        let collect = |radius: f32, nearest: &mut Vec<Near>, slots: &mut Vec<u32>| {
            nearest.clear();
            ctx.grid.gather_within(p, radius, NEIGHBOUR_CAP, slots);
            let columns = ctx.grid.columns();
            let mut last = u64::MAX;
            for &slot in slots.iter() {
                let slot = slot as usize;
                let (other, pos) = (columns.ids[slot], Vec2::new(columns.x[slot], columns.y[slot]));
                let d2 = p.distance_squared(pos);
                let key = (u64::from(d2.to_bits()) << 32) | u64::from(other);
                if other == id || key >= last {
                    continue;
                }
                let at = nearest.partition_point(|m| (m.d2, m.id) < (d2, other));
                let vel = Vec2::new(columns.vx[slot], columns.vy[slot]);
                nearest.insert(at, Near { d2, id: other, pos, vel });
                nearest.truncate(k);
                if nearest.len() == k {
                    last = nearest
                        .last()
                        .map_or(u64::MAX, |l| (u64::from(l.d2.to_bits()) << 32) | u64::from(l.id));
                }
            }
        };
        let quarter = 0.25 * self.neighbour_dist;
        collect(quarter, nearest, slots);
        if nearest.len() < k {
            collect(self.neighbour_dist, nearest, slots);
        }
    }

    /// Agent `id`'s half-planes into `self.lines` (obstacles and borders first); returns how
    /// many are the obstacles' and its preferred velocity.
    fn constraints(&mut self, ctx: &StepContext, group: &GroupView, id: u32) -> (usize, Vec2) {
        let i = id as usize;
        let (p, v, r) = (ctx.positions[i], ctx.velocities[i], ctx.radii[i]);
        self.lines.clear();
        // A surface further than this cannot be reached within the horizon at top speed.
        let reach = self.max_speed * self.tau_obstacles;
        if !ctx.obstacles.is_empty() {
            let query = Aabb { min: p, max: p }.inflate(reach + r);
            let (lines, tau) = (&mut self.lines, self.tau_obstacles);
            ctx.obstacles.for_each_near(query, |_, o: &Obstacle| {
                let s = o.surface(p);
                let gap = s.signed_distance - r;
                if gap < reach {
                    lines.push(surface_half_plane(s.normal, gap, tau));
                }
            });
        }
        let borders = [
            (p.x - r, Vec2::X),
            (ctx.bounds.x - r - p.x, Vec2::NEG_X),
            (p.y - r, Vec2::Y),
            (ctx.bounds.y - r - p.y, Vec2::NEG_Y),
        ];
        for (gap, normal) in borders {
            if gap < reach {
                self.lines.push(surface_half_plane(normal, gap, self.tau_obstacles));
            }
        }
        let hard = self.lines.len();
        self.gather_nearest(ctx, id, p);
        for n in &self.nearest {
            let rj = ctx.radii[n.id as usize];
            let apart = if id < n.id { Vec2::X } else { Vec2::NEG_X };
            self.lines.push(agent_half_plane(
                n.pos - p,
                v - n.vel,
                v,
                r + rj + CONTACT_MARGIN,
                self.tau,
                apart,
            ));
        }
        let way = self.way.at(p, group.goal);
        (hard, way.direction * self.pref_speed)
    }
}

impl Planner for Orca {
    fn interaction_radius(&self) -> f32 {
        self.neighbour_dist
    }

    /// The pedestrian baselines stop in their goal by themselves (preferred speed zero once
    /// inside, [`crate::planners::goal_way`]) and keep apart by their own model; walking them
    /// to places by the world would override the ORCA step that keeps them apart (the
    /// world's walkers do not reciprocate as the model assumes).
    fn max_speed(&self) -> f32 {
        self.max_speed
    }

    fn plan(&mut self, ctx: &StepContext, group: GroupView, _rng: &mut Rng, new_velocities: &mut [Vec2]) {
        self.way.prepare(ctx, &group, self.params.guidance);
        let mut scratch = std::mem::take(&mut self.scratch);
        for (k, id) in group.agents.clone().enumerate() {
            let (hard, v_pref) = self.constraints(ctx, &group, id);
            new_velocities[k] = solve(&self.lines, hard, v_pref, self.max_speed, &mut scratch);
        }
        self.scratch = scratch;
    }

    fn explain(&self, ctx: &StepContext, group: &GroupView, agent: u32) -> Explanation {
        let mut e = Explanation { scale: 60.0, ..Explanation::default() };
        if agent as usize >= ctx.positions.len() {
            return e;
        }
        let mut me = self.clone();
        me.way.prepare(ctx, group, self.params.guidance);
        let (hard, v_pref) = me.constraints(ctx, group, agent);
        let v = solve(&me.lines, hard, v_pref, me.max_speed, &mut me.scratch);
        e.vectors.push(NamedVector::new("preferred velocity", v_pref));
        e.vectors.push(NamedVector::new("ORCA velocity", v));
        e.applied = v;
        e.neighbours = me.nearest.iter().map(|n| n.id).collect();
        let violated = me.lines.iter().filter(|l| l.violation(v) > 1e-4).count();
        e.values.push(("half-planes".into(), me.lines.len() as f32));
        e.values.push(("obstacle half-planes".into(), hard as f32));
        e.state = if violated > 0 {
            format!(
                "densely packed: no velocity keeps all {} half-planes; {violated} given up least",
                me.lines.len()
            )
        } else {
            format!("the velocity nearest v_pref that keeps all {} half-planes", me.lines.len())
        };
        e
    }
}

/// The planner for a group of a scene: its parameters at the scene's scale.
pub fn for_scene(params: OrcaParams, scene: &crate::model::scene::Scene) -> Orca {
    Orca::with_scale(params, px_per_metre(scene))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pair_on_a_collision_course_gets_half_planes_that_exclude_it() {
        // B straight ahead 10 px, closing at 1 px/step: collides within τ = 30 steps.
        let h = agent_half_plane(
            Vec2::new(10.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 0.0),
            4.0,
            30.0,
            Vec2::X,
        );
        assert!(h.violation(Vec2::new(1.0, 0.0)) > 0.0, "{h:?}");
        // Standing still is always safe for a pair not yet touching.
        assert!(h.violation(Vec2::ZERO) <= 0.0);
    }

    #[test]
    fn the_linear_program_returns_v_pref_when_it_is_allowed() {
        let lines = [HalfPlane { point: Vec2::new(-1.0, 0.0), normal: Vec2::X }];
        let v = solve(&lines, 0, Vec2::new(0.5, 0.2), 2.0, &mut Vec::new());
        assert_eq!(v, Vec2::new(0.5, 0.2));
    }
}
