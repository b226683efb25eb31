//! One bounded series of samples taken every `every` steps, that halves when full: the memory
//! bound shared by the recording, the replay's position frames, the metric series and the
//! comparison's pane series.
//!
//! A sample is a step number and a row of `width` values. The series holds at most `cap`
//! samples; a sample offered when it is full first thins it: the interval doubles and only the
//! samples on the new interval stay (every other one), so a long run always fits and always
//! spans its whole length at an even spacing. [`BoundedSeries::thinned`] counts the thinnings,
//! so a front-end can say so instead of dropping anything silently.
//!
//! Optionally one step (an *anchor*, the replay's first step) survives every thinning even when
//! it is off the interval. Samples that must be held whatever the budget (the replay's
//! checkpoints of edits) go in with [`BoundedSeries::push_always`] and are kept by
//! [`BoundedSeries::shrink_to_cap`].

/// Samples of `width` values each, taken every [`BoundedSeries::every`] steps, at most
/// [`BoundedSeries::cap`] of them (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct BoundedSeries<T> {
    width: usize,
    cap: usize,
    every: u32,
    thinned: u32,
    anchor: Option<u32>,
    /// The step of each sample, increasing.
    steps: Vec<u32>,
    /// `values[s * width..(s + 1) * width]` is the row of sample `s`.
    values: Vec<T>,
}

impl<T> BoundedSeries<T> {
    /// An empty series of rows of `width` values, sampling every `every` steps (at least 1),
    /// holding at most `cap` samples.
    pub fn new(width: usize, cap: usize, every: u32) -> Self {
        Self {
            width,
            cap,
            every: every.max(1),
            thinned: 0,
            anchor: None,
            steps: Vec::new(),
            values: Vec::new(),
        }
    }

    /// The same series keeping the sample at `step` through every thinning.
    pub fn with_anchor(mut self, step: u32) -> Self {
        self.anchor = Some(step);
        self
    }

    /// The most samples that fit in `budget_bytes` when a row of `width` values takes
    /// `bytes_per_value` bytes each (a zero-width row counts as one value).
    pub fn cap_for_bytes(budget_bytes: usize, width: usize, bytes_per_value: usize) -> usize {
        budget_bytes / (width.max(1) * bytes_per_value.max(1))
    }

    /// Whether a sample at `step` would be taken now (it falls on the interval).
    pub fn due(&self, step: u32) -> bool {
        step.is_multiple_of(self.every)
    }

    /// Offers the row at `step` (later than every sample held). It is kept when it falls on the
    /// interval; a full series thins first, which may move the interval past it. Returns whether
    /// it was kept. `row` must yield `width` values.
    pub fn push(&mut self, step: u32, row: impl IntoIterator<Item = T>) -> bool {
        if !self.make_room(step) {
            return false;
        }
        let (len, width) = (self.values.len(), self.width);
        if self.values.capacity() < len + width {
            // Grow by doubling but never past the cap: plain `Vec` growth could reserve twice
            // the budget.
            let most = self.cap.saturating_mul(width).max(len + width);
            let want = (2 * len).max(64 * width).min(most).max(len + width);
            self.values.reserve_exact(want - len);
        }
        self.steps.push(step);
        self.values.extend(row);
        debug_assert_eq!(self.values.len(), self.steps.len() * width, "a row of the wrong width");
        true
    }

    /// Thins until a sample fits; `false` when `step` is off the interval or nothing is left to
    /// thin (a cap below two samples).
    fn make_room(&mut self, step: u32) -> bool {
        if !self.due(step) {
            return false;
        }
        while self.steps.len() >= self.cap {
            if self.steps.len() <= 1 || self.every > u32::MAX / 2 {
                return false;
            }
            self.thin(|_| false);
        }
        self.due(step)
    }

    /// Appends the row at `step` (later than every sample held) whatever the interval and the
    /// cap: a sample that must be held (the replay's checkpoint of an edit). Follow it with
    /// [`BoundedSeries::shrink_to_cap`].
    pub fn push_always(&mut self, step: u32, row: impl IntoIterator<Item = T>) {
        self.steps.push(step);
        self.values.extend(row);
    }

    /// Thins while the series holds more than its cap, keeping the anchor and the steps `keep`
    /// accepts through every thinning; stops when a thinning drops nothing (what is left must be
    /// kept, even over the cap).
    pub fn shrink_to_cap(&mut self, keep: impl Fn(u32) -> bool) {
        while self.steps.len() > self.cap.max(1) && self.every <= u32::MAX / 2 {
            if self.thin(&keep) == 0 {
                break;
            }
        }
    }

