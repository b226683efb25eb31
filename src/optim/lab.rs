//! The optimizer lab (issue 4 §2): one optimizer run stepped on demand, its best-so-far curve,
//! and, in 2-D, a picture of it: the function as a heat map with contour lines and the particles
//! with their trails and gbest, written directly into an RGBA buffer (no anti-aliasing: a frame
//! is a copy of the cached heat map plus a few hundred pixels).
//!
//! Colours: the value is shown on a log scale (`ln(1 + f − f_min)`) normalised over the grid,
//! from dark blue (low) to pale yellow (high); contour lines are drawn where the log value
//! crosses one of [`CONTOURS`] equally spaced levels between two neighbouring pixels.

use super::functions::{Benchmark, Function};
use super::problem::{Algorithm, Objective, Optimizer, Settings};
use crate::digest::Fnv1a;
use crate::rng::Rng;

/// Number of contour levels over the value range.
pub const CONTOURS: u32 = 14;
/// Positions kept per particle for its trail.
pub const TRAIL_LENGTH: usize = 24;
/// Colour of the particles (RGB).
pub const PARTICLE_COLOR: [u8; 3] = [0xff, 0xff, 0xff];
/// Colour of the gbest marker (RGB).
pub const GBEST_COLOR: [u8; 3] = [0xe0, 0x20, 0x20];
/// Colour of the contour lines (RGB).
const CONTOUR_COLOR: [u8; 3] = [0x10, 0x10, 0x18];

/// One optimizer run in the lab.
pub struct LabRun {
    function: Function,
    objective: Benchmark,
    optimizer: Box<dyn Optimizer + Send>,
    /// Best value after initialisation and after each iteration.
    curve: Vec<f64>,
    /// Per particle, its last [`TRAIL_LENGTH`] positions in the first two coordinates (oldest
    /// first).
    trails: Vec<Vec<[f64; 2]>>,
    iterations: u32,
    view: Option<HeatMap>,
    frame: Vec<u8>,
}

/// The cached heat map of a function at a size.
struct HeatMap {
    width: u32,
    height: u32,
    pixels: Vec<u8>,
}

/// Digest of an optimizer's state: the best value's bits and every position's bits (FNV-1a).
/// Equal digests natively and in wasm mean bit-identical runs.
pub fn run_digest(optimizer: &dyn Optimizer) -> String {
    let mut h = Fnv1a::new();
    for x in std::iter::once(optimizer.best_value()).chain(optimizer.positions().iter().copied()) {
        h.f64(x);
    }
    format!("{:016x} {:e}", h.finish(), optimizer.best_value())
}

/// The reference run whose digest is pinned natively and in wasm: IGSA on Ackley, d = 5,
/// N = 20, T = 100, seed 3 (stream 0).
pub fn reference_digest() -> String {
    let objective = Benchmark::new(Function::Ackley, 5);
    let settings = Settings { population: 20, iterations: 100, ..Settings::default() };
    let mut opt = Algorithm::Igsa.build(&objective, &settings, Rng::new(3, 0));
    for _ in 0..settings.iterations {
        opt.step(&objective);
    }
    run_digest(opt.as_ref())
}

/// The best value of run `run` (stream `run` of `seed`) of `algorithm` on `function` in `dim`
/// dimensions: one cell entry of a Table-3-style table. The page's worker calls it run by run.
pub fn best_of_run(
    algorithm: Algorithm,
    function: Function,
    dim: usize,
    settings: &Settings,
    seed: u32,
    run: u32,
) -> f64 {
    let objective = Benchmark::new(function, dim.max(1));
    let mut opt = algorithm.build(&objective, settings, super::run_rng(seed, run));
    for _ in 0..settings.iterations {
        opt.step(&objective);
    }
    opt.best_value()
}

impl LabRun {
    /// A fresh run of `algorithm` on `function` in `dim` dimensions with `settings`, seeded.
    pub fn new(algorithm: Algorithm, function: Function, dim: usize, settings: &Settings, seed: u32) -> Self {
        let objective = Benchmark::new(function, dim.max(1));
        let optimizer = algorithm.build(&objective, settings, Rng::new(seed, 0));
        let mut run = Self {
            function,
            objective,
            curve: Vec::new(),
            trails: Vec::new(),
            iterations: settings.iterations.max(1),
            optimizer,
            view: None,
            frame: Vec::new(),
        };
        run.curve.push(run.optimizer.best_value());
        run.record_trails();
        run
    }

    /// Dimension of the problem.
    pub fn dim(&self) -> usize {
        self.objective.bounds().dim()
    }

    /// Iterations done.
    pub fn iteration(&self) -> u32 {
        self.optimizer.iteration()
    }

