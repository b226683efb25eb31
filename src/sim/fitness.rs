//! The five elementary fitness measures of the GA-tuned virtual-force paper (DESIGN §3.5) and the
//! behaviours (B1–B3) and environments (E1–E3) of its experiment.
//!
//! Every measure is in [0, 1], computed per agent over its k = 7 nearest neighbours, averaged
//! over the agents of a frame, then over the frames:
//! - Gm, spacing: `min(1, Q_d / |R_j − R_e|)`, `R_j` the mean distance to the k nearest (14.2–14.4);
//! - Gg, goal distance: the same form with the distance to the goal and a desired distance `R_g`;
//! - Gc, no collision: the share of agents whose disc overlaps no other agent and no obstacle (14.5);
//! - Ga, orientation: `1 − mean_i |θ_j − θ_i| / π` over the k nearest (14.6–14.7);
//! - Gd, distance consistency: `min(1, Q_σ / σ_j)`, `σ_j` the deviation of those k distances (14.8–14.10).
//!
//! `Gsum = Sm Gm + Sg Gg + Sc Gc + Sa Ga + Sd Gd` (14.11), S chosen per behaviour.

use crate::model::forces_cases::Behaviour;
use crate::model::geometry::{Aabb, Obstacle};
use crate::spatial::{ObstacleIndex, QueryCap, SpatialGrid};
use glam::Vec2;
use serde::{Deserialize, Serialize};

/// Normalisations and quantisation factors of the measures. Lengths in px.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FitnessParams {
    /// Neighbours per agent (paper, after Miller: 7).
    pub k: u32,
    /// Neighbours farther than this are not counted among the k nearest (px).
    pub neighbour_radius: f32,
    /// `R_e`, the desired mean distance to the k nearest (px).
    pub desired_spacing: f32,
    /// `Q_d`: a spacing error up to this scores 1, beyond it `Q_d / error` (px).
    pub spacing_quantum: f32,
    /// Desired distance to the goal (px): 0 to follow, the guard radius to surround.
    pub desired_goal_distance: f32,
    /// Quantisation of the goal-distance error (px).
    pub goal_quantum: f32,
    /// `Q_σ`: a deviation of the k distances up to this scores 1 (px).
    pub spread_quantum: f32,
}

impl Default for FitnessParams {
    fn default() -> Self {
        Self {
            k: 7,
            neighbour_radius: 160.0,
            desired_spacing: 24.0,
            spacing_quantum: 4.0,
            desired_goal_distance: 0.0,
            goal_quantum: 40.0,
            spread_quantum: 4.0,
        }
    }
}

/// The designer's weights S of the five measures in Gsum.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct FitnessWeights {
    /// Sm, inter-agent distance.
    pub spacing: f64,
    /// Sg, distance to the goal.
    pub goal: f64,
    /// Sc, collision-free share.
    pub collision: f64,
    /// Sa, orientation consistency.
    pub orientation: f64,
    /// Sd, distance consistency.
    pub distance: f64,
}

/// The five measures, each in [0, 1].
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FitnessMeasures {
    /// Gm, inter-agent distance.
    pub gm: f64,
    /// Gg, distance to the goal.
    pub gg: f64,
    /// Gc, share of agents not in collision.
    pub gc: f64,
    /// Ga, orientation consistency.
    pub ga: f64,
    /// Gd, distance consistency.
    pub gd: f64,
}

impl FitnessMeasures {
    /// `Gsum = Sm Gm + Sg Gg + Sc Gc + Sa Ga + Sd Gd`.
    pub fn gsum(&self, s: &FitnessWeights) -> f64 {
        s.spacing * self.gm
            + s.goal * self.gg
            + s.collision * self.gc
            + s.orientation * self.ga
            + s.distance * self.gd
    }
}

/// `min(1, quantum / error)`: the paper's "normalised by the quantisation factor, clipped to (0, 1]".
#[inline]
pub fn quantised(quantum: f32, error: f32) -> f64 {
    if error <= quantum {
        1.0
    } else {
        f64::from(quantum / error)
    }
}

/// Absolute difference of two angles, wrapped into [0, π].
#[inline]
pub fn angle_difference(a: f32, b: f32) -> f32 {
    use std::f32::consts::TAU;
    let d = (a - b).abs();
    // Headings come from atan2 (within ±π), so d ≤ 2π and the remainder is rarely needed: `%`
    // is a library call that cost a third of a fitness sample. Below 2π it returns d unchanged,
    // and at exactly 2π both ways give 0.
    let d = if d > TAU { d % TAU } else { d };
    d.min(TAU - d)
}

