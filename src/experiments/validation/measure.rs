//! The suite's measurements as plain functions over recorded trajectories (metres, seconds), so
//! each can be checked on hand-placed paths with a known answer: section speed, arrival times,
//! closest approach, lane order, density and speed in a measurement area, where agents jam,
//! crossings of an exit line, exit flow, and the reference curves (Weidmann 1993, Seyfried et
//! al. 2005).

use glam::Vec2;

/// A run's sampled trajectories in metres: every agent at every frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Trajectories {
    /// Seconds between two frames.
    pub frame_s: f32,
    /// Group index of each agent.
    pub group: Vec<u32>,
    /// The frames, in time order; frame `k` is at `k × frame_s` seconds.
    pub frames: Vec<Frame>,
}

/// All agents at one instant.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    /// Positions (m; x to the right, y down as on the canvas).
    pub pos: Vec<Vec2>,
    /// Velocities (m/s).
    pub vel: Vec<Vec2>,
}

/// An axis-aligned rectangle in metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Area {
    /// Smallest corner (m).
    pub min: Vec2,
    /// Largest corner (m).
    pub max: Vec2,
}

impl Area {
    /// Whether `p` lies inside (edges included on the low side only).
    pub fn contains(&self, p: Vec2) -> bool {
        p.x >= self.min.x && p.x < self.max.x && p.y >= self.min.y && p.y < self.max.y
    }

    /// Area (m²).
    pub fn size(&self) -> f32 {
        (self.max.x - self.min.x).max(0.0) * (self.max.y - self.min.y).max(0.0)
    }
}

/// A line walkers leave across, in metres: where RiMEA counts the persons out of a room or a
/// corridor. Its two kinds are the ones the suite's scenes need (corridors along x or y).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ExitLine {
    /// The line x = `x` for y in `span`, crossed towards larger x.
    Rightward {
        /// Where the line is (m).
        x: f32,
        /// Its extent in y (m).
        span: (f32, f32),
    },
    /// The line y = `y` for x in `span`, crossed towards smaller y (up the canvas).
    Upward {
        /// Where the line is (m).
        y: f32,
        /// Its extent in x (m).
        span: (f32, f32),
    },
}

impl ExitLine {
    /// Whether `p` is on the line's out side (the line itself included).
    pub fn is_out(&self, p: Vec2) -> bool {
        match *self {
            ExitLine::Rightward { x, .. } => p.x >= x,
            ExitLine::Upward { y, .. } => p.y <= y,
        }
    }

    /// Where between `p` (inside) and `q` (out) the step from one to the other meets the line,
    /// as a fraction of the step, when it meets it within the line's span; `None` when the
    /// step does not go from in to out or passes beside the line.
    fn crossing(&self, p: Vec2, q: Vec2) -> Option<f32> {
        if self.is_out(p) || !self.is_out(q) {
            return None;
        }
        let (from, to, at, lateral, span) = match *self {
            ExitLine::Rightward { x, span } => (p.x, q.x, x, (p.y, q.y), span),
            ExitLine::Upward { y, span } => (p.y, q.y, y, (p.x, q.x), span),
        };
        let f = ((at - from) / (to - from)).clamp(0.0, 1.0);
        let across = lateral.0 + f * (lateral.1 - lateral.0);
        (span.0..=span.1).contains(&across).then_some(f)
    }
}

impl Trajectories {
    /// Number of agents.
    pub fn agents(&self) -> usize {
        self.group.len()
    }

    /// Seconds at (fractional) frame `k`.
    fn time(&self, k: f32) -> f32 {
        k * self.frame_s
    }

    /// The time agent `a` first crosses the line x = `x` going right (linear interpolation
    /// between frames), or `None` if it never does.
    pub fn crossing_time(&self, a: usize, x: f32) -> Option<f32> {
        for (k, w) in self.frames.windows(2).enumerate() {
            let (p, q) = (w[0].pos.get(a)?.x, w[1].pos.get(a)?.x);
            if p < x && q >= x {
                return Some(self.time(k as f32 + (x - p) / (q - p)));
            }
        }
        None
    }

