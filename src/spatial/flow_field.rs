//! Goal-derived flow field (lecture, "Flow Field": top-down guidance): a grid of cells over the
//! scene, each holding the direction of the shortest obstacle-free way to the goal.
//!
//! Built by Dijkstra from the goal's cell over the free cells (8-connected, a diagonal move only
//! between two free orthogonal neighbours so the way never cuts an obstacle's corner). A cell is
//! blocked when its centre lies within `clearance` of an obstacle. Cells near a wall cost more
//! to cross, so the field leads through the middle of passages rather than along their walls.
//! Every cell points at its neighbour of least distance; a blocked cell points at its best free
//! neighbour, so an agent pressed against a wall is led back into the open. Only exact IEEE
//! operations (+, ×, ÷, √): the same field on every platform.

use crate::digest::Fnv1a;
use crate::model::geometry::{Aabb, Obstacle};
use crate::spatial::ObstacleIndex;
use glam::Vec2;
use std::cell::RefCell;
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};
use std::rc::{Rc, Weak};

/// Side of a cell (px) unless the scene is so large that [`MAX_CELLS`] forces bigger ones.
pub const CELL: f32 = 10.0;
/// Most cells of a field (a 20,000 px square scene gets 40 px cells).
pub const MAX_CELLS: usize = 262_144;
/// Cells closer than this many cell sides to an obstacle cost up to twice as much to cross.
const WALL_MARGIN_CELLS: f32 = 2.5;

/// The eight neighbour offsets `(dx, dy)`; the first four are orthogonal.
const NEIGHBOURS: [(i32, i32); 8] = [(1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1)];

/// Bytes a field keeps per cell: its distance (`f32`) and direction (`Vec2`).
pub const BYTES_PER_CELL: u64 = 12;

/// The cell side (px), columns and rows of the field of a `bounds`-sized scene: [`CELL`]-sized
/// cells, grown by half until at most [`MAX_CELLS`] cover it.
pub fn grid_of(bounds: Vec2) -> (f32, u32, u32) {
    let mut cell = CELL;
    let w = bounds.x.max(1.0);
    let h = bounds.y.max(1.0);
    while ((w / cell).ceil() * (h / cell).ceil()) as usize > MAX_CELLS {
        cell *= 1.5;
    }
    let cols = ((w / cell).ceil() as u32).max(1);
    let rows = ((h / cell).ceil() as u32).max(1);
    (cell, cols, rows)
}

/// Cells of the field of a `bounds`-sized scene.
pub fn cells_of(bounds: Vec2) -> u64 {
    let (_, cols, rows) = grid_of(bounds);
    u64::from(cols) * u64::from(rows)
}

/// A flow field towards one goal.
#[derive(Clone, Debug)]
pub struct FlowField {
    cell: f32,
    cols: u32,
    rows: u32,
    /// Way length (px, weighted near walls) from each cell centre to the goal; ∞ if unreachable.
    distance: Vec<f32>,
    /// Unit direction towards the goal per cell; zero where none is known.
    direction: Vec<Vec2>,
}

impl FlowField {
    /// The field of a `bounds`-sized scene towards `goal`, cells blocked within `clearance` px of
    /// an obstacle.
    pub fn new(bounds: Vec2, obstacles: &ObstacleIndex, goal: Vec2, clearance: f32) -> Self {
        let (cell, cols, rows) = grid_of(bounds);
        let n = (cols * rows) as usize;
        let clearance = clearance.max(0.0);
        let margin = WALL_MARGIN_CELLS * cell;
        // Clear distance of each cell centre from the obstacles, capped at `margin`.
        let mut clear = vec![margin; n];
        if !obstacles.is_empty() {
            for (c, slot) in clear.iter_mut().enumerate() {
                let centre = centre_of(cell, cols, c);
                let query = Aabb { min: centre, max: centre }.inflate(margin.max(clearance));
                obstacles.for_each_near(query, |_, o: &Obstacle| {
                    *slot = slot.min(o.surface(centre).signed_distance);
                });
            }
        }
        let free: Vec<bool> = clear.iter().map(|&d| d >= clearance).collect();
        let mut field =
            Self { cell, cols, rows, distance: vec![f32::INFINITY; n], direction: vec![Vec2::ZERO; n] };
        let Some(start) = field.cell_index(goal) else { return field };
        // Dijkstra. Distances are ≥ 0, whose f32 bit patterns order like the numbers; ties break
        // by cell index, so the result does not depend on the heap's internals.
        let mut heap = BinaryHeap::new();
        field.distance[start] = centre_of(cell, cols, start).distance(goal);
        heap.push(Reverse((field.distance[start].to_bits(), start as u32)));
        while let Some(Reverse((bits, c))) = heap.pop() {
            let c = c as usize;
            let d = f32::from_bits(bits);
            if d > field.distance[c] {
                continue;
            }
            for (k, &(dx, dy)) in NEIGHBOURS.iter().enumerate() {
                let Some(m) = field.step(c, dx, dy) else { continue };
                if !free[m] {
                    continue;
                }
                if k >= 4
                    && !(field.step(c, dx, 0).is_some_and(|a| free[a])
                        && field.step(c, 0, dy).is_some_and(|b| free[b]))
                {
                    continue;
                }
                let length = if k >= 4 { cell * std::f32::consts::SQRT_2 } else { cell };
                let wall = 1.0 + (1.0 - clear[m] / margin).clamp(0.0, 1.0);
                let next = d + length * wall;
                if next < field.distance[m] {
                    field.distance[m] = next;
                    heap.push(Reverse((next.to_bits(), m as u32)));
                }
            }
        }
        for c in 0..n {
            let centre = centre_of(cell, cols, c);
            field.direction[c] = if c == start || field.next_to(c, start) {
                unit(goal - centre)
            } else if let Some(g) = field.gradient(c).filter(|_| free[c]) {
                // In the open: down the distance's gradient (central differences), which is
                // not bound to the eight grid directions, so neighbouring lanes stay parallel
                // instead of converging on one diagonal.
                unit(-g)
            } else {
                field.downhill(c, &free).map_or(Vec2::ZERO, |m| unit(centre_of(cell, cols, m) - centre))
            };
        }
        field
    }

