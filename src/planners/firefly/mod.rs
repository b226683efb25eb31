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
//! * No interpenetration (our resolution; the paper claims the result but the feeler alone does
//!   not give it: its disc, r_safe round a tip h ahead, comes no nearer than h − r_safe = 10 px
//!   and only straight ahead, so a firefly beside another, or one turning onto a leader, sees
//!   nothing; with the rules above 3,000–5,100 pair-steps overlapped by step 300 and the whole
//!   flock piled onto the target point, 330,000–390,000 by step 1,500). After the
//!   feeler and the avoidance, the velocity is cut by a **contact rule**: towards every agent
//!   whose body it could reach this step (any group, found in the same grid query) a firefly may
//!   move at most half the gap between the bodies less [`CONTACT_MARGIN`], whatever the other does,
//!   so a pair can never close its gap within one step (bodies already too close may not approach
//!   at all); towards an obstacle surface it may use the whole clearance less [`OBSTACLE_MARGIN`],
//!   so the world never has to push it out sideways into a neighbour; the world's borders count
//!   as such surfaces (without them, at brake 0.57–0.6 the crowd packed against the right border
//!   behind the target and the world's clamp pushed 2–14 pair-steps into overlap). Only the component towards
//!   the body is cut: the nearest velocity that meets every limit is taken ([`keep_apart`]), so a
//!   firefly slides along a body and the files keep flowing. Measured on the preset, seeds 1–10,
//!   1,500 steps: 0 overlapping pairs after step 1 (step 1 keeps 0–2 pairs that spawned more than
//!   2 × max_velocity deep); queue order 0.72–0.80 at step 1, 0.79–0.94 at step 300 (0.89–0.97
//!   before); arrival 0.96–1.00 (1.00 before). Alternatives measured (seeds 1–5 unless stated):
//!   three projection passes and a scale over non-negative limits only, margin 0.5 — 55–1,446
//!   pair-steps by 1,500 (bodies inside the margin were still pushed together in the jam at the
//!   target); with obstacles as contacts and bodies inside the margin not approached — only the
//!   spawn pairs left, arrival 0.90–1.00, 0.97–1.00 with ten passes, 0.96–1.00 with the exact
//!   nearest velocity (kept: nothing to tune, and sliding is what lets the crowd pack); margin 0.1 / 0.25 / 0.5 / 2 px (seeds 1–10): queue order at step 300 down
//!   to 0.76 (below step 1 on one seed) / 0.79 / 0.79 / 0.69, arrival down to 0.96 / 0.91 / 0.93
//!   / 0.66; saturating the brightness inside the goal radius (every firefly there drives for the
//!   centre) jams the crowd at the goal: arrival 0.68–0.74; capping the braked speed instead of
//!   setting it: 0.56–0.68; scaling the whole velocity (not only its component) for bodies within
//!   45° ahead deadlocks: 0.17–0.19; an extra brake (× `brake`) near a brighter firefly in front,
//!   meant to turn side-by-side pairs into files, lifts queue order to 0.91–0.97 but slows the
//!   files and the gathering: arrival 0.49–0.55 (0.51–0.90 when limited to bodies 30–90° aside,
//!   to moving ones or to gaps under 1–3 px); a gap ramp (speed towards a brighter body ahead ∝
//!   gap over 1–2 body diameters): arrival 0.56–0.78, queue order 0.57–0.89; the feeler against
//!   any firefly of the group, not only brighter ones: queue order 0.64–0.94, no gain.
//! * Fall in behind (our addition; the paper's feeler alone leaves pairs walking side by side in
//!   contact, which its zone cannot see): a firefly on its way — farther from the target than the
//!   goal radius plus 1.5 × r_safe — whose contacts include a brighter firefly of its group in
//!   front of its heading (ahead or beside) scales its velocity by `brake`, so the brighter one
//!   pulls ahead and the dimmer one drops into its file. Together with `brake` 0.55 (was 0.5, to
//!   win back the files' speed), seeds 1–10, 1,500 steps: still 0 overlapping pairs after step 1;
//!   queue order 0.88–0.99 at step 300 (mean 0.92; 0.79–0.94, mean 0.85 before); arrival
//!   0.975–1.00 (mean 0.989; 0.96–1.00, mean 0.991 before). Measured alternatives (seeds 1–10):
//!   the same brake for brighter contacts at any distance — arrival 0.43–0.70 (the crowd at the
//!   target brakes for itself); gated at goal + 1 / 2 / 3 r_safe — queue order min 0.87 / 0.84 /
//!   0.75, arrival min 0.94 / 0.975 / 0.96; brake 0.5 / 0.6 with the gate at goal + ~1 r_safe —
//!   arrival mean 0.95 / queue order min 0.82; steering the dimmer one to the slot behind the
//!   brighter one (aim β at the leader's position less 20 px along the file) when touching it more
//!   than 30° off the heading — queue order 0.89 mean but min 0.73–0.81 and arrival 0.95–0.97
//!   mean (0.36–0.70 without the distance gate); with its speed capped at 0.35–0.45 × max
//!   velocity or the slot along the leader's velocity: no better; the contact split giving the
//!   brighter one of a pair 0.7 / 0.9 / 1.0 of the gap (dimmer yields): queue order 0.83 / 0.77 /
//!   0.69 mean, arrival 0.95 / 0.77 / 0.63.
//!
//! The queue order figures above are of the former measure (heading within ±30° of the nearest
//! brighter firefly within 120 px, which this rule makes true from the first steps). Today's
//! `queue_order` is spacing-based (a brighter one within 16 px ahead, [`crate::sim::metrics`]):
//! seeds 1–10 read 0.00–0.01 at step 1 and 0.59–0.86 at step 300.