    /// The iteration budget (the schedules run over it); stepping stops there.
    pub fn iterations(&self) -> u32 {
        self.iterations
    }

    /// Advances `n` iterations (not beyond the budget).
    pub fn step(&mut self, n: u32) {
        for _ in 0..n {
            if self.optimizer.iteration() >= self.iterations {
                break;
            }
            self.optimizer.step(&self.objective);
            self.curve.push(self.optimizer.best_value());
            self.record_trails();
        }
    }

    fn record_trails(&mut self) {
        let dim = self.dim();
        let positions = self.optimizer.positions();
        let n = positions.len() / dim.max(1);
        self.trails.resize_with(n, Vec::new);
        for (i, trail) in self.trails.iter_mut().enumerate() {
            let row = &positions[i * dim..(i + 1) * dim];
            let p = [row[0], row.get(1).copied().unwrap_or(0.0)];
            if trail.len() == TRAIL_LENGTH {
                trail.remove(0);
            }
            trail.push(p);
        }
    }

    /// Best value so far.
    pub fn best_value(&self) -> f64 {
        self.optimizer.best_value()
    }

    /// Best point so far.
    pub fn best_position(&self) -> &[f64] {
        self.optimizer.best_position()
    }

    /// Current positions, row-major.
    pub fn positions(&self) -> &[f64] {
        self.optimizer.positions()
    }

    /// Number of particles.
    pub fn particles(&self) -> usize {
        self.optimizer.positions().len() / self.dim().max(1)
    }

    /// Best value after initialisation and after each iteration so far.
    pub fn curve(&self) -> &[f64] {
        &self.curve
    }

    /// Digest of the run's state (see [`run_digest`]).
    pub fn digest(&self) -> String {
        run_digest(self.optimizer.as_ref())
    }

    /// The last frame drawn by [`LabRun::render`]: `width × height` opaque RGBA.
    pub fn pixels(&self) -> &[u8] {
        &self.frame
    }

    /// Draws the first two coordinates: heat map with contours (cached per size), trails,
    /// particles, gbest. A size of 0 or over 4096 px is clamped.
    pub fn render(&mut self, width: u32, height: u32) {
        let (width, height) = (width.clamp(1, 4096), height.clamp(1, 4096));
        if self.view.as_ref().is_none_or(|v| v.width != width || v.height != height) {
            self.view = Some(heat_map(self.function, self.dim(), width, height));
        }
        let Some(view) = &self.view else { return };
        self.frame.clear();
        self.frame.extend_from_slice(&view.pixels);
        let half = self.function.half_range();
        let to_px = |p: [f64; 2]| -> (f64, f64) {
            (
                (p[0] + half) / (2.0 * half) * f64::from(width),
                (half - p[1]) / (2.0 * half) * f64::from(height),
            )
        };
        let (w, h) = (width as i64, height as i64);
        let frame = &mut self.frame;
        for trail in &self.trails {
            let len = trail.len();
            for (k, pair) in trail.windows(2).enumerate() {
                let alpha = 40 + (150 * (k + 1) / len.max(1)) as u32;
                let (a, b) = (to_px(pair[0]), to_px(pair[1]));
                line(frame, w, h, a, b, PARTICLE_COLOR, alpha);
            }
        }
        for trail in &self.trails {
            if let Some(&p) = trail.last() {
                let (x, y) = to_px(p);
                disc(frame, w, h, x, y, 2.5, PARTICLE_COLOR);
            }
        }
        let best = self.optimizer.best_position();
        let (bx, by) = to_px([best[0], best.get(1).copied().unwrap_or(0.0)]);
        for d in -6..=6 {
            let d = f64::from(d);
            for t in [-1.0, 0.0, 1.0] {
                put(frame, w, h, bx + d, by + t, GBEST_COLOR, 255);
                put(frame, w, h, bx + t, by + d, GBEST_COLOR, 255);
            }
        }
    }
}

