//! The collision-free speed model, written from the paper: Tordeux, Chraibi & Seyfried,
//! "Collision-free speed model for pedestrian dynamics", Traffic and Granular Flow '15 (2016),
//! arXiv:1512.05597 (TCS), cross-checked against JuPedSim's `CollisionFreeSpeedModel`.
//!
//! A first-order model: an agent has no inertia, it walks at once at `ẋ_i = V(s_i) e_i`
//! (TCS eq. 1), a speed from the spacing ahead along a direction from the goal and the neighbours.
//! All in SI units, converted from px with the scene's scale:
//! - speed (TCS eq. 2, the optimal-velocity function): `V(s) = min(v⁰, max(0, (s − ℓ)/T))`,
//!   T the time gap, ℓ the body length (here the two bodies' radii summed: the diameter of
//!   equal bodies);
//! - spacing (TCS eq. 3): `s_i` the distance to the nearest neighbour j ahead within a corridor
//!   of the body length: `e_i · (x_j − x_i) ≥ 0` and `|e_i^⊥ · (x_j − x_i)| ≤ ℓ`; with
//!   different bodies each neighbour's own ℓ, the speed the smallest `V(s_ij)`;
//! - direction (TCS eq. 4 and 5): `e_i = normalised(e⁰_i + Σ_j R(d_ij) e_ij + Σ_w R_w e_iw)`
//!   with `R(d) = a·exp((ℓ − d)/D)` and `e_ij` the unit vector from j to i; walls and the world's
//!   borders push likewise with `a_w·exp((r − d)/D_w)` along their normal, d the centre's
//!   distance to the wall (JuPedSim's geometry term). `e⁰` is the goal's flow field or the goal
//!   itself ([`super::goal_way`]).
//!
//! The direction is taken from the state at the start of the step and the spacing along that
//! new direction (as JuPedSim does). Neighbours hidden behind an obstacle (the segment between
//! the centres enters one) are not seen, as in JuPedSim. Inside its goal, or without one, an
//! agent stands still (its desired direction is zero; a first-order model has no other rest).
//! When the direction sums to zero the agent keeps its current heading.
//!
//! Why collision-free: with the explicit step `x += V(s) e Δt` an agent closes at most
//! `(s − ℓ) Δt / T` of the gap to the one ahead in a step (Δt = 1/60 s, T = 1 s: 1/60 of it), so
//! the gap ahead never closes. Only +, −, ×, ÷, √ and `libm::expf`: bit-identical natively and
//! in wasm.

use super::goal_way::{px_per_metre, GoalWay};
use super::planner::{GroupView, Planner, StepContext};
use crate::model::geometry::{length, Aabb, Obstacle};
use crate::model::params::CollisionFreeSpeedParams;
use crate::model::scene::{DEFAULT_PX_PER_METRE, DT};
use crate::planners::explain::{Explanation, NamedVector};
use crate::rng::Rng;
use crate::spatial::QueryCap;
use glam::Vec2;

/// Neighbour queries visit at most this many agents within the cut-off, among at most this many
/// agents of the scanned cells (the first in the grid's scan order): a pile costs a bounded
/// amount of work per agent.
const NEIGHBOUR_CAP: QueryCap = QueryCap { neighbours: 512, candidates: 4096 };
/// Walls further than this many wall ranges D_w weigh less than e⁻¹⁰ of a_w: left out.
const WALL_REACH_RANGES: f32 = 10.0;
/// Largest exponent of a repulsion: e³⁰ ≈ 10¹³ already outweighs everything else, and the cap
/// keeps the sum finite when bodies overlap deeply with a short range (e^{(ℓ − d)/D} would reach
/// f32's infinity past e⁸⁸, and the direction would be NaN).
const MAX_EXPONENT: f32 = 30.0;

