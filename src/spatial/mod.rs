//! Uniform grid for neighbour queries, rebuilt every step by a stable counting sort.
//!
//! Agents are stored cell by cell, in id order inside a cell, so a query visits candidates in
//! the same order on every platform: float sums over neighbours are reproducible bit for bit.
//!
//! Layer: spatial. Uses `model` only; planners and the world query it.

pub mod fine_cells;
pub mod flow_field;

use crate::model::geometry::{Aabb, Obstacle};
use glam::Vec2;
use std::ops::Range;

/// A uniform grid over a rectangle `[0, width] × [0, height]`. Points outside fall in edge cells.
#[derive(Clone, Debug)]
pub struct SpatialGrid {
    cell_size: f32,
    inv_cell: f32,
    cols: u32,
    rows: u32,
    /// `cell_start[c]..cell_start[c + 1]` indexes `ids`/`pos` for cell `c`.
    cell_start: Vec<u32>,
    /// Agents stored: `ids` and `columns` hold them, then [`CANDIDATE_LANES`] padding entries.
    len: usize,
    /// Agent ids in storage order (padding: `u32::MAX`).
    ids: Vec<u32>,
    /// The cell of each agent (by id) at the last rebuild ([`Self::cell_of_agent`]).
    scratch_cell: Vec<u32>,
    /// Scratch: the next free slot of each cell while scattering.
    scratch_next: Vec<u32>,
    /// Scratch: the entry (agent id, or `agents + k` for image `k`) of each storage slot.
    scratch_entry: Vec<u32>,
    /// Position x, y and velocity x, y in storage order (padding: NaN).
    columns: [Vec<f32>; 4],
    /// Most agents in one cell at the last rebuild.
    max_occupancy: u32,
}

/// A copy of agent `id` at `pos` for the neighbour queries ([`SpatialGrid::rebuild_with_images`]):
/// in a periodic band, an agent near one end as seen from beyond the other end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeriodicImage {
    /// The agent's id.
    pub id: u32,
    /// Where the copy stands (px).
    pub pos: Vec2,
}

/// Into `out`, the images of the agents within `reach` of either end of the periodic band
/// `[start, end)` (px, in x): each shifted by the band's length to just beyond the other end,
/// so a query of radius up to `reach` finds its neighbours across the seam (the minimum image
/// while `reach` is below half the band). Agents for which `present` is false have none.
pub fn periodic_images(
    positions: &[Vec2],
    present: impl Fn(usize) -> bool,
    (start, end): (f32, f32),
    reach: f32,
    out: &mut Vec<PeriodicImage>,
) {
    out.clear();
    let length = end - start;
    if length.is_nan() || length <= 0.0 || !reach.is_finite() {
        return;
    }
    let reach = reach.min(0.5 * length);
    for (i, &p) in positions.iter().enumerate() {
        if !present(i) {
            continue;
        }
        if p.x < start + reach {
            out.push(PeriodicImage { id: i as u32, pos: Vec2::new(p.x + length, p.y) });
        }
        if p.x >= end - reach {
            out.push(PeriodicImage { id: i as u32, pos: Vec2::new(p.x - length, p.y) });
        }
    }
}

/// How a capped scan ended: the visitor asked to stop, a cap cut it short, or every agent within
/// the radius was visited.
#[derive(Clone, Copy, PartialEq, Eq)]
enum CappedScan {
    Hit,
    Capped,
    Finished,
}

/// Limits of one capped neighbour query ([`SpatialGrid::for_each_within_capped`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QueryCap {
    /// Most agents within the radius visited.
    pub neighbours: usize,
    /// Most agents of the scanned cells tested (within the radius or not).
    pub candidates: usize,
}

/// The cap of the planners' neighbour rules: an agent considers at most 2,048 neighbours within
/// its query radius, among at most 8,192 agents of the cells the query scans (the first in scan
/// order). The widest query (firefly, 200 px on 200 px cells) finds at most about 1,800
/// non-overlapping 4 px discs within reach among about 5,200 in its cells, so no spread or
/// jammed crowd reaches the cap; a pile does, and then costs at most this much per agent.
pub const NEIGHBOUR_CAP: QueryCap = QueryCap { neighbours: 2048, candidates: 8192 };

/// One agent found by a query.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Neighbour {
    /// Agent id.
    pub id: u32,
    /// Its position.
    pub pos: Vec2,
    /// Its velocity.
    pub vel: Vec2,
    /// Squared distance to the query point.
    pub d2: f32,
}

/// Cells per agent above which the grid coarsens its cells (memory and rebuild cost stay O(N)),
/// as do the planners' fine cells ([`fine_cells`]).
const MAX_CELLS_PER_AGENT: usize = 4;
const MIN_CELL_BUDGET: usize = 16_384;

/// The grid's agents in storage order, one array per coordinate, each followed by
/// [`CANDIDATE_LANES`] padding entries (id `u32::MAX`, NaN coordinates): a kernel may read
/// [`CANDIDATE_LANES`] entries from any index of a run and mask out those past the run's end.
#[derive(Clone, Copy, Debug)]
pub struct Columns<'a> {
    /// Agent ids.
    pub ids: &'a [u32],
    /// Positions, x (px).
    pub x: &'a [f32],
    /// Positions, y (px).
    pub y: &'a [f32],
    /// Velocities, x (px/step).
    pub vx: &'a [f32],
    /// Velocities, y (px/step).
    pub vy: &'a [f32],
}

/// How many entries past a run [`Columns`] lets a kernel read.
pub const CANDIDATE_LANES: usize = 4;

/// The candidates of a query as runs of storage indexes into [`Columns`], in the grid's
/// storage order: filled by [`SpatialGrid::candidate_runs`] and
/// [`SpatialGrid::for_each_candidate_block`]; reused between calls to avoid allocating.
#[derive(Clone, Debug, Default)]
pub struct CandidateRuns {
    runs: Vec<Range<usize>>,
}

impl CandidateRuns {
    /// The runs, row by row.
    pub fn runs(&self) -> &[Range<usize>] {
        &self.runs
    }

    /// How many candidates the runs hold.
    pub fn len(&self) -> usize {
        self.runs.iter().map(ExactSizeIterator::len).sum()
    }

    /// Whether the runs hold no candidate.
    pub fn is_empty(&self) -> bool {
        self.runs.iter().all(|r| r.is_empty())
    }
}

