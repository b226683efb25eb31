//! PSO crowd (Chen & Lin 2009, DESIGN §3.2): every person is a particle minimising its own cost
//! landscape, with a stochastic acceptance test (local search) that keeps it out of obstacles.
//!
//! The paper's model, and how its open points are resolved here:
//!
//! * Cost of `p` relative to `q` (eq. 3): `C(p,q) = exp(−(Δx²/(σpx+σqx)² + Δy²/(σpy+σqy)²))`.
//!   Agents have σ = [`PsoParams::agent_sigma`] in both axes. The target has σ = the scene size
//!   ("the whole search area"). A **circle** obstacle has σ = its radius in both axes, so its cost
//!   is exactly eq. 3. **Rectangles and polygons** would be badly covered by an ellipse (a box's
//!   corners stick out of the ellipse through its half extents, concave shapes are worse), so their
//!   cost is eq. 3 written in the distance to the shape: with `d` the signed distance from `p` to the
//!   obstacle surface and `R` the obstacle's scope (half its shorter side, or of its bounding box's
//!   shorter side for a polygon), the σ-scaled distance is `s = (d + R)/(R + σp)` and
//!   `C = exp(−s²)`. For a circle (`R` = radius) this is the paper's formula; for every shape the
//!   no-go zone `s ≤ 1` is the shape grown by σp, so it always covers the shape.
//! * Objective (minimised): `F(p) = c_obs · max_{o∈O} C(p,o) + 1/C(p,g)`, O = static obstacles and
//!   every other agent; agents farther than `6σ` (s > 3, C < 1.3·10⁻⁴) are ignored, so the max runs
//!   over a grid query, never over all agents. Each agent evaluates F without itself: every agent
//!   sees its own landscape.
//! * `D` is the *direction part* of the velocity (the paper splits velocity into direction and
//!   speed), so it is kept a unit vector: `D ← unit(ω D + c1 r1 unit(pbest − p) + c2 r2 unit(gbest − p))`.
//!   Unnormalised, ω = 1 would let |D| grow without bound and freeze the heading.
//! * Speed `S = Vmax / F(p)` (F ≥ 1): slower near obstacles and crowds.
//! * pbest = the lowest-cost position this agent has stood on, re-evaluated on the current
//!   landscape every step (other agents and the target move); the current position replaces it
//!   when it is at least as good. gbest = the best of the group's pbests, each on its owner's
//!   landscape (the paper's "best position achieved by the swarm"), and of one **sight point** per
//!   agent: the point [`PsoParams::sight`] px ahead on the straight line to the target, on that
//!   agent's landscape (what a walking person sees of the way ahead). O(N) per step. Without sight
//!   points (sight = 0) a lone person or a small group has no information about where the target
//!   lies except its own history, and random-walks towards it with a ratchet (measured: 600 px
//!   head-on in 1000–3000 steps instead of ~400); the paper's two persons walk almost straight.
//! * Acceptance (eq. 4): a candidate with obstacle cost `f` is accepted with probability
//!   `1 − f/e^{−k} = 1 − exp(k − s²)`, clamped to [0, 1], where `s` is its smallest σ-scaled
//!   distance; `s² ≤ k` gives exactly 0, so with k ≥ 1 no agent ever enters a no-go zone.
//!   Positions outside the scene are never accepted. An agent that is already inside a zone (it
//!   was spawned there, or another agent stepped next to it) may take any candidate that leaves it
//!   or moves outwards, otherwise it would be frozen for ever. If the first candidate is refused, up to
//!   `retries` candidates turned by a random angle in (−20°, 20°) from it are tried and the accepted
//!   one of lowest F is kept; if none is accepted the agent stays and its heading becomes the least
//!   bad refused direction, so a person blocked head-on keeps turning instead of pushing forever.
//! * Hills (the paper's §5.6, "a crowd passing over mountains of three heights"): the ground
//!   height `h(p)` (sum of the scene's Gaussian hills) is one more object of the uniform model,
//!   with cost `e^{−k} · h / climb_limit`. It enters the max over O like an obstacle: the
//!   objective grows with height (people prefer the low way), and the acceptance step refuses
//!   every position with `h ≥ climb_limit`, so a hill higher than the limit is never climbed
//!   above that contour while a lower one is crossed, rarely at its top (acceptance
//!   `1 − h/climb_limit` there).
//! * With `acceptance` off the candidate is always taken and the world lets these agents pass
//!   through obstacles: the original PSO of the paper's Fig. 5(b).