/// `V(s) = min(v⁰, max(0, (s − ℓ)/T))` (TCS eq. 2): the speed (m/s) at spacing `s` (m, centre
/// to centre) behind a neighbour with body length `l` (m), desired speed `v0` (m/s) and time gap
/// `t` (s). Zero at `s ≤ ℓ`, `v⁰` from `s ≥ ℓ + v⁰T`, linear in between.
pub fn optimal_speed(s: f32, l: f32, v0: f32, t: f32) -> f32 {
    ((s - l) / t).max(0.0).min(v0)
}

/// Whether a neighbour at `rel = x_j − x_i` (m) is in the spacing's corridor ahead of direction
/// `e` (unit) for body length `l` (TCS eq. 3): ahead (`e · rel ≥ 0`) and at most `l` to the side.
pub fn ahead_in_corridor(e: Vec2, rel: Vec2, l: f32) -> bool {
    e.dot(rel) >= 0.0 && e.perp().dot(rel).abs() <= l
}

/// `a·exp((ℓ − d)/D) e_ij` (TCS eq. 5): neighbour j's push on agent i's direction, `rel = x_j − x_i`
/// (m), `l` the body length (m). Zero for coinciding centres (no direction to push along).
pub fn neighbour_repulsion(p: &CollisionFreeSpeedParams, rel: Vec2, l: f32) -> Vec2 {
    let d = length(rel);
    if d <= 0.0 {
        return Vec2::ZERO;
    }
    -rel / d * (p.neighbour_strength * libm::expf(((l - d) / p.neighbour_range).min(MAX_EXPONENT)))
}

/// `a_w·exp((r − d)/D_w) n`: a wall's push on the direction of a body of `radius` (m) whose centre
/// is `d` (m) from it, `normal` pointing from the wall to the body.
pub fn wall_repulsion(p: &CollisionFreeSpeedParams, radius: f32, d: f32, normal: Vec2) -> Vec2 {
    normal * (p.wall_strength * libm::expf(((radius - d) / p.wall_range).min(MAX_EXPONENT)))
}

/// One agent's step, by term (SI units).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Terms {
    /// Desired direction `e⁰` (unit, or zero inside the goal or without one).
    pub desired: Vec2,
    /// Sum of the neighbours' repulsions.
    pub neighbours: Vec2,
    /// Sum of the walls' and borders' repulsions.
    pub walls: Vec2,
    /// The walking direction `e` (unit, or zero when standing).
    pub direction: Vec2,
    /// Spacing ahead minus the body length, `s − ℓ` (m; infinite when nobody is ahead).
    pub gap: f32,
    /// The speed `V(s)` (m/s).
    pub speed: f32,
}

/// The collision-free speed planner for one group.
#[derive(Clone, Debug)]
pub struct CollisionFreeSpeed {
    params: CollisionFreeSpeedParams,
    way: GoalWay,
    /// Scene px per metre.
    scale: f32,
    scratch: Scratch,
}

/// Buffers one agent's step reuses (kept between steps: no allocation per agent).
#[derive(Clone, Debug, Default)]
struct Scratch {
    /// Grid slots of the agents within the cut-off.
    slots: Vec<u32>,
    /// Indexes of the obstacles near the agent (for the line of sight).
    near: Vec<u32>,
    /// The neighbours seen: position relative to the agent (m) and body length ℓ (m).
    seen: Vec<(Vec2, f32)>,
}

impl CollisionFreeSpeed {
    /// A planner with these parameters at the default scene scale.
    pub fn new(params: CollisionFreeSpeedParams) -> Self {
        Self::with_scale(params, DEFAULT_PX_PER_METRE)
    }

    /// A planner with these parameters for a scene of `px_per_metre`.
    pub fn with_scale(params: CollisionFreeSpeedParams, px_per_metre: f32) -> Self {
        Self { params, way: GoalWay::default(), scale: px_per_metre, scratch: Scratch::default() }
    }

    /// The parameters.
    pub fn params(&self) -> &CollisionFreeSpeedParams {
        &self.params
    }