/// The heat map of the function over its box in the first two coordinates (the others at 0,
/// where every benchmark has its optimum).
fn heat_map(function: Function, dim: usize, width: u32, height: u32) -> HeatMap {
    let (w, h) = (width as usize, height as usize);
    let half = function.half_range();
    let mut x = vec![0.0; dim.max(2)];
    let mut values = vec![0.0f64; w * h];
    for j in 0..h {
        for i in 0..w {
            x[0] = -half + (i as f64 + 0.5) / w as f64 * 2.0 * half;
            x[1] = half - (j as f64 + 0.5) / h as f64 * 2.0 * half;
            values[j * w + i] = function.value(&x);
        }
    }
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    for v in &mut values {
        *v = libm::log(1.0 + (*v - lo).max(0.0));
    }
    let hi = values.iter().copied().fold(0.0, f64::max).max(1e-12);
    let level = |v: f64| (v / hi * f64::from(CONTOURS)).floor() as i64;
    let mut pixels = vec![255u8; w * h * 4];
    for j in 0..h {
        for i in 0..w {
            let t = values[j * w + i] / hi;
            let mut rgb = ramp(t);
            let here = level(values[j * w + i]);
            let right = if i + 1 < w { level(values[j * w + i + 1]) } else { here };
            let below = if j + 1 < h { level(values[(j + 1) * w + i]) } else { here };
            if right != here || below != here {
                rgb = blend(rgb, CONTOUR_COLOR, 110);
            }
            pixels[(j * w + i) * 4..(j * w + i) * 4 + 3].copy_from_slice(&rgb);
        }
    }
    HeatMap { width, height, pixels }
}

/// Dark blue → teal → yellow, `t` in [0, 1].
fn ramp(t: f64) -> [u8; 3] {
    const STOPS: [[f64; 3]; 4] =
        [[20.0, 30.0, 90.0], [30.0, 120.0, 150.0], [140.0, 200.0, 110.0], [250.0, 240.0, 170.0]];
    let t = t.clamp(0.0, 1.0) * 3.0;
    let k = (t.floor() as usize).min(2);
    let f = t - k as f64;
    let mut out = [0u8; 3];
    for c in 0..3 {
        out[c] = (STOPS[k][c] + f * (STOPS[k + 1][c] - STOPS[k][c])).round() as u8;
    }
    out
}

fn blend(under: [u8; 3], over: [u8; 3], alpha: u32) -> [u8; 3] {
    let mix = |a: u8, b: u8| ((u32::from(a) * (255 - alpha) + u32::from(b) * alpha) / 255) as u8;
    [mix(under[0], over[0]), mix(under[1], over[1]), mix(under[2], over[2])]
}

fn put(frame: &mut [u8], w: i64, h: i64, x: f64, y: f64, rgb: [u8; 3], alpha: u32) {
    let (xi, yi) = (x.floor() as i64, y.floor() as i64);
    if xi < 0 || yi < 0 || xi >= w || yi >= h {
        return;
    }
    let at = ((yi * w + xi) * 4) as usize;
    let under = [frame[at], frame[at + 1], frame[at + 2]];
    frame[at..at + 3].copy_from_slice(&blend(under, rgb, alpha.min(255)));
}

fn disc(frame: &mut [u8], w: i64, h: i64, x: f64, y: f64, r: f64, rgb: [u8; 3]) {
    let reach = r.ceil() as i64;
    for dy in -reach..=reach {
        for dx in -reach..=reach {
            let (fx, fy) = (dx as f64, dy as f64);
            if fx * fx + fy * fy <= r * r {
                put(frame, w, h, x + fx, y + fy, rgb, 255);
            }
        }
    }
}

fn line(frame: &mut [u8], w: i64, h: i64, a: (f64, f64), b: (f64, f64), rgb: [u8; 3], alpha: u32) {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let steps = dx.abs().max(dy.abs()).ceil().min(4096.0) as i64;
    if steps == 0 || !steps.is_positive() {
        return;
    }
    for s in 0..=steps {
        let t = s as f64 / steps as f64;
        put(frame, w, h, a.0 + dx * t, a.1 + dy * t, rgb, alpha);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_steps_to_its_budget_and_its_curve_never_rises() {
        let settings = Settings { population: 10, iterations: 30, ..Settings::default() };
        let mut run = LabRun::new(Algorithm::Pso, Function::Sphere, 2, &settings, 4);
        run.step(100);
        assert_eq!(run.iteration(), 30);
        assert_eq!(run.curve().len(), 31);
        assert!(run.curve().windows(2).all(|w| w[1] <= w[0]));
        assert_eq!(run.particles(), 10);
    }

    #[test]
    fn the_picture_shows_particles_and_changes_as_they_move() {
        let settings = Settings { population: 12, iterations: 50, ..Settings::default() };
        let mut run = LabRun::new(Algorithm::Gsa, Function::Rastrigin, 2, &settings, 1);
        run.render(120, 100);
        let first = run.pixels().to_vec();
        assert_eq!(first.len(), 120 * 100 * 4);
        assert!(first.chunks(4).all(|p| p[3] == 255));
        let white = first.chunks(4).filter(|p| p[..3] == PARTICLE_COLOR).count();
        assert!(white >= 12, "{white} particle pixels");
        assert!(first.chunks(4).any(|p| p[..3] == GBEST_COLOR));
        run.step(5);
        run.render(120, 100);
        assert_ne!(first, run.pixels());
    }
}