use super::planner::{GroupView, Planner, StepContext};
use crate::model::geometry::{unit_or, Aabb, Obstacle};
use crate::model::params::PsoParams;
use crate::model::scene::ground_height;
use crate::planners::explain::{Explanation, NamedPoint, NamedVector};
use crate::rng::Rng;
use crate::spatial::{QueryCap, SpatialGrid};
use glam::Vec2;
use std::ops::Range;

/// Scaled distance beyond which a cost is treated as zero (`exp(−9)` ≈ 1.2·10⁻⁴).
const CUTOFF_SCALED: f32 = 3.0;
/// Neighbours (and candidates of the scanned cells) one cost evaluation looks at, the first in
/// the grid's scan order: the nearest of them sets the agent term. Within the 30 px cutoff of
/// the default σ fit about 40 non-overlapping 4 px discs (about 120 in the 3 × 3 cells
/// scanned), so only a pile reaches the cap; there it bounds the work per evaluation.
const NEIGHBOUR_CAP: QueryCap = QueryCap { neighbours: 128, candidates: 1024 };

/// The PSO crowd planner for one group. Per-agent state is struct-of-arrays indexed by the
/// agent's position within its group.
#[derive(Clone, Debug)]
pub struct Pso {
    params: PsoParams,
    /// Largest distance (px) from an obstacle's bounding box at which its cost is not negligible.
    obstacle_reach: f32,
    /// Unit direction part of each agent's velocity.
    direction: Vec<Vec2>,
    /// Each agent's best position.
    pbest: Vec<Vec2>,
    /// Scratch: cost of each pbest this step.
    pbest_cost: Vec<f32>,
    /// Scratch: objective at each agent's current position this step.
    here_cost: Vec<f32>,
    /// Scratch: smallest σ-scaled distance² at each agent's current position this step.
    here_scaled2: Vec<f32>,
    /// Scratch: per agent, what phase 1's scan round it found ([`Around`]), `None` where the
    /// query caps could bind and phase 2 asks the grid.
    around: Vec<Option<f32>>,
    /// Scratch: the positions of one agent's [`Near::Local`] list.
    near: Vec<Vec2>,
}

/// What one position costs an agent.
#[derive(Clone, Copy, Debug)]
struct Evaluation {
    /// Smallest σ-scaled distance², over obstacles and other agents (∞ if none near).
    scaled2: f32,
    /// The objective F.
    objective: f32,
}

impl Pso {
    /// A planner for a scene with these obstacles.
    pub fn new(params: PsoParams, obstacles: &[Obstacle]) -> Self {
        let sigma = params.agent_sigma;
        let obstacle_reach =
            obstacles.iter().map(|o| 2.0 * obstacle_scope(o) + CUTOFF_SCALED * sigma).fold(0.0f32, f32::max);
        Self {
            params,
            obstacle_reach,
            direction: Vec::new(),
            pbest: Vec::new(),
            pbest_cost: Vec::new(),
            here_cost: Vec::new(),
            here_scaled2: Vec::new(),
            around: Vec::new(),
            near: Vec::new(),
        }
    }

    /// The radius and squared radius of the agent–agent cost's neighbour query.
    fn cutoff(&self) -> (f32, f32) {
        let radius = CUTOFF_SCALED * (2.0 * self.params.agent_sigma);
        (radius, radius * radius)
    }

    /// The obstacle cost `max_{o∈O} C(p, o)` for a smallest σ-scaled distance².
    fn obstacle_cost(scaled2: f32) -> f32 {
        if scaled2.is_finite() {
            libm::expf(-scaled2)
        } else {
            0.0
        }
    }

    /// F at `p` on the landscape of agent `me`.
    fn evaluate(&self, ctx: &StepContext, me: u32, p: Vec2, goal: Option<Vec2>) -> Evaluation {
        let (radius, _) = self.cutoff();
        let nearest2 = ctx.grid.nearest_d2_within_capped(p, radius, NEIGHBOUR_CAP, me);
        self.evaluate_with(ctx, p, nearest2, goal)
    }