/// The same as [`SpatialGrid::k_nearest`] (the `k` nearest by `(distance², id)`, `exclude` left
/// out), but cheaper in a crowd: see [`k_nearest_from`], starting with a disc of one grid cell.
pub fn k_nearest(
    grid: &SpatialGrid,
    p: Vec2,
    k: usize,
    radius: f32,
    exclude: u32,
    out: &mut Vec<(f32, u32)>,
) {
    k_nearest_from(grid, p, k, radius, exclude, grid.cell_size(), out);
}

/// Neighbours (and candidates of the scanned cells) one query of the measures looks at, the
/// first in the grid's scan order. The 7 nearest of a crowd of non-overlapping 4 px discs lie
/// within about 20 px, among some 100 agents of the 40 px cells scanned; a sparse crowd widens
/// the disc but holds fewer agents. Only a pile reaches the cap, which bounds its cost per agent
/// (the measures then look at the first agents of the pile in scan order).
pub const FITNESS_QUERY_CAP: QueryCap = QueryCap { neighbours: 256, candidates: 256 };

/// [`k_nearest`] searching a disc of `start` px first and doubling it until the disc holds k
/// agents or reaches `radius`. Agents outside a disc that holds k are all farther than the k-th,
/// so the result does not depend on `start` (only the cost does); then it selects before sorting.
/// Each disc is searched within [`FITNESS_QUERY_CAP`] (a capped disc is the last searched).
pub fn k_nearest_from(
    grid: &SpatialGrid,
    p: Vec2,
    k: usize,
    radius: f32,
    exclude: u32,
    start: f32,
    out: &mut Vec<(f32, u32)>,
) {
    k_nearest_gathered(NearestQuery { grid, p, k, radius, exclude, start }, &mut Vec::new(), out);
}

/// One k-nearest query of the measures: the `k` nearest to `p` within `radius`, `exclude` left
/// out, searched in discs from `start` px (see [`k_nearest_from`]).
#[derive(Clone, Copy)]
struct NearestQuery<'a> {
    grid: &'a SpatialGrid,
    p: Vec2,
    k: usize,
    radius: f32,
    exclude: u32,
    start: f32,
}

impl NearestQuery<'_> {
    /// The disc search both forms of the query share: gathers a disc of `start` px (at least 1)
    /// into `slots` by [`SpatialGrid::gather_within`] (the agents
    /// [`SpatialGrid::for_each_within_capped`] visits, in its order, under
    /// [`FITNESS_QUERY_CAP`], found without a branch per candidate) and hands it to `take`, which
    /// returns how many agents other than `exclude` it found; doubles the disc until that is at
    /// least k, the disc reaches `radius`, or a cap bound (a capped disc is the last searched).
    #[inline]
    fn search_discs(&self, slots: &mut Vec<u32>, mut take: impl FnMut(&[u32]) -> usize) {
        let mut reach = self.start.max(1.0);
        loop {
            let disc = reach.min(self.radius);
            let capped = self.grid.gather_within(self.p, disc, FITNESS_QUERY_CAP, slots);
            if take(slots) >= self.k || disc >= self.radius || capped {
                break;
            }
            reach *= 2.0;
        }
    }
}

/// [`k_nearest_from`] with a reused buffer `slots` for the grid's storage slots: each disc of
/// [`NearestQuery::search_discs`], then its distances are those the grid's query computes.
fn k_nearest_gathered(query: NearestQuery, slots: &mut Vec<u32>, out: &mut Vec<(f32, u32)>) {
    match query.k {
        1..=8 => return k_nearest_sorted::<8>(query, slots, out),
        9..=16 => return k_nearest_sorted::<16>(query, slots, out),
        _ => {}
    }
    let NearestQuery { grid, p, k, exclude, .. } = query;
    let columns = grid.columns();
    query.search_discs(slots, |slots| {
        out.clear();
        out.extend(slots.iter().filter_map(|&slot| {
            let slot = slot as usize;
            let id = *columns.ids.get(slot)?;
            let q = Vec2::new(*columns.x.get(slot)?, *columns.y.get(slot)?);
            (id != exclude).then(|| (p.distance_squared(q), id))
        }));
        out.len()
    });
    let order = |a: &(f32, u32), b: &(f32, u32)| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1));
    if out.len() > k && k > 0 {
        out.select_nth_unstable_by(k - 1, order);
    }
    out.truncate(k);
    out.sort_unstable_by(order);
}

