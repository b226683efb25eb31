//! Fine cells over the world grid's agents, rebuilt once per step by the planners whose queries
//! are much smaller than the world grid's cells (firefly's survey, the virtual forces' view).
//!
//! This holds what those indexes share: the cell layout (size within the same cell budget as
//! the world grid, columns, rows, the cell of a coordinate) and a stable counting sort of the
//! world grid's storage slots into the cells. Each index keeps its own per-entry fields and
//! queries: it scatters slot `k` to entry [`FineCells::entry_of_slot`]`[k]`.

use super::{MAX_CELLS_PER_AGENT, MIN_CELL_BUDGET};
use glam::Vec2;

/// A layout of square cells over a world and the world grid's slots counted into them: cell by
/// cell in row-major order and, within a cell, by world-grid storage slot, so the entries'
/// order depends on the positions only (the same natively and in wasm).
#[derive(Clone, Debug, Default)]
pub struct FineCells {
    cell: f32,
    inv_cell: f32,
    cols: u32,
    rows: u32,
    /// `start[c]..start[c + 1]` are the entries of cell `c`.
    start: Vec<u32>,
    /// The entry of each slot: first each slot's cell, turned into its entry by the sort.
    entry_of_slot: Vec<u32>,
    /// Scratch: the next free entry of each cell while sorting.
    next: Vec<u32>,
}

impl FineCells {
    /// Lays cells of about `cell_size` px over a `bounds` world and counts the points `xs`,
    /// `ys` (the world grid's positions in storage order, one per slot) into them.
    ///
    /// A cell size that is not a positive finite number becomes the world's larger side; the
    /// cell grows by half until the world needs at most `MAX_CELLS_PER_AGENT` cells per
    /// point (at least `MIN_CELL_BUDGET`), as the world grid's does, so memory and rebuild
    /// stay O(N) in a huge world.
    pub fn rebuild(&mut self, bounds: Vec2, cell_size: f32, xs: &[f32], ys: &[f32]) {
        let n = xs.len().min(ys.len());
        let (width, height) = (bounds.x.max(1.0), bounds.y.max(1.0));
        let mut cell = if cell_size.is_finite() && cell_size > 0.0 { cell_size } else { width.max(height) };
        let budget = (n * MAX_CELLS_PER_AGENT).max(MIN_CELL_BUDGET);
        while ((width / cell).ceil() * (height / cell).ceil()) as usize > budget {
            cell *= 1.5;
        }
        self.cell = cell;
        self.inv_cell = 1.0 / cell;
        self.cols = ((width / cell).ceil() as u32).max(1);
        self.rows = ((height / cell).ceil() as u32).max(1);
        self.start.clear();
        self.start.resize((self.cols * self.rows) as usize + 1, 0);
        self.entry_of_slot.clear();
        for (&x, &y) in xs.iter().zip(ys) {
            let c = self.row(y) * self.cols + self.col(x);
            self.entry_of_slot.push(c);
            self.start[c as usize + 1] += 1;
        }
        for c in 1..self.start.len() {
            self.start[c] += self.start[c - 1];
        }
        self.next.clear();
        self.next.extend_from_slice(&self.start);
        // Slots in increasing order: within a cell the entries keep the world grid's order.
        for slot in &mut self.entry_of_slot {
            let next = &mut self.next[*slot as usize];
            *slot = *next;
            *next += 1;
        }
    }

    /// Side of a cell (px).
    #[inline]
    pub fn cell(&self) -> f32 {
        self.cell
    }

    /// Columns of cells.
    #[inline]
    pub fn cols(&self) -> u32 {
        self.cols
    }

    /// Rows of cells.
    #[inline]
    pub fn rows(&self) -> u32 {
        self.rows
    }

    /// `start()[c]..start()[c + 1]` are the entries of cell `c` (row-major): one more than the
    /// cells.
    #[inline]
    pub fn start(&self) -> &[u32] {
        &self.start
    }

    /// The entry of each world-grid slot counted at the last rebuild.
    #[inline]
    pub fn entry_of_slot(&self) -> &[u32] {
        &self.entry_of_slot
    }

    /// The column of cells holding `x`; points beyond an edge fall in the edge column.
    #[inline]
    pub fn col(&self, x: f32) -> u32 {
        self.coord(x, self.cols)
    }

    /// The row of cells holding `y`; points beyond an edge fall in the edge row.
    #[inline]
    pub fn row(&self, y: f32) -> u32 {
        self.coord(y, self.rows)
    }

    #[inline]
    fn coord(&self, v: f32, n: u32) -> u32 {
        // Saturating float→int cast, as the world grid's: NaN → 0, negatives → 0. Monotone, so
        // every point at or beyond a bound falls in the bound's cell or beyond.
        ((v * self.inv_cell) as u32).min(n - 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_are_cell_by_cell_and_by_slot_within_a_cell() {
        let mut cells = FineCells::default();
        // 2 × 2 cells of 10 px over a 20 × 20 world; slots 0 and 2 share the top-right cell.
        let (xs, ys) = ([15.0, 5.0, 19.0, -3.0, 25.0], [1.0, 15.0, 9.0, 2.0, 30.0]);
        cells.rebuild(Vec2::new(20.0, 20.0), 10.0, &xs, &ys);
        assert_eq!((cells.cols(), cells.rows(), cells.cell()), (2, 2, 10.0));
        assert_eq!(cells.start(), &[0, 1, 3, 4, 5]);
        assert_eq!(cells.entry_of_slot(), &[1, 3, 2, 0, 4]);
    }

    #[test]
    fn a_huge_world_coarsens_the_cells_to_the_budget() {
        let mut cells = FineCells::default();
        cells.rebuild(Vec2::new(1.0e6, 1.0e6), 1.0, &[], &[]);
        assert!((cells.cols() * cells.rows()) as usize <= MIN_CELL_BUDGET);
        cells.rebuild(Vec2::new(100.0, 50.0), f32::NAN, &[], &[]);
        assert_eq!((cells.cols(), cells.rows(), cells.cell()), (1, 1, 100.0));
    }
}
