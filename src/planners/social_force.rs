//! The social force model, written from the papers: Helbing & Molnár, "Social force model for
//! pedestrian dynamics", Phys. Rev. E 51, 4282 (1995) (HM), with the body and sliding-friction
//! forces of touching bodies of Helbing, Farkas & Vicsek, "Simulating dynamical features of
//! escape panic", Nature 407, 487 (2000) (HFV).
//!
//! The acceleration of pedestrian α (all in SI units, converted from px with the scene's scale):
//! - driving term (HM's acceleration term, HFV eq. 1): `(v⁰ e_α − v_α) / τ`, `e_α` the desired direction (the
//!   goal's flow field or the goal itself, [`super::goal_way`]); inside its goal the desired
//!   speed is 0 (it stops);
//! - repulsion by pedestrian β (HM's repulsive potential and its elliptical `b`): `f_αβ = −∇_r V(b)` with `V(b) = V⁰ e^{−b/σ}` and
//!   the ellipse `2b = √((‖r‖ + ‖r − y‖)² − ‖y‖²)`, `r = r_α − r_β`, `y = v_β Δt` (β's step:
//!   its velocity stands for `v_β e_β`); analytically
//!   `f = (V⁰/σ) e^{−b/σ} · (‖r‖ + ‖r − y‖)/(4b) · (r/‖r‖ + (r − y)/‖r − y‖)`;
//!   weighted by HM's field of view `w(e, f)`: 1 when `e_α · (−f) ≥ ‖f‖ cos φ` (β ahead), else c;
//!   with spec II of the ellipse (Johansson, Helbing & Shukla 2007, [`Ellipse::SpecIi`]) the
//!   step is the relative one, `y = (v_β − v_α) Δt`, and the same gradient (y held fixed, as in
//!   both papers);
//! - repulsion by a wall B (HM's border potential): `−∇U(‖r_αB‖)` with `U = U⁰ e^{−‖r_αB‖/R}`, i.e.
//!   `(U⁰/R) e^{−d/R} n` at distance d from the wall, n the wall's normal;
//! - touching bodies (HFV eq. 2 and 3, divided by the mass m): `k g(r_αβ − d_αβ) n_αβ` and the
//!   sliding friction `κ g(r_αβ − d_αβ) Δv^t_βα t_αβ`; at a wall `k g(r_α − d_αB) n` and
//!   `−κ g(r_α − d_αB) (v_α · t) t`; `g(x) = max(x, 0)`.
//!
//! The velocity is then `v + a Δt` (Δt = [`crate::DT`], semi-implicit Euler: the world moves by
//! the new velocity), limited to HM's maximal speed `v_max = 1.3 v⁰`. One numerical
//! safeguard the papers' small adaptive steps make unnecessary: a friction term is limited so one
//! step at most halves the sliding speed it acts on (with κ = 2.4·10⁵ and a 1/60 s step it would
//! otherwise reverse it and grow). Only +, −, ×, ÷, √ and `libm::expf`: bit-identical natively
//! and in wasm.

use super::goal_way::{px_per_metre, GoalWay};
use super::planner::{GroupView, Planner, StepContext};
use crate::model::geometry::{length, limit, Aabb, Obstacle};
use crate::model::params::{Ellipse, SocialForceParams};
use crate::model::scene::{DEFAULT_PX_PER_METRE, DT};
use crate::planners::explain::{Explanation, NamedVector};
use crate::rng::Rng;
use crate::spatial::QueryCap;
use glam::Vec2;

/// Neighbour queries visit at most this many agents within the interaction range, among at most
/// this many agents of the scanned cells (the first in the grid's scan order): a pile costs a
/// bounded amount of work per agent.
const NEIGHBOUR_CAP: QueryCap = QueryCap { neighbours: 512, candidates: 4096 };
/// Walls further than this many wall ranges R push with less than e⁻¹⁰ of U⁰/R: left out.
const WALL_REACH_RANGES: f32 = 10.0;
/// Largest share of a sliding speed one step of friction removes (see the module docs).
const MAX_FRICTION_SHARE: f32 = 0.5;

/// The accelerations acting on one pedestrian (m/s²), by term.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Terms {
    /// Driving term `(v⁰ e − v) / τ`.
    pub driving: Vec2,
    /// Social repulsion from other pedestrians (field-of-view weighted).
    pub agents: Vec2,
    /// Social repulsion from walls and borders.
    pub walls: Vec2,
    /// Body compression and sliding friction of touching bodies and walls.
    pub contact: Vec2,
}

impl Terms {
    /// Their sum: the acceleration.
    pub fn total(&self) -> Vec2 {
        self.driving + self.agents + self.walls + self.contact
    }
}

/// The driving term `(v⁰ e − v) / τ` (HFV eq. 1, HM's acceleration term) for desired direction `e` (unit or zero).
pub fn driving(p: &SocialForceParams, e: Vec2, v: Vec2) -> Vec2 {
    (e * p.desired_speed - v) / p.relaxation_time
}