use super::planner::{GroupView, Planner, StepContext};
use crate::model::geometry::limit;
use crate::model::geometry::{unit_or, Aabb};
use crate::model::params::FireflyParams;
use crate::planners::explain::{Explanation, NamedPoint, NamedVector};
use crate::rng::Rng;
use crate::spatial::QueryCap;
use glam::Vec2;
use near::{key, NearIndex};

mod near;

/// The firefly planner for one group. Per-agent state (mass) is indexed by the agent's position
/// within its group.
#[derive(Clone, Debug)]
pub struct Firefly {
    params: FireflyParams,
    mass: Vec<f32>,
    /// Buffers reused across agents.
    scratch: Scratch,
}

/// What one firefly's survey works in, reused across agents.
#[derive(Clone, Debug, Default)]
struct Scratch {
    /// The bodies (and surfaces) the firefly could reach this step.
    contacts: Vec<Contact>,
    /// Grid slots of the agents within a query's radius.
    slots: Vec<u32>,
    /// The largest body radius of any agent (px): how far a touching body's centre can lie.
    widest_body: f32,
    /// This step's fine index of the agents, when the group is a large share of them (see
    /// [`Firefly::plan`]); without it every survey queries the world grid.
    index: Option<NearIndex>,
    /// The bodies within reach found in the index: `(world-grid slot, index entry)`.
    close: Vec<(u32, u32)>,
}

impl Scratch {
    fn new(ctx: &StepContext) -> Self {
        Self { widest_body: ctx.radii.iter().copied().fold(0.0, f32::max), ..Self::default() }
    }
}

/// Most bodies the contact rule of one firefly keeps: the nearest (smallest allowed speed
/// towards them). Non-overlapping 4 px discs within reach of one number about 8, so only a pile
/// reaches it; there it keeps [`keep_apart`], whose cost grows with the cube of the contacts,
/// bounded.
const MAX_CONTACT_BODIES: usize = 16;

/// Neighbours (and candidates of the scanned cells) one survey query looks at, the first in the
/// grid's scan order. Within the feeler's reach (110 px) lie at most about 550 non-overlapping
/// 4 px discs, within the default view (200 px) about 1,800: only a pile reaches the cap.
const NEIGHBOUR_CAP: QueryCap = QueryCap { neighbours: 2048, candidates: 8192 };

/// Puts `contact` in place of the farthest of `bodies` (largest allowed speed, the last of
/// equals) if it is nearer: the contact list of a firefly in a pile keeps its nearest bodies.
fn keep_nearest(bodies: &mut [Contact], contact: Contact) {
    let mut farthest: Option<&mut Contact> = None;
    for b in bodies.iter_mut() {
        if farthest.as_ref().is_none_or(|f| b.allowed >= f.allowed) {
            farthest = Some(b);
        }
    }
    if let Some(f) = farthest.filter(|f| contact.allowed < f.allowed) {
        *f = contact;
    }
}

impl Firefly {
    /// A planner with these parameters.
    pub fn new(params: FireflyParams) -> Self {
        Self { params, mass: Vec::new(), scratch: Scratch::default() }
    }

    /// `β(r) = β0 exp(−γ (r / r_safe)^m)`.
    fn attractiveness(&self, distance: f32) -> f32 {
        let p = &self.params;
        let r = distance / p.safe_distance.max(1e-3);
        p.beta0 * libm::expf(-p.gamma * libm::powf(r, p.exponent))
    }

    /// Distance from the target (px) beyond which a firefly brakes for a brighter one it touches
    /// ahead: the goal radius plus two safe distances. Nearer, the crowd packs round the target
    /// and braking would only keep the last ones out.
    fn fall_in_behind_beyond(&self, group: &GroupView) -> f32 {
        group.goal.map_or(0.0, |(_, radius)| radius) + 1.5 * self.params.safe_distance
    }