/// A fixed, evenly spaced subset of a query's candidates, copied into padded columns of its own
/// (the same layout as [`Columns`], one run): what a neighbour rule looks at in a pile, where
/// the cells round an agent hold far more agents than a crowd of non-overlapping bodies can.
///
/// Of `total` candidates (the runs one after the other, in the grid's storage order) the `k`-th
/// sampled is candidate `⌊k · total / count⌋`, for `k` in `0..count`: the same subset on every
/// platform, spread over all the scanned cells instead of the first few. Filled once, it serves
/// every agent that shares the runs (the agents of one cell), so the copy costs little per agent.
#[derive(Clone, Debug, Default)]
pub struct CandidateSample {
    /// Sampled agent ids, then [`CANDIDATE_LANES`] padding entries (`u32::MAX`).
    ids: Vec<u32>,
    /// Position x, y and velocity x, y of the sampled agents, then padding (NaN).
    columns: [Vec<f32>; 4],
    /// The one run of sampled candidates: `0..count`.
    run: [Range<usize>; 1],
}

impl CandidateSample {
    /// Samples `count` of the candidates `runs` of `columns` (all of them, in order, when they
    /// hold no more than `count`).
    pub fn fill(&mut self, columns: Columns<'_>, runs: &[Range<usize>], count: usize) {
        let total: usize = runs.iter().map(ExactSizeIterator::len).sum();
        let count = count.min(total);
        self.ids.clear();
        for c in &mut self.columns {
            c.clear();
        }
        let mut rest = runs.iter();
        let (mut run, mut before) = (rest.next().cloned().unwrap_or_default(), 0usize);
        for k in 0..count {
            // ⌊k · total / count⌋ < total: exact in u64 for any in-memory count.
            let at = (k as u64 * total as u64 / count as u64) as usize;
            while at >= before + run.len() {
                before += run.len();
                run = rest.next().cloned().unwrap_or_default();
            }
            let slot = run.start + (at - before);
            self.ids.push(columns.ids.get(slot).copied().unwrap_or(u32::MAX));
            let [x, y, vx, vy] = &mut self.columns;
            for (out, from) in [(x, columns.x), (y, columns.y), (vx, columns.vx), (vy, columns.vy)] {
                out.push(from.get(slot).copied().unwrap_or(f32::NAN));
            }
        }
        self.ids.extend([u32::MAX; CANDIDATE_LANES]);
        for c in &mut self.columns {
            c.extend([f32::NAN; CANDIDATE_LANES]);
        }
        self.run = [Range { start: 0, end: count }];
    }

    /// The sampled agents as padded [`Columns`].
    pub fn columns(&self) -> Columns<'_> {
        let [x, y, vx, vy] = &self.columns;
        Columns { ids: &self.ids, x, y, vx, vy }
    }

    /// The sampled candidates as runs of [`Self::columns`]: one run, `0..count`.
    pub fn runs(&self) -> &[Range<usize>] {
        &self.run
    }
}

impl SpatialGrid {
    /// A grid for a `width × height` world whose queries mostly use radius `cell_size`.
    /// The cell grows if the world would need far more cells than `expected_agents` can fill.
    pub fn new(width: f32, height: f32, cell_size: f32, expected_agents: usize) -> Self {
        let width = width.max(1.0);
        let height = height.max(1.0);
        let mut cell = if cell_size.is_finite() && cell_size > 0.0 { cell_size } else { width.max(height) };
        let budget = (expected_agents * MAX_CELLS_PER_AGENT).max(MIN_CELL_BUDGET);
        while ((width / cell).ceil() * (height / cell).ceil()) as usize > budget {
            cell *= 1.5;
        }
        let cols = ((width / cell).ceil() as u32).max(1);
        let rows = ((height / cell).ceil() as u32).max(1);
        Self {
            cell_size: cell,
            inv_cell: 1.0 / cell,
            cols,
            rows,
            // One more cell past the world's: agents that are not there ([`Self::rebuild_present`]).
            cell_start: vec![0; (cols * rows + 2) as usize],
            len: 0,
            ids: Vec::new(),
            scratch_cell: Vec::new(),
            scratch_next: Vec::new(),
            scratch_entry: Vec::new(),
            columns: Default::default(),
            max_occupancy: 0,
        }
    }

    /// A grid with one cell: every query scans every agent. The O(N²) baseline for benchmarks.
    pub fn single_cell(width: f32, height: f32) -> Self {
        Self::new(width, height, f32::INFINITY, 0)
    }

    /// Side of a cell in px.
    pub fn cell_size(&self) -> f32 {
        self.cell_size
    }

    #[inline]
    fn cell_coord(&self, x: f32, n: u32) -> u32 {
        // Saturating float→int cast: NaN → 0, negatives → 0, huge → clamped.
        ((x * self.inv_cell) as u32).min(n - 1)
    }

    #[inline]
    fn cell_of(&self, p: Vec2) -> u32 {
        self.cell_coord(p.y, self.rows) * self.cols + self.cell_coord(p.x, self.cols)
    }

    /// Re-buckets all agents; `positions[i]` and `velocities[i]` belong to agent `i`.
    pub fn rebuild(&mut self, positions: &[Vec2], velocities: &[Vec2]) {
        self.rebuild_present(positions, velocities, |_| true);
    }

    /// [`Self::rebuild`] with the agents for which `present(i)` is false left out of every
    /// cell (agents that left the scene): no query, pair pass or candidate block meets them,
    /// and [`Self::cell_of_agent`] gives a cell past the world's. Held in one cell of the
    /// world instead, k of them would cost every query near it k tests.
    pub fn rebuild_present(
        &mut self,
        positions: &[Vec2],
        velocities: &[Vec2],
        present: impl Fn(usize) -> bool,
    ) {
        self.rebuild_with_images(positions, velocities, present, &[]);
    }