    /// F at `p` given the squared distance to the nearest other agent within the cutoff
    /// (`∞` if none): the agents' part of [`Self::evaluate`], found by the caller.
    fn evaluate_with(&self, ctx: &StepContext, p: Vec2, nearest2: f32, goal: Option<Vec2>) -> Evaluation {
        let scaled2 = self.scaled2_with(ctx, p, nearest2);
        Evaluation { scaled2, objective: self.objective(ctx, p, scaled2, goal) }
    }

    /// The smallest σ-scaled distance² at `p` over obstacles, other agents (the nearest at
    /// squared distance `nearest2`) and hills.
    fn scaled2_with(&self, ctx: &StepContext, p: Vec2, nearest2: f32) -> f32 {
        let sigma = self.params.agent_sigma;
        let mut scaled2 = f32::INFINITY;
        if !ctx.obstacles.is_empty() {
            let query = Aabb { min: p, max: p }.inflate(self.obstacle_reach);
            ctx.obstacles.for_each_near(query, |_, o| {
                let scope = obstacle_scope(o);
                let s = ((o.surface(p).signed_distance + scope) / (scope + sigma)).max(0.0);
                scaled2 = scaled2.min(s * s);
            });
        }
        // Agent–agent: σp + σq = 2σ in both axes, so the scaled distance is |p − q| / 2σ.
        let pair = 2.0 * sigma;
        scaled2 = scaled2.min(nearest2 / (pair * pair));
        if !ctx.scene.hills.is_empty() {
            // Hills join the uniform model as one more object: cost `e^{−k} · h / climb_limit`,
            // written as its σ-scaled distance² `k − ln(h / climb_limit)`, so ground at the climb
            // limit sits exactly on the no-go boundary and higher ground is never accepted.
            let h = ground_height(&ctx.scene.hills, p);
            if h > 0.0 {
                let s2 = self.params.k - libm::logf(h / self.params.climb_limit);
                scaled2 = scaled2.min(s2.max(0.0));
            }
        }
        scaled2
    }

    /// The objective F at `p` with smallest σ-scaled distance² `scaled2`.
    fn objective(&self, ctx: &StepContext, p: Vec2, scaled2: f32, goal: Option<Vec2>) -> f32 {
        let sigma = self.params.agent_sigma;
        let target = match goal {
            // 1/C(p, g) with the target's σ = the whole search area.
            Some(g) => {
                let d = p - g;
                let sx = ctx.bounds.x + sigma;
                let sy = ctx.bounds.y + sigma;
                libm::expf(d.x * d.x / (sx * sx) + d.y * d.y / (sy * sy))
            }
            None => 1.0,
        };
        self.params.obstacle_weight * Self::obstacle_cost(scaled2) + target
    }

    /// The new direction and velocity of agent `id` (index `k` in the group); `near` is
    /// scratch for its [`Near::Local`] list.
    #[allow(clippy::too_many_arguments, reason = "the plain inputs of a per-agent step, and its scratch")]
    fn move_agent(
        &self,
        ctx: &StepContext,
        k: usize,
        id: u32,
        gbest: Vec2,
        goal: Option<Vec2>,
        near: &mut Vec<Vec2>,
        rng: &mut Rng,
    ) -> (Vec2, Vec2) {
        let prm = &self.params;
        let p = ctx.positions[id as usize];
        let (r1, r2) = (rng.unit(), rng.unit());
        let here2 = self.here_scaled2[k];
        let old = self.direction[k];
        let pull = old * prm.inertia
            + unit_or(self.pbest[k] - p, Vec2::ZERO) * (prm.cognitive * r1)
            + unit_or(gbest - p, Vec2::ZERO) * (prm.social * r2);
        let direction = unit_or(pull, old);
        let speed = prm.max_speed / self.here_cost[k].max(1.0);
        if !prm.acceptance {
            return (direction, direction * speed);
        }
        let near = self.near_list(ctx.grid, k, id, p, speed, near);
        if self.try_move(ctx, id, p + direction * speed, here2, &near, rng).0 {
            return (direction, direction * speed);
        }
        let max_angle = prm.retry_angle_deg.to_radians();
        let mut best_accepted: Option<(f32, Vec2)> = None;
        let mut least_bad = (f32::NEG_INFINITY, direction);
        for _ in 0..prm.retries {
            let d = Vec2::from_angle(rng.range(-max_angle, max_angle)).rotate(direction);
            let candidate = p + d * speed;
            let (accepted, scaled2) = self.try_move(ctx, id, candidate, here2, &near, rng);
            if accepted {
                // The objective only ranks accepted candidates: refused ones skip its exps.
                let objective = self.objective(ctx, candidate, scaled2, goal);
                if best_accepted.is_none_or(|(c, _)| objective < c) {
                    best_accepted = Some((objective, d));
                }
            } else if scaled2 > least_bad.0 {
                least_bad = (scaled2, d);
            }
        }
        match best_accepted {
            Some((_, d)) => (d, d * speed),
            None => (least_bad.1, Vec2::ZERO),
        }
    }