/// The key ordering `(distance², id)` as [`k_nearest_gathered`] does (`f32::total_cmp`, then
/// the id) when compared as unsigned integers: `total_cmp`'s integer form of the distance with
/// its sign bit flipped (so unsigned order is its signed order), above the id.
#[inline]
fn nearest_key(d2: f32, id: u32) -> u64 {
    let bits = d2.to_bits();
    let ordered = bits ^ ((((bits as i32) >> 31) as u32) >> 1);
    (u64::from(ordered ^ 0x8000_0000) << 32) | u64::from(id)
}

/// The `(distance², id)` of a [`nearest_key`] (its transform of the bits is its own inverse:
/// it keeps the sign bit it depends on).
#[inline]
fn from_nearest_key(key: u64) -> (f32, u32) {
    let ordered = ((key >> 32) as u32) ^ 0x8000_0000;
    let bits = ordered ^ ((((ordered as i32) >> 31) as u32) >> 1);
    (f32::from_bits(bits), key as u32)
}

/// [`k_nearest_gathered`] for `k ≤ K`, the same discs and the same result, keeping the k
/// nearest as it goes: each candidate's [`nearest_key`] sinks through a sorted list of the `K`
/// smallest so far by a minimum and a maximum per place, without a branch. The selection and
/// sort it replaces branched on comparisons the CPU could not predict (a fifth of a sample).
/// Keys are distinct (ids are), so the first k of the list are the k smallest, in order.
fn k_nearest_sorted<const K: usize>(query: NearestQuery, slots: &mut Vec<u32>, out: &mut Vec<(f32, u32)>) {
    let NearestQuery { grid, p, k, exclude, .. } = query;
    let columns = grid.columns();
    let mut best = [u64::MAX; K];
    let mut found = 0usize;
    query.search_discs(slots, |slots| {
        best = [u64::MAX; K];
        found = 0;
        for &slot in slots {
            let slot = slot as usize;
            let (Some(&id), Some(&x), Some(&y)) =
                (columns.ids.get(slot), columns.x.get(slot), columns.y.get(slot))
            else {
                continue;
            };
            if id == exclude {
                continue;
            }
            found += 1;
            let mut key = nearest_key(p.distance_squared(Vec2::new(x, y)), id);
            for place in &mut best {
                let low = (*place).min(key);
                key = (*place).max(key);
                *place = low;
            }
        }
        found
    });
    out.clear();
    out.extend(best.iter().take(found.min(k)).map(|&key| from_nearest_key(key)));
}

/// One frame of the crowd as the fitness measures read it (struct-of-arrays, agent `i` at index
/// `i` of each slice).
#[derive(Clone, Copy)]
pub struct Frame<'a> {
    /// Centres (px).
    pub pos: &'a [Vec2],
    /// Velocities (px/step).
    pub vel: &'a [Vec2],
    /// Body radii (px).
    pub radius: &'a [f32],
    /// Each agent's goal position; agents without one are left out of Gg.
    pub goals: &'a [Option<Vec2>],
    /// The scene's obstacles.
    pub obstacles: &'a ObstacleIndex,
    /// Each agent's group; empty for no per-group measures.
    pub group_of: &'a [u32],
}

/// Accumulates the measures frame by frame.
#[derive(Clone, Debug)]
pub struct FitnessRecorder {
    params: FitnessParams,
    grid: SpatialGrid,
    /// Last heading of each agent (rad): kept while an agent stands still.
    headings: Vec<f32>,
    sums: [f64; 5],
    goal_frames: u64,
    frames: u64,
    near: Vec<(f32, u32)>,
    /// Scratch: the grid slots of a neighbour query.
    slots: Vec<u32>,
    /// Per-group sums over frames, filled by [`FitnessRecorder::record`].
    groups: Vec<GroupSums>,
    /// This frame's per-group sums over agents (reused buffer).
    frame_groups: Vec<GroupFrame>,
}

