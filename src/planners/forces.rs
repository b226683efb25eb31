//! Five weighted virtual forces, the model whose weights the genetic algorithm tunes (DESIGN §3.5).
//!
//! `F = s1 Fsep + s2 Falign + s3 Fcoh + s4 Ffol + s5 Fcol`, each force normalised to length ≤ 1,
//! applied as an acceleration of `|F| · max_force`; then the turn per step and the speed are
//! limited (the paper's translation and rotation speed limits). Agents see other agents in a
//! 330° cone up to 20 body sizes (body size = diameter).

use super::planner::{GroupView, Planner, StepContext};
use crate::model::geometry::limit;
use crate::model::geometry::{unit_or, Aabb, Obstacle};
use crate::model::params::ForcesParams;
use crate::planners::explain::{Explanation, NamedVector};
use crate::rng::Rng;
use crate::spatial::{Columns, QueryCap};
use glam::Vec2;

/// Steps between two samples of the goal's trace.
const TRACE_EVERY: u32 = 5;
/// Samples of the goal's trace kept (newest last).
const TRACE_LEN: usize = 64;
/// Older trace points tried when the followed point is out of sight (bounds the ray casts).
const TRACE_SEARCH: usize = 8;
/// Neighbours (and candidates of the scanned cells) an agent looks at, the first in the grid's
/// scan order. The default view (20 body sizes, 160 px) holds at most about 1,150
/// non-overlapping 4 px discs (about 3,300 in the 3 × 3 cells scanned): only a pile reaches the
/// cap, and there it bounds the work per agent.
const NEIGHBOUR_CAP: QueryCap = QueryCap { neighbours: 1536, candidates: 6144 };
/// Below this speed (px/step) an agent has no heading: it sees all round and turns freely.
const MIN_HEADING_SPEED: f32 = 1e-3;

/// The virtual-force planner for one group.
#[derive(Clone, Debug)]
pub struct Forces {
    params: ForcesParams,
    /// Recent goal positions (the leader's trace), oldest first.
    trace: Vec<Vec2>,
    /// Heading limit as (cos, sin) of the turn per step.
    max_turn: Vec2,
    /// Cosine of half the view angle.
    view_cos: f32,
    /// Scratch of one agent's neighbour pass, reused across agents.
    scratch: NeighbourScratch,
}

/// One agent's neighbours as columns (see [`Forces::agent_forces`]): the grid slots found, their
/// positions copied contiguously in the same order, then each one's separation term.
#[derive(Clone, Debug, Default)]
struct NeighbourScratch {
    /// Grid slots of the agents within range, in the grid's scan order.
    slots: Vec<u32>,
    /// Their positions.
    x: Vec<f32>,
    y: Vec<f32>,
    /// Each one's separation term (zero when it is not seen).
    sep_x: Vec<f32>,
    sep_y: Vec<f32>,
    /// Whether it is seen.
    seen: Vec<bool>,
}

impl Forces {
    /// A planner with these parameters.
    pub fn new(params: ForcesParams) -> Self {
        let turn = params.max_turn_deg.to_radians();
        let half_view = (0.5 * params.view_angle_deg).min(180.0).to_radians();
        Self {
            max_turn: Vec2::new(libm::cosf(turn), libm::sinf(turn)),
            view_cos: libm::cosf(half_view),
            params,
            trace: Vec::with_capacity(TRACE_LEN),
            scratch: NeighbourScratch::default(),
        }
    }

    /// The parameters.
    pub fn params(&self) -> &ForcesParams {
        &self.params
    }

    fn record_trace(&mut self, step: u32, goal: Vec2) {
        let moved = self.trace.last().is_none_or(|last| last.distance_squared(goal) > 1e-6);
        if moved && (step.is_multiple_of(TRACE_EVERY) || self.trace.is_empty()) {
            if self.trace.len() == TRACE_LEN {
                self.trace.remove(0);
            }
            self.trace.push(goal);
        }
    }

    /// The point `follow_offset` px behind the goal along its trace, as a trace index range to
    /// search: returns the point and the trace index it lies before.
    fn followed_point(&self, goal: Vec2) -> (Vec2, usize) {
        let mut left = self.params.follow_offset;
        let mut at = goal;
        for k in (0..self.trace.len()).rev() {
            let q = self.trace[k];
            let d = at.distance(q);
            if left <= d {
                let p = if d > 0.0 { at + (q - at) * (left / d) } else { at };
                return (p, k + 1);
            }
            left -= d;
            at = q;
        }
        (at, 0)
    }

