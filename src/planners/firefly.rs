//! Firefly crowd (Zhang, Wei & Chen 2017, DESIGN §3.3): dimmer fireflies are drawn to brighter
//! ones, a feeler makes them queue behind, and the brightest head straight for the target.
//!
//! The paper prints no equations; these are the standard firefly algorithm's, turned into a
//! force as its §2.1 describes, with these choices where it is silent:
//!
//! * Brightness `I = 1/|x − target|` (eq. 6), compared as squared distances (same order).
//!   Fireflies only see their own group (they share its target).
//! * Attractiveness `β(r) = β0 · exp(−γ (r/r_safe)^m)` (eq. 2). **Length unit: r_safe.** With r in
//!   px the paper's γ = 0.05 would make β vanish a few px away and nothing would aggregate; in units
//!   of the safe distance (50 px) β is 0.95 at 50 px, 0.64 at 150 px, 0.45 at 200 px.
//! * Each firefly moves towards the **nearest brighter firefly in view** (the most attractive one,
//!   since β falls with distance) within `view_radius`; standard FA sums over all brighter ones,
//!   which is O(N²) and, turned into a force, would just saturate. Following the nearest brighter
//!   one is also what lines them up.
//! * Eq. 3 gives the point `a = x_i + β(r)(x_j − x_i) + α·r_safe·(rand − ½)` (per axis, the random
//!   step in the same length unit); eq. 5 turns it into the "velocity force" `a − x_i`, applied as
//!   `v += force / mass`, `v = limit(v, max_velocity)`, `x += v` (Reynolds' Euler step the paper
//!   cites). Masses are drawn uniformly in [`FireflyParams::mass_min`, `mass_max`] ([20, 40] in the
//!   paper) from the seeded generator on the planner's first step.
//! * Equal brightness — no brighter firefly in view — gets the "max-speed force" towards the
//!   target: an acceleration of `max_velocity` along `unit(target − x)`.
//! * Feeler: a vector of length `h` along the velocity. If a brighter firefly lies within `r_safe`
//!   of its tip, the firefly does not apply the velocity force's magnitude that step but moves at
//!   `brake × max_velocity` in the direction the force update gives (§2.4 step 4: "when the safe
//!   distance holds update by eq. 5, otherwise scale the speed by a certain ratio"), so dimmer ones
//!   fall in behind brighter ones. Measured alternatives that failed: adding the force and then
//!   braking creeps onto the leader (steady state v = a) and overlaps; braking geometrically
//!   towards zero, with or without steering, deadlocks (every firefly waits on a brighter one that
//!   waits too; 1 of 80 arrived in 2400 steps).
//! * Obstacles: a collision is predicted when the position, the half-feeler tip or the feeler tip
//!   lies inside an obstacle (tested in that order, first hit wins). The avoidance acceleration
//!   `avoid_strength` is perpendicular to the velocity, on the side whose normal has a negative dot
//!   product with the direction into the obstacle. For a circle that direction is
//!   `centre − position`, as in the paper; for rectangles and polygons it is minus the outward
//!   surface normal nearest the position, which equals it for circles and works for any shape.

use super::{limit, GroupView, ParamSpec, Planner, StepContext};
use crate::diagnose::{Explanation, NamedPoint, NamedVector};
use crate::geometry::{unit_or, Aabb};
use crate::rng::Rng;
use glam::Vec2;
use serde::{Deserialize, Serialize};

