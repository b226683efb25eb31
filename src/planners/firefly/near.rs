//! A fine index of every agent for the firefly survey, rebuilt once per step: cells about a
//! contact's reach wide (12 px for the default 4 px bodies), so the survey's small discs — the
//! bodies it could touch, the nearest brighter firefly, the feeler tip's r_safe — scan tens of
//! agents instead of the hundreds per cell of the world grid, whose cells are as wide as the
//! 200 px view (625 agents per cell in a packed crowd).
//!
//! It answers the same questions as the survey's capped world-grid query, not approximately:
//! each entry keeps its world-grid storage slot (the order that query lists agents in), and
//! its position and brightness are copied bit for bit.

use crate::spatial::fine_cells::FineCells;
use crate::spatial::SpatialGrid;
use glam::Vec2;
use std::ops::Range;

/// The world grid's agents bucketed into fine cells, one array per field (struct of arrays),
/// cell by cell in row-major order and by world-grid slot within a cell ([`FineCells`]).
#[derive(Clone, Debug, Default)]
pub(super) struct NearIndex {
    /// The cells and each slot's entry.
    cells: FineCells,
    /// The entry's storage slot in the world grid ([`SpatialGrid::columns`]).
    pub slot: Vec<u32>,
    /// Agent id.
    pub id: Vec<u32>,
    /// Position x (px), the world grid's value.
    pub x: Vec<f32>,
    /// Position y (px), the world grid's value.
    pub y: Vec<f32>,
    /// Squared distance to the group's target for an agent of the group, +∞ for any other
    /// (and for all without a target): a firefly at `my2` from the target finds the brighter
    /// ones as `bright2 < my2`, the comparison the survey makes, with the same floats.
    pub bright2: Vec<f32>,
}

impl NearIndex {
    /// Re-buckets the agents of `grid` (all of them, any group) into cells of about
    /// `cell_size` px over a `bounds` world; `own` are the group's agents and `target` its
    /// target (brightness).
    pub(super) fn rebuild(
        &mut self,
        grid: &SpatialGrid,
        bounds: Vec2,
        cell_size: f32,
        own: &Range<u32>,
        target: Option<Vec2>,
    ) {
        let columns = grid.columns();
        let n = grid.ids_in_cell_order().len();
        let (xs, ys, ids) = (&columns.x[..n], &columns.y[..n], &columns.ids[..n]);
        self.cells.rebuild(bounds, cell_size, xs, ys);
        for v in [&mut self.slot, &mut self.id] {
            v.clear();
            v.resize(n, 0);
        }
        for v in [&mut self.x, &mut self.y, &mut self.bright2] {
            v.clear();
            v.resize(n, 0.0);
        }
        for (k, &e) in self.cells.entry_of_slot().iter().enumerate() {
            let e = e as usize;
            let (id, pos) = (ids[k], Vec2::new(xs[k], ys[k]));
            self.slot[e] = k as u32;
            self.id[e] = id;
            (self.x[e], self.y[e]) = (pos.x, pos.y);
            self.bright2[e] = match target {
                Some(t) if own.contains(&id) => pos.distance_squared(t),
                _ => f32::INFINITY,
            };
        }
    }

    /// The entries of the cells a disc of `radius` round `c` touches, widened by [`slack`]:
    /// one range per row of cells. Every agent whose squared distance to `c`, as computed in
    /// `f32`, is at most `radius²` lies in them.
    pub(super) fn rows(&self, c: Vec2, radius: f32) -> impl Iterator<Item = Range<usize>> + '_ {
        let r = radius + slack(c, radius);
        let cells = &self.cells;
        let (x0, x1) = (cells.col(c.x - r), cells.col(c.x + r));
        let (y0, y1) = (cells.row(c.y - r), cells.row(c.y + r));
        let (start, cols) = (cells.start(), cells.cols());
        (y0..=y1).map(move |cy| {
            let row = cy * cols;
            start[(row + x0) as usize] as usize..start[(row + x1 + 1) as usize] as usize
        })
    }

    /// Position of entry `e`.
    #[inline]
    pub(super) fn pos(&self, e: usize) -> Vec2 {
        Vec2::new(self.x[e], self.y[e])
    }

    /// The smallest [`key`] over the brighter fireflies than `id` (at `my2` from the target)
    /// among the entries [`Self::rows`] gives for `radius` round `c`, `test` giving each one's
    /// rank (squared distance) and whether it is a candidate; with its entry. Without a branch
    /// on brightness or `test`.
    #[inline(always)]
    pub(super) fn min_key(
        &self,
        c: Vec2,
        radius: f32,
        id: u32,
        my2: f32,
        test: impl Fn(Vec2) -> (f32, bool),
    ) -> (u64, usize) {
        let mut best = (u64::MAX, 0usize);
        for r in self.rows(c, radius) {
            let (ids, xs, ys, bright) =
                (&self.id[r.clone()], &self.x[r.clone()], &self.y[r.clone()], &self.bright2[r.clone()]);
            for (e, (((&other, &x), &y), &b2)) in r.zip(ids.iter().zip(xs).zip(ys).zip(bright)) {
                let (rank, candidate) = test(Vec2::new(x, y));
                let k = key(rank, other, candidate & (other != id) & (b2 < my2));
                if k < best.0 {
                    best = (k, e);
                }
            }
        }
        best
    }

    /// How many entries [`Self::rows`] holds: at least the agents within `radius` of `c`.
    pub(super) fn count(&self, c: Vec2, radius: f32) -> usize {
        self.rows(c, radius).map(|r| r.len()).sum()
    }
}

/// How far beyond `radius` a bounding box round `c` reaches so that it holds every point whose
/// squared distance, rounded in `f32`, is within `radius²`: the rounding of the distance and of
/// the box's bounds is a few units in the last place of `c` and `radius`, far below this.
pub(super) fn slack(c: Vec2, radius: f32) -> f32 {
    1.0 + 1e-5 * (c.x.abs().max(c.y.abs()) + radius.abs())
}

/// The nearest brighter firefly and the blocker are found as keys `(squared distance bits,
/// id)`: squared distances are finite and non-negative, so their bits order like them, and the
/// smallest key is the smallest `(squared distance, id)`, whatever order the candidates come
/// in. Computed for every candidate without branching on brightness (half of a crowd is
/// brighter, in no order a CPU could predict); `u64::MAX` when not a candidate.
#[inline(always)]
pub(super) fn key(d2: f32, other: u32, candidate: bool) -> u64 {
    if candidate {
        (u64::from(d2.to_bits()) << 32) | u64::from(other)
    } else {
        u64::MAX
    }
}