    /// Whether the segment `from → to` passes no obstacle.
    fn clear_line(ctx: &StepContext, from: Vec2, to: Vec2) -> bool {
        let query = Aabb { min: from.min(to), max: from.max(to) };
        let mut clear = true;
        ctx.obstacles.for_each_near(query, |_, o: &Obstacle| {
            if clear && o.ray_cast(from, to - from).is_some() {
                clear = false;
            }
        });
        clear
    }

    /// Following (after the leader-trace model of the paper's ref. 5): head for the followed
    /// point if the straight line to it is free, else for the newest older trace point that is
    /// in sight (among the next 8); steering `desired − velocity` normalised by the speed limit.
    fn following(&self, ctx: &StepContext, p: Vec2, vel: Vec2, goal: Option<(Vec2, f32)>) -> Vec2 {
        let Some((goal, _)) = goal else { return Vec2::ZERO };
        let (mut target, before) = self.followed_point(goal);
        if !ctx.obstacles.is_empty() && !Self::clear_line(ctx, p, target) {
            let oldest = before.saturating_sub(TRACE_SEARCH);
            if let Some(k) = (oldest..before).rev().find(|&k| Self::clear_line(ctx, p, self.trace[k])) {
                target = self.trace[k];
            }
        }
        let to = target - p;
        let d = to.length();
        let speed = self.params.max_speed * (d / self.params.slowing_distance).min(1.0);
        let desired = if d > 1e-6 { to * (speed / d) } else { Vec2::ZERO };
        limit((desired - vel) / self.params.max_speed, 1.0)
    }

    /// Collision: obstacles and borders the agent would reach within the horizon push it away
    /// (stronger the sooner), plus a push from surfaces closer than one body size.
    fn collision(&self, ctx: &StepContext, p: Vec2, vel: Vec2, radius: f32, towards: Vec2) -> Vec2 {
        let size = 2.0 * radius;
        let speed = vel.length();
        let heading = unit_or(vel, towards);
        let reach = speed * self.params.horizon_steps + radius;
        let mut force = Vec2::ZERO;
        if !ctx.obstacles.is_empty() {
            let query = Aabb { min: p, max: p }.inflate(reach.max(size) + radius);
            let side = heading.perp() * radius;
            let ray = heading * reach;
            let mut nearest: Option<(f32, Vec2)> = None;
            ctx.obstacles.for_each_near(query, |_, o: &Obstacle| {
                if speed > MIN_HEADING_SPEED {
                    for from in [p, p + side, p - side] {
                        if let Some(hit) = o.ray_cast(from, ray) {
                            if nearest.is_none_or(|(t, _)| hit.t < t) {
                                nearest = Some((hit.t, hit.normal));
                            }
                        }
                    }
                }
                let s = o.surface(p);
                let gap = s.signed_distance - radius;
                if gap < size {
                    force += s.normal * (1.0 - gap.max(0.0) / size);
                }
            });
            if let Some((t, normal)) = nearest {
                // Turn aside rather than brake: the normal's sideways part, or the side of the
                // goal for a head-on hit.
                let mut lateral = normal - heading * normal.dot(heading);
                if lateral.length_squared() < 1e-4 {
                    lateral = heading.perp() * if heading.perp().dot(towards) >= 0.0 { 1.0 } else { -1.0 };
                }
                force += unit_or(normal + unit_or(lateral, heading.perp()), normal) * (1.0 - t);
            }
        }
        // The world's borders are walls too.
        let horizon = self.params.horizon_steps;
        let walls = [
            (p.x - radius, -vel.x, Vec2::X),
            (ctx.bounds.x - radius - p.x, vel.x, Vec2::NEG_X),
            (p.y - radius, -vel.y, Vec2::Y),
            (ctx.bounds.y - radius - p.y, vel.y, Vec2::NEG_Y),
        ];
        for (gap, closing, inward) in walls {
            if closing > MIN_HEADING_SPEED {
                let steps = gap.max(0.0) / closing;
                if steps < horizon {
                    force += inward * (1.0 - steps / horizon);
                }
            }
        }
        limit(force, 1.0)
    }