    /// [`Self::rebuild_present`] plus `images`: copies of agents at other positions (a periodic
    /// band's agents shifted by its length, [`periodic_images`]), stored under their agent's id.
    /// A query near one end of the band then finds the agents at the other end where they stand
    /// relative to it (the minimum image), so every planner that reads positions from the grid
    /// sees across the seam. An agent's own image is a band's length away: beyond any shorter
    /// neighbour query. [`Self::ids_in_cell_order`] then lists an agent once per image as well;
    /// [`Self::cell_of_agent`] is the agent's own cell.
    pub fn rebuild_with_images(
        &mut self,
        positions: &[Vec2],
        velocities: &[Vec2],
        present: impl Fn(usize) -> bool,
        images: &[PeriodicImage],
    ) {
        let n = positions.len();
        let entries = n + images.len();
        let nowhere = self.cols * self.rows;
        self.cell_start.iter_mut().for_each(|c| *c = 0);
        self.scratch_cell.clear();
        for (i, &p) in positions.iter().enumerate() {
            let c = if present(i) { self.cell_of(p) } else { nowhere };
            self.scratch_cell.push(c);
            self.cell_start[c as usize + 1] += 1;
        }
        for image in images {
            let c = self.cell_of(image.pos);
            self.scratch_cell.push(c);
            self.cell_start[c as usize + 1] += 1;
        }
        let mut max_occupancy = 0;
        for c in 1..self.cell_start.len() {
            if c <= nowhere as usize {
                max_occupancy = max_occupancy.max(self.cell_start[c]);
            }
            self.cell_start[c] += self.cell_start[c - 1];
        }
        self.max_occupancy = max_occupancy;
        // Scatter in entry order (agents by id, then the images): stable, so each cell lists
        // its agents by increasing id, then the images in it.
        self.scratch_next.clear();
        self.scratch_next.extend_from_slice(&self.cell_start);
        let mut entry_of_slot = std::mem::take(&mut self.scratch_entry);
        entry_of_slot.clear();
        entry_of_slot.resize(entries, 0);
        let next = &mut self.scratch_next;
        for (e, &c) in self.scratch_cell.iter().enumerate() {
            let slot = next[c as usize] as usize;
            next[c as usize] += 1;
            entry_of_slot[slot] = e as u32;
        }
        // Every slot is written below; the padding after them stays.
        let padded = entries + CANDIDATE_LANES;
        self.len = entries;
        self.ids.clear();
        self.ids.resize(padded, u32::MAX);
        let [x, y, vx, vy] = &mut self.columns;
        for c in [&mut *x, &mut *y, &mut *vx, &mut *vy] {
            c.clear();
            c.resize(padded, f32::NAN);
        }
        // Then the columns in storage order: one scattered write per agent above instead of
        // five (at 100,000 agents the columns do not fit in the cache).
        for (slot, &e) in entry_of_slot.iter().enumerate() {
            let e = e as usize;
            let (id, p) = match e.checked_sub(n).and_then(|k| images.get(k)) {
                Some(image) => (image.id, image.pos),
                None => (e as u32, positions[e]),
            };
            let v = velocities.get(id as usize).copied().unwrap_or(Vec2::ZERO);
            self.ids[slot] = id;
            (x[slot], y[slot], vx[slot], vy[slot]) = (p.x, p.y, v.x, v.y);
        }
        self.scratch_entry = entry_of_slot;
    }

    /// Most agents in one cell at the last rebuild: a scan of a cell's agents costs up to this.
    pub fn max_cell_occupancy(&self) -> usize {
        self.max_occupancy as usize
    }