    /// The acceptance test of a candidate position: (accepted, its smallest σ-scaled
    /// distance²). Positions outside the scene (less the body radius) are refused; inside a
    /// no-go zone (`here2 ≤ k`), moves outwards are always accepted.
    fn try_move(
        &self,
        ctx: &StepContext,
        id: u32,
        candidate: Vec2,
        here2: f32,
        near: &Near,
        rng: &mut Rng,
    ) -> (bool, f32) {
        let scaled2 = self.scaled2_with(ctx, candidate, self.nearest2(ctx.grid, id, candidate, near));
        let r = Vec2::splat(ctx.radii[id as usize]);
        let inside = candidate.cmpge(r).all() && candidate.cmple(ctx.bounds - r).all();
        // Draw even for refused positions so the random stream does not depend on geometry edge cases.
        let draw = rng.unit();
        let escaping = here2 <= self.params.k && scaled2 > here2;
        let climbs = self.climbs_over_limit(ctx, ctx.positions[id as usize], candidate);
        (inside && !climbs && (escaping || draw < self.acceptance_probability(scaled2)), scaled2)
    }

    /// The squared distance from `c` to the nearest agent other than `me` within the cutoff
    /// (`∞` if none), as [`Self::evaluate`] finds it, looked up in `near`.
    fn nearest2(&self, grid: &SpatialGrid, me: u32, c: Vec2, near: &Near) -> f32 {
        let (radius, r2) = self.cutoff();
        match near {
            Near::Grid => grid.nearest_d2_within_capped(c, radius, NEIGHBOUR_CAP, me),
            Near::Local(list) => {
                // The grid's answer is the smallest squared distance to any other agent when
                // that is within the cutoff: `list` holds the agent that gives it (see
                // `near_list`), and `min` is exact in any order.
                let m = list.iter().fold(f32::INFINITY, |m, q| m.min(c.distance_squared(*q)));
                if m <= r2 {
                    m
                } else {
                    f32::INFINITY
                }
            }
        }
    }

    /// How far round agent `me` at `p` phase 1 scans: the cutoff, plus the farthest a point
    /// looked up with that scan lies from `p` (its pbest, a candidate move: `max_speed`), plus
    /// [`slack`].
    fn reach(&self, p: Vec2) -> f32 {
        let (radius, _) = self.cutoff();
        let reach = radius + self.params.max_speed;
        reach + slack(p, reach)
    }

