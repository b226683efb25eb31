//! Benchmark functions: the four of Liu & Liu 2022 Table 2 with its search ranges, plus the
//! standard Rastrigin and Rosenbrock. Every one has its minimum 0.

use super::problem::{Bounds, Objective, UnknownName};
use std::f64::consts::{E, PI};

/// A benchmark function (the search range is part of its definition here).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Function {
    /// Σ x², on [−80, 80] (paper's Table 2).
    Sphere,
    /// Ackley, on [−20, 20] (paper's Table 2).
    Ackley,
    /// Griewank, on [−250, 250] (paper's Table 2).
    Griewank,
    /// Rastrigin on the paper's [−4.06, 4.06].
    Rastrigin,
    /// Rastrigin on the customary [−5.12, 5.12].
    RastriginStandard,
    /// Rosenbrock's valley Σ 100(x_{i+1} − x_i²)² + (x_i − 1)², on [−30, 30] (Rashedi's F5).
    Rosenbrock,
}

impl Function {
    /// Every function, in table order.
    pub const ALL: &'static [Function] = &[
        Function::Sphere,
        Function::Ackley,
        Function::Griewank,
        Function::Rastrigin,
        Function::RastriginStandard,
        Function::Rosenbrock,
    ];

    /// The four functions of the paper's Table 2 and 3.
    pub const PAPER: &'static [Function] =
        &[Function::Sphere, Function::Ackley, Function::Griewank, Function::Rastrigin];

    /// The CLI name.
    pub fn name(self) -> &'static str {
        match self {
            Function::Sphere => "sphere",
            Function::Ackley => "ackley",
            Function::Griewank => "griewank",
            Function::Rastrigin => "rastrigin",
            Function::RastriginStandard => "rastrigin-5.12",
            Function::Rosenbrock => "rosenbrock",
        }
    }

    /// Looks a function up by its CLI name.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|f| f.name() == name)
    }

    /// [`Self::from_name`] for user input: an unknown name is refused with the known ones.
    pub fn parse(name: &str) -> Result<Self, UnknownName> {
        Self::from_name(name).ok_or_else(|| {
            let known: Vec<&str> = Self::ALL.iter().map(|f| f.name()).collect();
            UnknownName::Function(name.chars().take(40).collect(), known.join(", "))
        })
    }

    /// Half-width `h` of the search range `[−h, h]` in every coordinate.
    pub fn half_range(self) -> f64 {
        match self {
            Function::Sphere => 80.0,
            Function::Ackley => 20.0,
            Function::Griewank => 250.0,
            Function::Rastrigin => 4.06,
            Function::RastriginStandard => 5.12,
            Function::Rosenbrock => 30.0,
        }
    }

    /// The value at `x` (any dimension ≥ 1; Rosenbrock needs ≥ 2 to be more than a parabola).
    pub fn value(self, x: &[f64]) -> f64 {
        let d = x.len().max(1) as f64;
        match self {
            Function::Sphere => x.iter().map(|v| v * v).sum(),
            Function::Ackley => {
                let sq: f64 = x.iter().map(|v| v * v).sum();
                let cs: f64 = x.iter().map(|v| libm::cos(2.0 * PI * v)).sum();
                -20.0 * libm::exp(-0.2 * libm::sqrt(sq / d)) - libm::exp(cs / d) + 20.0 + E
            }
            Function::Griewank => {
                let sq: f64 = x.iter().map(|v| v * v).sum::<f64>() / 4000.0;
                let prod: f64 =
                    x.iter().enumerate().map(|(i, v)| libm::cos(v / libm::sqrt((i + 1) as f64))).product();
                sq - prod + 1.0
            }
            Function::Rastrigin | Function::RastriginStandard => {
                10.0 * d + x.iter().map(|v| v * v - 10.0 * libm::cos(2.0 * PI * v)).sum::<f64>()
            }
            Function::Rosenbrock => x
                .windows(2)
                .map(|w| {
                    let a = w[1] - w[0] * w[0];
                    let b = w[0] - 1.0;
                    100.0 * a * a + b * b
                })
                .sum(),
        }
    }
}

/// A benchmark function in a given dimension, as an [`Objective`].
#[derive(Clone, Debug, PartialEq)]
pub struct Benchmark {
    /// Which function.
    pub function: Function,
    bounds: Bounds,
}

impl Benchmark {
    /// `function` in `dim` dimensions on its standard range.
    pub fn new(function: Function, dim: usize) -> Self {
        let h = function.half_range();
        Self { function, bounds: Bounds::uniform(dim.max(1), -h, h) }
    }
}

impl Objective for Benchmark {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }

    fn evaluate(&self, x: &[f64]) -> f64 {
        self.function.value(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minimum_is_zero_at_the_known_point() {
        for &f in Function::ALL {
            let at = if f == Function::Rosenbrock { 1.0 } else { 0.0 };
            let x = vec![at; 30];
            assert!(f.value(&x).abs() < 1e-12, "{}: {}", f.name(), f.value(&x));
            // A point off the optimum is worse.
            let y = vec![at + 0.3; 30];
            assert!(f.value(&y) > 1e-3, "{}", f.name());
        }
    }

    #[test]
    fn names_round_trip() {
        for &f in Function::ALL {
            assert_eq!(Function::from_name(f.name()), Some(f));
        }
        assert_eq!(Function::from_name("nope"), None);
    }

    #[test]
    fn known_values() {
        // Rastrigin at x = 1 in every coordinate: each term 1 − 10 cos 2π + 10 = 1.
        assert!((Function::Rastrigin.value(&[1.0; 4]) - 4.0).abs() < 1e-9);
        // Rosenbrock at the origin: (0 − 1)² per pair.
        assert!((Function::Rosenbrock.value(&[0.0; 5]) - 4.0).abs() < 1e-12);
        // Sphere.
        assert_eq!(Function::Sphere.value(&[3.0, 4.0]), 25.0);
    }
}