    /// Agent `a`'s mean speed along x between the lines `x0 < x1` (m/s): their distance over
    /// the time between its crossings (RiMEA's measurement section), or `None`.
    pub fn section_speed(&self, a: usize, x0: f32, x1: f32) -> Option<f32> {
        let (t0, t1) = (self.crossing_time(a, x0)?, self.crossing_time(a, x1)?);
        (t1 > t0).then(|| (x1 - x0) / (t1 - t0))
    }

    /// The first time each agent's centre crosses `line` from its inside to its out side
    /// within its span (s, linear interpolation between frames), `None` for those that never
    /// do: the times people pass an exit, from positions alone (a walker the world removed at
    /// an exit stays where it left, on the out side).
    pub fn crossing_times(&self, line: ExitLine) -> Vec<Option<f32>> {
        (0..self.agents())
            .map(|a| {
                self.frames.windows(2).enumerate().find_map(|(k, w)| {
                    let f = line.crossing(*w[0].pos.get(a)?, *w[1].pos.get(a)?)?;
                    Some(self.time(k as f32 + f))
                })
            })
            .collect()
    }

    /// The first time each agent's centre is inside `area` (s), `None` for those never inside.
    pub fn arrival_times(&self, inside: impl Fn(Vec2) -> bool) -> Vec<Option<f32>> {
        (0..self.agents())
            .map(|a| {
                self.frames
                    .iter()
                    .position(|f| f.pos.get(a).is_some_and(|&p| inside(p)))
                    .map(|k| self.time(k as f32))
            })
            .collect()
    }

    /// The smallest gap between the bodies of agents `a` and `b` over all frames (m): centre
    /// distance minus both radii; negative when they overlapped.
    pub fn min_gap(&self, a: usize, b: usize, radius_a: f32, radius_b: f32) -> Option<f32> {
        self.frames
            .iter()
            .filter_map(|f| Some(f.pos.get(a)?.distance(*f.pos.get(b)?) - radius_a - radius_b))
            .min_by(f32::total_cmp)
    }

    /// Agents whose centre is inside a wall (`inside`) in some frame: wall crossings.
    pub fn agents_ever_inside(&self, inside: impl Fn(Vec2) -> bool) -> usize {
        (0..self.agents())
            .filter(|&a| self.frames.iter().any(|f| f.pos.get(a).is_some_and(|&p| inside(p))))
            .count()
    }

    /// Density (persons/m²), speed along +x (m/s) and specific flow (persons/(m·s)) in `area`,
    /// averaged over frames `from..`: density is the mean head count over the area's size, the
    /// speed the mean x-velocity of the agents inside (over all their samples), the flow their
    /// product (the hydrodynamic relation J_s = ρ v). `None` when no frame is left or no agent
    /// was ever inside.
    pub fn area_fundamental(&self, area: Area, from: usize) -> Option<FdPoint> {
        let frames = self.frames.get(from..).filter(|f| !f.is_empty())?;
        let size = area.size();
        if size <= 0.0 {
            return None;
        }
        let (mut heads, mut speed_sum) = (0usize, 0.0f64);
        for f in frames {
            for (p, v) in f.pos.iter().zip(&f.vel) {
                if area.contains(*p) {
                    heads += 1;
                    speed_sum += f64::from(v.x);
                }
            }
        }
        if heads == 0 {
            return None;
        }
        let density = heads as f64 / frames.len() as f64 / f64::from(size);
        let speed = speed_sum / heads as f64;
        Some(FdPoint { density, speed, flow: density * speed })
    }