    /// Scans the cells within [`Self::reach`] of `p` once: the smallest squared distance from
    /// `p` and from `pbest` to an agent other than `me` among those cells' agents, or `None`
    /// when the neighbour query of some point within `max_speed` of `p` could reach a cap of
    /// [`NEIGHBOUR_CAP`] (then the grid must answer each one).
    ///
    /// Why this is the grid's answer: for a point `c` within `max_speed` of `p`, every agent
    /// within the cutoff of `c` lies within `reach` of `p`, and `c`'s query scans a subset of
    /// the cells scanned here (cell coordinates grow with position). With at most
    /// `NEIGHBOUR_CAP.neighbours` agents within `reach` and `NEIGHBOUR_CAP.candidates` in the
    /// cells, no cap binds for `c`, and the grid returns the smallest squared distance to the
    /// other agents within the cutoff: the smallest over any superset of them, when that is
    /// within the cutoff (else ∞).
    fn scan_round(&self, grid: &SpatialGrid, p: Vec2, pbest: Vec2, me: u32) -> Option<(f32, f32)> {
        let reach = self.reach(p);
        let reach2 = reach * reach;
        let columns = grid.columns();
        // Running minima and counts per lane: independent chains (a minimum is the same in
        // any order). A NaN distance never passes `<`, as `min` ignores it.
        const LANES: usize = 4;
        let mut here = [f32::INFINITY; LANES];
        let mut best = [f32::INFINITY; LANES];
        let (mut within, mut candidates) = ([0u32; LANES], 0usize);
        for Range { start, end } in grid.query_rows(p, reach) {
            candidates += end - start;
            if candidates > NEIGHBOUR_CAP.candidates {
                return None;
            }
            let (Some(xs), Some(ys), Some(ids)) =
                (columns.x.get(start..end), columns.y.get(start..end), columns.ids.get(start..end))
            else {
                return None;
            };
            let mut lane = |lane: usize, x: f32, y: f32, id: u32| {
                let q = Vec2::new(x, y);
                let (d2, b2) = (p.distance_squared(q), pbest.distance_squared(q));
                within[lane] += u32::from(d2 <= reach2);
                let other = id != me;
                let d2 = if other { d2 } else { f32::INFINITY };
                let b2 = if other { b2 } else { f32::INFINITY };
                here[lane] = if d2 < here[lane] { d2 } else { here[lane] };
                best[lane] = if b2 < best[lane] { b2 } else { best[lane] };
            };
            let (xs4, ys4, ids4) = (xs.chunks_exact(LANES), ys.chunks_exact(LANES), ids.chunks_exact(LANES));
            let rest = xs4.remainder().iter().zip(ys4.remainder()).zip(ids4.remainder());
            for ((xs, ys), ids) in xs4.zip(ys4).zip(ids4) {
                for k in 0..LANES {
                    lane(k, xs[k], ys[k], ids[k]);
                }
            }
            for (k, ((&x, &y), &id)) in rest.enumerate() {
                lane(k, x, y, id);
            }
        }
        let min = |lanes: [f32; LANES]| lanes.iter().fold(f32::INFINITY, |m, &v| m.min(v));
        let within: u32 = within.iter().sum();
        (within as usize <= NEIGHBOUR_CAP.neighbours).then_some((min(here), min(best)))
    }

    /// Where the candidate moves of agent `me` (index `k`) at `p`, all within `speed` ≤
    /// `max_speed` of `p`, find their nearest other agent: the agents within
    /// `T = √here + 2·speed + slack` of `p`, `here` being phase 1's smallest squared distance
    /// from `p` ([`Self::scan_round`]). That agent is within `√here + speed` of a candidate,
    /// and any agent farther than `T` from `p` is farther than `√here + speed + slack` from
    /// it, so the list holds the nearest other agent of every candidate (a handful in a jam,
    /// instead of the whole cutoff disc for every retry). If no other agent lies within
    /// `reach` of `p`, none is within the cutoff of a candidate: an empty list.
    fn near_list<'a>(
        &self,
        grid: &SpatialGrid,
        k: usize,
        me: u32,
        p: Vec2,
        speed: f32,
        list: &'a mut Vec<Vec2>,
    ) -> Near<'a> {
        list.clear();
        let Some(here) = self.around.get(k).copied().flatten() else { return Near::Grid };
        let reach = self.reach(p);
        if here.partial_cmp(&(reach * reach)).is_none_or(|o| o == std::cmp::Ordering::Greater) {
            return Near::Local(list);
        }
        let t = here.sqrt() + 2.0 * speed + slack(p, reach);
        let t2 = t * t;
        let columns = grid.columns();
        for Range { start, end } in grid.query_rows(p, t) {
            let (Some(xs), Some(ys), Some(ids)) =
                (columns.x.get(start..end), columns.y.get(start..end), columns.ids.get(start..end))
            else {
                list.clear();
                return Near::Grid;
            };
            // Every candidate is written, and kept (the end advanced past it) when it is in:
            // no branch whose outcome the CPU could not predict.
            let mut kept = list.len();
            list.resize(kept + xs.len(), Vec2::ZERO);
            if let Some(out) = list.get_mut(kept..) {
                let mut n = 0;
                for ((&x, &y), &id) in xs.iter().zip(ys).zip(ids) {
                    let q = Vec2::new(x, y);
                    out[n] = q;
                    n += usize::from((id != me) & (p.distance_squared(q) <= t2));
                }
                kept += n;
            }
            list.truncate(kept);
        }
        Near::Local(list)
    }

    /// Whether moving from `from` to `candidate` climbs to ground at or above the climb limit.
    /// Refused even when escaping a crowd: pushed by its neighbours (their no-go zones), an
    /// agent could otherwise be accepted up a hill's slope whenever the hill is the lesser cost
    /// (measured with 300 people: 2 crossed the limit contour by up to 1.2 px).
    fn climbs_over_limit(&self, ctx: &StepContext, from: Vec2, candidate: Vec2) -> bool {
        if ctx.scene.hills.is_empty() || !self.params.acceptance {
            return false;
        }
        let h = ground_height(&ctx.scene.hills, candidate);
        h >= self.params.climb_limit && h > ground_height(&ctx.scene.hills, from)
    }

    /// Eq. 4 in σ-scaled distance: `1 − f e^{k} = 1 − exp(k − s²)`, exactly 0 when `s² ≤ k`.
    fn acceptance_probability(&self, scaled2: f32) -> f32 {
        if !scaled2.is_finite() {
            return 1.0;
        }
        if scaled2 <= self.params.k {
            // exp(k − s²) ≥ 1 clamps to 0: skip the exp (most retries in a jam end here).
            return 0.0;
        }
        (1.0 - libm::expf(self.params.k - scaled2)).clamp(0.0, 1.0)
    }
}

