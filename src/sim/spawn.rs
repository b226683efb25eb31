//! Where a scene's agents start: every group laid without overlap on a seeded jittered lattice
//! over its spawn region, in O(N), with the density limit that refuses a region too small.

use crate::model::geometry::{v, Aabb};
use crate::model::refusal::{Code, Message};
use crate::model::scene::{Scene, SceneError};
use crate::rng::Rng;
use crate::spatial::ObstacleIndex;
use glam::Vec2;

/// Random stream of group `g`'s placement is `STREAM_SPAWN + g` (a group's start does not
/// depend on the draws of the groups before it; the world's planners draw from another).
const STREAM_SPAWN: u32 = 0x100;
/// Most lattice places examined per group while spawning: bounds spawn time and memory for a
/// huge region mostly covered by obstacles (its finest lattice is coarsened to this many).
pub const MAX_SPAWN_PLACES: u64 = 1 << 21;

/// A lattice of `cols × rows` places tiling a rectangle: one body per place, its centre drawn
/// in the place shrunk by the body radius, so bodies of two places never overlap.
struct Lattice {
    origin: Vec2,
    place: Vec2,
    cols: u32,
    rows: u32,
}

impl Lattice {
    /// Places of side at least `spacing` (≥ 2 × radius) over `size`.
    fn new(origin: Vec2, size: Vec2, spacing: f32) -> Self {
        let cols = ((size.x / spacing) as u32).max(1);
        let rows = ((size.y / spacing) as u32).max(1);
        Self { origin, place: Vec2::new(size.x / cols as f32, size.y / rows as f32), cols, rows }
    }

    fn corner(&self, place: u32) -> Vec2 {
        let (i, j) = (place % self.cols, place / self.cols);
        self.origin + Vec2::new(i as f32 * self.place.x, j as f32 * self.place.y)
    }

    fn centre(&self, place: u32) -> Vec2 {
        self.corner(place) + 0.5 * self.place
    }
}

/// Spawns every group without overlap, in O(N): each group is laid on a jittered lattice over
/// its spawn region whose places are at least a body diameter apart, coarse enough to spread
/// the group over the whole region and refined until enough places are clear of obstacles and
/// of the groups placed before (largest bodies first). Returns the positions and the unit
/// start directions, agent by agent; refuses a group its region cannot hold (the density
/// limit), naming the group, its count and the most the region holds.
///
/// Work: the lattice places examined, each a constant number of cell lookups. Without
/// obstacles the first lattice has at most about as many places as agents; obstacles refine it,
/// by at least 0.9 in spacing a time, up to [`MAX_SPAWN_PLACES`] places per group.
pub fn spawn(scene: &Scene, obstacles: &ObstacleIndex) -> Result<Spawn, SceneError> {
    let mut offsets = Vec::with_capacity(scene.groups.len());
    let mut total = 0usize;
    for g in &scene.groups {
        offsets.push(total);
        total += g.count as usize;
    }
    let mut pos = vec![Vec2::ZERO; total];
    let mut dir = vec![Vec2::ZERO; total];
    let mut order: Vec<usize> = (0..scene.groups.len()).collect();
    order.sort_by(|&a, &b| scene.groups[b].agent_radius.total_cmp(&scene.groups[a].agent_radius));
    let mut placed = PlacedBodies::new();
    let mut places_examined = 0u64;
    for gi in order {
        let g = &scene.groups[gi];
        if g.count == 0 {
            continue;
        }
        let mut rng = Rng::new(scene.seed, STREAM_SPAWN.wrapping_add(gi as u32));
        let start = offsets[gi];
        let out = start..start + g.count as usize;
        places_examined += place_group(scene, obstacles, &placed, gi, &mut rng, &mut pos[out.clone()])?;
        for (p, d) in pos[out.clone()].iter().zip(&mut dir[out]) {
            placed.insert(*p, g.agent_radius);
            *d = Vec2::from_angle(rng.range(-std::f32::consts::PI, std::f32::consts::PI));
        }
    }
    Ok(Spawn { positions: pos, directions: dir, places_examined })
}

/// Where [`spawn`] put the agents, and the work it did.
#[derive(Clone, Debug)]
pub struct Spawn {
    /// Start position of every agent, in agent order (px).
    pub positions: Vec<Vec2>,
    /// Unit start heading of every agent (the world scales it by a quarter of the speed limit).
    pub directions: Vec<Vec2>,
    /// Lattice places examined over all groups and refinements (the spawn's work).
    pub places_examined: u64,
}