    /// The density profile along x (persons/m²): the mean head count per frame from frame
    /// `from` on in each of `bins` bins `bin` metres long from `x0`, across the whole `width`,
    /// over the bin's area. Empty when no frame is left. A homogeneous periodic crowd has the
    /// same density in every bin.
    pub fn density_profile(&self, x0: f32, bin: f32, bins: usize, width: f32, from: usize) -> Vec<f64> {
        let frames = self.frames.get(from..).unwrap_or_default();
        if frames.is_empty() || bin <= 0.0 || width <= 0.0 {
            return vec![];
        }
        let mut heads = vec![0usize; bins];
        for f in frames {
            for p in &f.pos {
                let k = ((p.x - x0) / bin).floor();
                if k >= 0.0 && (k as usize) < bins {
                    heads[k as usize] += 1;
                }
            }
        }
        let area = f64::from(bin) * f64::from(width);
        heads.iter().map(|&h| h as f64 / frames.len() as f64 / area).collect()
    }

    /// Rex & Löwen's lane order at frame `k`: for each agent, its neighbours in a band
    /// `|Δy| < lane/2`, `|Δx| < reach` (x distances taken round `period` when given) count as
    /// `s` of its group and `o` of others; the order is the mean of `((s − o)/(s + o))²` over
    /// agents with a neighbour: 1 for pure lanes, near 0 for a mixed crowd.
    pub fn lane_order(&self, k: usize, lane: f32, reach: f32, period: Option<f32>) -> Option<f32> {
        let f = self.frames.get(k)?;
        let (mut sum, mut counted) = (0.0f64, 0usize);
        for (i, p) in f.pos.iter().enumerate() {
            let (mut same, mut other) = (0u32, 0u32);
            for (j, q) in f.pos.iter().enumerate() {
                if i == j {
                    continue;
                }
                let mut dx = (q.x - p.x).abs();
                if let Some(l) = period {
                    dx = dx.rem_euclid(l);
                    dx = dx.min(l - dx);
                }
                if dx < reach && (q.y - p.y).abs() < lane * 0.5 {
                    if self.group.get(i) == self.group.get(j) {
                        same += 1;
                    } else {
                        other += 1;
                    }
                }
            }
            if same + other > 0 {
                let r = (f64::from(same) - f64::from(other)) / f64::from(same + other);
                sum += r * r;
                counted += 1;
            }
        }
        (counted > 0).then(|| (sum / counted as f64) as f32)
    }

    /// Where agents jam: the samples of agents slower than `v_jam` (m/s), split by x into
    /// before `x_in`, between `x_in` and `x_out`, and after `x_out`; samples that `skip`
    /// (arrived agents standing in their goal) are not counted.
    pub fn jam_samples(&self, v_jam: f32, x_in: f32, x_out: f32, skip: impl Fn(Vec2) -> bool) -> [u32; 3] {
        let mut zones = [0u32; 3];
        for f in &self.frames {
            for (p, v) in f.pos.iter().zip(&f.vel) {
                if skip(*p) || v.length() >= v_jam {
                    continue;
                }
                let zone = if p.x < x_in {
                    0
                } else if p.x < x_out {
                    1
                } else {
                    2
                };
                zones[zone] += 1;
            }
        }
        zones
    }
}

/// One point of a fundamental diagram.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FdPoint {
    /// Density (persons/m², or persons/m in single file).
    pub density: f64,
    /// Mean speed (m/s).
    pub speed: f64,
    /// Specific flow (persons/(m·s), or persons/s in single file).
    pub flow: f64,
}

/// The exit flow (persons/s) from the times agents left: (n − 1) over the time between the
/// first and the last exit, so a room emptying at a steady rate gives that rate. `None` with
/// fewer than two exits or no time between them.
pub fn exit_flow(exit_times: &[Option<f32>]) -> Option<f64> {
    let mut times: Vec<f32> = exit_times.iter().flatten().copied().collect();
    times.sort_by(f32::total_cmp);
    let (first, last) = (*times.first()?, *times.last()?);
    (times.len() >= 2 && last > first).then(|| (times.len() - 1) as f64 / f64::from(last - first))
}

/// The number of agents out by each of `frames` frames `frame_s` apart, from their exit times:
/// RiMEA's "persons out over time" curve.
pub fn out_over_time(exit_times: &[Option<f32>], frames: usize, frame_s: f32) -> Vec<u32> {
    (0..frames)
        .map(|k| {
            let t = k as f32 * frame_s;
            exit_times.iter().flatten().filter(|&&e| e <= t).count() as u32
        })
        .collect()
}