    /// The sideways avoidance acceleration if the position, half feeler or feeler tip is inside
    /// an obstacle.
    /// The velocity the force gives, braked as the survey says (`plan` and `explain` share it).
    fn braked_velocity(&self, vel: Vec2, acceleration: Vec2, heading: Vec2, survey: &Survey) -> Vec2 {
        let prm = &self.params;
        // §2.4 step 4: the velocity force while the safe distance holds; otherwise the speed
        // is scaled to `brake × max_velocity`, still steering by the force.
        let forced = limit(vel + acceleration, prm.max_velocity);
        let mut v = if survey.blocker.is_some() {
            unit_or(forced, heading) * (prm.max_velocity * prm.brake)
        } else {
            forced
        };
        // Fall in behind: a brighter firefly touching ahead or beside is one the feeler cannot
        // see (its zone starts 10 px ahead); braking lets it pull ahead into the file.
        if survey.brighter_in_contact_ahead {
            v *= prm.brake;
        }
        v
    }

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

/// What one grid query around a firefly finds.
struct Survey {
    /// The nearest brighter firefly of the group in view: `(squared distance, id, position)`.
    nearest: Option<(f32, u32, Vec2)>,
    /// The brighter firefly nearest the feeler tip, within r_safe of it.
    blocker: Option<(f32, u32, Vec2)>,
    /// A brighter firefly of the group is among the contacts, in front of the firefly's
    /// heading, while the firefly is still on its way (see [`Firefly::fall_in_behind_beyond`]).
    brighter_in_contact_ahead: bool,
}

/// A body close enough to be reached this step: the unit direction towards it and the largest
/// speed allowed towards it (negative: the firefly must move away).
#[derive(Clone, Copy, Debug)]
struct Contact {
    towards: Vec2,
    allowed: f32,
}

/// Gap (px) the contact rule keeps between two bodies, so rounding never makes them touch.
const CONTACT_MARGIN: f32 = 0.3;

/// Clearance (px) the contact rule keeps from obstacle surfaces: a 2 px step along the tangent of
/// an 18 px tree dips about 0.1 px into it.
const OBSTACLE_MARGIN: f32 = 0.5;

/// Rounding allowance (px/step) when checking a candidate velocity against the contacts.
const FEASIBLE_SLACK: f32 = 1e-4;

/// Projection passes of the fallback in [`keep_apart`].
const FALLBACK_PASSES: usize = 10;

/// The velocity nearest `v` whose speed towards every contact is within that contact's
/// allowance: `v` itself, its projection onto one contact's limit, or a corner of two (a 2-D
/// quadratic programme over a handful of half-planes, solved by trying each candidate). The
/// sideways part is kept, so a firefly slides along a body instead of stopping at it. When no
/// candidate meets every limit (bodies already inside the margin on opposite sides), projection
/// passes and then a uniform scale make sure no body is approached any further.
fn keep_apart(v: Vec2, contacts: &[Contact]) -> Vec2 {
    let meets = |w: Vec2, c: &Contact| w.dot(c.towards) <= c.allowed + FEASIBLE_SLACK;
    // Whether `w` meets every limit. The contact that failed the last check is tried first: in
    // a jam no candidate is feasible and most fail on the same body, so a check costs one or
    // two products instead of a pass over the list (the answer does not depend on the order).
    let mut last_failed = 0usize;
    let mut feasible = |w: Vec2| {
        if contacts.get(last_failed).is_some_and(|c| !meets(w, c)) {
            return false;
        }
        match contacts.iter().position(|c| !meets(w, c)) {
            Some(k) => {
                last_failed = k;
                false
            }
            None => true,
        }
    };
    if feasible(v) {
        return v;
    }
    let mut best: Option<(f32, Vec2)> = None;
    let mut consider = |w: Vec2| {
        let d2 = w.distance_squared(v);
        // The cheap test first: only a nearer candidate than the best is checked against
        // every contact (both tests are pure, so the choice is the same either way round).
        if best.is_none_or(|(best_d2, _)| d2 < best_d2) && feasible(w) {
            best = Some((d2, w));
        }
    };
    for (k, a) in contacts.iter().enumerate() {
        consider(v - a.towards * (v.dot(a.towards) - a.allowed));
        for b in &contacts[k + 1..] {
            let det = a.towards.perp_dot(b.towards);
            if det.abs() > 1e-6 {
                // The corner w·a.towards = a.allowed, w·b.towards = b.allowed (Cramer's rule).
                consider(Vec2::new(
                    (a.allowed * b.towards.y - b.allowed * a.towards.y) / det,
                    (a.towards.x * b.allowed - b.towards.x * a.allowed) / det,
                ));
            }
        }
    }
    if let Some((_, w)) = best {
        return w;
    }
    let mut w = v;
    for _ in 0..FALLBACK_PASSES {
        let before = w;
        for c in contacts {
            let along = w.dot(c.towards);
            if along > c.allowed {
                w -= c.towards * (along - c.allowed);
            }
        }
        if (w.x.to_bits(), w.y.to_bits()) == (before.x.to_bits(), before.y.to_bits()) {
            // A pass that left `w` as it was, bit for bit: the ones left would repeat it.
            break;
        }
    }
    // Zero speed meets every limit clamped at zero: bodies inside the margin are not approached.
    let mut scale = 1.0f32;
    for c in contacts {
        let allowed = c.allowed.max(0.0);
        let along = w.dot(c.towards);
        if along > allowed {
            scale = scale.min(allowed / along);
        }
    }
    w * scale
}

impl Firefly {
    /// One grid query around firefly `id`: the nearest brighter firefly in view and the one
    /// blocking the feeler tip (none without a target: all are equally bright), and, into
    /// `contacts`, every agent whose body it could reach this step.
    fn survey(
        &self,
        ctx: &StepContext,
        group: &GroupView,
        id: u32,
        target: Option<Vec2>,
        scratch: &mut Scratch,
    ) -> Survey {
        let Scratch { contacts, slots, widest_body, index, close } = scratch;
        let widest_body = *widest_body;
        let prm = &self.params;
        let i = id as usize;
        let p = ctx.positions[i];
        let my2 = target.map_or(0.0, |t| p.distance_squared(t));
        let heading = unit_or(ctx.velocities[i], unit_or(target.unwrap_or(p) - p, Vec2::X));
        let tip = p + heading * prm.feeler_length;
        let (view2, safe2) = (prm.view_radius * prm.view_radius, prm.safe_distance * prm.safe_distance);
        let my_radius = ctx.radii.get(i).copied().unwrap_or(0.0);
        let on_the_way = target.is_some() && my2 > self.fall_in_behind_beyond(group).powi(2);
        let mut survey = Survey { nearest: None, blocker: None, brighter_in_contact_ahead: false };
        contacts.clear();
        // Obstacles do not move: the whole clearance (less a margin that covers the curvature of
        // a sideways step) may be used, so the world never has to push the firefly out sideways
        // into a neighbour.
        let reach = my_radius + OBSTACLE_MARGIN + prm.max_velocity;
        ctx.obstacles.for_each_near(
            Aabb { min: p - Vec2::splat(reach), max: p + Vec2::splat(reach) },
            |_, o| {
                let s = o.surface(p);
                let allowed = s.signed_distance - my_radius - OBSTACLE_MARGIN;
                if allowed < prm.max_velocity {
                    contacts.push(Contact { towards: -s.normal, allowed });
                }
            },
        );
        // The world's borders are walls like obstacles: the world clamps a body back inside
        // them, which would push it into a neighbour (seen at the right border behind the target).
        for (towards, clearance) in [
            (Vec2::NEG_X, p.x),
            (Vec2::X, ctx.bounds.x - p.x),
            (Vec2::NEG_Y, p.y),
            (Vec2::Y, ctx.bounds.y - p.y),
        ] {
            let allowed = clearance - my_radius - OBSTACLE_MARGIN;
            if allowed < prm.max_velocity {
                contacts.push(Contact { towards, allowed });
            }
        }
        // The agents within the feeler's reach hold the contacts and the blocker, and usually
        // the nearest brighter firefly; the rest of the view is searched only when none of
        // them is brighter.
        let columns = ctx.grid.columns();
        let contact_reach = my_radius + widest_body + CONTACT_MARGIN + 2.0 * prm.max_velocity;
        let near_radius = (prm.feeler_length + prm.safe_distance).max(contact_reach);
        let near_radius = near_radius.min(self.interaction_radius());
        let is_own = |other: u32| other.wrapping_sub(group.agents.start) < group.agents.len() as u32;
        let toucher = Toucher { id, p, my_radius, max_velocity: prm.max_velocity, heading, on_the_way };
        let mut list =
            ContactList { before: contacts.len(), contacts, bodies: 0, farthest: f32::NEG_INFINITY };
        // No body lies within reach of a contact unless within this (the widest body's reach).
        let widest_reach2 = contact_reach * contact_reach;
        let near2 = near_radius * near_radius;
        let (mut nearest, mut blocker) = (None, None);
        let t = target.unwrap_or(p);
        if let Some(ix) = index.as_ref().filter(|ix| index_answers(ctx, ix, p, near_radius)) {
            // The fine index holds the same agents as the world grid's query of `near_radius`
            // (its caps do not bind, see `index_answers`): a few small discs answer what that
            // query's ~600 neighbours in a packed crowd do. First the bodies within reach
            // (listed in the world grid's order, which the contact list depends on) and the
            // nearest brighter firefly if it lies among them: none nearer can lie farther out.
            let reach = contact_reach.min(near_radius);
            close.clear();
            for r in ix.rows(p, reach) {
                for e in r {
                    let d2 = p.distance_squared(ix.pos(e));
                    if d2 < widest_reach2 && d2 <= near2 && ix.id[e] != id {
                        close.push((ix.slot[e], e as u32));
                    }
                }
            }
            // World-grid slots are unique: the order is that of the grid's scan.
            close.sort_unstable();
            for &(_, e) in close.iter() {
                let e = e as usize;
                let (other, pos) = (ix.id[e], ix.pos(e));
                let their_radius = ctx.radii.get(other as usize).copied().unwrap_or(0.0);
                let d2 = p.distance_squared(pos);
                if toucher.touch(&mut list, their_radius, other, pos, d2, || ix.bright2[e] < my2) {
                    survey.brighter_in_contact_ahead = true;
                }
            }
            if target.is_some() {
                // The nearest brighter firefly in view: within a contact's reach (in a packed
                // crowd one is there), else within four (in a spread one), else anywhere within
                // `near_radius`. One found within a radius is the nearest: every one nearer
                // lies within that radius too.
                let mut best = (u64::MAX, 0usize);
                for radius in [reach, (4.0 * reach).min(near_radius), near_radius] {
                    let radius2 = radius * radius;
                    best = ix.min_key(p, radius, id, my2, |pos| {
                        let d2 = p.distance_squared(pos);
                        (d2, (d2 <= view2) & (d2 <= near2) & (d2 <= radius2))
                    });
                    if best.0 != u64::MAX {
                        break;
                    }
                }
                nearest = found(best.0, ix.pos(best.1));
                // The blocker: the brighter firefly nearest the tip, within r_safe of it; first
                // within a contact's reach of the tip (in a crowd the tip lies among brighter
                // ones), as above.
                let safe = prm.safe_distance.abs();
                for radius in [reach.min(safe), safe] {
                    let radius2 = radius * radius;
                    best = ix.min_key(tip, radius, id, my2, |pos| {
                        let at_tip = pos.distance_squared(tip);
                        (at_tip, (at_tip < safe2) & (at_tip <= radius2) & (p.distance_squared(pos) <= near2))
                    });
                    if best.0 != u64::MAX {
                        break;
                    }
                }
                blocker = found(best.0, ix.pos(best.1));
            }
        } else {
            // One branch-free pass over the world grid's query.
            ctx.grid.gather_within(p, near_radius, NEIGHBOUR_CAP, slots);
            let (mut nearest_key, mut nearest_slot) = (u64::MAX, 0usize);
            let (mut blocker_key, mut blocker_slot) = (u64::MAX, 0usize);
            for &k in slots.iter() {
                let k = k as usize;
                let (other, pos) = (columns.ids[k], Vec2::new(columns.x[k], columns.y[k]));
                let d2 = p.distance_squared(pos);
                if d2 < widest_reach2 && other != id {
                    let their_radius = ctx.radii.get(other as usize).copied().unwrap_or(0.0);
                    let brighter = || target.is_some_and(|t| is_own(other) && pos.distance_squared(t) < my2);
                    if toucher.touch(&mut list, their_radius, other, pos, d2, brighter) {
                        survey.brighter_in_contact_ahead = true;
                    }
                }
                // Brighter: of the group, nearer the target (no target: none is brighter).
                let brighter =
                    target.is_some() & (other != id) & is_own(other) & (pos.distance_squared(t) < my2);
                let at_tip = pos.distance_squared(tip);
                let b = key(at_tip, other, brighter & (at_tip < safe2));
                if b < blocker_key {
                    (blocker_key, blocker_slot) = (b, k);
                }
                let n = key(d2, other, brighter & (d2 <= view2));
                if n < nearest_key {
                    (nearest_key, nearest_slot) = (n, k);
                }
            }
            let at = |k: usize| Vec2::new(columns.x[k], columns.y[k]);
            blocker = found(blocker_key, at(blocker_slot));
            nearest = found(nearest_key, at(nearest_slot));
        }
        survey.blocker = blocker;
        survey.nearest = nearest;
        let Some(target) = target else { return survey };
        if survey.nearest.is_none() && near_radius < prm.view_radius {
            // No brighter firefly within the feeler's reach: the nearest one farther off.
            let (mut nearest, mut nearest_slot) = (u64::MAX, 0usize);
            ctx.grid.gather_within(p, prm.view_radius, NEIGHBOUR_CAP, slots);
            for &k in slots.iter() {
                let k = k as usize;
                let (other, pos) = (columns.ids[k], Vec2::new(columns.x[k], columns.y[k]));
                let d2 = p.distance_squared(pos);
                let brighter =
                    (other != id) & (d2 > near2) & is_own(other) & (pos.distance_squared(target) < my2);
                let n = key(d2, other, brighter);
                if n < nearest {
                    (nearest, nearest_slot) = (n, k);
                }
            }
            survey.nearest = found(nearest, Vec2::new(columns.x[nearest_slot], columns.y[nearest_slot]));
        }
        survey
    }
}

/// The `(squared distance, id, position)` a key found, if any.
fn found(key: u64, pos: Vec2) -> Option<(f32, u32, Vec2)> {
    (key != u64::MAX).then(|| (f32::from_bits((key >> 32) as u32), key as u32, pos))
}

/// Whether `index` answers the survey exactly as the world grid's capped query of
/// `near_radius` round `p` would: neither cap binds (the scanned cells hold no more candidates
/// than its cap, the fine cells round the disc no more agents than its neighbour cap), and the
/// disc, widened by [`near::slack`], lies inside the cells that query scans, so every agent
/// within `near_radius` is one it lists.
fn index_answers(ctx: &StepContext, index: &NearIndex, p: Vec2, near_radius: f32) -> bool {
    p.is_finite()
        && ctx.grid.query_cells(p, near_radius + near::slack(p, near_radius))
            == ctx.grid.query_cells(p, near_radius)
        && match ctx.grid.query_candidates(p, near_radius) {
            n if n > NEIGHBOUR_CAP.candidates => false,
            // No more agents within the radius than candidates.
            n if n <= NEIGHBOUR_CAP.neighbours => true,
            _ => index.count(p, near_radius) <= NEIGHBOUR_CAP.neighbours,
        }
}

/// The surveying firefly, as the contact rule sees it.
struct Toucher {
    id: u32,
    p: Vec2,
    my_radius: f32,
    max_velocity: f32,
    heading: Vec2,
    on_the_way: bool,
}

impl Toucher {
    /// Offers `other` (radius `their_radius`, at `pos`, `d2` away, within the widest body's
    /// reach) to the contact list if its body is within reach; returns whether it is a
    /// brighter firefly of the group ahead that the firefly, on its way, falls in behind
    /// (`brighter` is asked only then).
    #[inline]
    fn touch(
        &self,
        list: &mut ContactList,
        their_radius: f32,
        other: u32,
        pos: Vec2,
        d2: f32,
        brighter: impl FnOnce() -> bool,
    ) -> bool {
        let (p, my_radius) = (self.p, self.my_radius);
        // Each of the two moves at most half the gap (less a margin) towards the other per
        // step, whatever the other does, so together they cannot close it in one step. The
        // limit binds only within 2 × max_velocity of touching: the square root only then.
        let reach = my_radius + their_radius + CONTACT_MARGIN + 2.0 * self.max_velocity;
        if d2 >= reach * reach {
            return false;
        }
        let allowed = 0.5 * (d2.sqrt() - my_radius - their_radius - CONTACT_MARGIN);
        // Coincident bodies part along x, the lower id to the left.
        let apart = if other < self.id { Vec2::NEG_X } else { Vec2::X };
        list.offer(Contact { towards: unit_or(pos - p, apart), allowed });
        self.on_the_way && self.heading.dot(pos - p) > 0.0 && brighter()
    }
}

/// The contact list of one survey while its neighbours are visited in the world grid's scan
/// order: the bodies after the obstacles' and borders' surfaces, at most
/// [`MAX_CONTACT_BODIES`] of them, the nearest.
struct ContactList<'a> {
    contacts: &'a mut Vec<Contact>,
    /// Surfaces listed before the bodies.
    before: usize,
    bodies: usize,
    /// The largest allowed speed among the bodies kept (the farthest of them).
    farthest: f32,
}