    /// The agents in storage order as padded [`Columns`].
    pub fn columns(&self) -> Columns<'_> {
        let [x, y, vx, vy] = &self.columns;
        Columns { ids: &self.ids, x, y, vx, vy }
    }

    /// Agent ids in storage order: cell by cell, by id inside a cell. Visiting agents in this
    /// order keeps the cells their queries touch hot in the cache.
    pub fn ids_in_cell_order(&self) -> &[u32] {
        self.ids.get(..self.len).unwrap_or_default()
    }

    /// Position and velocity of the agent in storage slot `k`.
    #[inline]
    fn slot(&self, k: usize) -> (Vec2, Vec2) {
        let [x, y, vx, vy] = &self.columns;
        (Vec2::new(x[k], y[k]), Vec2::new(vx[k], vy[k]))
    }

    /// Calls `visit` for every agent within `radius` of `p`
    /// (including one at `p` itself), cell by cell in row-major order, by id within a cell.
    #[inline]
    pub fn for_each_within(&self, p: Vec2, radius: f32, mut visit: impl FnMut(Neighbour)) {
        let r2 = radius * radius;
        let x0 = self.cell_coord(p.x - radius, self.cols);
        let x1 = self.cell_coord(p.x + radius, self.cols);
        let y0 = self.cell_coord(p.y - radius, self.rows);
        let y1 = self.cell_coord(p.y + radius, self.rows);
        for cy in y0..=y1 {
            let row = cy * self.cols;
            // Cells x0..=x1 of one row are contiguous in storage.
            let start = self.cell_start[(row + x0) as usize] as usize;
            let end = self.cell_start[(row + x1 + 1) as usize] as usize;
            for k in start..end {
                let (q, v) = self.slot(k);
                let d2 = p.distance_squared(q);
                if d2 <= r2 {
                    visit(Neighbour { id: self.ids[k], pos: q, vel: v, d2 });
                }
            }
        }
    }

    /// The storage ranges of the cells a query of `radius` round `p` scans, one per row of
    /// cells (the cells of a row are contiguous in storage), top row first: indexes into
    /// [`Self::columns`]. The cells of a query are those of every query whose box
    /// `[p − radius, p + radius]` it contains (cell coordinates grow with position), so a
    /// caller can bound the candidates of many nearby queries by one wider query.
    #[inline]
    pub fn query_rows(&self, p: Vec2, radius: f32) -> impl Iterator<Item = Range<usize>> + '_ {
        self.query_cell_ranges(p, radius)
            .map(move |cells| self.cell_start[cells.start] as usize..self.cell_start[cells.end] as usize)
    }

    /// The cells `[x0, y0, x1, y1]` (inclusive) a query of `radius` round `p` scans: every agent
    /// it can visit lies in them. A caller comparing them with a slightly wider query's tells
    /// whether the query's disc, with that margin, lies inside the scanned cells.
    pub fn query_cells(&self, p: Vec2, radius: f32) -> [u32; 4] {
        [
            self.cell_coord(p.x - radius, self.cols),
            self.cell_coord(p.y - radius, self.rows),
            self.cell_coord(p.x + radius, self.cols),
            self.cell_coord(p.y + radius, self.rows),
        ]
    }

    /// How many agents the cells a query of `radius` round `p` scans hold: no more than
    /// `cap.candidates` means the candidate cap of a capped query cannot cut it short.
    pub fn query_candidates(&self, p: Vec2, radius: f32) -> usize {
        self.query_rows(p, radius).map(|r| r.len()).sum()
    }

    /// How many cells the grid has; cells are numbered row by row ([`Self::cell_of_agent`]).
    pub fn cell_count(&self) -> usize {
        (self.cols * self.rows) as usize
    }

    /// The cell agent `i` was stored in at the last rebuild (where the queries find it).
    pub fn cell_of_agent(&self, i: usize) -> Option<usize> {
        self.scratch_cell.get(i).map(|&c| c as usize)
    }

    /// The cells a query of `radius` round `p` scans ([`Self::for_each_within`],
    /// [`Self::for_each_within_capped`]), one range of cell numbers per row of cells: a caller
    /// that keeps a count per cell of the agents it looks for can skip a query that would find
    /// none.
    #[inline]
    pub fn query_cell_ranges(&self, p: Vec2, radius: f32) -> impl Iterator<Item = Range<usize>> + '_ {
        let x0 = self.cell_coord(p.x - radius, self.cols);
        let x1 = self.cell_coord(p.x + radius, self.cols);
        let y0 = self.cell_coord(p.y - radius, self.rows);
        let y1 = self.cell_coord(p.y + radius, self.rows);
        (y0..=y1).map(move |cy| {
            let row = cy * self.cols;
            (row + x0) as usize..(row + x1 + 1) as usize
        })
    }

    /// [`Self::for_each_within`] that stops after visiting `cap.neighbours` agents within
    /// `radius` or testing `cap.candidates` agents of the cells it scans, whichever comes first:
    /// the first ones in its scan order (rows of cells, by id within a cell), so the result is
    /// the same on every platform. Returns whether it stopped early (more agents may lie within
    /// `radius`). Neighbour rules use it so an agent in a pile costs a bounded amount of work.
    #[inline]
    pub fn for_each_within_capped(
        &self,
        p: Vec2,
        radius: f32,
        cap: QueryCap,
        mut visit: impl FnMut(Neighbour),
    ) -> bool {
        let end = self.scan_capped(p, radius, cap, |n| {
            visit(n);
            false
        });
        end != CappedScan::Finished
    }

    /// Whether `hit` holds for some agent within `radius` of `p` among the first
    /// `cap.candidates` agents of the cells scanned (and the first `cap.neighbours` of them within
    /// `radius`), in [`Self::for_each_within_capped`]'s order: the same answer as testing every
    /// agent that query visits, but it stops at the first hit. An overlap test in a crowd of
    /// bodies touching each other so costs a few candidates instead of the whole cap.
    #[inline]
    pub fn any_within_capped(
        &self,
        p: Vec2,
        radius: f32,
        cap: QueryCap,
        hit: impl FnMut(Neighbour) -> bool,
    ) -> bool {
        self.scan_capped(p, radius, cap, hit) == CappedScan::Hit
    }

    /// The smallest squared distance from `p` to an agent other than `exclude` among those
    /// [`Self::for_each_within_capped`] visits (within `radius`, capped), or infinity: the same
    /// answer, found without a branch per candidate when the caps do not bind (the count of
    /// candidates and of agents within `radius` tells), else by that query.
    pub fn nearest_d2_within_capped(&self, p: Vec2, radius: f32, cap: QueryCap, exclude: u32) -> f32 {
        let r2 = radius * radius;
        let [xs, ys, _, _] = &self.columns;
        // The minimum over every other agent of the cells is the answer when it is within
        // `radius` (else none is): no branch on the distance test, whose outcome the CPU could
        // not predict. One running minimum and count per lane: independent chains, and the
        // minimum of a set is the same in any order.
        let (mut best, mut within, mut candidates) =
            ([f32::INFINITY; CANDIDATE_LANES], [0u32; CANDIDATE_LANES], 0usize);
        for Range { start, end } in self.query_rows(p, radius) {
            candidates += end - start;
            if candidates > cap.candidates {
                break;
            }
            if let (Some(xs), Some(ys), Some(ids)) =
                (xs.get(start..end), ys.get(start..end), self.ids.get(start..end))
            {
                let mut lane = |lane: usize, x: f32, y: f32, id: u32| {
                    let d2 = p.distance_squared(Vec2::new(x, y));
                    within[lane] += u32::from(d2 <= r2);
                    let d2 = if id != exclude { d2 } else { f32::INFINITY };
                    // `<` is `min` here: a NaN distance (never within reach) is ignored by both.
                    best[lane] = if d2 < best[lane] { d2 } else { best[lane] };
                };
                let (xs4, ys4, ids4) = (
                    xs.chunks_exact(CANDIDATE_LANES),
                    ys.chunks_exact(CANDIDATE_LANES),
                    ids.chunks_exact(CANDIDATE_LANES),
                );
                let rest = xs4.remainder().iter().zip(ys4.remainder()).zip(ids4.remainder());
                for ((xs, ys), ids) in xs4.zip(ys4).zip(ids4) {
                    for k in 0..CANDIDATE_LANES {
                        lane(k, xs[k], ys[k], ids[k]);
                    }
                }
                for (k, ((&x, &y), &id)) in rest.enumerate() {
                    lane(k, x, y, id);
                }
            }
        }
        let within: usize = within.iter().map(|&w| w as usize).sum();
        let best = best.iter().fold(f32::INFINITY, |m, &b| m.min(b));
        if candidates <= cap.candidates && within <= cap.neighbours {
            return if best <= r2 { best } else { f32::INFINITY };
        }
        let mut nearest = f32::INFINITY;
        self.for_each_within_capped(p, radius, cap, |n| {
            if n.id != exclude {
                nearest = nearest.min(n.d2);
            }
        });
        nearest
    }

    /// The scan both capped queries share: visits the agents within `radius` of `p` in scan
    /// order until `stop` returns true for one of them or a cap is reached.
    #[inline(always)]
    fn scan_capped(
        &self,
        p: Vec2,
        radius: f32,
        cap: QueryCap,
        mut stop: impl FnMut(Neighbour) -> bool,
    ) -> CappedScan {
        let r2 = radius * radius;
        let (mut neighbours, mut candidates) = (cap.neighbours, cap.candidates);
        for Range { start, end } in self.query_rows(p, radius) {
            let scanned = end.min(start.saturating_add(candidates));
            candidates -= scanned - start;
            for k in start..scanned {
                let (q, v) = self.slot(k);
                let d2 = p.distance_squared(q);
                if d2 <= r2 {
                    if neighbours == 0 {
                        return CappedScan::Capped;
                    }
                    neighbours -= 1;
                    if stop(Neighbour { id: self.ids[k], pos: q, vel: v, d2 }) {
                        return CappedScan::Hit;
                    }
                }
            }
            if scanned < end {
                return CappedScan::Capped;
            }
        }
        CappedScan::Finished
    }

    /// Sets `slots` to the storage slots (indexes into [`Self::columns`]) of the agents within
    /// `radius` of `p`, in [`Self::for_each_within`]'s order, capped like
    /// [`Self::for_each_within_capped`] (returns whether the cap cut the list short).
    ///
    /// The distance tests run four candidates at a time and write their slots without a branch
    /// per candidate, whose outcome the CPU could not predict (see `gather_run`), so a
    /// caller's loop over the slots then runs without mispredictions either.
    pub fn gather_within(&self, p: Vec2, radius: f32, cap: QueryCap, slots: &mut Vec<u32>) -> bool {
        slots.clear();
        let r2 = radius * radius;
        let [xs, ys, _, _] = &self.columns;
        let mut candidates = cap.candidates;
        for Range { start, end } in self.query_rows(p, radius) {
            let scanned = end.min(start.saturating_add(candidates));
            candidates -= scanned - start;
            let base = slots.len();
            // Room for the last block's whole write past the agents found.
            slots.resize(base + (scanned - start) + GATHER_BLOCK, 0);
            let mut found = base;
            if let (Some(out), Some(xs), Some(ys)) =
                (slots.get_mut(base..), xs.get(start..scanned), ys.get(start..scanned))
            {
                found += gather_run(p, r2, start as u32, xs, ys, out);
            }
            slots.truncate(found);
            if slots.len() > cap.neighbours {
                slots.truncate(cap.neighbours);
                return true;
            }
            if scanned < end {
                return true;
            }
        }
        false
    }

    /// Sets `runs` to the candidates for a query of `radius` around `p`: a superset of
    /// [`Self::for_each_within`] in the grid's storage order. When cells are no larger than
    /// `2 × radius` that is every agent of the cells within `radius` of `p`'s cell, the same block
    /// for every point of the cell (what [`Self::for_each_candidate_block`] shares between them);
    /// on a coarser grid, the cells the disc's bounding box touches.
    pub fn candidate_runs(&self, p: Vec2, radius: f32, runs: &mut CandidateRuns) {
        let cells = if self.shares_blocks(radius) {
            let rings = self.rings(radius);
            let (cx, cy) = (self.cell_coord(p.x, self.cols), self.cell_coord(p.y, self.rows));
            [
                cx.saturating_sub(rings),
                cy.saturating_sub(rings),
                cx.saturating_add(rings).min(self.cols - 1),
                cy.saturating_add(rings).min(self.rows - 1),
            ]
        } else {
            [
                self.cell_coord(p.x - radius, self.cols),
                self.cell_coord(p.y - radius, self.rows),
                self.cell_coord(p.x + radius, self.cols),
                self.cell_coord(p.y + radius, self.rows),
            ]
        };
        self.cell_runs(cells, runs);
    }

    /// Calls `visit(agents, runs)` for every group of agents that share candidates: each
    /// non-empty cell's agents (storage slots) with the runs
    /// [`Self::candidate_runs`] gives every one of them, found once per cell. On a grid too
    /// coarse for `radius`, one agent at a time.
    pub fn for_each_candidate_block(
        &self,
        radius: f32,
        runs: &mut CandidateRuns,
        mut visit: impl FnMut(Range<usize>, &CandidateRuns),
    ) {
        let shared = self.shares_blocks(radius);
        for cell in 0..(self.cols * self.rows) as usize {
            let agents = self.cell_start[cell] as usize..self.cell_start[cell + 1] as usize;
            if agents.is_empty() {
                continue;
            }
            if shared {
                self.candidate_runs(self.slot(agents.start).0, radius, runs);
                visit(agents, runs);
            } else {
                for k in agents {
                    self.candidate_runs(self.slot(k).0, radius, runs);
                    visit(k..k + 1, runs);
                }
            }
        }
    }

    /// Whether all points of a cell can share one candidate block for queries of `radius`
    /// without it growing much past the disc's bounding box.
    fn shares_blocks(&self, radius: f32) -> bool {
        self.cell_size <= 2.0 * radius
    }

    /// How many rings of cells around a cell hold every point within `radius` of it.
    fn rings(&self, radius: f32) -> u32 {
        // Saturating cast: an infinite cell (one-cell grid) needs no ring.
        (radius * self.inv_cell).ceil() as u32
    }

    /// Sets `runs` to the agents of cells `[x0, y0, x1, y1]` (inclusive), row by row.
    fn cell_runs(&self, [x0, y0, x1, y1]: [u32; 4], runs: &mut CandidateRuns) {
        runs.runs.clear();
        for cy in y0..=y1 {
            let row = cy * self.cols;
            // Cells x0..=x1 of one row are contiguous in the sorted arrays.
            let start = self.cell_start[(row + x0) as usize] as usize;
            let end = self.cell_start[(row + x1 + 1) as usize] as usize;
            if start < end {
                runs.runs.push(start..end);
            }
        }
    }

    /// Ids of agents within `radius` of `p`, sorted by `(distance², id)`.
    pub fn within_distance(&self, p: Vec2, radius: f32, out: &mut Vec<(f32, u32)>) {
        out.clear();
        self.for_each_within(p, radius, |n| out.push((n.d2, n.id)));
        out.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    }

    /// The `k` nearest agents to `p` within `max_radius` (excluding `exclude`), by `(distance², id)`.
    pub fn k_nearest(&self, p: Vec2, k: usize, max_radius: f32, exclude: u32, out: &mut Vec<(f32, u32)>) {
        self.within_distance(p, max_radius, out);
        out.retain(|&(_, id)| id != exclude);
        out.truncate(k);
    }

    /// Calls `visit(a, b)` once for every unordered pair of agents closer than `radius`
    /// (`radius` ≤ cell size), `a < b`.
    ///
    /// Half-neighbourhood scan: an agent is tested against the later agents of its own cell and,
    /// only when it lies within `radius` of that border, against the cell to its right and the
    /// three cells below. A pair in two cells is so seen once, from the earlier cell; with a
    /// body-sized radius and perception-sized cells most agents test their own cell only.
    pub fn for_each_pair_within(&self, radius: f32, visit: impl FnMut(u32, u32)) {
        self.for_each_pair_within_capped(radius, usize::MAX, visit);
    }

    /// [`Self::for_each_pair_within`] with each agent tested against at most `cap` others (the
    /// first in its scan order: own cell, right cell, row below), so a pile costs at most
    /// `cap` tests per agent. Returns whether some agent had candidates left untested (then
    /// pairs may be missing).
    pub fn for_each_pair_within_capped(
        &self,
        radius: f32,
        cap: usize,
        mut visit: impl FnMut(u32, u32),
    ) -> bool {
        let r2 = radius * radius;
        let (cols, rows) = (self.cols as usize, self.rows as usize);
        let [xs, ys, _, _] = &self.columns;
        let (xs, ys, ids) = (&xs[..self.len], &ys[..self.len], &self.ids[..self.len]);
        let cell_range = |cx: usize, cy: usize| {
            let c = cy * cols + cx;
            self.cell_start[c] as usize..self.cell_start[c + 1] as usize
        };
        let mut capped = false;
        // Tests agent `k` (at `p`) against the agents stored in `others`, at most `left` of them.
        let mut test = |k: usize, p: Vec2, others: Range<usize>, left: &mut usize| {
            let end = others.end.min(others.start.saturating_add(*left));
            capped |= end < others.end;
            *left -= end.saturating_sub(others.start);
            for other in others.start..end {
                let d = p - Vec2::new(xs[other], ys[other]);
                if d.dot(d) < r2 {
                    let (a, b) = (ids[k], ids[other]);
                    visit(a.min(b), a.max(b));
                }
            }
        };
        for cy in 0..rows {
            for cx in 0..cols {
                let here = cell_range(cx, cy);
                // Border lines of this cell; points outside the world sit in edge cells, so
                // an edge cell's outer side is open and never near a neighbour cell.
                let right = (cx + 1 < cols).then(|| (cx + 1) as f32 * self.cell_size);
                let bottom = (cy + 1 < rows).then(|| (cy + 1) as f32 * self.cell_size);
                let left = cx as f32 * self.cell_size;
                for k in here.clone() {
                    let mut budget = cap;
                    let p = Vec2::new(xs[k], ys[k]);
                    test(k, p, k + 1..here.end, &mut budget);
                    let near_right = right.is_some_and(|x| x - p.x < radius);
                    if near_right {
                        test(k, p, cell_range(cx + 1, cy), &mut budget);
                    }
                    if !bottom.is_some_and(|y| y - p.y < radius) {
                        continue;
                    }
                    let near_left = cx > 0 && p.x - left < radius;
                    let first = if near_left { cx - 1 } else { cx };
                    let last = if near_right { cx + 1 } else { cx };
                    // Cells first..=last of the next row are contiguous in storage.
                    let below = cell_range(first, cy + 1).start..cell_range(last, cy + 1).end;
                    test(k, p, below, &mut budget);
                }
            }
        }
        capped
    }
}