/// The time the last agent arrived (s), or `None` if one never did.
pub fn evacuation_time(arrivals: &[Option<f32>]) -> Option<f32> {
    arrivals.iter().try_fold(0.0f32, |latest, t| t.map(|t| latest.max(t)))
}

/// Weidmann (1993): free speed 1.34 m/s, γ = 1.913 m⁻², jam density 5.4 m⁻².
pub const WEIDMANN: (f64, f64, f64) = (1.34, 1.913, 5.4);

/// Weidmann's (1993) speed at density `rho` (persons/m²), m/s:
/// `v = v0 (1 − exp(−γ (1/ρ − 1/ρmax)))`, 0 at and beyond the jam density.
pub fn weidmann_speed(rho: f64) -> f64 {
    let (v0, gamma, rho_max) = WEIDMANN;
    if rho <= 0.0 {
        return v0;
    }
    (v0 * (1.0 - (-gamma * (1.0 / rho - 1.0 / rho_max)).exp())).max(0.0)
}

/// Weidmann's (1993) specific flow at density `rho` (persons/m²), persons/(m·s): `J_s = ρ·v(ρ)`,
/// the reference line of the flow–density diagram beside the speed–density one.
pub fn weidmann_specific_flow(rho: f64) -> f64 {
    rho.max(0.0) * weidmann_speed(rho)
}