/// The social repulsion of a wall at distance `d` (m, centre to wall) along its unit `normal`
/// (pointing to the pedestrian): `(U⁰/R) e^{−d/R} n` (HM's border potential `U⁰ e^{−d/R}`).
pub fn wall_repulsion(p: &SocialForceParams, d: f32, normal: Vec2) -> Vec2 {
    normal * (p.wall_strength / p.wall_range * libm::expf(-d / p.wall_range))
}

/// The contact forces of a wall on a body of `radius` (m) at distance `d` (m) moving at `v`
/// (m/s), per unit mass (HFV eq. 3): `(k g(r − d) n − κ g(r − d)(v·t) t) / m`, the friction
/// limited as the module docs say. Zero when not touching.
pub fn wall_contact(p: &SocialForceParams, radius: f32, d: f32, normal: Vec2, v: Vec2) -> Vec2 {
    let overlap = radius - d;
    if overlap <= 0.0 {
        return Vec2::ZERO;
    }
    let t = normal.perp();
    normal * (p.body_force * overlap / p.mass) - t * (friction_rate(p, overlap) * v.dot(t))
}

/// `κ g / m` (1/s), limited so one step removes at most [`MAX_FRICTION_SHARE`] of a sliding speed.
fn friction_rate(p: &SocialForceParams, overlap: f32) -> f32 {
    (p.friction * overlap / p.mass).min(MAX_FRICTION_SHARE / DT)
}

/// A pedestrian's body as the forces see it, in SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Body {
    /// Position (m).
    pub position: Vec2,
    /// Velocity (m/s).
    pub velocity: Vec2,
    /// Radius (m).
    pub radius: f32,
}

/// Everything pedestrian `a` with desired direction `e` (unit, or zero when it has none) feels
/// from pedestrian `b` (HM's repulsion with `w(e, f)`, HFV eq. 2): the social repulsion and the
/// contact forces, per unit mass.
pub fn agent_forces(p: &SocialForceParams, a: Body, e: Vec2, b: Body) -> (Vec2, Vec2) {
    agent_forces_in_view(p, view_cos(p), a, e, b)
}

/// cos φ, φ half the field of view: the weight `w(e, f)` is 1 within it.
fn view_cos(p: &SocialForceParams) -> f32 {
    libm::cosf((0.5 * p.view_angle_deg).to_radians())
}

/// [`agent_forces`] with cos φ ([`view_cos`]) given: a step computes it once per agent, not
/// once per pair (the same value: the same floats).
fn agent_forces_in_view(p: &SocialForceParams, cos_phi: f32, a: Body, e: Vec2, b: Body) -> (Vec2, Vec2) {
    let (r_a, v_a, r_b, v_b) = (a.position, a.velocity, b.position, b.velocity);
    let r = r_a - r_b;
    let d = length(r);
    if d <= 0.0 {
        return (Vec2::ZERO, Vec2::ZERO);
    }
    let n = r / d;
    let y = match p.ellipse {
        Ellipse::SpecI => v_b * p.step_time,
        Ellipse::SpecIi => (v_b - v_a) * p.step_time,
    };
    let ry = r - y;
    let dy = length(ry);
    let sum = d + dy;
    let b2 = sum * sum - y.length_squared();
    let social = if b2 > 0.0 && dy > 0.0 {
        let b = 0.5 * b2.sqrt();
        let f = (n + ry / dy)
            * (p.agent_strength / p.agent_range * libm::expf(-b / p.agent_range) * sum / (4.0 * b));
        // Field of view: full weight for a pedestrian ahead (the force points away from it).
        let f_len = length(f);
        if e == Vec2::ZERO || e.dot(-f) >= f_len * cos_phi {
            f
        } else {
            f * p.out_of_view_weight
        }
    } else {
        Vec2::ZERO
    };
    let overlap = a.radius + b.radius - d;
    let contact = if overlap > 0.0 {
        let t = n.perp();
        let sliding = (v_b - v_a).dot(t);
        n * (p.body_force * overlap / p.mass) + t * (friction_rate(p, overlap) * sliding)
    } else {
        Vec2::ZERO
    };
    (social, contact)
}

/// The social force planner for one group.
#[derive(Clone, Debug)]
pub struct SocialForce {
    params: SocialForceParams,
    way: GoalWay,
    /// Scene px per metre.
    scale: f32,
    /// Scratch: grid slots of one agent's neighbours.
    slots: Vec<u32>,
}

impl SocialForce {
    /// A planner with these parameters at the default scene scale.
    pub fn new(params: SocialForceParams) -> Self {
        Self::with_scale(params, DEFAULT_PX_PER_METRE)
    }

    /// A planner with these parameters for a scene of `px_per_metre`.
    pub fn with_scale(params: SocialForceParams, px_per_metre: f32) -> Self {
        Self { params, way: GoalWay::default(), scale: px_per_metre, slots: Vec::new() }
    }

    /// The parameters.
    pub fn params(&self) -> &SocialForceParams {
        &self.params
    }