/// Candidates [`SpatialGrid::gather_within`] tests at once.
const GATHER_BLOCK: usize = 4;

/// `GATHER_ORDER[m]`: the lanes set in the 4-bit mask `m`, in increasing order, then zeros.
const GATHER_ORDER: [[u32; GATHER_BLOCK]; 16] = {
    let mut table = [[0u32; GATHER_BLOCK]; 16];
    let mut m = 0;
    while m < 16 {
        let (mut lane, mut n) = (0, 0);
        while lane < GATHER_BLOCK {
            if m & (1 << lane) != 0 {
                table[m][n] = lane as u32;
                n += 1;
            }
            lane += 1;
        }
        m += 1;
    }
    table
};

/// `GATHER_COUNT[m]`: how many lanes the 4-bit mask `m` sets (a table: `count_ones` is no
/// single instruction on the baseline x86-64 target).
const GATHER_COUNT: [usize; 16] = [0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4];

/// Writes to the front of `out` the slots (`first` + index) of the points of `xs`, `ys` within
/// `√r2` of `p`, in order, and returns how many; `out` holds at least `xs.len()` +
/// [`GATHER_BLOCK`] entries, and those past the count are scratch. Four points at a time: one
/// mask of their four distance tests, then their slots written in one go and the count advanced
/// by the mask's population, so no branch depends on where the points lie.
fn gather_run(p: Vec2, r2: f32, first: u32, xs: &[f32], ys: &[f32], out: &mut [u32]) -> usize {
    let mut n = 0;
    let mut slot = first;
    let (x_blocks, y_blocks) = (xs.chunks_exact(GATHER_BLOCK), ys.chunks_exact(GATHER_BLOCK));
    let (x_rest, y_rest) = (x_blocks.remainder(), y_blocks.remainder());
    for (x, y) in x_blocks.zip(y_blocks) {
        let mut mask = 0usize;
        for lane in 0..GATHER_BLOCK {
            let inside = p.distance_squared(Vec2::new(x[lane], y[lane])) <= r2;
            mask |= usize::from(inside) << lane;
        }
        if let Some(to) = out.get_mut(n..n + GATHER_BLOCK) {
            for (o, &lane) in to.iter_mut().zip(&GATHER_ORDER[mask]) {
                *o = slot + lane;
            }
        }
        n += GATHER_COUNT[mask];
        slot += GATHER_BLOCK as u32;
    }
    for (&x, &y) in x_rest.iter().zip(y_rest) {
        if let Some(o) = out.get_mut(n) {
            *o = slot;
        }
        n += usize::from(p.distance_squared(Vec2::new(x, y)) <= r2);
        slot += 1;
    }
    n
}

