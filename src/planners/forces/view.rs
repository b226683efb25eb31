//! The neighbour pass of the virtual forces (DESIGN §3.5): every agent sums, over the robots
//! in its view (330° cone, 20 body sizes), the separation push and, over those of its own
//! group, their velocities and offsets (alignment and cohesion).
//!
//! A fine index of every agent, rebuilt once per step ([`ViewIndex`]), holds the candidates:
//! cells of about 8 agents where the crowd is densest (between an eighth and a half of the view
//! range: 20 px in a packed crowd of 4 px bodies), and of each row of cells only those the view
//! disc reaches, so a query scans little beyond the disc, where the world grid's 3 × 3 cells as
//! wide as the view hold about four agents per neighbour. It finds the same neighbours: every
//! agent within range, unless a pile makes [`CANDIDATE_CAP`] bind.
//!
//! The sums run over the candidates without a branch, [`LANES`] at a time: candidate `k` of a
//! run of cells (a row, in storage order) adds to partial sum `k mod LANES`, and the partial
//! sums are combined in one fixed tree at the end ([`fold`]). The order depends on the
//! positions only, never on the machine, so a run is the same natively and in wasm; one long
//! chain of additions per sum would make each add wait for the previous one.

use crate::spatial::fine_cells::FineCells;
use crate::spatial::SpatialGrid;
use glam::{BVec4A, Vec2, Vec4};
use std::ops::Range;

/// Partial sums per force (candidates looked at together: one SSE or wasm SIMD vector).
pub(super) const LANES: usize = 4;

/// Candidates an agent looks at at most, the first in scan order (rows of cells, top row
/// first, storage order within a row). The view (20 body sizes, 160 px) holds at most about
/// 1,450 non-overlapping discs (hexagonal packing), which its rows of cells hold with fewer
/// than 2,200 others: only a pile reaches the cap, and there it bounds the work per agent.
pub(super) const CANDIDATE_CAP: usize = 4096;

/// Most cells of the index per view range: their side is at least the range divided by this.
const MAX_CELLS_PER_RANGE: f32 = 8.0;
/// Agents per cell of the index the densest part of the crowd aims at.
const AGENTS_PER_CELL: f32 = 8.0;

/// Every agent bucketed into fine cells, one array per field, cell by cell in row-major order
/// and by world-grid storage slot within a cell (so the order depends on the positions only:
/// [`FineCells`]).
#[derive(Clone, Debug, Default)]
pub(super) struct ViewIndex {
    /// The cells and each slot's entry.
    cells: FineCells,
    /// Agent id of each entry.
    id: Vec<u32>,
    /// Position of each entry, the world grid's values.
    x: Vec<f32>,
    y: Vec<f32>,
    /// Velocity of each entry of the group the index was built for, the world grid's values;
    /// zero for the others.
    vx: Vec<f32>,
    vy: Vec<f32>,
    /// 1 for an entry of that group, else 0.
    member: Vec<f32>,
}

/// One agent's view: what decides whether a candidate is a neighbour it sees.
#[derive(Clone, Copy, Debug)]
pub(super) struct Viewer {
    /// Its position.
    pub p: Vec2,
    /// Its body size (diameter, px).
    pub size: f32,
    /// Its view range (px).
    pub range: f32,
    /// Its unit heading, if it moves (else it sees all round).
    pub heading: Option<Vec2>,
    /// Cosine of half the view angle.
    pub view_cos: f32,
}

/// The sums of one agent's neighbour pass, combined.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct ViewSums {
    /// Σ `(p − q) · size / d²` over the neighbours seen: each pushes with `away · size / d`.
    pub separation: Vec2,
    /// Σ velocity over the neighbours seen of the agent's group.
    pub velocity: Vec2,
    /// Σ `(p − q)` over the neighbours seen of the agent's group.
    pub offset: Vec2,
    /// How many neighbours seen are of the agent's group.
    pub flock: u32,
}

/// The loop invariants of one agent's pass over its candidates, one copy per lane.
#[derive(Clone, Copy)]
struct Test {
    p: Vec2,
    range: f32,
    px: Vec4,
    py: Vec4,
    r2: Vec4,
    size: Vec4,
    /// Unit heading (zero without one) and whether the cone applies.
    hx: Vec4,
    hy: Vec4,
    cone: BVec4A,
    /// `view_cos²`.
    cos2: Vec4,
    /// Whether `view_cos < 0` (a view wider than 180°).
    wide: bool,
}