/// One group's measures summed over frames (each frame's value a mean over the group's agents).
#[derive(Clone, Copy, Debug, Default)]
struct GroupSums {
    sums: [f64; 5],
    goal_frames: u64,
    frames: u64,
}

/// One group's measures summed over its agents within a frame.
#[derive(Clone, Copy, Debug, Default)]
struct GroupFrame {
    sums: [f64; 5],
    agents: u32,
    with_goal: u32,
}

/// Mean of `sum` over `frames` (0 when there are none).
fn per_frame(sum: f64, frames: u64) -> f64 {
    if frames == 0 {
        0.0
    } else {
        sum / frames as f64
    }
}

impl FitnessRecorder {
    /// A recorder for `agents` agents in a `width × height` world.
    pub fn new(params: FitnessParams, width: f32, height: f32, agents: usize) -> Self {
        // A quarter of the neighbour radius: the k nearest usually lie in the first disc
        // [`k_nearest`] searches (one cell), which then scans few cells.
        let cell = (0.25 * params.neighbour_radius).max(1.0);
        Self {
            grid: SpatialGrid::new(width, height, cell, agents),
            headings: vec![0.0; agents],
            params,
            sums: [0.0; 5],
            goal_frames: 0,
            frames: 0,
            near: Vec::new(),
            slots: Vec::new(),
            groups: Vec::new(),
            frame_groups: Vec::new(),
        }
    }

    /// The parameters.
    pub fn params(&self) -> &FitnessParams {
        &self.params
    }

    /// Frames recorded so far.
    pub fn frames(&self) -> u64 {
        self.frames
    }

    /// Records one frame, overall and per group (see [`Frame`]). Degenerate frames (no agents)
    /// are skipped. A group's measures average its own agents; their k nearest neighbours come
    /// from any group (the crowd an agent is in), so the overall measures are unchanged by
    /// grouping.
    pub fn record(&mut self, frame: Frame) {
        let Frame { pos, vel, radius, goals, obstacles, group_of } = frame;
        let n = pos.len();
        let groups = group_of.iter().map(|&g| g as usize + 1).max().unwrap_or(0);
        if self.groups.len() < groups {
            self.groups.resize(groups, GroupSums::default());
        }
        self.frame_groups.clear();
        self.frame_groups.resize(groups, GroupFrame::default());
        if n == 0 {
            return;
        }
        self.headings.resize(n, 0.0);
        for (h, v) in self.headings.iter_mut().zip(vel) {
            if v.length_squared() > 1e-8 {
                *h = libm::atan2f(v.y, v.x);
            }
        }
        self.grid.rebuild(pos, vel);
        let prm = &self.params;
        let max_radius = radius.iter().copied().fold(0.0f32, f32::max);
        let (mut gm, mut gg, mut gc, mut ga, mut gd) = (0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64);
        let mut with_goal = 0u32;
        let mut reach = self.grid.cell_size();
        for (j, &p) in pos.iter().enumerate() {
            let r = radius.get(j).copied().unwrap_or(0.0);
            // The k nearest within the radius; an agent alone scores 0 on Gm, Ga and Gd.
            // The previous agent's k-th distance is a good first disc in an even crowd.
            let query = NearestQuery {
                grid: &self.grid,
                p,
                k: prm.k as usize,
                radius: prm.neighbour_radius,
                exclude: j as u32,
                start: reach,
            };
            k_nearest_gathered(query, &mut self.slots, &mut self.near);
            reach = self.near.last().map_or(reach, |(d2, _)| d2.sqrt() * 1.05);
            // This agent's values: [Gm, Gg, Gc, Ga, Gd] (Gc below).
            let mut mine = [0.0f64; 5];
            if !self.near.is_empty() {
                let k = self.near.len() as f32;
                let mean = self.near.iter().map(|(d2, _)| d2.sqrt()).sum::<f32>() / k;
                let var = self.near.iter().map(|(d2, _)| (d2.sqrt() - mean).powi(2)).sum::<f32>() / k;
                let orient = self
                    .near
                    .iter()
                    .map(|&(_, i)| angle_difference(self.headings[j], self.headings[i as usize]))
                    .sum::<f32>()
                    / k;
                mine[0] = quantised(prm.spacing_quantum, (mean - prm.desired_spacing).abs());
                mine[4] = quantised(prm.spread_quantum, var.sqrt());
                mine[3] = 1.0 - f64::from(orient / std::f32::consts::PI);
                gm += mine[0];
                gd += mine[4];
                ga += mine[3];
            }
            let has_goal = if let Some(goal) = goals.get(j).copied().flatten() {
                with_goal += 1;
                mine[1] = quantised(prm.goal_quantum, (p.distance(goal) - prm.desired_goal_distance).abs());
                gg += mine[1];
                true
            } else {
                false
            };
            // The first overlap settles it (in a jam, usually the first candidate or so).
            let mut hit = self.grid.any_within_capped(p, r + max_radius, FITNESS_QUERY_CAP, |q| {
                let rq = radius.get(q.id as usize).copied().unwrap_or(0.0);
                q.id != j as u32 && q.d2 < (r + rq) * (r + rq)
            });
            if !hit && !obstacles.is_empty() {
                // The world pushes agents out to `radius + 0.01`: only a real overlap counts.
                obstacles.for_each_near(Aabb { min: p, max: p }.inflate(r), |_, o: &Obstacle| {
                    hit |= o.surface(p).signed_distance < r - 1e-3;
                });
            }
            if !hit {
                gc += 1.0;
                mine[2] = 1.0;
            }
            if let Some(frame) = group_of.get(j).and_then(|&g| self.frame_groups.get_mut(g as usize)) {
                for (sum, value) in frame.sums.iter_mut().zip(mine) {
                    *sum += value;
                }
                frame.agents += 1;
                frame.with_goal += u32::from(has_goal);
            }
        }
        for (total, frame) in self.groups.iter_mut().zip(&self.frame_groups) {
            if frame.agents == 0 {
                continue;
            }
            let inv = 1.0 / f64::from(frame.agents);
            for i in [0, 2, 3, 4] {
                total.sums[i] += frame.sums[i] * inv;
            }
            if frame.with_goal > 0 {
                total.sums[1] += frame.sums[1] / f64::from(frame.with_goal);
                total.goal_frames += 1;
            }
            total.frames += 1;
        }
        let inv = 1.0 / n as f64;
        self.sums[0] += gm * inv;
        self.sums[2] += gc * inv;
        self.sums[3] += ga * inv;
        self.sums[4] += gd * inv;
        if with_goal > 0 {
            self.sums[1] += gg / f64::from(with_goal);
            self.goal_frames += 1;
        }
        self.frames += 1;
    }