    /// Whether cell `m` is one of the eight neighbours of cell `c`.
    fn next_to(&self, c: usize, m: usize) -> bool {
        NEIGHBOURS.iter().any(|&(dx, dy)| self.step(c, dx, dy) == Some(m))
    }

    /// The distance gradient at cell `c` by central differences, if its four orthogonal
    /// neighbours all have a distance.
    fn gradient(&self, c: usize) -> Option<Vec2> {
        let d = |dx: i32, dy: i32| self.step(c, dx, dy).map(|m| self.distance[m]).filter(|d| d.is_finite());
        Some(Vec2::new(d(1, 0)? - d(-1, 0)?, d(0, 1)? - d(0, -1)?))
    }

    /// The neighbour of `c` down which the distance falls most steeply (per px travelled),
    /// below `c`'s own (any reached neighbour for a blocked or unreached cell); ties by index.
    fn downhill(&self, c: usize, free: &[bool]) -> Option<usize> {
        let own = if free[c] { self.distance[c] } else { f32::INFINITY };
        let mut best: Option<(f32, usize)> = None;
        for (k, &(dx, dy)) in NEIGHBOURS.iter().enumerate() {
            let Some(m) = self.step(c, dx, dy) else { continue };
            let d = self.distance[m];
            if !d.is_finite() || d >= own {
                continue;
            }
            if k >= 4
                && free[c]
                && !(self.step(c, dx, 0).is_some_and(|a| free[a])
                    && self.step(c, 0, dy).is_some_and(|b| free[b]))
            {
                continue;
            }
            // Per unit length: an absolute drop would favour the longer diagonal steps. From a
            // blocked cell any way out will do, so the nearest reached cell wins.
            let length = if k >= 4 { std::f32::consts::SQRT_2 } else { 1.0 };
            let score = if own.is_finite() { (d - own) / length } else { d };
            if best.is_none_or(|(bs, bm)| (score, m) < (bs, bm)) {
                best = Some((score, m));
            }
        }
        best.map(|(_, m)| m)
    }

    /// The cell `(dx, dy)` away from cell `c`, if inside the grid.
    fn step(&self, c: usize, dx: i32, dy: i32) -> Option<usize> {
        let x = (c as u32 % self.cols) as i32 + dx;
        let y = (c as u32 / self.cols) as i32 + dy;
        if x < 0 || y < 0 || x >= self.cols as i32 || y >= self.rows as i32 {
            return None;
        }
        Some((y as u32 * self.cols + x as u32) as usize)
    }

    /// The cell holding `p`, if `p` is inside the scene.
    fn cell_index(&self, p: Vec2) -> Option<usize> {
        if !p.is_finite() || p.x < 0.0 || p.y < 0.0 {
            return None;
        }
        let x = (p.x / self.cell) as u32;
        let y = (p.y / self.cell) as u32;
        (x < self.cols && y < self.rows).then_some((y * self.cols + x) as usize)
    }

    /// Side of a cell (px).
    pub fn cell_size(&self) -> f32 {
        self.cell
    }