/// Static obstacles bucketed into a coarse grid, so a query near a point only tests the
/// obstacles whose bounding boxes reach it.
#[derive(Clone, Debug)]
pub struct ObstacleIndex {
    obstacles: Vec<Obstacle>,
    aabbs: Vec<Aabb>,
    /// Cell ranges `[x0, y0, x1, y1]` each obstacle covers.
    ranges: Vec<[u32; 4]>,
    inv_cell: f32,
    cols: u32,
    rows: u32,
    cell_start: Vec<u32>,
    ids: Vec<u32>,
}

/// Side of an obstacle-index cell in px (grown for huge worlds).
const OBSTACLE_CELL: f32 = 64.0;

impl ObstacleIndex {
    /// Indexes `obstacles` over a `width × height` world.
    pub fn new(obstacles: Vec<Obstacle>, width: f32, height: f32) -> Self {
        Self::with_cell_size(obstacles, width, height, OBSTACLE_CELL)
    }

    /// [`ObstacleIndex::new`] with cells of `cell` px (grown for huge worlds): smaller cells for
    /// callers that query small boxes among many small obstacles (the IGSA path fitness).
    pub fn with_cell_size(obstacles: Vec<Obstacle>, width: f32, height: f32, cell: f32) -> Self {
        let (width, height) = (width.max(1.0), height.max(1.0));
        let mut cell = cell.max(1.0);
        while ((width / cell).ceil() * (height / cell).ceil()) as usize > MIN_CELL_BUDGET {
            cell *= 1.5;
        }
        let inv_cell = 1.0 / cell;
        let cols = ((width / cell).ceil() as u32).max(1);
        let rows = ((height / cell).ceil() as u32).max(1);
        let coord = |x: f32, n: u32| ((x * inv_cell) as u32).min(n - 1);
        let aabbs: Vec<Aabb> = obstacles.iter().map(Obstacle::aabb).collect();
        let ranges: Vec<[u32; 4]> = aabbs
            .iter()
            .map(|b| [coord(b.min.x, cols), coord(b.min.y, rows), coord(b.max.x, cols), coord(b.max.y, rows)])
            .collect();
        let mut cell_start = vec![0u32; (cols * rows + 1) as usize];
        for r in &ranges {
            for cy in r[1]..=r[3] {
                for cx in r[0]..=r[2] {
                    cell_start[(cy * cols + cx) as usize + 1] += 1;
                }
            }
        }
        for c in 1..cell_start.len() {
            cell_start[c] += cell_start[c - 1];
        }
        let mut next = cell_start.clone();
        let mut ids = vec![0u32; cell_start[cell_start.len() - 1] as usize];
        for (i, r) in ranges.iter().enumerate() {
            for cy in r[1]..=r[3] {
                for cx in r[0]..=r[2] {
                    let c = (cy * cols + cx) as usize;
                    ids[next[c] as usize] = i as u32;
                    next[c] += 1;
                }
            }
        }
        Self { obstacles, aabbs, ranges, inv_cell, cols, rows, cell_start, ids }
    }