/// What one block of candidates adds, lane by lane.
struct Terms {
    /// Seen, and seen and of the agent's group.
    seen: BVec4A,
    member: BVec4A,
    /// `p − q`.
    dx: Vec4,
    dy: Vec4,
    /// `size / |p − q|²`.
    push: Vec4,
}

impl Test {
    fn new(v: &Viewer) -> Self {
        let h = v.heading.unwrap_or(Vec2::ZERO);
        Self {
            p: v.p,
            range: v.range,
            px: Vec4::splat(v.p.x),
            py: Vec4::splat(v.p.y),
            r2: Vec4::splat(v.range * v.range),
            size: Vec4::splat(v.size),
            hx: Vec4::splat(h.x),
            hy: Vec4::splat(h.y),
            cone: BVec4A::splat(v.heading.is_some()),
            cos2: Vec4::splat(v.view_cos * v.view_cos),
            wide: v.view_cos < 0.0,
        }
    }

    /// The terms of the candidates of `c`, one per lane.
    ///
    /// Seen: within the range, not at `p` (as the agent itself is), and in the view cone: the
    /// direction to it, `−d / |d|` for `d = p − q`, at most half the view angle off the
    /// heading `h`. With `u = d · h` that is `−u ≥ view_cos · |d|`, decided on squares without
    /// a square root: for a view wider than 180° (`view_cos < 0`) hidden means `u > 0` and
    /// `u² > view_cos² d²`, else `u > 0` or `u² ≥ view_cos² d²` fails.
    #[inline(always)]
    fn terms<const WIDE: bool>(&self, c: &Block) -> Terms {
        let dx = self.px - c.x;
        let dy = self.py - c.y;
        let d2 = dx * dx + dy * dy;
        let u = dx * self.hx + dy * self.hy;
        let (ahead_off, far_off) = (u.cmpgt(Vec4::ZERO), (u * u).cmpgt(self.cos2 * d2));
        let behind = if WIDE { ahead_off & far_off } else { ahead_off | !far_off };
        let seen = c.valid & d2.cmple(self.r2) & d2.cmpgt(Vec4::ZERO) & !(self.cone & behind);
        // A neighbour at contact pushes with 1, at two body sizes with ½, …
        Terms { seen, member: seen & c.member.cmpgt(Vec4::ZERO), dx, dy, push: self.size / d2 }
    }
}

/// [`LANES`] candidates, one per lane.
#[derive(Clone, Copy)]
struct Block {
    x: Vec4,
    y: Vec4,
    /// Velocity of a member of the group, else zero.
    vx: Vec4,
    vy: Vec4,
    /// 1 for a member of the group, else 0.
    member: Vec4,
    /// The lanes within the run (the others hold the next cells' agents or padding).
    valid: BVec4A,
}

/// Each lane's index.
const LANE: Vec4 = Vec4::new(0.0, 1.0, 2.0, 3.0);

/// The partial sums, one per lane.
#[derive(Clone, Copy)]
struct Lanes {
    sep_x: Vec4,
    sep_y: Vec4,
    vel_x: Vec4,
    vel_y: Vec4,
    off_x: Vec4,
    off_y: Vec4,
    flock: Vec4,
}

impl Lanes {
    const ZERO: Self = Self {
        sep_x: Vec4::ZERO,
        sep_y: Vec4::ZERO,
        vel_x: Vec4::ZERO,
        vel_y: Vec4::ZERO,
        off_x: Vec4::ZERO,
        off_y: Vec4::ZERO,
        flock: Vec4::ZERO,
    };

    /// Adds a block of candidates, one per lane. One not seen adds +0: a sum that starts at +0
    /// never becomes −0, so that leaves it unchanged bit for bit, without a branch. Vector
    /// instructions (glam's SSE2 natively, SIMD128 in wasm) give the same IEEE results as
    /// one float at a time.
    #[inline(always)]
    fn add<const WIDE: bool>(&mut self, t: &Test, c: &Block) {
        let Terms { seen, member, dx, dy, push } = t.terms::<WIDE>(c);
        let keep = |m: BVec4A, v: Vec4| Vec4::select(m, v, Vec4::ZERO);
        self.sep_x += keep(seen, dx * push);
        self.sep_y += keep(seen, dy * push);
        // Zero for the other groups' agents.
        self.vel_x += keep(seen, c.vx);
        self.vel_y += keep(seen, c.vy);
        self.flock += keep(seen, c.member);
        self.off_x += keep(member, dx);
        self.off_y += keep(member, dy);
    }