    /// Doubles the interval and keeps the samples on it, the anchor and the steps `keep`
    /// accepts; returns how many samples went.
    fn thin(&mut self, keep: impl Fn(u32) -> bool) -> usize {
        self.every = self.every.saturating_mul(2);
        self.thinned += 1;
        let (width, before) = (self.width, self.steps.len());
        let mut kept = 0;
        for s in 0..before {
            let step = self.steps[s];
            if step.is_multiple_of(self.every) || Some(step) == self.anchor || keep(step) {
                if kept != s {
                    self.steps[kept] = step;
                    // Move row `s` down to row `kept` (any `T`: swapped, not copied).
                    let (low, high) = self.values.split_at_mut(s * width);
                    low[kept * width..(kept + 1) * width].swap_with_slice(&mut high[..width]);
                }
                kept += 1;
            }
        }
        self.truncate_to(kept);
        before - kept
    }

    /// Drops the samples after `step`.
    pub fn truncate_after(&mut self, step: u32) {
        self.truncate_to(self.steps.partition_point(|&s| s <= step));
    }

    /// Drops the samples at `step` and later.
    pub fn truncate_before(&mut self, step: u32) {
        self.truncate_to(self.steps.partition_point(|&s| s < step));
    }

    fn truncate_to(&mut self, samples: usize) {
        self.steps.truncate(samples);
        self.values.truncate(samples * self.width);
    }

    /// Drops every sample and takes rows of `width` values from now on; the interval and the
    /// thinning count stay.
    pub fn clear_samples(&mut self, width: usize) {
        self.steps.clear();
        self.values.clear();
        self.width = width;
    }

    /// The sampled steps, increasing.
    pub fn steps(&self) -> &[u32] {
        &self.steps
    }

    /// Number of samples held.
    pub fn len(&self) -> usize {
        self.steps.len()
    }

    /// Whether no sample is held.
    pub fn is_empty(&self) -> bool {
        self.steps.is_empty()
    }

    /// The row of sample `s` (empty past the end).
    pub fn row(&self, s: usize) -> &[T] {
        let start = (s * self.width).min(self.values.len());
        let end = ((s + 1) * self.width).min(self.values.len());
        &self.values[start..end]
    }

    /// Every row, one after the other.
    pub fn values(&self) -> &[T] {
        &self.values
    }

    /// Values per sample.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Most samples held.
    pub fn cap(&self) -> usize {
        self.cap
    }

    /// Steps between samples now.
    pub fn every(&self) -> u32 {
        self.every
    }

    /// How many times the series was thinned.
    pub fn thinned(&self) -> u32 {
        self.thinned
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_full_series_halves_doubles_its_interval_and_spans_the_run() {
        let mut s = BoundedSeries::new(2, 10, 1);
        for step in 0..1000u32 {
            s.push(step, [step, step + 1]);
            assert!(s.len() <= 10);
        }
        assert!(s.thinned() >= 6, "{}", s.thinned());
        assert_eq!(s.steps()[0], 0);
        assert!(s.steps().windows(2).all(|w| w[1] - w[0] == s.every()));
        assert!(*s.steps().last().expect("samples") + s.every() > 999);
        for (i, &step) in s.steps().iter().enumerate() {
            assert_eq!(s.row(i), &[step, step + 1], "rows move with their steps");
        }
    }

    #[test]
    fn the_anchor_survives_thinning_and_truncation_cuts_either_side() {
        let mut s = BoundedSeries::new(1, 4, 1).with_anchor(7);
        for step in 7..40u32 {
            s.push(step, [step]);
        }
        assert_eq!(s.steps()[0], 7);
        assert!(s.steps()[1..].iter().all(|x| x % s.every() == 0), "{:?}", s.steps());
        let last = *s.steps().last().expect("samples");
        s.truncate_after(last - 1);
        assert!(s.steps().iter().all(|&x| x < last));
        s.truncate_before(8);
        assert_eq!(s.steps(), &[7]);
        assert_eq!(s.values(), &[7]);
    }

    #[test]
    fn a_cap_below_two_samples_keeps_one_and_stops_thinning() {
        let mut s = BoundedSeries::new(1, 1, 1);
        assert!(s.push(0, [0u8]));
        for step in 1..100 {
            assert!(!s.push(step, [1]));
        }
        assert_eq!((s.len(), s.thinned(), s.every()), (1, 0, 1));
        assert_eq!(BoundedSeries::<u8>::cap_for_bytes(100, 3, 4), 8);
    }
}