    /// All obstacles, in scene order.
    pub fn obstacles(&self) -> &[Obstacle] {
        &self.obstacles
    }

    /// Whether the index holds no obstacle.
    pub fn is_empty(&self) -> bool {
        self.obstacles.is_empty()
    }

    /// Calls `visit(index, obstacle)` once for each obstacle whose bounding box overlaps `query`.
    #[inline]
    pub fn for_each_near(&self, query: Aabb, mut visit: impl FnMut(u32, &Obstacle)) {
        if self.obstacles.is_empty() {
            return;
        }
        let coord = |x: f32, n: u32| ((x * self.inv_cell) as u32).min(n - 1);
        let (qx0, qy0) = (coord(query.min.x, self.cols), coord(query.min.y, self.rows));
        let (qx1, qy1) = (coord(query.max.x, self.cols), coord(query.max.y, self.rows));
        for cy in qy0..=qy1 {
            for cx in qx0..=qx1 {
                let c = (cy * self.cols + cx) as usize;
                for &id in &self.ids[self.cell_start[c] as usize..self.cell_start[c + 1] as usize] {
                    let r = self.ranges[id as usize];
                    // Report each obstacle only from the first cell where it meets the query.
                    if (cx, cy) != (r[0].max(qx0), r[1].max(qy0)) {
                        continue;
                    }
                    if self.aabbs[id as usize].overlaps(&query) {
                        visit(id, &self.obstacles[id as usize]);
                    }
                }
            }
        }
    }