/// Extra distance (px) the local neighbour lists reach past what they must cover: far more
/// than the rounding of the positions, candidate points and squared distances involved
/// (relative 10⁻⁶ of the coordinates and distances), so no agent is missed by a rounding.
fn slack(p: Vec2, distance: f32) -> f32 {
    0.25 + 1e-4 * (p.abs().max_element() + distance)
}

/// Where the nearest-agent lookups of one agent's candidate moves go ([`Pso::near_list`]).
enum Near<'a> {
    /// The grid, as [`Pso::evaluate`] asks it.
    Grid,
    /// A list of other agents' positions that holds the nearest one to every candidate.
    Local(&'a [Vec2]),
}

/// Agent `k`'s bests re-evaluated on the current landscape (phase 1 of a step).
struct Reevaluated {
    /// The evaluation at the agent's position.
    here: Evaluation,
    /// Its best position after the update.
    pbest: Vec2,
    /// That position's cost now.
    pbest_cost: f32,
    /// Its sight point towards the target and that point's cost, a gbest candidate.
    sight: Option<(f32, Vec2)>,
    /// [`Pso::scan_round`]'s smallest squared distance from the agent's position, if no
    /// query cap can bind round it.
    around: Option<f32>,
}

/// Makes `(cost, p)` the best if it is cheaper (ties keep the earlier one).
fn offer_best(best: &mut Option<(f32, Vec2)>, cost: f32, p: Vec2) {
    if best.is_none_or(|(c, _)| cost < c) {
        *best = Some((cost, p));
    }
}

impl Pso {
    /// Phase 1 for one agent: the cost here, the updated pbest and the sight point.
    fn reevaluate(&self, ctx: &StepContext, k: usize, id: u32, goal: Option<Vec2>) -> Reevaluated {
        let p = ctx.positions[id as usize];
        let old_best = self.pbest.get(k).copied().unwrap_or(p);
        // Both points' nearest agents from one scan where it gives the grid's answer.
        let (radius, r2) = self.cutoff();
        let grid = |c: Vec2| ctx.grid.nearest_d2_within_capped(c, radius, NEIGHBOUR_CAP, id);
        let cut = |m: f32| if m <= r2 { m } else { f32::INFINITY };
        let max_speed = self.params.max_speed;
        let around = self.scan_round(ctx.grid, p, old_best, id);
        let (here_near, best_near) = match around {
            Some((h, b)) if p.distance_squared(old_best) <= max_speed * max_speed => (cut(h), cut(b)),
            Some((h, _)) => (cut(h), grid(old_best)),
            None => (grid(p), grid(old_best)),
        };
        let here = self.evaluate_with(ctx, p, here_near, goal);
        let best = self.evaluate_with(ctx, old_best, best_near, goal).objective;
        let (pbest, pbest_cost) = if here.objective <= best { (p, here.objective) } else { (old_best, best) };
        let sight = goal.filter(|_| self.params.sight > 0.0).map(|g| {
            let to = g - p;
            let sight = p + to * (self.params.sight / to.length().max(self.params.sight));
            (self.evaluate(ctx, id, sight, goal).objective, sight)
        });
        Reevaluated { here, pbest, pbest_cost, sight, around: around.map(|(h, _)| h) }
    }
}

