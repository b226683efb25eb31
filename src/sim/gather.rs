//! Goals as places that fill (DESIGN §4, "Goals and arrival"): the free places inside a goal
//! that gathers, handed out to the agents that reach it, so a crowd fills its goal the way a
//! waiting area fills instead of piling onto its centre or stopping on first contact.
//!
//! The places are a hexagonal lattice of body-sized cells inside the goal's disc. Each group
//! heading for the goal takes them in its own order, deepest first along the way it comes
//! from, so the part of the goal an agent walks through to reach its place is still empty.

use glam::Vec2;

/// Gap between neighbouring places beyond the bodies' diameter (px): bodies at rest never
/// touch, so no rounding makes two of them overlap.
const PLACE_GAP: f32 = 0.5;

/// Sideways weight of the fill order: of two places equally deep, the one nearer the line
/// the group comes along is taken first, so the filled part of the goal grows as a rounded
/// front instead of a flat one that reaches the sides first.
const SIDEWAYS_WEIGHT: f32 = 0.25;

/// A goal too large for its crowd gets places only in a central disc holding this many times
/// the agents heading for it (plus [`ROOMY_EXTRA`]): the work stays bounded by the crowd,
/// not by the goal's area.
const ROOMY_FACTOR: f32 = 2.0;
const ROOMY_EXTRA: f32 = 16.0;

/// How many of the deepest free places an arriving agent chooses from (the nearest to it).
const CLAIM_CHOICE: usize = 12;

/// Area of a lattice cell per place, as a multiple of the spacing squared (√3/2).
const CELL_AREA: f32 = 0.866_025_4;

/// Distance between neighbouring places for bodies of radius `body` (px).
pub fn place_spacing(body: f32) -> f32 {
    2.0 * body + PLACE_GAP
}

/// About how many bodies of radius `body` a goal of radius `radius` holds (its lattice of
/// places, counted without obstacles or the world's border): for the scene check's notice.
pub fn capacity(radius: f32, body: f32) -> u64 {
    let spacing = place_spacing(body);
    let inner = (radius - body).max(0.0);
    let estimate = std::f64::consts::PI * f64::from(inner) * f64::from(inner)
        / (f64::from(CELL_AREA) * f64::from(spacing) * f64::from(spacing));
    if estimate > 200_000.0 {
        return estimate as u64;
    }
    lattice(Vec2::ZERO, inner, spacing).len().max(1) as u64
}

/// The lattice points within `reach` of `centre`, `spacing` apart, row by row (the centre is
/// always one of them).
fn lattice(centre: Vec2, reach: f32, spacing: f32) -> Vec<Vec2> {
    let row_height = spacing * CELL_AREA;
    let rows = (reach / row_height).floor() as i32;
    let mut out = Vec::new();
    for row in -rows..=rows {
        let y = row as f32 * row_height;
        let shift = if row.rem_euclid(2) == 1 { 0.5 * spacing } else { 0.0 };
        let columns = (reach / spacing).ceil() as i32 + 1;
        for column in -columns..=columns {
            let offset = Vec2::new(column as f32 * spacing + shift, y);
            if offset.length() <= reach + 1e-3 {
                out.push(centre + offset);
            }
        }
    }
    out
}

/// Where an agent stands with its goal ([`crate::sim::world::World::arrivals`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arrival {
    /// Steered by its planner (on its way, or its goal does not gather or still moves).
    Moving,
    /// Inside its goal, walking to the place it took there (the place's number).
    Walking(u32),
    /// Its goal is full: pressing towards the goal's centre until the crowd stops it.
    Pressing,
    /// At rest in its goal (parked, solid to others).
    Parked,
    /// At rest outside its full goal, waiting for room (solid to others).
    Waiting,
    /// Left the scene through its exit goal.
    Exited,
}

impl Arrival {
    /// Whether the agent stands still for good and is solid to the others.
    pub fn at_rest(self) -> bool {
        matches!(self, Arrival::Parked | Arrival::Waiting)
    }
}

/// The places of one goal and which are taken.
#[derive(Clone, Debug)]
pub struct GoalPlaces {
    /// The goal's centre where it rests (px).
    pub centre: Vec2,
    /// The goal's radius (px).
    pub radius: f32,
    places: Vec<Vec2>,
    taken: Vec<bool>,
    free: usize,
    /// Places a body has come to rest on.
    filled: usize,
    /// Per group heading for the goal, its places in the order it takes them, and how far
    /// along that order every place before is taken.
    orders: Vec<(u32, Vec<u32>, usize)>,
    /// Whether places were left out because the goal is much larger than its crowd: then it
    /// is never full.
    roomy: bool,
}