    /// The direction towards the goal at `p`: the cell directions around `p` blended bilinearly,
    /// as a unit vector; zero where the field knows no way (outside the scene, enclosed space).
    pub fn direction_at(&self, p: Vec2) -> Vec2 {
        if !p.is_finite() {
            return Vec2::ZERO;
        }
        let fx = (p.x / self.cell - 0.5).clamp(0.0, (self.cols - 1) as f32);
        let fy = (p.y / self.cell - 0.5).clamp(0.0, (self.rows - 1) as f32);
        let (x0, y0) = (fx as u32, fy as u32);
        let (x1, y1) = ((x0 + 1).min(self.cols - 1), (y0 + 1).min(self.rows - 1));
        let (tx, ty) = (fx - x0 as f32, fy - y0 as f32);
        let at = |x: u32, y: u32| self.direction[(y * self.cols + x) as usize];
        let blend = at(x0, y0) * ((1.0 - tx) * (1.0 - ty))
            + at(x1, y0) * (tx * (1.0 - ty))
            + at(x0, y1) * ((1.0 - tx) * ty)
            + at(x1, y1) * (tx * ty);
        unit(blend)
    }

    /// Way length (px, wall-weighted) from `p`'s cell to the goal; ∞ if unknown.
    pub fn distance_at(&self, p: Vec2) -> f32 {
        self.cell_index(p).map_or(f32::INFINITY, |c| self.distance[c])
    }
}

fn centre_of(cell: f32, cols: u32, c: usize) -> Vec2 {
    let c = c as u32;
    Vec2::new(((c % cols) as f32 + 0.5) * cell, ((c / cols) as f32 + 0.5) * cell)
}

fn unit(v: Vec2) -> Vec2 {
    let len = v.length();
    if len > 1e-9 && len.is_finite() {
        v / len
    } else {
        Vec2::ZERO
    }
}

/// What a cached flow field was built from: the field is rebuilt when one of these changes.
#[derive(Clone, Copy, Debug, PartialEq)]
struct FieldKey {
    goal_cell: (i32, i32),
    obstacles: u64,
    bounds: Vec2,
    clearance: f32,
}

/// Everything [`FlowField::new`] reads, exactly (bit patterns): two builds from equal inputs
/// give the same field, so they may share one.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct BuildInputs {
    goal: [u32; 2],
    obstacles: u64,
    bounds: [u32; 2],
    clearance: u32,
}

impl BuildInputs {
    fn new(bounds: Vec2, obstacles: u64, goal: Vec2, clearance: f32) -> Self {
        Self {
            goal: [goal.x.to_bits(), goal.y.to_bits()],
            obstacles,
            bounds: [bounds.x.to_bits(), bounds.y.to_bits()],
            clearance: clearance.to_bits(),
        }
    }
}

/// The flow fields a world's groups hold, by what they were built from, so groups heading for
/// the same goal point among the same obstacles with the same clearance share one field instead
/// of building and keeping a copy each (a field is up to [`MAX_CELLS`] cells, 12 bytes each:
/// 500 one-agent groups of a 20,000 px world once kept 500 copies, 927 MB).
///
/// It holds weak references only: a field lives as long as a group holds it, and an entry
/// whose field is gone is swept out as the store grows. Sharing changes no result: a field is
/// a pure function of its inputs (`BuildInputs`), so a shared one is the field the group would
/// have built itself, bit for bit. (The obstacles enter as their 64-bit fingerprint, as they
/// already did for when a group rebuilds its field.)
#[derive(Clone, Debug, Default)]
pub struct FlowFieldStore {
    built: RefCell<FieldsByInputs>,
}

/// The store's table and its size after the last sweep of dead entries.
#[derive(Clone, Debug, Default)]
struct FieldsByInputs {
    fields: HashMap<BuildInputs, Weak<FlowField>>,
    swept_at: usize,
}

impl FlowFieldStore {
    /// The field built from these inputs: the one a group already holds, else a new one.
    fn field(&self, inputs: BuildInputs, build: impl FnOnce() -> FlowField) -> Rc<FlowField> {
        let mut table = self.built.borrow_mut();
        if let Some(field) = table.fields.get(&inputs).and_then(Weak::upgrade) {
            return field;
        }
        let field = Rc::new(build());
        table.fields.insert(inputs, Rc::downgrade(&field));
        // Goals that move leave dead entries behind: sweep them whenever the table doubled.
        if table.fields.len() > 2 * table.swept_at.max(16) {
            table.fields.retain(|_, field| field.strong_count() > 0);
            table.swept_at = table.fields.len();
        }
        field
    }

    /// How many distinct fields the world's groups hold now.
    pub fn live_fields(&self) -> usize {
        self.built.borrow().fields.values().filter(|field| field.strong_count() > 0).count()
    }
}

/// A flow field kept between steps (a planner holds one per group): rebuilt only when the goal
/// moves to another cell, the obstacles or the world's size change, or the clearance does. The
/// field itself comes from the world's [`FlowFieldStore`], shared with every group that would
/// build the same one.
#[derive(Clone, Debug, Default)]
pub struct CachedFlowField(Option<(FieldKey, Rc<FlowField>)>);