impl ContactList<'_> {
    fn offer(&mut self, contact: Contact) {
        if self.bodies < MAX_CONTACT_BODIES {
            self.contacts.push(contact);
            self.bodies += 1;
            self.farthest = self.farthest.max(contact.allowed);
        } else if contact.allowed < self.farthest {
            // Only a nearer body than the farthest kept changes the list (a pile).
            let kept = self.contacts.get_mut(self.before..).unwrap_or_default();
            keep_nearest(kept, contact);
            self.farthest = kept.iter().fold(f32::NEG_INFINITY, |m, c| m.max(c.allowed));
        }
    }
}

impl Planner for Firefly {
    /// firefly agents gather at their goal by themselves: its feeler queues each behind a brighter one and the crowd gathers at the target without touching. Walking them to places by the
    /// world (straight, not seen by this planner's avoidance) would make them overlap.
    fn interaction_radius(&self) -> f32 {
        self.params.view_radius.max(self.params.feeler_length + self.params.safe_distance)
    }

    fn max_speed(&self) -> f32 {
        self.params.max_velocity
    }

    /// The same terms as `plan` without the random step (its expectation is zero): the brighter
    /// firefly followed, the feeler and whether a brighter one blocks its tip, the avoidance and
    /// the cut that keeps bodies apart.
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
        e.values.push(("brightness 1/|x − target|".into(), 1.0 / p.distance(target).max(1e-3)));
        let heading = unit_or(vel, unit_or(target - p, Vec2::X));
        let mut scratch = Scratch::new(ctx);
        let survey = self.survey(ctx, group, agent, Some(target), &mut scratch);
        let contacts = scratch.contacts;
        let view2 = prm.view_radius * prm.view_radius;
        ctx.grid.for_each_within(p, prm.view_radius, |nb| {
            if nb.id != agent
                && nb.d2 <= view2
                && group.agents.contains(&nb.id)
                && nb.pos.distance_squared(target) < p.distance_squared(target)
            {
                e.neighbours.push(nb.id);
            }
        });
        e.vectors.push(NamedVector::px("feeler", heading * prm.feeler_length));
        let acceleration = match survey.nearest {
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
        if let Some((_, _, q)) = survey.blocker {
            e.points.push(NamedPoint::new("brighter firefly at the feeler tip", q));
        }
        let v = self.braked_velocity(vel, acceleration, heading, &survey);
        if survey.brighter_in_contact_ahead {
            e.values.push(("falling in behind a brighter firefly it touches".into(), 1.0));
        }
        let avoid = self.avoid(ctx, p, unit_or(v, heading));
        if avoid != Vec2::ZERO {
            e.vectors.push(NamedVector::new("obstacle avoidance", avoid));
        }
        let free = limit(v + avoid, prm.max_velocity);
        let kept = keep_apart(free, &contacts);
        if kept != free {
            e.vectors.push(NamedVector::new("kept apart from touching bodies", kept - free));
        }
        e.applied = limit(kept, prm.max_velocity) - vel;
        e.state = match (kept != free, survey.blocker.is_some(), survey.nearest.is_some()) {
            (true, _, _) => "slowed towards a body it would touch".into(),
            (false, true, _) => "queued: a brighter firefly is at the feeler tip (braking)".into(),
            (false, false, true) => "attracted by the nearest brighter firefly".into(),
            (false, false, false) => "brightest in view: max-speed force to the target".into(),
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
        let unit_len = prm.safe_distance;
        let target = group.goal.map(|(t, _)| t);
        let mut scratch = std::mem::take(&mut self.scratch);
        scratch.widest_body = ctx.radii.iter().copied().fold(0.0, f32::max);
        // The fine index costs a pass over every agent of the world: worth it when the group is
        // a fair share of them (it answers exactly as the world grid does, only faster).
        if n * 4 >= ctx.positions.len() && n > 0 {
            let cell = 2.0 * scratch.widest_body + CONTACT_MARGIN + 2.0 * prm.max_velocity;
            scratch.index.get_or_insert_with(NearIndex::default).rebuild(
                ctx.grid,
                ctx.bounds,
                cell,
                &group.agents,
                target,
            );
        } else {
            scratch.index = None;
        }
        for (k, id) in group.agents.clone().enumerate() {
            let i = id as usize;
            let p = ctx.positions[i];
            let vel = ctx.velocities[i];
            let mass = self.mass[k].max(1e-3);
            let survey = self.survey(ctx, &group, id, target, &mut scratch);
            let contacts = &scratch.contacts;
            let Some(target) = target else {
                // No target: every firefly is equally bright; drift with a little noise.
                let noise = Vec2::new(rng.unit() - 0.5, rng.unit() - 0.5) * (prm.alpha * unit_len);
                let v = limit(vel + noise / mass, prm.max_velocity);
                new_velocities[k] = limit(keep_apart(v, contacts), prm.max_velocity);
                continue;
            };
            let heading = unit_or(vel, unit_or(target - p, Vec2::X));
            let acceleration = match survey.nearest {
                Some((d2, _, q)) => {
                    let beta = self.attractiveness(d2.sqrt());
                    let noise = Vec2::new(rng.unit() - 0.5, rng.unit() - 0.5) * (prm.alpha * unit_len);
                    // Eq. 5: the velocity force a − x_i, with a from eq. 3.
                    ((q - p) * beta + noise) / mass
                }
                None => unit_or(target - p, heading) * prm.max_velocity,
            };
            let mut v = self.braked_velocity(vel, acceleration, heading, &survey);
            v += self.avoid(ctx, p, unit_or(v, heading));
            let free = limit(v, prm.max_velocity);
            new_velocities[k] = limit(keep_apart(free, contacts), prm.max_velocity);
        }
        self.scratch = scratch;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::{PlannerConfig, PlannerKind};
    use crate::{presets, Goal, Region, Scene, World};

    /// A square crowd of `n` bodies of `radius` packed `spacing` apart (in body diameters),
    /// heading for a goal at its centre, as `examples/step_cost.rs` builds its worst case.
    fn packed(n: u32, radius: f32, spacing: f32) -> Scene {
        let side = (f64::from(n).sqrt().ceil() as f32) * 2.0 * radius * spacing;
        let world = side + 200.0;
        let mut s = Scene::empty(world, world);
        let (lo, hi) = (100.0 + radius, 100.0 + side - radius);
        s.goals.push(Goal::fixed([0.5 * world, 0.5 * world], 20.0));
        let mut g = presets::constant_density(1, 1.0).groups.remove(0);
        g.count = n;
        g.spawn = Region { min: [lo, lo], max: [hi, hi] };
        g.goal = Some(0);
        g.agent_radius = radius;
        g.planner = PlannerKind::Firefly.default_config();
        s.groups.push(g);
        s
    }

    /// Surveys every firefly of `world` with the fine index and through the world grid alone:
    /// the two must agree bit for bit (the index is only a faster way to the same answers).
    /// Returns how many surveys the index answered.
    fn check_surveys_agree(world: &World) -> usize {
        let ctx = world.step_context();
        let mut answered = 0;
        for (g, group) in world.scene().groups.iter().enumerate() {
            let PlannerConfig::Firefly(params) = &group.planner else { continue };
            let ff = Firefly::new(params.clone());
            let Some(view) = world.group_view(g) else { continue };
            let target = view.goal.map(|(t, _)| t);
            let mut plain = Scratch::new(&ctx);
            let mut indexed = Scratch::new(&ctx);
            let mut index = NearIndex::default();
            let cell = 2.0 * indexed.widest_body + CONTACT_MARGIN + 2.0 * params.max_velocity;
            index.rebuild(ctx.grid, ctx.bounds, cell, &view.agents, target);
            indexed.index = Some(index);
            for id in view.agents.clone() {
                let a = ff.survey(&ctx, &view, id, target, &mut plain);
                let b = ff.survey(&ctx, &view, id, target, &mut indexed);
                let bits = |s: &Survey| {
                    let f = |o: Option<(f32, u32, Vec2)>| {
                        o.map(|(d, i, q)| (d.to_bits(), i, q.x.to_bits(), q.y.to_bits()))
                    };
                    (f(s.nearest), f(s.blocker), s.brighter_in_contact_ahead)
                };
                assert_eq!(bits(&a), bits(&b), "agent {id}");
                let cbits = |c: &[Contact]| {
                    c.iter()
                        .map(|c| (c.towards.x.to_bits(), c.towards.y.to_bits(), c.allowed.to_bits()))
                        .collect::<Vec<_>>()
                };
                assert_eq!(cbits(&plain.contacts), cbits(&indexed.contacts), "agent {id}");
                let p = ctx.positions[id as usize];
                let ix = indexed.index.as_ref().expect("index");
                let contact_reach =
                    ctx.radii[id as usize] + indexed.widest_body + CONTACT_MARGIN + 2.0 * params.max_velocity;
                let near_radius = (params.feeler_length + params.safe_distance)
                    .max(contact_reach)
                    .min(ff.interaction_radius());
                answered += usize::from(index_answers(&ctx, ix, p, near_radius));
            }
        }
        answered
    }

    fn run_and_check(scene: Scene, steps: &[u32]) -> usize {
        let mut world = World::new_beyond_cost_limit(scene).expect("valid scene");
        let mut answered = 0;
        let mut done = 0;
        for &s in steps {
            world.step_n(s - done);
            done = s;
            answered += check_surveys_agree(&world);
        }
        answered
    }

    #[test]
    fn the_fine_index_answers_the_survey_as_the_world_grid_does() {
        // A packed crowd (the worst case), a spread one, the paper's preset with obstacles,
        // fireflies among another planner's agents, and bodies spawned overlapping in a pile
        // (caps bind: the world grid answers those).
        let answered = run_and_check(packed(1600, 4.0, 1.0), &[0, 1, 25]);
        assert!(answered > 3 * 1500, "the index answered {answered} surveys");
        let mut spread = presets::constant_density_to_centre(1500, 9.0, 20.0);
        spread.groups[0].planner = PlannerKind::Firefly.default_config();
        assert!(run_and_check(spread, &[0, 30]) > 2 * 1400);
        for seed in 1..=3 {
            assert!(run_and_check(presets::firefly_migration_with_seed(seed), &[0, 50, 200]) > 0);
        }
        let mut mixed = packed(1600, 4.0, 2.0);
        let mut other = mixed.groups[0].clone();
        other.planner = PlannerKind::Boids.default_config();
        other.count = 800;
        mixed.groups.push(other);
        mixed.groups[0].count = 800;
        assert!(run_and_check(mixed, &[0, 20]) > 0);
        // Bodies of 1 px radius at the density limit: thousands within the feeler's reach,
        // the caps bind and the world grid answers.
        let pile = packed(6400, 1.0, 1.0);
        let answered = run_and_check(pile, &[0, 5]);
        assert!(answered < 2 * 6400, "the index answered {answered} surveys");
        let mut drifting = packed(900, 4.0, 1.2);
        drifting.groups[0].goal = None;
        run_and_check(drifting, &[0, 10]);
    }

    /// `keep_apart` as it was before its feasibility check learnt which contact fails and its
    /// fallback stopped at a fixed point: the reference the faster one must match bit for bit.
    fn keep_apart_reference(v: Vec2, contacts: &[Contact]) -> Vec2 {
        let feasible = |w: Vec2| contacts.iter().all(|c| w.dot(c.towards) <= c.allowed + FEASIBLE_SLACK);
        if feasible(v) {
            return v;
        }
        let mut best: Option<(f32, Vec2)> = None;
        let mut consider = |w: Vec2| {
            let d2 = w.distance_squared(v);
            if feasible(w) && best.is_none_or(|(best_d2, _)| d2 < best_d2) {
                best = Some((d2, w));
            }
        };
        for (k, a) in contacts.iter().enumerate() {
            consider(v - a.towards * (v.dot(a.towards) - a.allowed));
            for b in &contacts[k + 1..] {
                let det = a.towards.perp_dot(b.towards);
                if det.abs() > 1e-6 {
                    consider(Vec2::new(
                        (a.allowed * b.towards.y - b.allowed * a.towards.y) / det,
                        (a.towards.x * b.allowed - b.towards.x * a.allowed) / det,
                    ));
                }
            }
        }
        if let Some((_, w)) = best {
            return w;
        }
        let mut w = v;
        for _ in 0..FALLBACK_PASSES {
            for c in contacts {
                let along = w.dot(c.towards);
                if along > c.allowed {
                    w -= c.towards * (along - c.allowed);
                }
            }
        }
        let mut scale = 1.0f32;
        for c in contacts {
            let allowed = c.allowed.max(0.0);
            let along = w.dot(c.towards);
            if along > allowed {
                scale = scale.min(allowed / along);
            }
        }
        w * scale
    }

    #[test]
    fn keep_apart_matches_its_reference_bit_for_bit() {
        let mut rng = Rng::new(7, 0);
        let (mut fallbacks, mut projected) = (0, 0);
        for case in 0..20_000 {
            let n = 1 + case % MAX_CONTACT_BODIES;
            let contacts: Vec<Contact> = (0..n)
                .map(|_| {
                    let angle = rng.range(0.0, std::f32::consts::TAU);
                    // Lattice directions (exact opposites) as in a packed crowd, or any.
                    let angle = if rng.unit() < 0.5 {
                        (angle / std::f32::consts::FRAC_PI_4).round() * std::f32::consts::FRAC_PI_4
                    } else {
                        angle
                    };
                    Contact { towards: Vec2::new(angle.cos(), angle.sin()), allowed: rng.range(-0.5, 2.5) }
                })
                .collect();
            let v = Vec2::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0));
            let (a, b) = (keep_apart(v, &contacts), keep_apart_reference(v, &contacts));
            assert_eq!((a.x.to_bits(), a.y.to_bits()), (b.x.to_bits(), b.y.to_bits()), "case {case}");
            fallbacks += usize::from(a.length() < 1e-3);
            projected += usize::from(a != v);
        }
        assert!(fallbacks > 100 && projected > 1000, "{fallbacks} near-stops, {projected} cut");
    }
}