/// Firefly parameters. Lengths in px, speeds in px/step, accelerations in px/step².
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FireflyParams {
    /// Speed limit (px/step). Range 0.1…20, default 2 (paper).
    pub max_velocity: f32,
    /// α, random step, in units of r_safe. Range 0…1, default 0.2 (paper).
    pub alpha: f32,
    /// β0, attractiveness at distance 0. Range 0…2, default 1 (paper).
    pub beta0: f32,
    /// γ, light absorption per (r / r_safe)^m. Range 0…10, default 0.05 (paper).
    pub gamma: f32,
    /// m, exponent of the distance in β. Range 1…4, default 2 (paper).
    pub exponent: f32,
    /// h, feeler length (px) = body length / 2 + r_safe. Range 0…300, default 60 (paper).
    pub feeler_length: f32,
    /// r_safe, the largest safe distance (px), also the length unit of β. Range 1…300, default 50
    /// (paper).
    pub safe_distance: f32,
    /// Speed, as a share of max_velocity, of a firefly with a brighter one within r_safe of its
    /// feeler tip. Range 0…1, default 0.5.
    pub brake: f32,
    /// Lightest firefly mass. Range 1…200, default 20 (paper).
    pub mass_min: f32,
    /// Heaviest firefly mass. Range 1…200, default 40 (paper).
    pub mass_max: f32,
    /// Brighter fireflies farther than this (px) are not seen. Range 10…1000, default 200.
    pub view_radius: f32,
    /// Sideways acceleration when an obstacle is ahead (px/step²). Range 0…10, default 1.
    pub avoid_strength: f32,
}

impl Default for FireflyParams {
    fn default() -> Self {
        Self {
            max_velocity: 2.0,
            alpha: 0.2,
            beta0: 1.0,
            gamma: 0.05,
            exponent: 2.0,
            feeler_length: 60.0,
            safe_distance: 50.0,
            brake: 0.5,
            mass_min: 20.0,
            mass_max: 40.0,
            view_radius: 200.0,
            avoid_strength: 1.0,
        }
    }
}

impl FireflyParams {
    /// The parameter table (sliders, range checks, docs).
    pub const SPECS: &'static [ParamSpec] = &[
        ParamSpec::number("max_velocity", "Max velocity", "px/step", (0.1, 20.0, 0.1), 2.0, "Speed limit."),
        ParamSpec::number(
            "alpha",
            "Random step α",
            "× r_safe",
            (0.0, 1.0, 0.01),
            0.2,
            "Size of the random part of each move.",
        ),
        ParamSpec::number("beta0", "β0", "", (0.0, 2.0, 0.05), 1.0, "Attractiveness at distance 0."),
        ParamSpec::number(
            "gamma",
            "Absorption γ",
            "",
            (0.0, 10.0, 0.01),
            0.05,
            "Light absorption: smaller γ, stronger pull from far away (distance in units of r_safe).",
        ),
        ParamSpec::number("exponent", "Exponent m", "", (1.0, 4.0, 0.1), 2.0, "Power of the distance in β."),
        ParamSpec::number(
            "feeler_length",
            "Feeler length h",
            "px",
            (0.0, 300.0, 1.0),
            60.0,
            "Length of the feeler along the velocity: body/2 + r_safe.",
        ),
        ParamSpec::number(
            "safe_distance",
            "Safe distance r_safe",
            "px",
            (1.0, 300.0, 1.0),
            50.0,
            "A brighter firefly this close to the feeler tip slows the firefly down.",
        ),
        ParamSpec::number(
            "brake",
            "Brake factor",
            "×",
            (0.0, 1.0, 0.05),
            0.5,
            "Speed (× max velocity) while a brighter firefly is at the feeler tip.",
        ),
        ParamSpec::number("mass_min", "Mass min", "", (1.0, 200.0, 1.0), 20.0, "Lightest firefly."),
        ParamSpec::number("mass_max", "Mass max", "", (1.0, 200.0, 1.0), 40.0, "Heaviest firefly."),
        ParamSpec::number(
            "view_radius",
            "View radius",
            "px",
            (10.0, 1000.0, 5.0),
            200.0,
            "Brighter fireflies farther away are not seen.",
        ),
        ParamSpec::number(
            "avoid_strength",
            "Avoidance",
            "px/step²",
            (0.0, 10.0, 0.1),
            1.0,
            "Sideways push when the feeler meets an obstacle.",
        ),
    ];
}

/// The firefly planner for one group. Per-agent state (mass) is indexed by the agent's position
/// within its group.
#[derive(Clone, Debug)]
pub struct Firefly {
    params: FireflyParams,
    mass: Vec<f32>,
}

impl Firefly {
    /// A planner with these parameters.
    pub fn new(params: FireflyParams) -> Self {
        Self { params, mass: Vec::new() }
    }