    /// Turns `next` towards at most `max_turn` away from the heading of `vel`.
    fn limit_turn(&self, vel: Vec2, next: Vec2) -> Vec2 {
        let (speed, next_speed) = (vel.length(), next.length());
        if speed <= MIN_HEADING_SPEED || next_speed <= MIN_HEADING_SPEED {
            return next;
        }
        let (from, to) = (vel / speed, next / next_speed);
        if from.dot(to) >= self.max_turn.x {
            return next;
        }
        let sign = if from.perp_dot(to) >= 0.0 { 1.0 } else { -1.0 };
        let turn = Vec2::new(self.max_turn.x, sign * self.max_turn.y);
        turn.rotate(from) * next_speed
    }
}

impl Planner for Forces {
    fn interaction_radius(&self) -> f32 {
        // The view range is in body sizes; the grid is sized for the default 4 px radius and
        // `plan` queries with each agent's own range.
        self.params.view_range_sizes * 8.0
    }

    fn max_speed(&self) -> f32 {
        self.params.max_speed
    }

    /// Arrived agents would pile onto the goal (separation is soft): the world parks them.
    fn parks_at_goal(&self) -> bool {
        true
    }

    fn explain(&self, ctx: &StepContext, group: &GroupView, agent: u32) -> Explanation {
        let prm = &self.params;
        let mut e = Explanation { scale: 150.0, ..Explanation::default() };
        if agent as usize >= ctx.positions.len() {
            return e;
        }
        let mut neighbours = Vec::new();
        let forces =
            self.agent_forces(ctx, group, agent, &mut NeighbourScratch::default(), |id| neighbours.push(id));
        for ((name, f), s) in FORCE_NAMES.iter().zip(forces).zip(prm.weights()) {
            e.vectors.push(NamedVector::new(name, f * (s * prm.max_force)));
        }
        e.applied = e.vectors.iter().map(|v| v.vector).sum();
        e.neighbours = neighbours;
        e.state = "five weighted forces; the turn per step is limited after the sum".into();
        e
    }

    fn plan(&mut self, ctx: &StepContext, group: GroupView, _rng: &mut Rng, new_velocities: &mut [Vec2]) {
        if let Some((goal, _)) = group.goal {
            self.record_trace(ctx.step, goal);
        }
        let mut scratch = std::mem::take(&mut self.scratch);
        for (k, id) in group.agents.clone().enumerate() {
            let forces = self.agent_forces(ctx, &group, id, &mut scratch, |_| {});
            let vel = ctx.velocities[id as usize];
            let force: Vec2 = forces.iter().zip(self.params.weights()).map(|(f, s)| *f * s).sum();
            let next = self.limit_turn(vel, vel + force * self.params.max_force);
            new_velocities[k] = limit(next, self.params.max_speed);
        }
        self.scratch = scratch;
    }
}

/// Names of the five forces, in weight order (the explanation's arrows).
const FORCE_NAMES: [&str; 5] =
    ["s1 separation", "s2 alignment", "s3 cohesion", "s4 following", "s5 collision"];