/// The scope `R` of an obstacle (px): its radius, or half the shorter side of its (bounding) box.
fn obstacle_scope(o: &Obstacle) -> f32 {
    match o {
        Obstacle::Circle { radius, .. } => *radius,
        _ => {
            let b = o.aabb();
            let size = b.max - b.min;
            0.5 * size.x.min(size.y).max(0.0)
        }
    }
}

impl Planner for Pso {
    /// PSO agents gather at their goal by themselves: its objective keeps every agent off the others (agent σ) round the target, the paper's gathering. Walking them to places by the
    /// world (straight, not seen by this planner's avoidance) would make them overlap.
    fn interaction_radius(&self) -> f32 {
        CUTOFF_SCALED * 2.0 * self.params.agent_sigma
    }

    fn max_speed(&self) -> f32 {
        self.params.max_speed
    }

    fn passes_through_obstacles(&self) -> bool {
        !self.params.acceptance
    }

    fn cost_at(&self, ctx: &StepContext, group: &GroupView, agent: u32, p: Vec2) -> Option<f32> {
        Some(self.evaluate(ctx, agent, p, group.goal.map(|(g, _)| g)).objective)
    }

    /// Recomputes phase 1 for the whole group (gbest needs it) and the agent's expected move:
    /// the pull terms with r1 = r2 = ½, the speed its cost allows, and the first candidate and
    /// evenly spaced retries with their acceptance probability (the step draws the retry angles
    /// at random; a probability of 0 is a certain refusal).
    fn explain(&self, ctx: &StepContext, group: &GroupView, agent: u32) -> Explanation {
        let prm = &self.params;
        let goal = group.goal.map(|(g, _)| g);
        let start = group.agents.start;
        let mut e = Explanation { scale: 20.0, ..Explanation::default() };
        let Some(k) = agent.checked_sub(start).map(|k| k as usize).filter(|&k| k < group.agents.len()) else {
            return e;
        };
        let mut gbest: Option<(f32, Vec2)> = None;
        let mut mine = None;
        for j in 0..group.agents.len() {
            let r = self.reevaluate(ctx, j, start + j as u32, goal);
            offer_best(&mut gbest, r.pbest_cost, r.pbest);
            if let Some((cost, sight)) = r.sight {
                offer_best(&mut gbest, cost, sight);
            }
            if j == k {
                mine = Some(r);
            }
        }
        let (Some(mine), Some((_, gbest))) = (mine, gbest) else { return e };
        let p = ctx.positions[agent as usize];
        let old = self
            .direction
            .get(k)
            .copied()
            .unwrap_or_else(|| unit_or(ctx.velocities[agent as usize], Vec2::X));
        let inertia = old * prm.inertia;
        let cognitive = unit_or(mine.pbest - p, Vec2::ZERO) * (prm.cognitive * 0.5);
        let social = unit_or(gbest - p, Vec2::ZERO) * (prm.social * 0.5);
        e.vectors.push(NamedVector::new("inertia ωD", inertia));
        e.vectors.push(NamedVector::new("cognitive (to pbest)", cognitive));
        e.vectors.push(NamedVector::new("social (to gbest)", social));
        let direction = unit_or(inertia + cognitive + social, old);
        let speed = prm.max_speed / mine.here.objective.max(1.0);
        e.points.push(NamedPoint::new("pbest", mine.pbest));
        e.points.push(NamedPoint::new("gbest", gbest));
        let max_angle = prm.retry_angle_deg.to_radians();
        let tries = 1 + prm.retries;
        let mut accepted = 0;
        for t in 0..tries {
            let angle = if t == 0 || tries < 2 {
                0.0
            } else {
                -max_angle + 2.0 * max_angle * (t - 1) as f32 / (tries - 2).max(1) as f32
            };
            let candidate = p + Vec2::from_angle(angle).rotate(direction) * speed;
            let ev = self.evaluate(ctx, agent, candidate, goal);
            let r = Vec2::splat(ctx.radii[agent as usize]);
            let inside = candidate.cmpge(r).all() && candidate.cmple(ctx.bounds - r).all();
            let escaping = mine.here.scaled2 <= prm.k && ev.scaled2 > mine.here.scaled2;
            let probability = if self.climbs_over_limit(ctx, p, candidate) {
                0.0
            } else if !prm.acceptance || escaping {
                1.0
            } else if inside {
                self.acceptance_probability(ev.scaled2)
            } else {
                0.0
            };
            if probability > 0.0 {
                accepted += 1;
            }
            let name = if probability > 0.0 { "candidate" } else { "rejected candidate" };
            e.points.push(NamedPoint::new(name, candidate));
            if t == 0 {
                e.values.push(("acceptance of the first candidate".into(), probability));
                if probability > 0.0 {
                    break;
                }
            }
        }
        e.applied = direction * speed;
        e.values.push(("cost F here".into(), mine.here.objective));
        e.values.push(("obstacle cost".into(), Self::obstacle_cost(mine.here.scaled2)));
        e.values.push(("speed allowed".into(), speed));
        let pair = 2.0 * prm.agent_sigma;
        ctx.grid.for_each_within(p, CUTOFF_SCALED * pair, |n| {
            if n.id != agent {
                e.neighbours.push(n.id);
            }
        });
        e.state = if accepted == 0 {
            "every candidate refused: stays this step".into()
        } else if Self::obstacle_cost(mine.here.scaled2) > 0.05 {
            "slowed: an obstacle or another person is near (obstacle cost above 0.05)".into()
        } else {
            "walking towards gbest".into()
        };
        e
    }

