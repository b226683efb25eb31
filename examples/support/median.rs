//! The median the timing examples report: robust to the odd slow sample (another process's turn
//! on the core, a page fault) that a mean would take in.

/// The middle of `samples` once sorted (the upper middle of an even count); panics when empty.
pub fn median(mut samples: Vec<f64>) -> f64 {
    samples.sort_by(f64::total_cmp);
    samples[samples.len() / 2]
}