    /// Agent `id`'s step from the step's state; `seen` is called with every neighbour taken
    /// into account.
    fn terms(
        &self,
        ctx: &StepContext,
        group: &GroupView,
        id: u32,
        scratch: &mut Scratch,
        mut seen: impl FnMut(u32),
    ) -> Terms {
        let Scratch { slots, near, seen: ahead } = scratch;
        let prm = &self.params;
        let i = id as usize;
        let to_m = 1.0 / self.scale;
        let p_px = ctx.positions[i];
        let (p, radius) = (p_px * to_m, ctx.radii[i] * to_m);
        let desired = self.way.at(p_px, group.goal).direction;
        let mut terms = Terms { desired, gap: f32::INFINITY, ..Terms::default() };
        if desired == Vec2::ZERO {
            return terms;
        }

        let obstacles = ctx.obstacles.obstacles();
        near.clear();
        if !ctx.obstacles.is_empty() {
            let wall_reach = WALL_REACH_RANGES * prm.wall_range + radius;
            let query = Aabb { min: p_px, max: p_px }.inflate(prm.cutoff.max(wall_reach) * self.scale);
            ctx.obstacles.for_each_near(query, |k, o: &Obstacle| {
                near.push(k);
                let s = o.surface(p_px);
                let d = s.signed_distance * to_m;
                if d < wall_reach {
                    terms.walls += wall_repulsion(prm, radius, d, s.normal);
                }
            });
        }
        let reach = WALL_REACH_RANGES * prm.wall_range + radius;
        let bounds = ctx.bounds * to_m;
        for (d, normal) in
            [(p.x, Vec2::X), (bounds.x - p.x, Vec2::NEG_X), (p.y, Vec2::Y), (bounds.y - p.y, Vec2::NEG_Y)]
        {
            if d < reach {
                terms.walls += wall_repulsion(prm, radius, d, normal);
            }
        }

        ctx.grid.gather_within(p_px, prm.cutoff * self.scale, NEIGHBOUR_CAP, slots);
        let columns = ctx.grid.columns();
        // The neighbours seen: (relative position in m, body length in m).
        let visible = |k: usize| -> Option<(u32, Vec2, f32)> {
            let other = columns.ids[k];
            if other == id {
                return None;
            }
            let q_px = Vec2::new(columns.x[k], columns.y[k]);
            let hidden = near.iter().any(|&o| obstacles[o as usize].segment_entry(p_px, q_px).is_some());
            if hidden {
                return None;
            }
            Some((other, (q_px - p_px) * to_m, radius + ctx.radii[other as usize] * to_m))
        };
        // The direction from every neighbour seen first, then the spacing along it.
        ahead.clear();
        for &k in slots.iter() {
            if let Some((other, rel, l)) = visible(k as usize) {
                seen(other);
                terms.neighbours += neighbour_repulsion(prm, rel, l);
                ahead.push((rel, l));
            }
        }
        let sum = desired + terms.neighbours + terms.walls;
        let n = length(sum);
        terms.direction = if n > 1e-6 {
            sum / n
        } else {
            let v = ctx.velocities[i];
            let speed = length(v);
            if speed > 0.0 {
                v / speed
            } else {
                desired
            }
        };
        let e = terms.direction;
        let mut speed = prm.desired_speed;
        for &(rel, l) in ahead.iter() {
            if ahead_in_corridor(e, rel, l) {
                let s = length(rel);
                terms.gap = terms.gap.min(s - l);
                speed = speed.min(optimal_speed(s, l, prm.desired_speed, prm.time_gap));
            }
        }
        terms.speed = speed;
        terms
    }
}

impl Planner for CollisionFreeSpeed {
    fn interaction_radius(&self) -> f32 {
        self.params.cutoff * self.scale
    }

    /// The pedestrian baselines stop in their goal by themselves (desired direction zero once
    /// inside, [`crate::planners::goal_way`]) and keep apart by their own model.
    fn max_speed(&self) -> f32 {
        self.params.desired_speed * self.scale * DT
    }