    fn plan(&mut self, ctx: &StepContext, group: GroupView, rng: &mut Rng, new_velocities: &mut [Vec2]) {
        let n = group.agents.len();
        let goal = group.goal.map(|(g, _)| g);
        let start = group.agents.start;
        if self.direction.len() != n {
            // First step (or a resized group): the velocities the world spawned are random,
            // as the paper initialises them.
            self.direction = (0..n)
                .map(|k| {
                    let fallback = Vec2::from_angle(rng.range(-std::f32::consts::PI, std::f32::consts::PI));
                    unit_or(ctx.velocities[start as usize + k], fallback)
                })
                .collect();
            self.pbest = (0..n).map(|k| ctx.positions[start as usize + k]).collect();
            self.pbest_cost = vec![0.0; n];
            self.here_cost = vec![0.0; n];
            self.here_scaled2 = vec![0.0; n];
            self.around = vec![None; n];
        }

        // Phase 1: re-evaluate every pbest on the current landscape; the group's best is gbest.
        let mut gbest: Option<(f32, Vec2)> = None;
        for k in 0..n {
            let id = start + k as u32;
            let r = self.reevaluate(ctx, k, id, goal);
            self.here_cost[k] = r.here.objective;
            self.here_scaled2[k] = r.here.scaled2;
            self.around[k] = r.around;
            self.pbest[k] = r.pbest;
            self.pbest_cost[k] = r.pbest_cost;
            offer_best(&mut gbest, r.pbest_cost, r.pbest);
            if let Some((cost, sight)) = r.sight {
                offer_best(&mut gbest, cost, sight);
            }
        }
        let Some((_, gbest)) = gbest else { return };

        // Phase 2: direction, speed, acceptance.
        let mut near = std::mem::take(&mut self.near);
        for (k, out) in new_velocities.iter_mut().enumerate().take(n) {
            let id = start + k as u32;
            let (direction, velocity) = self.move_agent(ctx, k, id, gbest, goal, &mut near, rng);
            self.direction[k] = direction;
            *out = velocity;
        }
        self.near = near;
    }
}