/// Places the agents of group `gi` (see [`spawn`]) into `out`; returns the places examined.
fn place_group(
    scene: &Scene,
    obstacles: &ObstacleIndex,
    placed: &PlacedBodies,
    gi: usize,
    rng: &mut Rng,
    out: &mut [Vec2],
) -> Result<u64, SceneError> {
    let g = &scene.groups[gi];
    let r = g.agent_radius;
    // Centres lie in the spawn region, moved in where it reaches closer to a border than a
    // radius (see `centre_bounds`).
    let (lo, hi) = centre_bounds(r, Vec2::new(scene.width, scene.height));
    let first = v(g.spawn.min).clamp(lo, hi);
    let last = v(g.spawn.max).clamp(lo, hi);
    // The lattice tiles the centres' rectangle grown by a radius: its first and last places put
    // centres on the rectangle's sides, and a single place fits a side shorter than a body.
    let origin = first - Vec2::splat(r);
    let size = last - first + Vec2::splat(2.0 * r);
    let wanted = out.len();
    let area = f64::from(size.x) * f64::from(size.y);
    let finest = (2.0 * r).max((area / MAX_SPAWN_PLACES as f64).sqrt() as f32);
    let mut spacing = finest.max((area / wanted as f64).sqrt() as f32);
    let mut examined = 0u64;
    let (lattice, mut free) = loop {
        let lattice = Lattice::new(origin, size, spacing);
        examined += u64::from(lattice.cols) * u64::from(lattice.rows);
        let free: Vec<u32> = (0..lattice.cols * lattice.rows)
            .filter(|&k| {
                let c = lattice.centre(k);
                clear_of_obstacles(obstacles, c, r) && placed.clear(c, r)
            })
            .collect();
        if free.len() >= wanted {
            break (lattice, free);
        }
        if spacing <= finest {
            return Err(SceneError::Blocked(
                Message::new(Code::SceneDensity)
                    .with("group", gi + 1)
                    .with("name", g.name.clone())
                    .with("count", g.count)
                    .with("radius", r)
                    .with("width", g.spawn.max[0] - g.spawn.min[0])
                    .with("height", g.spawn.max[1] - g.spawn.min[1])
                    .with("most", free.len()),
            ));
        }
        // Refine towards the spacing the free share suggests, at least a little each time.
        let ratio = (free.len() as f32 / (1.1 * wanted as f32)).sqrt().clamp(0.25, 0.9);
        spacing = finest.max(spacing * ratio);
    };
    // A seeded partial shuffle picks which free places get an agent.
    for a in 0..wanted {
        let j = a + rng.below((free.len() - a) as u32) as usize;
        free.swap(a, j);
    }
    let room = lattice.place - Vec2::splat(2.0 * r);
    for (p, &k) in out.iter_mut().zip(&free) {
        let jittered =
            lattice.corner(k) + Vec2::splat(r) + room.max(Vec2::ZERO) * Vec2::new(rng.unit(), rng.unit());
        *p = if clear_of_obstacles(obstacles, jittered, r) && placed.clear(jittered, r) {
            jittered
        } else {
            lattice.centre(k)
        };
    }
    Ok(examined)
}

/// The corners of the rectangle of centres that keeps a body of `radius` inside a world of
/// size `bounds`. Along a side shorter than the body the range is the middle point: the body
/// stays centred there, overhanging both borders equally.
pub fn centre_bounds(radius: f32, bounds: Vec2) -> (Vec2, Vec2) {
    let r = Vec2::splat(radius).min(0.5 * bounds);
    (r, bounds - r)
}

/// Whether a body of `radius` at `p` keeps clear of every obstacle.
fn clear_of_obstacles(obstacles: &ObstacleIndex, p: Vec2, radius: f32) -> bool {
    let mut clear = true;
    let query = Aabb { min: p - Vec2::splat(radius), max: p + Vec2::splat(radius) };
    obstacles.for_each_near(query, |_, o| clear &= o.surface(p).signed_distance >= radius);
    clear
}

/// Bodies placed so far, for the overlap check of the next ones.
struct PlacedBodies {
    /// First body of each `(class, cell)` bucket; `next` chains the rest.
    head: std::collections::HashMap<u64, u32>,
    next: Vec<u32>,
    pos: Vec<Vec2>,
    radius: Vec<f32>,
    in_class: [u32; SIZE_CLASSES],
}

impl PlacedBodies {
    fn new() -> Self {
        Self {
            head: std::collections::HashMap::new(),
            next: Vec::new(),
            pos: Vec::new(),
            radius: Vec::new(),
            in_class: [0; SIZE_CLASSES],
        }
    }

    fn key(class: usize, p: Vec2) -> u64 {
        let cell = (2u32 << class) as f32;
        let (cx, cy) = ((p.x / cell).max(0.0) as u64, (p.y / cell).max(0.0) as u64);
        ((class as u64) << 48) | (cx << 24) | cy
    }

    fn insert(&mut self, p: Vec2, radius: f32) {
        let class = size_class(radius);
        let id = self.pos.len() as u32;
        let previous = self.head.insert(Self::key(class, p), id).unwrap_or(u32::MAX);
        self.next.push(previous);
        self.pos.push(p);
        self.radius.push(radius);
        self.in_class[class] += 1;
    }

    /// Whether a body of `radius` at `p` stays clear of every placed body. Groups are placed
    /// largest radius first, so every placed body is in `p`'s class or above: 3×3 cells each.
    fn clear(&self, p: Vec2, radius: f32) -> bool {
        for class in 0..SIZE_CLASSES {
            if self.in_class[class] == 0 {
                continue;
            }
            let cell = (2u32 << class) as f32;
            let reach = ((radius + (1u32 << class) as f32) / cell).ceil() as i64;
            let (cx, cy) = ((p.x / cell).max(0.0) as i64, (p.y / cell).max(0.0) as i64);
            for y in (cy - reach).max(0)..=cy + reach {
                for x in (cx - reach).max(0)..=cx + reach {
                    let key = ((class as u64) << 48) | ((x as u64) << 24) | y as u64;
                    let mut id = self.head.get(&key).copied().unwrap_or(u32::MAX);
                    while id != u32::MAX {
                        let gap = radius + self.radius[id as usize];
                        if p.distance_squared(self.pos[id as usize]) < gap * gap {
                            return false;
                        }
                        id = self.next[id as usize];
                    }
                }
            }
        }
        true
    }
}

/// Body radii grouped by powers of two: class `k` holds radii below `2^k` px (k = 0 for radii
/// under 1 px), bucketed in cells of `2^(k+1)` px, so a body touches at most 3×3 cells of its
/// class and any class above it: the check of a new body costs a bounded number of cells.
const SIZE_CLASSES: usize = 8;

fn size_class(radius: f32) -> usize {
    let mut k = 0;
    while k + 1 < SIZE_CLASSES && radius >= (1u32 << k) as f32 {
        k += 1;
    }
    k
}