impl GoalPlaces {
    /// The places of a goal at `centre` of `radius` for bodies of radius `body`, where
    /// `placeable` holds (inside the world, clear of obstacles), for `crowd` agents at most
    /// heading for it. `approaches` gives, per group heading for it, where the group comes
    /// from (its centroid): its places are ordered deepest first along that way.
    pub fn new(
        centre: Vec2,
        radius: f32,
        body: f32,
        crowd: usize,
        approaches: &[(u32, Vec2)],
        placeable: impl Fn(Vec2) -> bool,
    ) -> Self {
        let spacing = place_spacing(body);
        let inner = (radius - body).max(0.0);
        let roomy_reach = (((crowd as f32) * ROOMY_FACTOR + ROOMY_EXTRA) * CELL_AREA * spacing * spacing
            / std::f32::consts::PI)
            .sqrt()
            + spacing;
        let roomy = roomy_reach < inner;
        let reach = inner.min(roomy_reach);
        let places: Vec<Vec2> =
            lattice(centre, reach, spacing).into_iter().filter(|&p| placeable(p)).collect();
        let orders = approaches
            .iter()
            .map(|&(group, from)| {
                // A group around the goal (coming from every side) fills it from the centre out.
                let around = from.distance(centre) < radius;
                let way = (centre - from).try_normalize().unwrap_or(Vec2::X);
                let key = |p: Vec2| {
                    let w = p - centre;
                    if around {
                        w.length()
                    } else {
                        -w.dot(way) + SIDEWAYS_WEIGHT * w.perp_dot(way).abs()
                    }
                };
                let mut order: Vec<u32> = (0..places.len() as u32).collect();
                order.sort_by(|&a, &b| {
                    key(places[a as usize]).total_cmp(&key(places[b as usize])).then(a.cmp(&b))
                });
                (group, order, 0)
            })
            .collect();
        let free = places.len();
        Self { centre, radius, taken: vec![false; places.len()], places, free, filled: 0, orders, roomy }
    }

    /// Number of places.
    pub fn capacity(&self) -> usize {
        self.places.len()
    }

    /// Whether a body rests on every place (never for a goal much larger than its crowd):
    /// then the late-comers wait outside. While some are only claimed by agents walking to
    /// them, the others go on as their planner steers them.
    pub fn is_full(&self) -> bool {
        self.filled >= self.places.len() && !self.roomy
    }

    /// Records that a body came to rest on a place it took.
    pub fn fill(&mut self) {
        self.filled += 1;
    }

    /// Where place `k` is.
    pub fn place(&self, k: u32) -> Vec2 {
        self.places.get(k as usize).copied().unwrap_or(self.centre)
    }

    /// Takes a free place for an agent of `group` at `from`: of the next [`CLAIM_CHOICE`] free
    /// places in the group's order (deepest first along its way in), the one nearest to the
    /// agent, so agents coming in side by side walk to places side by side instead of
    /// crossing each other's way.
    pub fn claim_for_group(&mut self, group: u32, from: Vec2) -> Option<u32> {
        let (_, order, next) = self.orders.iter_mut().find(|(g, _, _)| *g == group)?;
        while *next < order.len() && self.taken[order[*next] as usize] {
            *next += 1;
        }
        let places = &self.places;
        let taken = &self.taken;
        let k = order[*next..].iter().copied().filter(|&k| !taken[k as usize]).take(CLAIM_CHOICE).min_by(
            |&a, &b| {
                from.distance_squared(places[a as usize])
                    .total_cmp(&from.distance_squared(places[b as usize]))
                    .then(a.cmp(&b))
            },
        )?;
        self.taken[k as usize] = true;
        self.free -= 1;
        Some(k)
    }

    /// Takes the free place nearest to `p` (for an agent that could not reach the place it
    /// had: it takes one beside it).
    pub fn claim_nearest(&mut self, p: Vec2) -> Option<u32> {
        let k = (0..self.places.len()).filter(|&k| !self.taken[k]).min_by(|&a, &b| {
            p.distance_squared(self.places[a]).total_cmp(&p.distance_squared(self.places[b]))
        })?;
        self.taken[k] = true;
        self.free -= 1;
        Some(k as u32)
    }

    /// Gives place `k` back.
    pub fn release(&mut self, k: u32) {
        if let Some(t) = self.taken.get_mut(k as usize) {
            if *t {
                *t = false;
                self.free += 1;
                for (_, _, next) in &mut self.orders {
                    *next = 0;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn places_lie_inside_the_goal_and_do_not_overlap() {
        let g = GoalPlaces::new(Vec2::new(100.0, 100.0), 40.0, 4.0, 1000, &[(0, Vec2::ZERO)], |_| true);
        assert!(g.capacity() > 15);
        for k in 0..g.capacity() as u32 {
            assert!(g.place(k).distance(g.centre) <= 36.0 + 1e-3);
            for j in 0..k {
                assert!(g.place(k).distance(g.place(j)) >= 8.0, "places {k} and {j} overlap");
            }
        }
        assert_eq!(capacity(40.0, 4.0), g.capacity() as u64);
    }

    #[test]
    fn a_group_fills_from_the_far_side_then_the_goal_is_full() {
        let mut g = GoalPlaces::new(Vec2::new(100.0, 0.0), 60.0, 4.0, 1000, &[(3, Vec2::ZERO)], |_| true);
        let first = g.claim_for_group(3, Vec2::ZERO).map(|k| g.place(k));
        assert!(first.is_some_and(|p| p.x > 140.0), "first place {first:?} is on the far side");
        let mut taken = 1;
        while g.claim_for_group(3, Vec2::ZERO).is_some() {
            taken += 1;
        }
        assert_eq!(taken, g.capacity());
        assert!(!g.is_full(), "taken, but nobody rests there yet");
        for _ in 0..taken {
            g.fill();
        }
        assert!(g.is_full());
        assert_eq!(g.claim_for_group(7, Vec2::ZERO), None, "a group that does not head there gets none");
    }

    #[test]
    fn a_roomy_goal_has_places_for_its_crowd_only_and_is_never_full() {
        let mut g = GoalPlaces::new(Vec2::ZERO, 5000.0, 1.0, 10, &[(0, Vec2::new(-1.0, 0.0))], |_| true);
        assert!(g.capacity() < 200, "{} places", g.capacity());
        while g.claim_for_group(0, Vec2::ZERO).is_some() {}
        assert!(!g.is_full());
    }
}