    /// `β(r) = β0 exp(−γ (r / r_safe)^m)`.
    fn attractiveness(&self, distance: f32) -> f32 {
        let p = &self.params;
        let r = distance / p.safe_distance.max(1e-3);
        p.beta0 * libm::expf(-p.gamma * libm::powf(r, p.exponent))
    }

    /// The sideways avoidance acceleration if the position, half feeler or feeler tip is inside
    /// an obstacle.
    fn avoid(&self, ctx: &StepContext, p: Vec2, heading: Vec2) -> Vec2 {
        if ctx.obstacles.is_empty() || self.params.avoid_strength <= 0.0 {
            return Vec2::ZERO;
        }
        let feeler = heading * self.params.feeler_length;
        for probe in [p, p + feeler * 0.5, p + feeler] {
            let mut into: Option<Vec2> = None;
            ctx.obstacles.for_each_near(Aabb { min: probe, max: probe }, |_, o| {
                if into.is_none() && o.contains(probe) {
                    into = Some(-o.surface(p).normal);
                }
            });
            if let Some(into) = into {
                let normal = if heading.perp().dot(into) < 0.0 { heading.perp() } else { -heading.perp() };
                return normal * self.params.avoid_strength;
            }
        }
        Vec2::ZERO
    }
}

impl Planner for Firefly {
    fn interaction_radius(&self) -> f32 {
        self.params.view_radius.max(self.params.feeler_length + self.params.safe_distance)
    }

    fn max_speed(&self) -> f32 {
        self.params.max_velocity
    }

    /// The same terms as `plan` without the random step (its expectation is zero): the brighter
    /// firefly followed, the feeler and whether a brighter one blocks its tip, the avoidance.
    fn explain(&self, ctx: &StepContext, group: &GroupView, agent: u32) -> Explanation {
        let prm = &self.params;
        let mut e = Explanation { scale: 15.0, ..Explanation::default() };
        let k = agent.wrapping_sub(group.agents.start) as usize;
        let i = agent as usize;
        let (Some(&p), Some(&vel)) = (ctx.positions.get(i), ctx.velocities.get(i)) else { return e };
        let mass = self.mass.get(k).copied().unwrap_or(0.5 * (prm.mass_min + prm.mass_max)).max(1e-3);
        e.values.push(("mass".into(), mass));
        let Some((target, _)) = group.goal else {
            e.state = "no target: every firefly equally bright, drifting".into();
            return e;
        };
        let my2 = p.distance_squared(target);
        e.values.push(("brightness 1/|x − target|".into(), 1.0 / my2.sqrt().max(1e-3)));
        let heading = unit_or(vel, unit_or(target - p, Vec2::X));
        let tip = p + heading * prm.feeler_length;
        let (view2, safe2) = (prm.view_radius * prm.view_radius, prm.safe_distance * prm.safe_distance);
        let mut nearest: Option<(f32, u32, Vec2)> = None;
        let mut blocker: Option<(f32, u32, Vec2)> = None;
        ctx.grid.for_each_within(p, self.interaction_radius(), |nb| {
            if nb.id == agent || !group.agents.contains(&nb.id) || nb.pos.distance_squared(target) >= my2 {
                return;
            }
            let at_tip = nb.pos.distance_squared(tip);
            if at_tip < safe2 && blocker.is_none_or(|(d2, j, _)| (at_tip, nb.id) < (d2, j)) {
                blocker = Some((at_tip, nb.id, nb.pos));
            }
            if nb.d2 <= view2 {
                e.neighbours.push(nb.id);
                if nearest.is_none_or(|(d2, j, _)| (nb.d2, nb.id) < (d2, j)) {
                    nearest = Some((nb.d2, nb.id, nb.pos));
                }
            }
        });
        e.vectors.push(NamedVector::px("feeler", heading * prm.feeler_length));
        let acceleration = match nearest {
            Some((d2, j, q)) => {
                let beta = self.attractiveness(d2.sqrt());
                e.values.push(("attractiveness β".into(), beta));
                e.values.push(("followed firefly".into(), j as f32));
                e.points.push(NamedPoint::new("brighter firefly followed", q));
                let a = (q - p) * beta / mass;
                e.vectors.push(NamedVector::new("attraction β(xj − xi)/m", a));
                a
            }
            None => {
                let a = unit_or(target - p, heading) * prm.max_velocity;
                e.vectors.push(NamedVector::new("max-speed force to the target", a));
                a
            }
        };
        if let Some((_, _, q)) = blocker {
            e.points.push(NamedPoint::new("brighter firefly at the feeler tip", q));
        }
        let forced = limit(vel + acceleration, prm.max_velocity);
        let v = if blocker.is_some() {
            unit_or(forced, heading) * (prm.max_velocity * prm.brake)
        } else {
            forced
        };
        let avoid = self.avoid(ctx, p, unit_or(v, heading));
        if avoid != Vec2::ZERO {
            e.vectors.push(NamedVector::new("obstacle avoidance", avoid));
        }
        e.applied = limit(v + avoid, prm.max_velocity) - vel;
        e.state = match (blocker.is_some(), nearest.is_some()) {
            (true, _) => "queued: a brighter firefly is at the feeler tip (braking)".into(),
            (false, true) => "attracted by the nearest brighter firefly".into(),
            (false, false) => "brightest in view: max-speed force to the target".into(),
        };
        e
    }