    /// The measures averaged over the frames recorded (all 0 before the first frame).
    pub fn measures(&self) -> FitnessMeasures {
        measures_of(&self.sums, self.frames, self.goal_frames)
    }

    /// Group `g`'s measures averaged over the frames recorded with
    /// [`FitnessRecorder::record`] in which it had agents; `None` before the first.
    pub fn group_measures(&self, g: usize) -> Option<FitnessMeasures> {
        let group = self.groups.get(g).filter(|group| group.frames > 0)?;
        Some(measures_of(&group.sums, group.frames, group.goal_frames))
    }
}

/// Sums over frames → means; Gg over the frames that had an agent with a goal.
fn measures_of(sums: &[f64; 5], frames: u64, goal_frames: u64) -> FitnessMeasures {
    FitnessMeasures {
        gm: per_frame(sums[0], frames),
        gg: per_frame(sums[1], goal_frames),
        gc: per_frame(sums[2], frames),
        ga: per_frame(sums[3], frames),
        gd: per_frame(sums[4], frames),
    }
}

impl Behaviour {
    /// The measures' parameters expressing this behaviour.
    pub fn fitness_params(self) -> FitnessParams {
        let base = FitnessParams::default();
        match self {
            // A loose group (3 body sizes apart) that reaches its goal.
            Behaviour::GroupMoving => FitnessParams { desired_spacing: 24.0, goal_quantum: 40.0, ..base },
            // Close to the goal and to each other (1.5 body sizes).
            Behaviour::Following => {
                FitnessParams { desired_spacing: 12.0, spacing_quantum: 3.0, goal_quantum: 25.0, ..base }
            }
            // On a ring 48 px around the goal.
            Behaviour::Guarding => FitnessParams {
                desired_spacing: 20.0,
                desired_goal_distance: 48.0,
                goal_quantum: 8.0,
                ..base
            },
        }
    }