impl CachedFlowField {
    /// Brings the field up to date for `goal`, cells blocked within `clearance` px of an
    /// obstacle ([`FlowField::new`]), taking it from `store` when a group already built it.
    pub fn update(
        &mut self,
        store: &FlowFieldStore,
        bounds: Vec2,
        obstacles: &ObstacleIndex,
        goal: Vec2,
        clearance: f32,
    ) {
        let fingerprint = obstacles_fingerprint(obstacles.obstacles());
        let key = FieldKey {
            goal_cell: ((goal.x / CELL) as i32, (goal.y / CELL) as i32),
            obstacles: fingerprint,
            bounds,
            clearance,
        };
        if self.0.as_ref().is_none_or(|(k, _)| *k != key) {
            let inputs = BuildInputs::new(bounds, fingerprint, goal, clearance);
            let field = store.field(inputs, || FlowField::new(bounds, obstacles, goal, clearance));
            self.0 = Some((key, field));
        }
    }

    /// The field, once built.
    pub fn get(&self) -> Option<&FlowField> {
        self.0.as_ref().map(|(_, field)| field.as_ref())
    }

    /// Forgets the field (straight guidance needs none).
    pub fn clear(&mut self) {
        self.0 = None;
    }
}

/// A fingerprint of an obstacle list (FNV-1a over every coordinate's bits): a cached field is
/// rebuilt when the obstacles it was built around change.
pub fn obstacles_fingerprint(obstacles: &[Obstacle]) -> u64 {
    let mut h = Fnv1a::new();
    let mut eat = |x: f32| h.f32(x);
    for o in obstacles {
        match o {
            Obstacle::Circle { center, radius } => {
                [1.0, center[0], center[1], *radius].into_iter().for_each(&mut eat)
            }
            Obstacle::Rect { min, max } => {
                [2.0, min[0], min[1], max[0], max[1]].into_iter().for_each(&mut eat)
            }
            Obstacle::Polygon { points } => {
                eat(3.0);
                points.iter().for_each(|p| {
                    eat(p[0]);
                    eat(p[1]);
                });
            }
        }
    }
    h.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn walls() -> ObstacleIndex {
        // A wall across the middle with a gap at the bottom.
        let wall = Obstacle::Rect { min: [190.0, 0.0], max: [210.0, 160.0] };
        ObstacleIndex::new(vec![wall], 400.0, 200.0)
    }

    #[test]
    fn the_field_leads_around_a_wall_through_its_gap() {
        let field = FlowField::new(Vec2::new(400.0, 200.0), &walls(), Vec2::new(350.0, 50.0), 4.0);
        // In front of the wall, straight-line seeking would push into it; the field points down
        // towards the gap.
        let d = field.direction_at(Vec2::new(150.0, 50.0));
        assert!(d.y > 0.5, "{d}");
        // Past the gap, it points up-right to the goal.
        let d = field.direction_at(Vec2::new(260.0, 180.0));
        assert!(d.x > 0.0 && d.y < 0.0, "{d}");
        // Walking the field from the left reaches the goal.
        let mut p = Vec2::new(30.0, 40.0);
        for _ in 0..200 {
            p += field.direction_at(p) * 5.0;
        }
        assert!(p.distance(Vec2::new(350.0, 50.0)) < 15.0, "{p}");
        assert!(field.distance_at(Vec2::new(150.0, 50.0)) > 300.0);
    }

    #[test]
    fn enclosed_space_has_no_direction_and_fingerprints_see_edits() {
        let ring = vec![
            Obstacle::Rect { min: [0.0, 0.0], max: [100.0, 20.0] },
            Obstacle::Rect { min: [0.0, 80.0], max: [100.0, 100.0] },
            Obstacle::Rect { min: [80.0, 0.0], max: [100.0, 100.0] },
            Obstacle::Rect { min: [0.0, 0.0], max: [20.0, 100.0] },
        ];
        let index = ObstacleIndex::new(ring.clone(), 300.0, 100.0);
        let field = FlowField::new(Vec2::new(300.0, 100.0), &index, Vec2::new(250.0, 50.0), 4.0);
        assert_eq!(field.direction_at(Vec2::new(50.0, 50.0)), Vec2::ZERO);
        assert!(!field.distance_at(Vec2::new(50.0, 50.0)).is_finite());
        let mut moved = ring.clone();
        moved[0] = Obstacle::Rect { min: [0.0, 0.0], max: [100.0, 21.0] };
        assert_ne!(obstacles_fingerprint(&ring), obstacles_fingerprint(&moved));
        assert_eq!(obstacles_fingerprint(&ring), obstacles_fingerprint(&ring.clone()));
    }
}