    fn plan(&mut self, ctx: &StepContext, group: GroupView, rng: &mut Rng, new_velocities: &mut [Vec2]) {
        let n = group.agents.len();
        let prm = self.params.clone();
        if self.mass.len() != n {
            let (lo, hi) = (prm.mass_min.min(prm.mass_max), prm.mass_min.max(prm.mass_max));
            self.mass = (0..n).map(|_| rng.range(lo, hi)).collect();
        }
        let look = self.interaction_radius();
        let view2 = prm.view_radius * prm.view_radius;
        let safe2 = prm.safe_distance * prm.safe_distance;
        let unit_len = prm.safe_distance;
        for (k, id) in group.agents.clone().enumerate() {
            let i = id as usize;
            let p = ctx.positions[i];
            let vel = ctx.velocities[i];
            let mass = self.mass[k].max(1e-3);
            let Some((target, _)) = group.goal else {
                // No target: every firefly is equally bright; drift with a little noise.
                let noise = Vec2::new(rng.unit() - 0.5, rng.unit() - 0.5) * (prm.alpha * unit_len);
                new_velocities[k] = limit(vel + noise / mass, prm.max_velocity);
                continue;
            };
            let my2 = p.distance_squared(target);
            let heading = unit_or(vel, unit_or(target - p, Vec2::X));
            let tip = p + heading * prm.feeler_length;

            // One grid query: the nearest brighter firefly in view, and whether one sits at the tip.
            let mut nearest: Option<(f32, u32, Vec2)> = None;
            let mut blocked = false;
            ctx.grid.for_each_within(p, look, |nb| {
                if nb.id == id || !group.agents.contains(&nb.id) || nb.pos.distance_squared(target) >= my2 {
                    return;
                }
                if nb.pos.distance_squared(tip) < safe2 {
                    blocked = true;
                }
                if nb.d2 <= view2 && nearest.is_none_or(|(d2, j, _)| (nb.d2, nb.id) < (d2, j)) {
                    nearest = Some((nb.d2, nb.id, nb.pos));
                }
            });

            let acceleration = match nearest {
                Some((d2, _, q)) => {
                    let beta = self.attractiveness(d2.sqrt());
                    let noise = Vec2::new(rng.unit() - 0.5, rng.unit() - 0.5) * (prm.alpha * unit_len);
                    // Eq. 5: the velocity force a − x_i, with a from eq. 3.
                    ((q - p) * beta + noise) / mass
                }
                None => unit_or(target - p, heading) * prm.max_velocity,
            };
            // §2.4 step 4: the velocity force while the safe distance holds; otherwise the speed
            // is scaled to `brake × max_velocity`, still steering by the force.
            let forced = limit(vel + acceleration, prm.max_velocity);
            let mut v =
                if blocked { unit_or(forced, heading) * (prm.max_velocity * prm.brake) } else { forced };
            v += self.avoid(ctx, p, unit_or(v, heading));
            new_velocities[k] = limit(v, prm.max_velocity);
        }
    }
}