    fn combine(&self) -> ViewSums {
        ViewSums {
            separation: Vec2::new(fold(self.sep_x), fold(self.sep_y)),
            velocity: Vec2::new(fold(self.vel_x), fold(self.vel_y)),
            offset: Vec2::new(fold(self.off_x), fold(self.off_y)),
            // Whole numbers below 2²⁴ (the candidate cap): exact.
            flock: fold(self.flock) as u32,
        }
    }
}

/// The partial sums added in one fixed tree: `(0 + 1) + (2 + 3)`.
fn fold(s: Vec4) -> f32 {
    let [a, b, c, d] = s.to_array();
    (a + b) + (c + d)
}

impl ViewIndex {
    /// Re-buckets every agent of `grid` into cells of `range / 8` to `range / 2` px (grown for
    /// huge worlds) over a `bounds` world, for views of about `range` px from the agents of
    /// `group`.
    pub(super) fn rebuild(&mut self, grid: &SpatialGrid, bounds: Vec2, range: f32, group: &Range<u32>) {
        let columns = grid.columns();
        let n = grid.ids_in_cell_order().len();
        // Cells of about `AGENTS_PER_CELL` agents where the crowd is densest (the world grid's
        // fullest cell tells), between range / 8 and range / 2: a dense crowd's rows hold few
        // agents beyond the view disc, a sparse one's few cells.
        let densest = grid.max_cell_occupancy() as f32 / (grid.cell_size() * grid.cell_size());
        let ideal = (AGENTS_PER_CELL / densest).sqrt();
        let divisions = (range / ideal).ceil();
        let divisions =
            if divisions.is_nan() { MAX_CELLS_PER_RANGE } else { divisions.clamp(2.0, MAX_CELLS_PER_RANGE) };
        let (xs, ys) = (&columns.x[..n], &columns.y[..n]);
        let (vxs, vys, ids) = (&columns.vx[..n], &columns.vy[..n], &columns.ids[..n]);
        self.cells.rebuild(bounds, range / divisions, xs, ys);
        // Every entry up to `n` is written below; `LANES` padding entries follow.
        self.id.clear();
        self.id.resize(n + LANES, u32::MAX);
        for v in [&mut self.x, &mut self.y] {
            v.clear();
            v.resize(n + LANES, f32::NAN);
        }
        for v in [&mut self.vx, &mut self.vy, &mut self.member] {
            v.clear();
            v.resize(n + LANES, 0.0);
        }
        for (k, &e) in self.cells.entry_of_slot().iter().enumerate() {
            let e = e as usize;
            let member = group.contains(&ids[k]);
            self.id[e] = ids[k];
            (self.x[e], self.y[e]) = (xs[k], ys[k]);
            (self.vx[e], self.vy[e]) = if member { (vxs[k], vys[k]) } else { (0.0, 0.0) };
            self.member[e] = if member { 1.0 } else { 0.0 };
        }
    }

    /// Calls `visit` with the candidates of a view of `range` round `p`: one run of entries per
    /// row of cells, top row first, each the cells of the row the disc reaches (widened by
    /// [`slack`]), cut after [`CANDIDATE_CAP`] candidates in all. Every agent whose squared distance to `p`, as
    /// computed in `f32`, is at most `range²` lies in them (unless the cap cut them).
    #[inline(always)]
    fn for_each_run(&self, p: Vec2, range: f32, mut visit: impl FnMut(Range<usize>)) {
        let r = range + slack(p, range);
        let cells = &self.cells;
        let (cell, cols, rows) = (cells.cell(), cells.cols(), cells.rows());
        let (y0, y1) = (cells.row(p.y - r), cells.row(p.y + r));
        let mut budget = CANDIDATE_CAP;
        for cy in y0..=y1 {
            // The row's span of y; edge rows also hold the points beyond the world's edge.
            let top = if cy == 0 { f32::NEG_INFINITY } else { cy as f32 * cell };
            let bottom = if cy + 1 == rows { f32::INFINITY } else { (cy + 1) as f32 * cell };
            let dy = (top - p.y).max(p.y - bottom).max(0.0);
            let half = (r * r - dy * dy).max(0.0).sqrt();
            let (x0, x1) = (cells.col(p.x - half), cells.col(p.x + half));
            let row = cy * cols;
            let (Some(&start), Some(&end)) =
                (cells.start().get((row + x0) as usize), cells.start().get((row + x1 + 1) as usize))
            else {
                continue;
            };
            let (start, end) = (start as usize, end as usize);
            let end = end.min(start + budget);
            budget -= end - start;
            if start < end {
                visit(start..end);
            }
        }
    }