    /// The designer's weights S (they sum to 100, so Gsum is a score out of 100).
    pub fn weights(self) -> FitnessWeights {
        match self {
            Behaviour::GroupMoving => FitnessWeights {
                spacing: 35.0,
                goal: 20.0,
                collision: 20.0,
                orientation: 15.0,
                distance: 10.0,
            },
            Behaviour::Following => FitnessWeights {
                spacing: 10.0,
                goal: 45.0,
                collision: 25.0,
                orientation: 10.0,
                distance: 10.0,
            },
            Behaviour::Guarding => FitnessWeights {
                spacing: 20.0,
                goal: 40.0,
                collision: 25.0,
                orientation: 5.0,
                distance: 10.0,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_obstacles() -> ObstacleIndex {
        ObstacleIndex::new(vec![], 1000.0, 1000.0)
    }

    fn params(k: u32) -> FitnessParams {
        FitnessParams {
            k,
            neighbour_radius: 500.0,
            desired_spacing: 10.0,
            spacing_quantum: 2.0,
            desired_goal_distance: 0.0,
            goal_quantum: 5.0,
            spread_quantum: 1.0,
        }
    }

    #[test]
    fn quantisation_clips_to_one() {
        assert_eq!(quantised(2.0, 0.0), 1.0);
        assert_eq!(quantised(2.0, 2.0), 1.0);
        assert_eq!(quantised(2.0, 8.0), 0.25);
        assert_eq!(quantised(0.0, 0.0), 1.0);
        assert!((angle_difference(3.0, -3.0) - (std::f32::consts::TAU - 6.0)).abs() < 1e-6);
        assert!((angle_difference(0.5, 0.25) - 0.25).abs() < 1e-6);
    }

    #[test]
    fn three_agents_in_a_row_by_hand() {
        // Agents at x = 0, 10, 30 (y = 100), k = 2, all neighbours of each other.
        // Mean distances: a 20, b 15, c 25 → errors 10, 5, 15 → Gm = (0.2 + 0.4 + 2/15) / 3.
        // Deviations: a 10, b 5, c 5 → Gd = (0.1 + 0.2 + 0.2) / 3.
        // Headings 0, 0, π/2: a and b each see one same and one perpendicular heading (1 − ¼),
        // c sees two perpendicular ones (1 − ½) → Ga = (0.75 + 0.75 + 0.5) / 3.
        // Goal at (0, 100): distances 0, 10, 30 → Gg = (1 + 0.5 + 1/6) / 3. No overlap: Gc = 1.
        let pos = [Vec2::new(100.0, 100.0), Vec2::new(110.0, 100.0), Vec2::new(130.0, 100.0)];
        let vel = [Vec2::X, Vec2::X, Vec2::Y];
        let mut rec = FitnessRecorder::new(params(2), 1000.0, 1000.0, 3);
        let goal = Some(Vec2::new(100.0, 100.0));
        rec.record(Frame {
            pos: &pos,
            vel: &vel,
            radius: &[1.0; 3],
            goals: &[goal; 3],
            obstacles: &no_obstacles(),
            group_of: &[],
        });
        let m = rec.measures();
        let close = |a: f64, b: f64| (a - b).abs() < 1e-6;
        assert!(close(m.gm, (0.2 + 0.4 + 2.0 / 15.0) / 3.0), "{m:?}");
        assert!(close(m.gd, 0.5 / 3.0), "{m:?}");
        assert!(close(m.ga, (0.75 + 0.75 + 0.5) / 3.0), "{m:?}");
        assert!(close(m.gg, (1.0 + 0.5 + 1.0 / 6.0) / 3.0), "{m:?}");
        assert!(close(m.gc, 1.0), "{m:?}");
    }

    #[test]
    fn collisions_with_agents_and_obstacles_count_once_per_agent() {
        // a and b overlap (distance 3 < 2 + 2); c sits in an obstacle; d is free: Gc = 1/4.
        let pos = [
            Vec2::new(100.0, 100.0),
            Vec2::new(103.0, 100.0),
            Vec2::new(300.0, 300.0),
            Vec2::new(500.0, 500.0),
        ];
        let obstacles = ObstacleIndex::new(
            vec![Obstacle::Circle { center: [302.0, 300.0], radius: 5.0 }],
            1000.0,
            1000.0,
        );
        let mut rec = FitnessRecorder::new(params(2), 1000.0, 1000.0, 4);
        rec.record(Frame {
            pos: &pos,
            vel: &[Vec2::X; 4],
            radius: &[2.0; 4],
            goals: &[None; 4],
            obstacles: &obstacles,
            group_of: &[],
        });
        assert!((rec.measures().gc - 0.25).abs() < 1e-9);
        // No agent has a goal: Gg stays 0 rather than averaging nothing.
        assert_eq!(rec.measures().gg, 0.0);
    }

    #[test]
    fn frames_average_and_gsum_weighs() {
        let mut rec = FitnessRecorder::new(params(1), 1000.0, 1000.0, 2);
        // Frame 1: spacing 10 (exact) → Gm 1; frame 2: spacing 30 → error 20 → 0.1.
        rec.record(Frame {
            pos: &[Vec2::new(0.0, 0.0), Vec2::new(10.0, 0.0)],
            vel: &[Vec2::X; 2],
            radius: &[1.0; 2],
            goals: &[None; 2],
            obstacles: &no_obstacles(),
            group_of: &[],
        });
        rec.record(Frame {
            pos: &[Vec2::new(0.0, 0.0), Vec2::new(30.0, 0.0)],
            vel: &[Vec2::X; 2],
            radius: &[1.0; 2],
            goals: &[None; 2],
            obstacles: &no_obstacles(),
            group_of: &[],
        });
        let m = rec.measures();
        assert_eq!(rec.frames(), 2);
        assert!((m.gm - 0.55).abs() < 1e-6, "{m:?}");
        // One neighbour: no spread, same heading.
        assert_eq!((m.gd, m.ga, m.gc), (1.0, 1.0, 1.0));
        let s = FitnessWeights { spacing: 2.0, goal: 100.0, collision: 1.0, orientation: 1.0, distance: 1.0 };
        assert!((m.gsum(&s) - (1.1 + 3.0)).abs() < 1e-6);
    }

    #[test]
    fn groups_average_their_own_agents_and_leave_the_overall_unchanged() {
        // Group 0: a at 100, b at 110 (y = 100); group 1: c at 130. k = 2, neighbours from any
        // group, so every agent's values are those of `three_agents_in_a_row_by_hand`:
        // Gm a 0.2, b 0.4, c 2/15; Gd 0.1, 0.2, 0.2; Ga 0.75, 0.75, 0.5; Gg 1, 0.5, 1/6.
        let pos = [Vec2::new(100.0, 100.0), Vec2::new(110.0, 100.0), Vec2::new(130.0, 100.0)];
        let vel = [Vec2::X, Vec2::X, Vec2::Y];
        let goals = [Some(Vec2::new(100.0, 100.0)); 3];
        let mut grouped = FitnessRecorder::new(params(2), 1000.0, 1000.0, 3);
        grouped.record(Frame {
            pos: &pos,
            vel: &vel,
            radius: &[1.0; 3],
            goals: &goals,
            obstacles: &no_obstacles(),
            group_of: &[0, 0, 1],
        });
        let mut plain = FitnessRecorder::new(params(2), 1000.0, 1000.0, 3);
        plain.record(Frame {
            pos: &pos,
            vel: &vel,
            radius: &[1.0; 3],
            goals: &goals,
            obstacles: &no_obstacles(),
            group_of: &[],
        });
        assert_eq!(grouped.measures(), plain.measures());
        assert_eq!(plain.group_measures(0), None, "record alone keeps no groups");

        let close = |a: f64, b: f64| (a - b).abs() < 1e-6;
        let first = grouped.group_measures(0).expect("group 0 sampled");
        assert!(close(first.gm, 0.3) && close(first.gd, 0.15), "{first:?}");
        assert!(close(first.ga, 0.75) && close(first.gg, 0.75) && close(first.gc, 1.0), "{first:?}");
        let second = grouped.group_measures(1).expect("group 1 sampled");
        assert!(close(second.gm, 2.0 / 15.0) && close(second.gg, 1.0 / 6.0), "{second:?}");
        assert!(close(second.ga, 0.5) && close(second.gd, 0.2), "{second:?}");
        assert_eq!(grouped.group_measures(2), None);

        // A second frame where group 1 has no goal: its Gg averages the first frame only.
        grouped.record(Frame {
            pos: &pos,
            vel: &vel,
            radius: &[1.0; 3],
            goals: &[goals[0], goals[1], None],
            obstacles: &no_obstacles(),
            group_of: &[0, 0, 1],
        });
        let second = grouped.group_measures(1).expect("group 1 sampled");
        assert!(close(second.gg, 1.0 / 6.0) && close(second.gm, 2.0 / 15.0), "{second:?}");
    }

    #[test]
    fn angle_difference_is_the_shorter_way_round() {
        use std::f32::consts::{PI, TAU};
        assert_eq!(angle_difference(PI, -PI), 0.0);
        assert!((angle_difference(0.1, TAU + 0.3) - 0.2).abs() < 1e-5, "beyond a full turn");
        assert!((angle_difference(-3.0, 3.0) - (TAU - 6.0)).abs() < 1e-6);
        assert!((angle_difference(-PI / 2.0, PI / 2.0) - PI).abs() < 1e-6);
    }

    #[test]
    fn a_lone_agent_and_an_empty_frame() {
        let mut rec = FitnessRecorder::new(params(7), 1000.0, 1000.0, 1);
        rec.record(Frame {
            pos: &[],
            vel: &[],
            radius: &[],
            goals: &[],
            obstacles: &no_obstacles(),
            group_of: &[],
        });
        assert_eq!(rec.frames(), 0);
        rec.record(Frame {
            pos: &[Vec2::new(5.0, 5.0)],
            vel: &[Vec2::ZERO],
            radius: &[1.0],
            goals: &[None],
            obstacles: &no_obstacles(),
            group_of: &[],
        });
        let m = rec.measures();
        assert_eq!((m.gm, m.ga, m.gd, m.gc), (0.0, 0.0, 0.0, 1.0));
    }

    #[test]
    fn selecting_k_nearest_equals_the_grid_query() {
        let mut rng = crate::rng::Rng::new(4, 0);
        let points: Vec<Vec2> =
            (0..300).map(|_| Vec2::new(rng.range(0.0, 200.0), rng.range(0.0, 200.0).floor())).collect();
        let mut grid = SpatialGrid::new(200.0, 200.0, 20.0, points.len());
        grid.rebuild(&points, &[]);
        let (mut ours, mut theirs) = (Vec::new(), Vec::new());
        for (i, &p) in points.iter().enumerate() {
            for k in [0, 1, 7, 8, 9, 16, 17, 400] {
                k_nearest(&grid, p, k, 30.0, i as u32, &mut ours);
                grid.k_nearest(p, k, 30.0, i as u32, &mut theirs);
                assert_eq!(ours, theirs, "agent {i}, k {k}");
                // The first disc searched changes the cost, never the answer.
                for start in [0.5, 3.0, 11.0, 100.0] {
                    k_nearest_from(&grid, p, k, 30.0, i as u32, start, &mut ours);
                    assert_eq!(ours, theirs, "agent {i}, k {k}, start {start}");
                }
            }
        }
    }

    #[test]
    fn nearest_keys_order_as_total_cmp_then_id_and_round_trip() {
        let values = [
            f32::NEG_INFINITY,
            -3.5,
            -0.0,
            0.0,
            1e-40,
            0.25,
            64.0,
            64.000_01,
            f32::MAX,
            f32::INFINITY,
            f32::NAN,
            -f32::NAN,
        ];
        for &a in &values {
            for &b in &values {
                for (ia, ib) in [(3u32, 5u32), (5, 3), (4, 4), (0, u32::MAX)] {
                    let expected = a.total_cmp(&b).then(ia.cmp(&ib));
                    assert_eq!(nearest_key(a, ia).cmp(&nearest_key(b, ib)), expected, "{a} {ia} vs {b} {ib}");
                }
            }
            let (d2, id) = from_nearest_key(nearest_key(a, 17));
            assert_eq!((d2.to_bits(), id), (a.to_bits(), 17));
        }
    }

    #[test]
    fn codes_round_trip() {
        for b in Behaviour::ALL {
            assert_eq!(Behaviour::from_code(b.code()), Some(b));
            let s = b.weights();
            let total = s.spacing + s.goal + s.collision + s.orientation + s.distance;
            assert!((total - 100.0).abs() < 1e-9, "{b:?}");
        }
        for e in crate::model::forces_cases::Environment::ALL {
            assert_eq!(crate::model::forces_cases::Environment::from_code(&e.code().to_uppercase()), Some(e));
        }
        assert_eq!(Behaviour::from_code("b4"), None);
    }
}