    /// The terms of agent `id`'s acceleration (m/s²) from the step's state; `seen` is called
    /// with every neighbour that exerts a force.
    fn terms(
        &self,
        ctx: &StepContext,
        group: &GroupView,
        id: u32,
        slots: &mut Vec<u32>,
        mut seen: impl FnMut(u32),
    ) -> Terms {
        let prm = &self.params;
        let i = id as usize;
        let (to_m, to_ms) = (1.0 / self.scale, 1.0 / (self.scale * DT));
        let (p_px, r_px) = (ctx.positions[i], ctx.radii[i]);
        let (p, v, radius) = (p_px * to_m, ctx.velocities[i] * to_ms, r_px * to_m);
        let way = self.way.at(p_px, group.goal);
        let e = way.direction;
        let mut terms = Terms { driving: driving(prm, e, v), ..Terms::default() };

        ctx.grid.gather_within(p_px, prm.interaction_range * self.scale, NEIGHBOUR_CAP, slots);
        let columns = ctx.grid.columns();
        let cos_phi = view_cos(prm);
        for &k in slots.iter() {
            let k = k as usize;
            let other = columns.ids[k];
            if other == id {
                continue;
            }
            let q = Vec2::new(columns.x[k], columns.y[k]) * to_m;
            let w = Vec2::new(columns.vx[k], columns.vy[k]) * to_ms;
            let rb = ctx.radii[other as usize] * to_m;
            let me = Body { position: p, velocity: v, radius };
            let (social, contact) =
                agent_forces_in_view(prm, cos_phi, me, e, Body { position: q, velocity: w, radius: rb });
            if social != Vec2::ZERO || contact != Vec2::ZERO {
                seen(other);
            }
            terms.agents += social;
            terms.contact += contact;
        }

        let reach = WALL_REACH_RANGES * prm.wall_range + radius;
        let wall = |d: f32, normal: Vec2, terms: &mut Terms| {
            terms.walls += wall_repulsion(prm, d, normal);
            terms.contact += wall_contact(prm, radius, d, normal, v);
        };
        if !ctx.obstacles.is_empty() {
            let query = Aabb { min: p_px, max: p_px }.inflate(reach * self.scale);
            ctx.obstacles.for_each_near(query, |_, o: &Obstacle| {
                let s = o.surface(p_px);
                let d = s.signed_distance * to_m;
                if d < reach {
                    wall(d, s.normal, &mut terms);
                }
            });
        }
        let bounds = ctx.bounds * to_m;
        for (d, normal) in
            [(p.x, Vec2::X), (bounds.x - p.x, Vec2::NEG_X), (p.y, Vec2::Y), (bounds.y - p.y, Vec2::NEG_Y)]
        {
            if d < reach {
                wall(d, normal, &mut terms);
            }
        }
        terms
    }

    /// The new velocity (px/step) of an agent with velocity `v_px` under acceleration `a` (m/s²).
    fn integrate(&self, v_px: Vec2, a: Vec2) -> Vec2 {
        let to_ms = 1.0 / (self.scale * DT);
        let v = limit(v_px * to_ms + a * DT, self.params.max_speed());
        v * (self.scale * DT)
    }
}

impl Planner for SocialForce {
    fn interaction_radius(&self) -> f32 {
        self.params.interaction_range * self.scale
    }

    /// The pedestrian baselines stop in their goal by themselves (preferred speed zero once
    /// inside, [`crate::planners::goal_way`]) and keep apart by their own model; walking them
    /// to places by the world would override the social force step that keeps them apart (the
    /// world's walkers do not reciprocate as the model assumes).
    fn max_speed(&self) -> f32 {
        self.params.max_speed() * self.scale * DT
    }

    fn plan(&mut self, ctx: &StepContext, group: GroupView, _rng: &mut Rng, new_velocities: &mut [Vec2]) {
        self.way.prepare(ctx, &group, self.params.guidance);
        let mut slots = std::mem::take(&mut self.slots);
        for (k, id) in group.agents.clone().enumerate() {
            let a = self.terms(ctx, &group, id, &mut slots, |_| {}).total();
            new_velocities[k] = self.integrate(ctx.velocities[id as usize], a);
        }
        self.slots = slots;
    }

    fn explain(&self, ctx: &StepContext, group: &GroupView, agent: u32) -> Explanation {
        let mut e = Explanation { scale: 10.0, ..Explanation::default() };
        if agent as usize >= ctx.positions.len() {
            return e;
        }
        let mut me = self.clone();
        me.way.prepare(ctx, group, self.params.guidance);
        let mut neighbours = Vec::new();
        let t = me.terms(ctx, group, agent, &mut Vec::new(), |id| neighbours.push(id));
        for (name, f) in
            [("driving", t.driving), ("agents", t.agents), ("walls", t.walls), ("contact", t.contact)]
        {
            e.vectors.push(NamedVector::new(name, f));
        }
        e.applied = t.total();
        e.neighbours = neighbours;
        e.state = "acceleration in m/s²: driving term, social repulsion, body and friction forces".into();
        e
    }
}

/// The planner for a group of a scene: its parameters at the scene's scale.
pub fn for_scene(params: SocialForceParams, scene: &crate::model::scene::Scene) -> SocialForce {
    SocialForce::with_scale(params, px_per_metre(scene))
}