impl Forces {
    /// The five normalised forces on agent `id` from the step's state, in [`FORCE_NAMES`] order;
    /// `seen` is called with every neighbour in view. `plan` and `explain` both use it.
    fn agent_forces(
        &self,
        ctx: &StepContext,
        group: &GroupView,
        id: u32,
        scratch: &mut NeighbourScratch,
        mut seen: impl FnMut(u32),
    ) -> [Vec2; 5] {
        let prm = &self.params;
        let i = id as usize;
        let p = ctx.positions[i];
        let vel = ctx.velocities[i];
        let radius = ctx.radii[i];
        let size = 2.0 * radius;
        let range = prm.view_range_sizes * size;
        let speed = vel.length();
        let heading = if speed > MIN_HEADING_SPEED { Some(vel / speed) } else { None };

        // The agents in range (a branch-free pass), in the grid's scan order.
        ctx.grid.gather_within(p, range, NEIGHBOUR_CAP, &mut scratch.slots);
        let columns = ctx.grid.columns();
        let n = scratch.terms(columns, p, size, heading, self.view_cos);
        // The sums in scan order, as one loop adding only the neighbours seen would: one not
        // seen (or not in the group) adds +0, which leaves a sum of +0 and nonzero values
        // unchanged (such a sum is never −0), so they are bit for bit the same.
        let s = &*scratch;
        let (mut sep, mut sum_vel, mut sum_pos, mut n_flock) = (Vec2::ZERO, Vec2::ZERO, Vec2::ZERO, 0u32);
        let flock = group.agents.clone();
        // Columns of one length and slots clamped to it (a no-op: they index the grid), so the
        // loads need no bounds check.
        let len = columns.ids.len().min(columns.vx.len()).min(columns.vy.len());
        let (ids, vxs, vys) = (&columns.ids[..len], &columns.vx[..len], &columns.vy[..len]);
        let last = len.saturating_sub(1);
        let terms = s.slots[..n]
            .iter()
            .zip(&s.x[..n])
            .zip(&s.y[..n])
            .zip(&s.sep_x[..n])
            .zip(&s.sep_y[..n])
            .zip(&s.seen[..n]);
        for (((((&k, &x), &y), &sx), &sy), &seen_it) in terms {
            let k = (k as usize).min(last);
            let counts = seen_it & flock.contains(&ids[k]);
            // All ones when it counts, else zero: the terms become +0 without a branch.
            let mask = u32::from(counts).wrapping_neg();
            let keep = |v: f32| f32::from_bits(v.to_bits() & mask);
            sep += Vec2::new(sx, sy);
            sum_vel += Vec2::new(keep(vxs[k]), keep(vys[k]));
            sum_pos += Vec2::new(keep(x), keep(y));
            n_flock += u32::from(counts);
        }
        for (&k, &seen_it) in s.slots[..n].iter().zip(&s.seen[..n]) {
            if seen_it {
                seen(columns.ids.get(k as usize).copied().unwrap_or(u32::MAX));
            }
        }
        let separation = limit(sep, 1.0);
        let (alignment, cohesion) = if n_flock > 0 {
            let inv = 1.0 / n_flock as f32;
            (
                limit((sum_vel * inv - vel) / prm.max_speed, 1.0),
                limit((sum_pos * inv - p) / (0.5 * range), 1.0),
            )
        } else {
            (Vec2::ZERO, Vec2::ZERO)
        };
        let following = self.following(ctx, p, vel, group.goal);
        let towards = group.goal.map_or(Vec2::X, |(g, _)| unit_or(g - p, Vec2::X));
        let collision = self.collision(ctx, p, vel, radius, towards);

        [separation, alignment, cohesion, following, collision]
    }
}