    /// The sums of the neighbour pass of `viewer` ([`ViewSums`]), in the lane order of the
    /// module docs.
    pub(super) fn sums(&self, viewer: &Viewer) -> ViewSums {
        let t = Test::new(viewer);
        let mut lanes = Lanes::ZERO;
        if t.wide {
            self.for_each_block(&t, |c| lanes.add::<true>(&t, c));
        } else {
            self.for_each_block(&t, |c| lanes.add::<false>(&t, c));
        }
        lanes.combine()
    }

    /// Calls `seen` with the id of every neighbour [`Self::sums`] counts as seen, in its order.
    pub(super) fn for_each_seen(&self, viewer: &Viewer, mut seen: impl FnMut(u32)) {
        let t = Test::new(viewer);
        self.for_each_block_at(&t, |first, c| {
            let lanes = if t.wide { t.terms::<true>(c).seen } else { t.terms::<false>(c).seen };
            let mask = lanes.bitmask();
            for l in 0..LANES {
                if mask & (1 << l) != 0 {
                    seen(self.id.get(first + l).copied().unwrap_or(u32::MAX));
                }
            }
        });
    }

    /// Calls `visit` with the id and position of every agent whose centre lies within `reach` of
    /// `p` (squared distances compared in `f32`), the agent at `p` itself included, in scan
    /// order (rows of cells, top row first), until `visit` returns false: the bodies a step
    /// could touch (the contact rule of `Forces::keep_bodies_apart`). All round: a body
    /// touching from behind is felt, not seen.
    pub(super) fn for_each_within(&self, p: Vec2, reach: f32, mut visit: impl FnMut(u32, Vec2) -> bool) {
        let reach2 = reach * reach;
        let mut going = true;
        self.for_each_run(p, reach, |r| {
            for e in r {
                if !going {
                    return;
                }
                let (Some(&id), Some(&x), Some(&y)) = (self.id.get(e), self.x.get(e), self.y.get(e)) else {
                    return;
                };
                let q = Vec2::new(x, y);
                if p.distance_squared(q) <= reach2 {
                    going = visit(id, q);
                }
            }
        });
    }

    /// Calls `visit` with the candidates of [`Self::for_each_run`] in blocks of [`LANES`]: each run
    /// from its start, its last block padded.
    #[inline(always)]
    fn for_each_block(&self, t: &Test, mut visit: impl FnMut(&Block)) {
        self.for_each_block_at(t, |_, c| visit(c));
    }

    /// [`Self::for_each_block`] that also passes the entry of each block's first lane.
    #[inline(always)]
    fn for_each_block_at(&self, t: &Test, mut visit: impl FnMut(usize, &Block)) {
        self.for_each_run(t.p, t.range, |r| {
            let mut k = 0;
            // The columns hold `LANES` padding entries after the last agent: a block may start
            // anywhere in a run.
            while k < r.len() {
                let e = r.start + k;
                let (Some(x), Some(y), Some(vx), Some(vy), Some(m)) = (
                    self.x.get(e..e + LANES),
                    self.y.get(e..e + LANES),
                    self.vx.get(e..e + LANES),
                    self.vy.get(e..e + LANES),
                    self.member.get(e..e + LANES),
                ) else {
                    return;
                };
                let rest = r.len() - k;
                let valid =
                    if rest >= LANES { BVec4A::splat(true) } else { LANE.cmplt(Vec4::splat(rest as f32)) };
                let c = Block {
                    x: Vec4::from_slice(x),
                    y: Vec4::from_slice(y),
                    vx: Vec4::from_slice(vx),
                    vy: Vec4::from_slice(vy),
                    member: Vec4::from_slice(m),
                    valid,
                };
                visit(e, &c);
                k += LANES;
            }
        });
    }
}

