//! Five weighted virtual forces, the model whose weights the genetic algorithm tunes (DESIGN §3.5).
//!
//! `F = s1 Fsep + s2 Falign + s3 Fcoh + s4 Ffol + s5 Fcol`, each force normalised to length ≤ 1,
//! applied as an acceleration of `|F| · max_force`; then the turn per step and the speed are
//! limited (the paper's translation and rotation speed limits). Agents see other agents in a
//! 330° cone up to 20 body sizes (body size = diameter).
//!
//! The neighbour pass (separation over every robot seen, alignment and cohesion over those of
//! the agent's own group) lives in `view.rs`: a fine index rebuilt every step finds each agent's
//! candidates (the same neighbours as a query of the world grid, among far fewer
//! candidates), and the sums run four candidates at a time into four partial sums, candidate
//! `k` of a row of cells into sum `k mod 4`, combined as `(s0 + s1) + (s2 + s3)`. That order is
//! fixed by the positions alone, so a run is the same natively and in wasm; it is not the
//! order of one running sum in the world grid's scan order, which the planner used until the
//! neighbour pass had to get cheaper (10,000 packed agents at 30 frames per second on the
//! page): one chain of additions per sum made every add wait for the previous one. The
//! separation push `away · size / d` is computed as `(p − q) · size / d²`, and the view cone is
//! tested on squares, without a square root; cohesion sums the offsets `p − q` rather than
//! the positions. The model is the paper's; only the rounding differs from the earlier order.
//!
//! After the sum, a step that would make the agent's disc overlap another body (agent or
//! obstacle) is cut short: the paper's "if the new configuration is in collision, local
//! strategies avoid it" ([`Forces::keep_bodies_apart`]). The forces alone cannot keep bodies
//! apart: each is clamped to length 1, so separation (at most s1) loses against following and
//! cohesion pulling a crowd together, and a group round a stopped goal piled into a disc of
//! about 19 px whatever its size.

use super::planner::{GroupView, Planner, StepContext};
use crate::model::geometry::limit;
use crate::model::geometry::{unit_or, Aabb, Obstacle};
use crate::model::params::ForcesParams;
use crate::planners::explain::{Explanation, NamedVector};
use crate::rng::Rng;
use glam::Vec2;
use view::{ViewIndex, Viewer};

mod view;

/// Steps between two samples of the goal's trace.
const TRACE_EVERY: u32 = 5;
/// Samples of the goal's trace kept (newest last).
const TRACE_LEN: usize = 64;
/// Older trace points tried when the followed point is out of sight (bounds the ray casts).
const TRACE_SEARCH: usize = 8;
/// Below this speed (px/step) an agent has no heading: it sees all round and turns freely.
const MIN_HEADING_SPEED: f32 = 1e-3;
/// Rounds of sliding a step along the bodies it would enter ([`Forces::keep_bodies_apart`]):
/// a crowded agent touches at most about six; what is left after four rounds is braked away.
const CONTACT_ROUNDS: usize = 4;
/// Most bodies the contact rule looks at per agent ([`Forces::find_contacts`]): packed
/// hexagonally, discs of one size put 6 within two full-speed steps (4 px) of a 4 px body's
/// disc, 12 for 2 px bodies and 30 for 1 px ones; more only in a pile of overlapping bodies
/// or of bodies below 1 px, whose work the cap bounds (the first found are kept away from,
/// the others may be entered).
const CONTACT_CAP: usize = 32;
/// Gap (px) the contact rule keeps between two discs: discs that exactly touch, positions
/// rounded to `f32` (a unit in the last place is 6·10⁻⁵ px at 1,000 px), would overlap by a
/// rounding about every other step and count as collisions.
const CONTACT_SKIN: f32 = 0.01;

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
    /// The step's index of every agent for the neighbour pass, rebuilt by `plan`.
    index: ViewIndex,
    /// Scratch of `plan`: the contacts of one agent ([`Forces::find_contacts`]).
    contacts: Vec<Contact>,
}