    /// Whether `p` lies inside any obstacle.
    #[inline]
    pub fn contains(&self, p: Vec2) -> bool {
        if self.obstacles.is_empty() {
            return false;
        }
        let mut inside = false;
        self.for_each_near(Aabb { min: p, max: p }, |_, o| inside |= o.contains(p));
        inside
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_core::{Rng, SeedableRng};

    #[test]
    fn periodic_images_are_found_across_the_seam_under_their_agents_id() {
        // Band [100, 500) px; agent 0 near its left end, agent 1 near its right end, agent 2 in
        // the middle, agent 3 gone (not present).
        let pos =
            [Vec2::new(105.0, 50.0), Vec2::new(490.0, 50.0), Vec2::new(300.0, 50.0), Vec2::new(101.0, 10.0)];
        let vel = [Vec2::X, Vec2::Y, Vec2::ZERO, Vec2::ZERO];
        let present = |i: usize| i != 3;
        let mut images = vec![];
        periodic_images(&pos, present, (100.0, 500.0), 30.0, &mut images);
        assert_eq!(
            images,
            vec![
                PeriodicImage { id: 0, pos: Vec2::new(505.0, 50.0) },
                PeriodicImage { id: 1, pos: Vec2::new(90.0, 50.0) },
            ]
        );
        let mut grid = SpatialGrid::new(600.0, 100.0, 30.0, 4);
        grid.rebuild_with_images(&pos, &vel, present, &images);
        // From agent 0, agent 1 stands 15 px behind it across the seam, with its own velocity.
        let mut found = vec![];
        grid.for_each_within(pos[0], 30.0, |n| found.push((n.id, n.pos, n.vel)));
        found.sort_by_key(|f| f.0);
        assert_eq!(found, vec![(0, pos[0], Vec2::X), (1, Vec2::new(90.0, 50.0), Vec2::Y)]);
        // The agent's own cell is where it stands, not its image's.
        assert_eq!(grid.cell_of_agent(0), Some(grid.cell_of(pos[0]) as usize));
        // Without images the same grid is the plain one.
        let mut plain = SpatialGrid::new(600.0, 100.0, 30.0, 4);
        plain.rebuild_present(&pos, &vel, present);
        grid.rebuild_with_images(&pos, &vel, present, &[]);
        assert_eq!(grid.ids_in_cell_order(), plain.ids_in_cell_order());
        assert_eq!(grid.ids_in_cell_order().len(), 4);
    }

    fn brute(points: &[Vec2], p: Vec2, r: f32) -> Vec<(f32, u32)> {
        let mut v: Vec<(f32, u32)> = points
            .iter()
            .enumerate()
            .map(|(i, q)| (p.distance_squared(*q), i as u32))
            .filter(|(d2, _)| *d2 <= r * r)
            .collect();
        v.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        v
    }

    /// `count` random points in a `w × h` world, then points exactly on cell borders and corners,
    /// just beside them, and outside the world (two close together).
    fn scattered_points(seed: u64, count: usize, (w, h): (f32, f32), cell: f32) -> Vec<Vec2> {
        let mut rng = rand_pcg::Pcg32::seed_from_u64(seed);
        let mut unit = || (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32;
        let mut points: Vec<Vec2> = (0..count).map(|_| Vec2::new(unit() * w, unit() * h)).collect();
        let rows = (h / cell) as u32;
        for i in 0..=(w / cell) as u32 {
            let corner = Vec2::new(i as f32, (i % rows) as f32) * cell;
            points.extend([corner, corner + Vec2::new(-0.5, 0.5)]);
        }
        points.extend([Vec2::new(-3.0, 5.0), Vec2::new(-2.0, 5.5), Vec2::new(w + 4.0, h + 4.0)]);
        points
    }

    #[test]
    fn grid_equals_brute_force_including_cell_borders() {
        let (w, h, cell) = (500.0, 300.0, 25.0);
        let points = scattered_points(7, 2000, (w, h), cell);
        let mut grid = SpatialGrid::new(w, h, cell, points.len());
        grid.rebuild(&points, &[]);
        let mut out = Vec::new();
        for (i, &p) in points.iter().enumerate() {
            for r in [cell * 0.5, cell, cell * 1.7] {
                grid.within_distance(p, r, &mut out);
                assert_eq!(out, brute(&points, p, r), "agent {i} radius {r}");
            }
        }
    }

    #[test]
    fn pairs_are_counted_once() {
        let points =
            vec![Vec2::new(1.0, 1.0), Vec2::new(2.0, 1.0), Vec2::new(30.0, 30.0), Vec2::new(1.5, 1.5)];
        let mut grid = SpatialGrid::new(100.0, 100.0, 10.0, 4);
        grid.rebuild(&points, &[]);
        let mut pairs = Vec::new();
        grid.for_each_pair_within(2.0, |a, b| pairs.push((a, b)));
        pairs.sort();
        assert_eq!(pairs, vec![(0, 1), (0, 3), (1, 3)]);
    }

    #[test]
    fn agents_left_out_are_met_by_no_query_pair_or_block() {
        let (w, h, cell) = (300.0, 200.0, 20.0);
        let points = scattered_points(5, 800, (w, h), cell);
        let present = |i: usize| !i.is_multiple_of(3);
        let mut grid = SpatialGrid::new(w, h, cell, points.len());
        grid.rebuild_present(&points, &[], present);
        // The same as a grid of the present agents alone (ids mapped back).
        let kept: Vec<usize> = (0..points.len()).filter(|&i| present(i)).collect();
        let kept_points: Vec<Vec2> = kept.iter().map(|&i| points[i]).collect();
        let mut out = Vec::new();
        for &p in &points {
            grid.within_distance(p, cell * 1.3, &mut out);
            let expected: Vec<(f32, u32)> = brute(&kept_points, p, cell * 1.3)
                .into_iter()
                .map(|(d2, k)| (d2, kept[k as usize] as u32))
                .collect();
            assert_eq!(out, expected);
        }
        let mut pairs = 0;
        grid.for_each_pair_within(cell, |a, b| {
            assert!(present(a as usize) && present(b as usize));
            pairs += 1;
        });
        assert!(pairs > 0);
        let mut runs = CandidateRuns::default();
        let mut blocked = 0;
        grid.for_each_candidate_block(cell, &mut runs, |agents, _| blocked += agents.len());
        assert_eq!(blocked, kept.len());
        assert_eq!(grid.cell_of_agent(0), Some(grid.cell_count()));
        assert!(grid.cell_of_agent(1).is_some_and(|c| c < grid.cell_count()));
    }

    #[test]
    fn pairs_equal_brute_force_across_cell_borders() {
        let (w, h, cell) = (300.0, 200.0, 20.0);
        // Dense enough for many pairs.
        let points = scattered_points(11, 1500, (w, h), cell);
        let mut grid = SpatialGrid::new(w, h, cell, points.len());
        grid.rebuild(&points, &[]);
        for radius in [3.0, 8.0, cell] {
            let mut pairs = Vec::new();
            grid.for_each_pair_within(radius, |a, b| pairs.push((a, b)));
            pairs.sort_unstable();
            let mut expected = Vec::new();
            for a in 0..points.len() {
                for b in a + 1..points.len() {
                    if points[a].distance_squared(points[b]) < radius * radius {
                        expected.push((a as u32, b as u32));
                    }
                }
            }
            assert!(expected.len() > 50, "the test needs pairs (radius {radius})");
            assert_eq!(pairs, expected, "radius {radius}");
        }
    }

    #[test]
    fn obstacle_index_reports_each_nearby_obstacle_once() {
        let obstacles = vec![
            Obstacle::Rect { min: [0.0, 0.0], max: [300.0, 20.0] },
            Obstacle::Circle { center: [500.0, 500.0], radius: 10.0 },
            Obstacle::Circle { center: [100.0, 100.0], radius: 90.0 },
        ];
        let index = ObstacleIndex::new(obstacles, 1000.0, 1000.0);
        let mut seen = Vec::new();
        let q = Aabb { min: Vec2::new(0.0, 0.0), max: Vec2::new(400.0, 400.0) };
        index.for_each_near(q, |i, _| seen.push(i));
        seen.sort();
        assert_eq!(seen, vec![0, 2]);
        assert!(index.contains(Vec2::new(500.0, 505.0)));
        assert!(!index.contains(Vec2::new(700.0, 700.0)));
    }

    #[test]
    fn a_sample_spreads_evenly_over_all_runs_and_keeps_small_ones_whole() {
        let (w, h, cell) = (300.0, 200.0, 20.0);
        let points = scattered_points(5, 3000, (w, h), cell);
        let velocities: Vec<Vec2> = (0..points.len()).map(|i| Vec2::new(i as f32, -(i as f32))).collect();
        let mut grid = SpatialGrid::new(w, h, cell, points.len());
        grid.rebuild(&points, &velocities);
        let (columns, mut runs, mut sample) =
            (grid.columns(), CandidateRuns::default(), CandidateSample::default());
        grid.candidate_runs(Vec2::new(150.0, 100.0), 45.0, &mut runs);
        assert!(runs.runs().len() >= 3 && runs.len() > 200, "{:?}", runs.runs());
        let all: Vec<usize> = runs.runs().iter().flat_map(Clone::clone).collect();
        for count in [1, 7, 64, 200, all.len(), all.len() + 10] {
            sample.fill(columns, runs.runs(), count);
            let taken = count.min(all.len());
            assert_eq!(sample.runs(), std::slice::from_ref(&(0..taken)));
            let s = sample.columns();
            for k in 0..taken {
                let slot = all[k * all.len() / taken];
                assert_eq!(s.ids[k], columns.ids[slot]);
                let id = s.ids[k] as usize;
                assert_eq!((s.x[k], s.y[k]), (points[id].x, points[id].y));
                assert_eq!((s.vx[k], s.vy[k]), (velocities[id].x, velocities[id].y));
            }
            // Padding after the sample, as after the grid's own columns.
            assert!(
                s.ids[taken..].iter().all(|&id| id == u32::MAX) && s.ids.len() == taken + CANDIDATE_LANES
            );
            assert!(s.x[taken..].iter().all(|x| x.is_nan()));
        }
    }

    #[test]
    fn any_within_capped_answers_as_testing_every_visited_agent() {
        let (w, h, cell) = (200.0, 200.0, 20.0);
        let points = scattered_points(3, 4000, (w, h), cell);
        let mut grid = SpatialGrid::new(w, h, cell, points.len());
        grid.rebuild(&points, &[]);
        let cap = QueryCap { neighbours: 40, candidates: 90 };
        let mut answers = [0; 2];
        for (i, &p) in points.iter().enumerate().step_by(7) {
            for radius in [1.0, 4.0, 15.0] {
                let hit = |n: Neighbour| n.id != i as u32 && n.d2 < 6.0 && n.id.is_multiple_of(3);
                let mut expected = false;
                grid.for_each_within_capped(p, radius, cap, |n| expected |= hit(n));
                let mut tested = 0;
                let any = grid.any_within_capped(p, radius, cap, |n| {
                    tested += 1;
                    hit(n)
                });
                assert_eq!(any, expected, "agent {i} radius {radius}");
                answers[usize::from(any)] += 1;
                if any {
                    assert!(tested <= cap.neighbours);
                }
            }
        }
        assert!(answers[0] > 100 && answers[1] > 100, "both answers occur: {answers:?}");
    }

    #[test]
    fn single_cell_grid_scans_everything() {
        let points = vec![Vec2::new(1.0, 1.0), Vec2::new(99.0, 99.0)];
        let mut grid = SpatialGrid::single_cell(100.0, 100.0);
        grid.rebuild(&points, &[]);
        let mut out = Vec::new();
        grid.within_distance(Vec2::ZERO, 1000.0, &mut out);
        assert_eq!(out.len(), 2);
    }
}