/// How far beyond `range` the rows of cells reach so that they hold every point whose squared
/// distance, rounded in `f32`, is within `range²`: the rounding of the distance, of the cells'
/// bounds and of the chord is a few units in the last place of `p` and `range`, far below this.
fn slack(p: Vec2, range: f32) -> f32 {
    1.0 + 1e-5 * (p.x.abs().max(p.y.abs()) + range.abs())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_core::{Rng, SeedableRng};

    /// The index's candidates hold every agent the world grid finds within the range, and
    /// [`ViewIndex::for_each_seen`] lists exactly those it sees.
    #[test]
    fn the_rows_hold_every_agent_in_range() {
        let (w, h) = (900.0, 500.0);
        let mut rng = rand_pcg::Pcg32::seed_from_u64(3);
        let mut unit = || (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32;
        let mut points: Vec<Vec2> = (0..3000).map(|_| Vec2::new(unit() * w, unit() * h)).collect();
        // On cell borders (20 px cells), outside the world and on top of each other.
        points.extend((0..45).map(|i| Vec2::new(20.0 * i as f32, 20.0 * (i % 25) as f32)));
        points.extend([Vec2::new(-5.0, 3.0), Vec2::new(w + 7.0, h + 2.0), Vec2::new(300.0, 300.0)]);
        points.extend([Vec2::new(300.0, 300.0), Vec2::new(300.0, 300.0 + 160.0)]);
        let mut grid = SpatialGrid::new(w, h, 160.0, points.len());
        grid.rebuild(&points, &[]);
        let group = 0..points.len() as u32;
        let mut hidden = 0;
        let mut index = ViewIndex::default();
        index.rebuild(&grid, Vec2::new(w, h), 160.0, &group);
        for (i, &p) in points.iter().enumerate().step_by(5).chain([(3047, &points[3047])]) {
            let mut expected = Vec::new();
            grid.for_each_within(p, 160.0, |n| {
                if n.id != i as u32 && n.d2 > 0.0 {
                    expected.push(n.id);
                }
            });
            let viewer = Viewer { p, size: 8.0, range: 160.0, heading: None, view_cos: -1.0 };
            let mut found = Vec::new();
            index.for_each_seen(&viewer, |id| found.push(id));
            expected.sort_unstable();
            found.sort_unstable();
            assert_eq!(found, expected, "agent {i} at {p}");
            assert_eq!(index.sums(&viewer).flock as usize, expected.len());
            // With a heading, the cone hides some: the sums count those listed.
            let viewer = Viewer { heading: Some(Vec2::from_angle(i as f32)), view_cos: -0.5, ..viewer };
            let mut in_cone = 0;
            index.for_each_seen(&viewer, |_| in_cone += 1);
            assert!(in_cone <= found.len(), "agent {i}");
            hidden += found.len() - in_cone;
            assert_eq!(index.sums(&viewer).flock as usize, in_cone, "agent {i}");
        }
        assert!(hidden > 1000, "the cone hid only {hidden}");
    }

    /// The cone test on squares agrees with the angle: 165° off the heading is the edge of a
    /// 330° view, 95° that of a 190° one and 60° that of a 120° one.
    #[test]
    fn the_cone_hides_what_lies_beyond_half_the_view_angle() {
        for (half, off) in [(165.0f32, [160.0f32, 170.0]), (95.0, [90.0, 100.0]), (60.0, [55.0, 65.0])] {
            let viewer = Viewer {
                p: Vec2::ZERO,
                size: 8.0,
                range: 160.0,
                heading: Some(Vec2::X),
                view_cos: half.to_radians().cos(),
            };
            let t = Test::new(&viewer);
            for (deg, seen) in [(off[0], true), (off[1], false), (-off[0], true), (-off[1], false)] {
                let q = Vec2::from_angle(deg.to_radians()) * 50.0;
                let c = Block {
                    x: Vec4::splat(q.x),
                    y: Vec4::splat(q.y),
                    vx: Vec4::ZERO,
                    vy: Vec4::ZERO,
                    member: Vec4::ONE,
                    valid: BVec4A::splat(true),
                };
                let lanes = if t.wide { t.terms::<true>(&c).seen } else { t.terms::<false>(&c).seen };
                assert_eq!(
                    lanes.bitmask(),
                    if seen { 15 } else { 0 },
                    "half view {half}°, neighbour {deg}° off"
                );
            }
        }
    }
}