/// A body an agent's step could touch: the unit direction towards it and how far the agent may
/// move along that direction this step (its share of the gap less [`CONTACT_SKIN`]: half for
/// another agent, all for an obstacle; negative when they are closer: the agent must back off
/// by that much).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Contact {
    towards: Vec2,
    allowed: f32,
    /// Whether the bodies overlap now.
    overlaps: bool,
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
            index: ViewIndex::default(),
            contacts: Vec::new(),
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

    /// The bodies agent `id` could touch this step, into `contacts` (cleared first): every
    /// obstacle, then every agent of any group (in the index's scan order), whose surface is
    /// within two steps at full speed of its disc (`widest`: the largest radius of any agent),
    /// the first [`CONTACT_CAP`] only. Two agents exactly on top of
    /// each other are told apart by id: the lower one backs off towards −x.
    fn find_contacts(
        &self,
        ctx: &StepContext,
        index: &ViewIndex,
        id: u32,
        widest: f32,
        contacts: &mut Vec<Contact>,
    ) {
        contacts.clear();
        let i = id as usize;
        let (p, radius) = (ctx.positions[i], ctx.radii[i]);
        let margin = 2.0 * self.params.max_speed;
        if !ctx.obstacles.is_empty() {
            // Obstacles do not move: the whole gap is the agent's. Slid along here, the step
            // needs no sliding by the world, which would push it into a neighbour.
            let query = Aabb { min: p, max: p }.inflate(radius + margin);
            ctx.obstacles.for_each_near(query, |_, o: &Obstacle| {
                let s = o.surface(p);
                let gap = s.signed_distance - radius;
                if gap < margin && contacts.len() < CONTACT_CAP {
                    contacts.push(Contact {
                        towards: -s.normal,
                        allowed: gap - CONTACT_SKIN,
                        overlaps: gap < 0.0,
                    });
                }
            });
        }
        index.for_each_within(p, radius + widest + margin, |other, q| {
            if other == id {
                return true;
            }
            let touch = radius + ctx.radii.get(other as usize).copied().unwrap_or(0.0);
            let d = p.distance(q);
            let gap = d - touch;
            if gap < margin {
                let towards = if d > 0.0 {
                    (q - p) / d
                } else if id < other {
                    Vec2::X
                } else {
                    Vec2::NEG_X
                };
                contacts.push(Contact { towards, allowed: 0.5 * (gap - CONTACT_SKIN), overlaps: gap < 0.0 });
            }
            contacts.len() < CONTACT_CAP
        });
    }

    /// The paper's "if the new configuration is in collision, local strategies avoid it"
    /// (§14.2): the weighted forces give `next`; a step that would make two bodies overlap is
    /// cut. The five forces are normalised and clamped to length 1, so no weighting of them
    /// makes separation win at contact: a crowd pulled towards a point by following (s4 = 0.84)
    /// and cohesion outweighs a separation of at most s1 = 0.42 and piles into a disc whose size
    /// does not depend on how many it holds (30 bodies in a disc of about 19 px round a stopped
    /// goal, 37–53 overlapping pairs every step). So after the sum every agent moves at most
    /// half the gap towards any body near it (the other half is the other's: their distance
    /// cannot fall below contact), and backs off by half an overlap it finds.
    ///
    /// First the velocity slides along the bodies it would enter (its part into each removed, a
    /// few rounds, in scan order): crowded agents flow round each other into free places
    /// rather than freezing where they first touch. That slide keeps the turn limit (`vel` is
    /// the velocity before the step): turned back to the limit, the agent brakes along its
    /// heading just short of contact, and turns further on the steps after (a stopped robot
    /// turns freely). Only backing off an overlap (left by the world's walls or another
    /// group's planner) may turn faster: that is a shove, not steering. Whatever the slide
    /// found, the last brake guarantees the rule, so it holds however the rounds end.
    ///
    /// The weights keep their meaning as the balance of the five forces; but separation no
    /// longer has to keep bodies apart at contact, so Gc (share of agents not in collision)
    /// is 1 whatever the weights, and the genetic algorithm trades the other four measures.
    fn keep_bodies_apart(&self, vel: Vec2, next: Vec2, contacts: &[Contact]) -> Vec2 {
        if contacts.is_empty() {
            return next;
        }
        let mut slid = next;
        for _ in 0..CONTACT_ROUNDS {
            let mut entered = false;
            for c in contacts {
                let along = slid.dot(c.towards);
                if along > c.allowed {
                    slid -= c.towards * (along - c.allowed);
                    entered = true;
                }
            }
            if !entered {
                break;
            }
        }
        let slid = limit(slid, self.params.max_speed);
        let overlapping = contacts.iter().any(|c| c.overlaps);
        let step = if !overlapping {
            self.limit_turn(vel, slid)
        } else if contacts.iter().all(|c| slid.dot(c.towards) <= c.allowed) {
            slid
        } else {
            // Wedged: the slide found no way out; back off every overlap by half, no more.
            let back_off: Vec2 =
                contacts.iter().filter(|c| c.allowed < 0.0).map(|c| c.towards * c.allowed).sum();
            limit(back_off, self.params.max_speed)
        };
        // Never further towards a body than its share of the gap (none into one it overlaps):
        // brake along the step, which keeps its heading.
        let brake = contacts.iter().fold(1.0f32, |brake, c| {
            let (along, room) = (step.dot(c.towards), c.allowed.max(0.0));
            if along > room {
                brake.min(room / along)
            } else {
                brake
            }
        });
        step * brake
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

    fn explain(&self, ctx: &StepContext, group: &GroupView, agent: u32) -> Explanation {
        let prm = &self.params;
        let mut e = Explanation { scale: 150.0, ..Explanation::default() };
        if agent as usize >= ctx.positions.len() {
            return e;
        }
        let mut neighbours = Vec::new();
        let mut index = ViewIndex::default();
        index.rebuild(ctx.grid, ctx.bounds, self.interaction_radius(), &group.agents);
        let forces = self.agent_forces(ctx, group, agent, &index, Some(&mut |id| neighbours.push(id)));
        for ((name, f), s) in FORCE_NAMES.iter().zip(forces).zip(prm.weights()) {
            e.vectors.push(NamedVector::new(name, f * (s * prm.max_force)));
        }
        e.applied = e.vectors.iter().map(|v| v.vector).sum();
        e.neighbours = neighbours;
        e.state = "five weighted forces; the turn per step is limited after the sum, and the step stops short of touching another body".into();
        e
    }

    fn plan(&mut self, ctx: &StepContext, group: GroupView, _rng: &mut Rng, new_velocities: &mut [Vec2]) {
        if let Some((goal, _)) = group.goal {
            self.record_trace(ctx.step, goal);
        }
        let mut index = std::mem::take(&mut self.index);
        let mut contacts = std::mem::take(&mut self.contacts);
        index.rebuild(ctx.grid, ctx.bounds, self.interaction_radius(), &group.agents);
        let widest = ctx.radii.iter().fold(0.0f32, |a, &r| a.max(r));
        for (k, id) in group.agents.clone().enumerate() {
            let forces = self.agent_forces(ctx, &group, id, &index, None);
            let vel = ctx.velocities[id as usize];
            let force: Vec2 = forces.iter().zip(self.params.weights()).map(|(f, s)| *f * s).sum();
            let next = self.limit_turn(vel, vel + force * self.params.max_force);
            let next = limit(next, self.params.max_speed);
            self.find_contacts(ctx, &index, id, widest, &mut contacts);
            new_velocities[k] = self.keep_bodies_apart(vel, next, &contacts);
        }
        self.index = index;
        self.contacts = contacts;
    }
}