    fn plan(&mut self, ctx: &StepContext, group: GroupView, _rng: &mut Rng, new_velocities: &mut [Vec2]) {
        self.way.prepare(ctx, &group, self.params.guidance);
        let mut scratch = std::mem::take(&mut self.scratch);
        let to_px_step = self.scale * DT;
        for (k, id) in group.agents.clone().enumerate() {
            let t = self.terms(ctx, &group, id, &mut scratch, |_| {});
            new_velocities[k] = t.direction * (t.speed * to_px_step);
        }
        self.scratch = scratch;
    }

    fn explain(&self, ctx: &StepContext, group: &GroupView, agent: u32) -> Explanation {
        let mut e = Explanation { scale: 20.0, ..Explanation::default() };
        if agent as usize >= ctx.positions.len() {
            return e;
        }
        let mut me = self.clone();
        me.way.prepare(ctx, group, self.params.guidance);
        let mut neighbours = Vec::new();
        let t = me.terms(ctx, group, agent, &mut Scratch::default(), |id| neighbours.push(id));
        for (name, v) in [
            ("desired direction", t.desired),
            ("neighbours", t.neighbours),
            ("walls", t.walls),
            ("walking direction", t.direction),
        ] {
            e.vectors.push(NamedVector::new(name, v));
        }
        e.applied = t.direction * t.speed;
        e.neighbours = neighbours;
        e.values.push(("speed (m/s)".into(), t.speed));
        if t.gap.is_finite() {
            e.values.push(("gap ahead (m)".into(), t.gap));
        }
        e.state =
            "speed = min(v⁰, (spacing ahead − ℓ) / T) along the direction from goal, neighbours and walls"
                .into();
        e
    }
}

/// The planner for a group of a scene: its parameters at the scene's scale.
pub fn for_scene(params: CollisionFreeSpeedParams, scene: &crate::model::scene::Scene) -> CollisionFreeSpeed {
    CollisionFreeSpeed::with_scale(params, px_per_metre(scene))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_speed_is_zero_up_to_the_body_length_then_linear_then_v0() {
        let (l, v0, t) = (0.4, 1.2, 1.0);
        for s in [0.0, 0.2, 0.4] {
            assert_eq!(optimal_speed(s, l, v0, t), 0.0, "s = {s}");
        }
        for s in [1.6, 2.0, 50.0] {
            assert_eq!(optimal_speed(s, l, v0, t), v0, "s = {s}: free");
        }
        // Linear between ℓ and ℓ + v⁰T, slope 1/T.
        for (s, v) in [(0.5, 0.1), (0.9, 0.5), (1.4, 1.0)] {
            assert!((optimal_speed(s, l, v0, t) - v).abs() < 1e-6, "s = {s}");
            assert!((optimal_speed(s, l, v0, 2.0) - v / 2.0).abs() < 1e-6, "T = 2 s halves the slope");
        }
    }

    #[test]
    fn only_neighbours_ahead_within_a_body_length_to_the_side_set_the_spacing() {
        let e = Vec2::X;
        assert!(ahead_in_corridor(e, Vec2::new(1.0, 0.3), 0.4));
        assert!(!ahead_in_corridor(e, Vec2::new(1.0, 0.5), 0.4), "beside the corridor");
        assert!(!ahead_in_corridor(e, Vec2::new(-1.0, 0.0), 0.4), "behind");
    }

    #[test]
    fn repulsion_points_away_and_is_a_at_contact() {
        let p = CollisionFreeSpeedParams::default();
        let r = neighbour_repulsion(&p, Vec2::new(0.4, 0.0), 0.4);
        assert!((r - Vec2::new(-p.neighbour_strength, 0.0)).length() < 1e-5, "{r}");
        let far = neighbour_repulsion(&p, Vec2::new(0.0, 1.4), 0.4);
        assert!(far.y < 0.0 && far.length() < p.neighbour_strength * 1e-4, "{far}");
        assert_eq!(neighbour_repulsion(&p, Vec2::ZERO, 0.4), Vec2::ZERO);
        let deep = neighbour_repulsion(
            &CollisionFreeSpeedParams { neighbour_range: 0.01, ..p },
            Vec2::X * 1e-3,
            2.0,
        );
        assert!(deep.is_finite(), "capped exponent: {deep}");
    }
}