impl NeighbourScratch {
    /// Copies the positions of the gathered slots, then computes each neighbour's separation
    /// term for an agent at `p` (body size `size`, unit `heading` if it moves): `away · size / d`
    /// for a neighbour seen (in the view cone and not at `p`, as the agent itself is), else 0;
    /// returns how many neighbours there are. The float operations per neighbour of one loop
    /// over them, without a branch: the square roots and divisions vectorise.
    fn terms(
        &mut self,
        columns: Columns<'_>,
        p: Vec2,
        size: f32,
        heading: Option<Vec2>,
        view_cos: f32,
    ) -> usize {
        let n = self.slots.len();
        // Every entry up to `n` is written below: the buffers only grow.
        for c in [&mut self.x, &mut self.y, &mut self.sep_x, &mut self.sep_y] {
            if c.len() < n {
                c.resize(n, 0.0);
            }
        }
        if self.seen.len() < n {
            self.seen.resize(n, false);
        }
        // Columns of one length and slots clamped to it (a no-op: they index the grid), so the
        // loads need no bounds check.
        let len = columns.x.len().min(columns.y.len());
        if len == 0 {
            return 0;
        }
        let (xs, ys) = (&columns.x[..len], &columns.y[..len]);
        for ((&k, x), y) in self.slots.iter().zip(&mut self.x[..n]).zip(&mut self.y[..n]) {
            let k = (k as usize).min(len - 1);
            (*x, *y) = (xs[k], ys[k]);
        }
        let (cone, h) = (heading.is_some(), heading.unwrap_or(Vec2::ZERO));
        let outputs = self.sep_x[..n].iter_mut().zip(&mut self.sep_y[..n]).zip(&mut self.seen[..n]);
        for ((&x, &y), ((sx, sy), seen)) in self.x[..n].iter().zip(&self.y[..n]).zip(outputs) {
            let pos = Vec2::new(x, y);
            let d2 = p.distance_squared(pos);
            let d = d2.sqrt();
            let away = (p - pos) / d;
            // Outside the view cone: more than 165° off the heading (330° view).
            let hidden = cone & (-away.dot(h) < view_cos);
            let visible = (d2 > 0.0) & !hidden;
            // A neighbour at contact pushes with 1, at two body sizes with ½, …
            let push = away * (size / d);
            *sx = if visible { push.x } else { 0.0 };
            *sy = if visible { push.y } else { 0.0 };
            *seen = visible;
        }
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::PlannerConfig;
    use crate::model::scene::{Goal, GoalMotion, Group, Region, Scene};
    use crate::World;

    fn scene(obstacles: Vec<Obstacle>, params: ForcesParams) -> Scene {
        let mut s = Scene::empty(600.0, 400.0);
        s.obstacles = obstacles;
        s.goals.push(Goal {
            position: [100.0, 200.0],
            radius: 20.0,
            motion: Some(GoalMotion::Polyline { points: vec![[100.0, 200.0], [550.0, 200.0]], speed: 1.0 }),
        });
        s.groups.push(Group {
            name: "f".into(),
            color: "#336699".into(),
            count: 25,
            spawn: Region { min: [20.0, 150.0], max: [90.0, 250.0] },
            goal: Some(0),
            agent_radius: 4.0,
            planner: PlannerConfig::Forces(params),
        });
        s
    }

    #[test]
    fn a_run_stays_finite_within_limits_and_out_of_obstacles() {
        let params = ForcesParams { max_turn_deg: 5.0, ..ForcesParams::default() };
        let walls = vec![
            Obstacle::Rect { min: [280.0, 0.0], max: [320.0, 180.0] },
            Obstacle::Rect { min: [280.0, 220.0], max: [320.0, 400.0] },
            Obstacle::Circle { center: [450.0, 150.0], radius: 10.0 },
        ];
        let mut world = World::new(scene(walls, params.clone())).expect("valid");
        let mut previous: Vec<Vec2> = world.velocities().to_vec();
        let cos_turn = libm::cosf(params.max_turn_deg.to_radians()) - 1e-4;
        for _ in 0..400 {
            world.step();
            for (i, (&p, &v)) in world.positions().iter().zip(world.velocities()).enumerate() {
                assert!(p.is_finite() && v.is_finite(), "agent {i}");
                assert!(v.length() <= params.max_speed + 1e-4, "agent {i} speed {}", v.length());
                assert!(!world.obstacles().contains(p), "agent {i} inside an obstacle at {p}");
                let u = previous[i];
                // The world may remove the part into a wall; the planner's own turn is limited.
                if u.length() > 0.1 && v.length() > 0.1 && !near_wall(&world, p) {
                    assert!(u.normalize().dot(v.normalize()) >= cos_turn, "agent {i} turned too fast");
                }
            }
            previous = world.velocities().to_vec();
        }
        // The group followed the goal through the gap.
        let past_wall = world.positions().iter().filter(|p| p.x > 320.0).count();
        assert!(past_wall > 12, "only {past_wall} of 25 agents passed the wall");
    }

    fn near_wall(world: &World, p: Vec2) -> bool {
        let b = world.scene();
        let r = 4.5;
        let mut near = p.x < r || p.y < r || p.x > b.width - r || p.y > b.height - r;
        world.obstacles().for_each_near(Aabb { min: p, max: p }.inflate(r), |_, o| {
            near |= o.surface(p).signed_distance < r;
        });
        near
    }

    #[test]
    fn the_view_cone_hides_agents_right_behind() {
        let forces = Forces::new(ForcesParams::default());
        // Half of 330° is 165°: a neighbour 170° off the heading is hidden, one 160° off is seen.
        let heading = Vec2::X;
        let at = |deg: f32| Vec2::from_angle(deg.to_radians());
        assert!(at(170.0).dot(heading) < forces.view_cos);
        assert!(at(160.0).dot(heading) >= forces.view_cos);
    }

    #[test]
    fn zero_weights_keep_the_velocity() {
        let mut params = ForcesParams::default();
        params.set_weights([0.0; 5]);
        let mut world = World::new(scene(vec![], params)).expect("valid");
        let v0 = world.velocities().to_vec();
        world.step();
        // Nothing steers, and spawn speeds are far from walls: the velocities stay.
        assert_eq!(world.velocities(), &v0[..]);
    }

    #[test]
    fn the_followed_point_lies_behind_the_goal_on_its_trace() {
        let mut forces = Forces::new(ForcesParams { follow_offset: 15.0, ..ForcesParams::default() });
        for (step, x) in [(0, 0.0), (5, 10.0), (10, 20.0)] {
            forces.record_trace(step, Vec2::new(x, 0.0));
        }
        let (p, before) = forces.followed_point(Vec2::new(20.0, 0.0));
        assert!(p.distance(Vec2::new(5.0, 0.0)) < 1e-5, "{p}");
        assert_eq!(before, 1);
    }
}