/// Names of the five forces, in weight order (the explanation's arrows).
const FORCE_NAMES: [&str; 5] =
    ["s1 separation", "s2 alignment", "s3 cohesion", "s4 following", "s5 collision"];

impl Forces {
    /// The five normalised forces on agent `id` from the step's state, in [`FORCE_NAMES`] order,
    /// its neighbours found in `index` (rebuilt for this step); `seen`, if given, is called with
    /// every neighbour in view. `plan` and `explain` both use it.
    fn agent_forces(
        &self,
        ctx: &StepContext,
        group: &GroupView,
        id: u32,
        index: &ViewIndex,
        seen: Option<&mut dyn FnMut(u32)>,
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

        let viewer = Viewer { p, size, range, heading, view_cos: self.view_cos };
        let sums = index.sums(&viewer);
        if let Some(seen) = seen {
            index.for_each_seen(&viewer, seen);
        }
        let separation = limit(sums.separation, 1.0);
        let (alignment, cohesion) = if sums.flock > 0 {
            let inv = 1.0 / sums.flock as f32;
            // The mean offset `p − q` of the flock is `p − centre`: cohesion pulls along its
            // opposite.
            (
                limit((sums.velocity * inv - vel) / prm.max_speed, 1.0),
                limit(-(sums.offset * inv) / (0.5 * range), 1.0),
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
            on_arrival: crate::model::scene::OnArrival::Gather,
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