/// Seyfried et al. (2005), single file: a walker needs `0.36 + 1.06 v` metres of line, so at
/// `rho` persons/m the speed is `(1/ρ − 0.36)/1.06`, within 0…1.34 m/s.
pub fn seyfried_speed(rho: f64) -> f64 {
    if rho <= 0.0 {
        return 1.34;
    }
    ((1.0 / rho - 0.36) / 1.06).clamp(0.0, 1.34)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One agent per entry of `xs` walking with `vel`, sampled every `dt`.
    fn walk(starts: &[Vec2], vel: Vec2, frames: usize, dt: f32) -> Trajectories {
        Trajectories {
            frame_s: dt,
            group: vec![0; starts.len()],
            frames: (0..frames)
                .map(|k| Frame {
                    pos: starts.iter().map(|&p| p + vel * (k as f32 * dt)).collect(),
                    vel: vec![vel; starts.len()],
                })
                .collect(),
        }
    }

    #[test]
    fn section_speed_of_a_steady_walker_is_its_speed() {
        let t = walk(&[Vec2::new(0.0, 1.0)], Vec2::new(1.25, 0.0), 400, 0.1);
        let v = t.section_speed(0, 5.0, 35.0).expect("crosses both lines");
        assert!((v - 1.25).abs() < 1e-3, "{v}");
        assert_eq!(t.crossing_time(0, 100.0), None, "never reaches x = 100");
        let t0 = t.crossing_time(0, 5.0).expect("crosses");
        assert!((t0 - 4.0).abs() < 1e-3, "{t0}");
    }

    #[test]
    fn arrivals_min_gap_and_walls() {
        // Two walkers head-on on lines 0.5 m apart: centres come within 0.5 m.
        let mut t = walk(&[Vec2::new(0.0, 0.0)], Vec2::new(1.0, 0.0), 101, 0.1);
        let other = walk(&[Vec2::new(10.0, 0.5)], Vec2::new(-1.0, 0.0), 101, 0.1);
        for (f, g) in t.frames.iter_mut().zip(other.frames) {
            f.pos.extend(g.pos);
            f.vel.extend(g.vel);
        }
        t.group = vec![0, 1];
        let gap = t.min_gap(0, 1, 0.2, 0.2).expect("two agents");
        assert!((gap - 0.1).abs() < 1e-3, "{gap}");
        let overlap = t.min_gap(0, 1, 0.3, 0.3).expect("two agents");
        assert!(overlap < 0.0);
        let arrivals = t.arrival_times(|p| p.x >= 8.0);
        assert!((arrivals[0].expect("agent 0 reaches x = 8") - 8.0).abs() < 1e-3);
        assert_eq!(arrivals[1], Some(0.0), "agent 1 starts past x = 8");
        assert_eq!(evacuation_time(&[Some(1.0), Some(3.0)]), Some(3.0));
        assert_eq!(evacuation_time(&[Some(1.0), None]), None);
        // A wall 0.2 m wide across agent 0's line at x = 4.
        assert_eq!(t.agents_ever_inside(|p| (4.0..4.2).contains(&p.x) && p.y.abs() < 0.1), 1);
    }

    #[test]
    fn area_density_speed_and_flow() {
        // 2 agents per metre on a 1 m wide strip, walking 0.8 m/s: ρ = 2, v = 0.8, J = 1.6.
        let starts: Vec<Vec2> = (0..40).map(|i| Vec2::new(i as f32 * 0.5, 0.5)).collect();
        let mut t = walk(&starts, Vec2::new(0.8, 0.0), 50, 0.1);
        // Wrap positions into a 20 m ring so the area keeps its count.
        for f in &mut t.frames {
            for p in &mut f.pos {
                p.x = p.x.rem_euclid(20.0);
            }
        }
        let area = Area { min: Vec2::new(5.0, 0.0), max: Vec2::new(15.0, 1.0) };
        let fd = t.area_fundamental(area, 10).expect("agents inside");
        assert!((fd.density - 2.0).abs() < 0.11, "{fd:?}");
        assert!((fd.speed - 0.8).abs() < 1e-5, "{fd:?}");
        assert!((fd.flow - fd.density * fd.speed).abs() < 1e-12);
        assert_eq!(t.area_fundamental(area, 50), None, "no frame left");
    }

    #[test]
    fn density_profile_counts_heads_per_bin() {
        // 3 agents in the first 2 m bin, 1 in the second, none in the third, on a 1 m strip.
        let starts = [0.5, 1.0, 1.9, 2.5].map(|x| Vec2::new(x, 0.5));
        let t = walk(&starts, Vec2::ZERO, 4, 0.1);
        assert_eq!(t.density_profile(0.0, 2.0, 3, 1.0, 1), vec![1.5, 0.5, 0.0]);
        assert!(t.density_profile(0.0, 2.0, 3, 1.0, 4).is_empty(), "no frame left");
    }

    #[test]
    fn lane_order_is_one_for_lanes_and_zero_for_a_checkerboard() {
        let lanes = Trajectories {
            frame_s: 1.0,
            group: vec![0, 0, 0, 1, 1, 1],
            frames: vec![Frame {
                pos: vec![
                    Vec2::new(0.0, 0.5),
                    Vec2::new(1.0, 0.5),
                    Vec2::new(2.0, 0.5),
                    Vec2::new(0.0, 1.5),
                    Vec2::new(1.0, 1.5),
                    Vec2::new(2.0, 1.5),
                ],
                vel: vec![Vec2::ZERO; 6],
            }],
        };
        assert_eq!(lanes.lane_order(0, 0.6, 3.0, None), Some(1.0));
        // One line alternating groups on a ring of 4: each agent has 1 same, 2 others → 1/9.
        let mixed = Trajectories {
            frame_s: 1.0,
            group: vec![0, 1, 0, 1],
            frames: vec![Frame {
                pos: (0..4).map(|i| Vec2::new(i as f32, 0.5)).collect(),
                vel: vec![Vec2::ZERO; 4],
            }],
        };
        let order = mixed.lane_order(0, 0.6, 2.5, Some(4.0)).expect("neighbours");
        assert!((order - 1.0 / 9.0).abs() < 1e-6, "{order}");
        // Without the ring, the end agents see 1 same and 1 other (0) or 0 same 1 other (1).
        assert!(mixed.lane_order(0, 0.6, 1.5, None).expect("neighbours") > 0.99);
        assert_eq!(mixed.lane_order(3, 0.6, 1.5, None), None, "no such frame");
    }

    #[test]
    fn jam_zones_and_exit_flow() {
        let t = Trajectories {
            frame_s: 1.0,
            group: vec![0; 4],
            frames: vec![Frame {
                pos: vec![
                    Vec2::new(1.0, 0.0),
                    Vec2::new(5.0, 0.0),
                    Vec2::new(9.0, 0.0),
                    Vec2::new(20.0, 0.0),
                ],
                vel: vec![Vec2::ZERO, Vec2::new(0.05, 0.0), Vec2::new(1.0, 0.0), Vec2::ZERO],
            }],
        };
        assert_eq!(t.jam_samples(0.1, 4.0, 8.0, |p| p.x > 15.0), [1, 1, 0]);
        // Ten exits one every 0.5 s: 2 persons/s.
        let times: Vec<Option<f32>> = (0..10).map(|k| Some(3.0 + k as f32 * 0.5)).chain([None]).collect();
        assert!((exit_flow(&times).expect("flow") - 2.0).abs() < 1e-9);
        assert_eq!(exit_flow(&[Some(1.0)]), None);
    }

    #[test]
    fn exit_line_crossings_are_counted_once_inside_the_span() {
        // Three walkers going up past y = 1: one inside the span x 10…12, one beside it, one
        // that crosses, turns back and crosses again (counted once, at its first crossing).
        let line = ExitLine::Upward { y: 1.0, span: (10.0, 12.0) };
        let t = Trajectories {
            frame_s: 0.5,
            group: vec![0; 3],
            frames: [3.0, 2.0, 0.5, 1.5, 0.5]
                .iter()
                .enumerate()
                .map(|(k, &y)| Frame {
                    pos: vec![
                        Vec2::new(11.0, 3.0 - k as f32),
                        Vec2::new(9.0, 3.0 - k as f32),
                        Vec2::new(10.5, y),
                    ],
                    vel: vec![Vec2::ZERO; 3],
                })
                .collect(),
        };
        let times = t.crossing_times(line);
        assert!((times[0].expect("crosses") - 1.0).abs() < 1e-6, "{times:?}");
        assert_eq!(times[1], None, "passes beside the line");
        assert!((times[2].expect("crosses") - (0.5 + 0.5 * (1.0 / 1.5))).abs() < 1e-6, "{times:?}");
        assert_eq!(out_over_time(&times, 5, 0.5), vec![0, 0, 2, 2, 2]);
        let right = ExitLine::Rightward { x: 5.0, span: (0.0, 2.0) };
        assert!(right.is_out(Vec2::new(5.0, 1.0)) && !right.is_out(Vec2::new(4.9, 1.0)));
        assert_eq!(right.crossing(Vec2::new(4.0, 1.0), Vec2::new(6.0, 1.0)), Some(0.5));
        assert_eq!(right.crossing(Vec2::new(6.0, 1.0), Vec2::new(4.0, 1.0)), None, "walking back in");
    }

    #[test]
    fn reference_curves() {
        assert!((weidmann_speed(0.0) - 1.34).abs() < 1e-12);
        assert_eq!(weidmann_speed(5.4), 0.0);
        assert_eq!(weidmann_speed(6.0), 0.0);
        // Weidmann's flow peaks near 1.2 persons/(m·s) at about 1.75 persons/m².
        let (peak, at) = (1..=60)
            .map(|k| k as f64 / 10.0)
            .map(|r| (weidmann_specific_flow(r), r))
            .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
        assert!((1.15..1.3).contains(&peak), "{peak}");
        assert!((1.5..2.0).contains(&at), "{at}");
        // Nobody passes at zero density or in a jam: the flow curve starts and ends at 0.
        assert_eq!(weidmann_specific_flow(0.0), 0.0);
        assert_eq!(weidmann_specific_flow(5.4), 0.0);
        assert!((weidmann_speed(1.0) - 1.34 * (1.0 - (-1.913f64 * (1.0 - 1.0 / 5.4)).exp())).abs() < 1e-12);
        assert!((seyfried_speed(1.0) - (0.64 / 1.06)).abs() < 1e-12);
        assert_eq!(seyfried_speed(0.1), 1.34);
        assert_eq!(seyfried_speed(3.0), 0.0);
    }
}
