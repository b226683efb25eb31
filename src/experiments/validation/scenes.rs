//! The scene built for each test, in metres (drawn at [`PX_PER_METRE`]): corridors, a corner,
//! rooms with doors, a bottleneck. Each builder takes the planner every group uses.

use super::measure::ExitLine;
use super::units::{config_at_speed, px, SetupError, BODY_RADIUS_M, PX_PER_METRE};
use crate::model::geometry::Obstacle;
use crate::model::params::{PlannerConfig, PlannerKind};
use crate::model::scene::{Goal, Group, Region, Scene};
use crate::rng::Rng;
use glam::Vec2;

/// Group colours, in order.
const COLOURS: &[&str] = &["#2f6fdf", "#d9482b", "#2b9d48", "#a23bc4", "#d49a1c", "#1c9aa8"];

/// A scene of `w × h` metres.
fn world(name: &str, w: f32, h: f32) -> Scene {
    Scene { name: name.into(), px_per_metre: PX_PER_METRE, ..Scene::empty(px(w), px(h)) }
}

/// A group of `count` walkers spawned in `[min, max]` (m) heading for goal `goal`.
fn walkers(
    name: &str,
    k: usize,
    count: u32,
    min: [f32; 2],
    max: [f32; 2],
    goal: u32,
    cfg: &PlannerConfig,
) -> Group {
    Group {
        name: name.into(),
        color: COLOURS[k % COLOURS.len()].into(),
        count,
        spawn: Region { min: [px(min[0]), px(min[1])], max: [px(max[0]), px(max[1])] },
        goal: Some(goal),
        agent_radius: px(BODY_RADIUS_M),
        planner: cfg.clone(),
    }
}

/// A wall from `min` to `max` (m).
fn wall(min: [f32; 2], max: [f32; 2]) -> Obstacle {
    Obstacle::Rect { min: [px(min[0]), px(min[1])], max: [px(max[0]), px(max[1])] }
}

/// An exit at `at` (m) of radius `r` (m): in the RiMEA tests a walker that reaches it has left
/// the building ([`crate::model::scene::OnArrival::Exit`]).
fn goal(at: [f32; 2], r: f32) -> Goal {
    Goal::fixed([px(at[0]), px(at[1])], px(r)).exit()
}

/// T1: one walker in a 40 m × 2 m corridor, from its left end to a goal at its right end.
pub fn free_walking(cfg: &PlannerConfig) -> Scene {
    let mut s = world("validate-t1-free-walking", 40.0, 2.0);
    s.goals.push(goal([39.4, 1.0], 0.5));
    s.groups.push(walkers("walker", 0, 1, [0.3, 0.7], [0.9, 1.3], 0, cfg));
    s
}

/// Where a periodic band starts (m): 10 m of world before it, as after it, so no world border
/// is within any planner's reach of the seam (a border is a wall to the pedestrian models:
/// with the seam on the world's left border every walker that wrapped was shoved forward and
/// the crowd piled up there, 11.6 vs 3.05 persons/m² at 6 in social force, issue 25).
pub const PERIODIC_BAND_START: f32 = 10.0;

/// A corridor `width` metres wide whose x is periodic over `[10, 10 + length)` m
/// ([`PERIODIC_BAND_START`], [`crate::sim::world::World::set_periodic_x`]), with `count`
/// walkers spread over the band heading for a goal 19 m past its end (so they keep walking
/// right). The world is `length + 30` m long: 10 m before the band, 20 m after it, where the
/// playground, which has no periodic corridor, shows the crowd walking on to that goal. Returns
/// the scene and the periodic band (px).
pub fn periodic_corridor(
    name: &str,
    cfg: &PlannerConfig,
    count: u32,
    length: f32,
    width: f32,
) -> (Scene, (f32, f32)) {
    let start = PERIODIC_BAND_START;
    let mut s = world(name, start + length + 20.0, width);
    s.goals.push(goal([start + length + 19.0, width * 0.5], (width * 0.5).min(0.5)));
    // Centres in [start, start + length − one body diameter]: none on the band's end (the
    // world wraps a centre that leaves the band, not one that starts outside it: a walker
    // spawned at x = 30 m walked on outside the band), and the seam's gap to the first
    // walker's image is at least a body diameter, so no two bodies start overlapping there.
    let last = start + length - 2.0 * BODY_RADIUS_M;
    s.groups.push(walkers("crowd", 0, count, [start, 0.0], [last, width], 0, cfg));
    (s, (px(start), px(start + length)))
}

/// Counter-flow: two groups of `count` spread over the same periodic 20 m × 4 m corridor, one
/// heading right, one left (goals 9 m beyond either end of the band `[10, 30)` m).
pub fn counter_flow(cfg: &PlannerConfig, count: u32) -> (Scene, (f32, f32)) {
    let mut s = world("validate-counter-flow", 40.0, 4.0);
    s.goals.push(goal([39.0, 2.0], 0.5));
    s.goals.push(goal([1.0, 2.0], 0.5));
    s.groups.push(walkers("rightward", 0, count, [10.0, 0.0], [30.0, 4.0], 0, cfg));
    s.groups.push(walkers("leftward", 1, count, [10.0, 0.0], [30.0, 4.0], 1, cfg));
    (s, (px(10.0), px(30.0)))
}

/// The corner's geometry (m): a corridor `width` wide going right along the bottom for `leg`
/// metres, then turning left (up the screen) for `leg` metres to an exit at its end, and on
/// beyond the exit for [`BEYOND_EXIT`] metres to the world's top border.
#[derive(Clone, Copy, Debug)]
pub struct Corner {
    /// Length of each leg along its outer wall (m).
    pub leg: f32,
    /// Corridor width (m).
    pub width: f32,
}

/// How far the world goes on past an exit (m): an exit on the world's border is also a wall to
/// the planners that keep off the border (Boids' containment), so the suite's exits are doors
/// with room beyond them, as in RiMEA's drawings.
pub const BEYOND_EXIT: f32 = 2.0;

/// An exit across the end of a corridor `width` wide whose end's middle is `end` (m): a disc
/// as wide as the corridor centred on the end. A walker's centre reaches it only past the
/// line half a width before the end ([`ExitLine`]s are drawn there).
fn corridor_exit(end: [f32; 2], width: f32) -> Goal {
    goal(end, width * 0.5)
}

impl Corner {
    /// The walls: the inside block, the outer bottom and the outer right; the exit across the
    /// second leg's end, [`BEYOND_EXIT`] below the world's top border.
    pub fn scene(&self, name: &str, cfg: &PlannerConfig, count: u32, start_len: f32) -> Scene {
        let (l, w, m) = (self.leg, self.width, BEYOND_EXIT);
        let mut s = world(name, l + 1.0, l + 1.0 + m);
        s.obstacles.push(wall([0.0, 0.0], [l - w, l - w + m]));
        s.obstacles.push(wall([0.0, l + m], [l + 1.0, l + 1.0 + m]));
        s.obstacles.push(wall([l, 0.0], [l + 1.0, l + m]));
        s.goals.push(corridor_exit([l - w * 0.5, m], w));
        s.groups.push(walkers("crowd", 0, count, [0.2, l - w + 0.2 + m], [start_len, l - 0.2 + m], 0, cfg));
        s
    }

    /// The exit line: across the second leg half a width before its end, where the exit
    /// begins (m).
    pub fn exit_line(&self) -> ExitLine {
        ExitLine::Upward { y: BEYOND_EXIT + self.width * 0.5, span: (self.leg - self.width, self.leg) }
    }

    /// The exit's centre (m): a walker whose centre is within half a width of it has left.
    pub fn exit_centre(&self) -> Vec2 {
        Vec2::new(self.leg - self.width * 0.5, BEYOND_EXIT)
    }
}

/// T15's straight comparison: a corridor `length` × `width` m with the crowd in its first
/// `start_len` metres and an exit across its end ([`BEYOND_EXIT`] before the world's end).
pub fn straight(
    name: &str,
    cfg: &PlannerConfig,
    count: u32,
    length: f32,
    width: f32,
    start_len: f32,
) -> Scene {
    let mut s = world(name, length + BEYOND_EXIT, width);
    s.goals.push(corridor_exit([length, width * 0.5], width));
    s.groups.push(walkers("crowd", 0, count, [0.2, 0.2], [start_len, width - 0.2], 0, cfg));
    s
}

/// The exit line of [`straight`]'s corridor: half a width before its end (m).
pub fn straight_exit_line(length: f32, width: f32) -> ExitLine {
    ExitLine::Rightward { x: length - width * 0.5, span: (0.0, width) }
}

/// Which wall of a room a door is in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// x = room's left.
    Left,
    /// x = room's right.
    Right,
    /// y = room's top.
    Top,
    /// y = room's bottom.
    Bottom,
}

/// A square room `side` metres wide whose interior starts at `margin` metres from the world's
/// edges, walls 0.4 m thick, with doors `door` metres wide in the middle of the given walls.
#[derive(Clone, Copy, Debug)]
pub struct Room {
    /// Interior side (m).
    pub side: f32,
    /// Space outside the walls (m).
    pub margin: f32,
    /// Door width (m).
    pub door: f32,
}

/// Wall thickness of the rooms (m).
const WALL: f32 = 0.4;

impl Room {
    /// Whether `p` (m) is inside the room's interior.
    pub fn inside(&self, p: Vec2) -> bool {
        let (a, b) = (self.margin, self.margin + self.side);
        p.x > a && p.x < b && p.y > a && p.y < b
    }

    /// The walls with gaps for `doors`.
    fn walls(&self, doors: &[Side]) -> Vec<Obstacle> {
        let (a, b) = (self.margin, self.margin + self.side);
        let (c, h) = ((a + b) * 0.5, self.door * 0.5);
        let mut out = vec![];
        for side in [Side::Left, Side::Right, Side::Top, Side::Bottom] {
            // The wall's span along its length (corners included on the horizontal walls).
            let (lo, hi) = match side {
                Side::Left | Side::Right => (a, b),
                Side::Top | Side::Bottom => (a - WALL, b + WALL),
            };
            let spans = if doors.contains(&side) { vec![(lo, c - h), (c + h, hi)] } else { vec![(lo, hi)] };
            for (s0, s1) in spans {
                out.push(match side {
                    Side::Left => wall([a - WALL, s0], [a, s1]),
                    Side::Right => wall([b, s0], [b + WALL, s1]),
                    Side::Top => wall([s0, a - WALL], [s1, a]),
                    Side::Bottom => wall([s0, b], [s1, b + WALL]),
                });
            }
        }
        out
    }

    /// A goal 3 m outside the door in `side`.
    fn goal_beyond(&self, side: Side) -> Goal {
        let (a, b) = (self.margin, self.margin + self.side);
        let c = (a + b) * 0.5;
        let at = match side {
            Side::Left => [a - 3.0, c],
            Side::Right => [b + 3.0, c],
            Side::Top => [c, a - 3.0],
            Side::Bottom => [c, b + 3.0],
        };
        goal(at, 1.5)
    }

    /// The room with doors in `doors`; `groups` lists each group's door, count and spawn
    /// rectangle relative to the interior (m).
    pub fn scene(
        &self,
        name: &str,
        cfg: &PlannerConfig,
        doors: &[Side],
        groups: &[(Side, u32, [f32; 4])],
    ) -> Scene {
        let size = self.side + 2.0 * self.margin;
        let mut s = world(name, size, size);
        s.obstacles = self.walls(doors);
        for (k, &(door, count, r)) in groups.iter().enumerate() {
            let g = doors.iter().position(|&d| d == door).unwrap_or(0) as u32;
            let m = self.margin;
            s.groups.push(walkers(
                &format!("to {door:?}").to_lowercase(),
                k,
                count,
                [m + r[0], m + r[1]],
                [m + r[2], m + r[3]],
                g,
                cfg,
            ));
        }
        s.goals = doors.iter().map(|&d| self.goal_beyond(d)).collect();
        s
    }
}

/// T9's room: 20 m square, 2 m doors, 1,000 walkers. Two doors (left, right: each half of
/// the room to its nearer one) or four (each quadrant to one door).
pub fn large_room(cfg: &PlannerConfig, four: bool, count: u32) -> (Scene, Room) {
    let room = Room { side: 20.0, margin: 5.0, door: 2.0 };
    let (lo, mid, hi) = (0.4, 10.0, 19.6);
    let scene = if four {
        let q = count / 4;
        room.scene(
            "validate-t9-four-exits",
            cfg,
            &[Side::Left, Side::Top, Side::Right, Side::Bottom],
            &[
                (Side::Left, q, [lo, lo, mid, mid]),
                (Side::Top, q, [mid, lo, hi, mid]),
                (Side::Right, q, [mid, mid, hi, hi]),
                (Side::Bottom, count - 3 * q, [lo, mid, mid, hi]),
            ],
        )
    } else {
        let half = count / 2;
        room.scene(
            "validate-t9-two-exits",
            cfg,
            &[Side::Left, Side::Right],
            &[(Side::Left, half, [lo, lo, mid, hi]), (Side::Right, count - half, [mid, lo, hi, hi])],
        )
    };
    (scene, room)
}

/// T8's room: 10 m square, one 1.5 m door on the right, `count` walkers.
pub fn small_room(cfg: &PlannerConfig, count: u32) -> (Scene, Room) {
    let room = Room { side: 10.0, margin: 4.0, door: 1.5 };
    let scene =
        room.scene("validate-t8-room", cfg, &[Side::Right], &[(Side::Right, count, [0.4, 0.4, 7.0, 9.6])]);
    (scene, room)
}

/// T12's bottleneck (m): room 10 × 10, corridor from x = 10 to 16, 2 m wide, second room
/// from 16 to 26 with its exit (a door as wide as the corridor) in its right wall at x = 26,
/// [`BEYOND_EXIT`] before the world's border.
pub const BOTTLENECK: (f32, f32, f32) = (10.0, 16.0, 2.0);

/// Where T12's last exit is (m): the door's middle in the second room's right wall.
pub const BOTTLENECK_EXIT: [f32; 2] = [26.0, 5.0];

/// T12: 150 walkers leave a room through a corridor into a second room and out of its exit.
pub fn bottleneck(cfg: &PlannerConfig, count: u32) -> Scene {
    let (x_in, x_out, w) = BOTTLENECK;
    let [x_exit, y_exit] = BOTTLENECK_EXIT;
    let mut s = world("validate-t12-bottleneck", x_exit + BEYOND_EXIT, 10.0);
    let (y0, y1) = (5.0 - w * 0.5, 5.0 + w * 0.5);
    s.obstacles.push(wall([x_in, 0.0], [x_out, y0]));
    s.obstacles.push(wall([x_in, y1], [x_out, 10.0]));
    s.obstacles.push(wall([x_exit, 0.0], [x_exit + BEYOND_EXIT, y_exit - w * 0.5]));
    s.obstacles.push(wall([x_exit, y_exit + w * 0.5], [x_exit + BEYOND_EXIT, 10.0]));
    s.goals.push(corridor_exit(BOTTLENECK_EXIT, w));
    s.groups.push(walkers("crowd", 0, count, [0.3, 0.3], [8.0, 9.7], 0, cfg));
    s
}

/// T12's two counting lines (m): the corridor's end (the flow out of the bottleneck) and the
/// last exit's line, 1 m before the door (where the exit begins).
pub fn bottleneck_lines() -> (ExitLine, ExitLine) {
    let (_, x_out, w) = BOTTLENECK;
    (
        ExitLine::Rightward { x: x_out, span: (5.0 - w * 0.5, 5.0 + w * 0.5) },
        ExitLine::Rightward { x: BOTTLENECK_EXIT[0] - w * 0.5, span: (0.0, 10.0) },
    )
}

/// T7's age groups: name and desired-speed range (m/s). Illustrative ranges in the shape of
/// Weidmann's speed-by-age curve, not the guideline's table.
pub const AGE_GROUPS: &[(&str, f32, f32)] =
    &[("children", 0.9, 1.2), ("adults", 1.2, 1.6), ("older", 1.0, 1.3), ("seniors", 0.6, 0.9)];

/// Subgroups per age group: the model has one desired speed per group, so each age group is
/// split into this many groups whose speeds are drawn uniformly from its range.
pub const SUBGROUPS: usize = 5;

/// T7: each age group walks its own 3 m lane of a 50 m × 12 m hall to its goal; its walkers
/// are [`SUBGROUPS`] groups of two with speeds drawn (seeded) from its range, all starting
/// within the first 4.5 m (before the measured section). Returns the scene
/// and each group's (age group index, desired speed m/s).
pub fn demographics(kind: PlannerKind) -> Result<(Scene, Vec<(usize, f32)>), SetupError> {
    let mut s = world("validate-t7-demographics", 50.0, 12.0);
    let mut rng = Rng::new(7, 0x7007);
    let mut speeds = vec![];
    for (a, &(name, lo, hi)) in AGE_GROUPS.iter().enumerate() {
        let y = a as f32 * 3.0;
        s.goals.push(goal([49.0, y + 1.5], 0.8));
        for k in 0..SUBGROUPS {
            let v = rng.range(lo, hi);
            let cfg = config_at_speed(kind, v)?;
            // Every start before the x = 5 m line the speed is measured from (at 1.6 m
            // apart the last two pairs started at 6.4–7.8 m and were never measured).
            let x = k as f32 * 0.9;
            s.groups.push(walkers(
                &format!("{name} {}", k + 1),
                a,
                2,
                [x + 0.05, y + 0.3],
                [x + 0.85, y + 2.7],
                a as u32,
                &cfg,
            ));
            speeds.push((a, v));
        }
    }
    Ok((s, speeds))
}

/// Jülich check: 10 walkers in two files walk 16 m past a square pillar to a goal, in a 40 m
/// square world, everything turned by `angle` (rad) about the world's centre. Returns the
/// scene and the walkers' exact start positions (px), turned the same way.
pub fn turned_walk(cfg: &PlannerConfig, angle: f32) -> (Scene, Vec<Vec2>) {
    let c = Vec2::splat(20.0);
    let rot = Vec2::from_angle(angle);
    let turn = |p: Vec2| c + rot.rotate(p - c);
    let mut s = world("validate-rotation", 40.0, 40.0);
    let pillar = [[19.0, 18.5], [21.0, 18.5], [21.0, 19.5], [19.0, 19.5]];
    s.obstacles.push(Obstacle::Polygon {
        points: pillar
            .iter()
            .map(|&[x, y]| turn(Vec2::new(x, y)) * PX_PER_METRE)
            .map(|p| [p.x, p.y])
            .collect(),
    });
    let g = turn(Vec2::new(28.0, 20.0));
    s.goals.push(goal([g.x, g.y], 1.0));
    let starts: Vec<Vec2> = (0..10)
        .map(|i| Vec2::new(11.0 + (i / 2) as f32 * 0.8, 19.5 + (i % 2) as f32 * 1.0))
        .map(|p| turn(p) * PX_PER_METRE)
        .collect();
    let s0 = turn(Vec2::new(11.0, 19.5));
    s.groups.push(walkers("walkers", 0, 10, [s0.x - 1.0, s0.y - 1.0], [s0.x + 3.0, s0.y + 3.0], 0, cfg));
    (s, starts)
}

/// The head-on walkers' lateral offset (m): the west walker walks on a line 1 cm below the
/// east walker's. From exactly collinear starts the check tests a symmetric model's
/// tie-breaking, not its avoidance: JuPedSim's collision-free speed and social force models
/// deadlock there too, and pass with this offset (issue 25).
pub const HEAD_ON_OFFSET_M: f32 = 0.01;

/// Jülich check: two walkers 16 m apart in a 20 m × 6 m field, on lines [`HEAD_ON_OFFSET_M`]
/// apart, each heading for the other's start (its line's far end). Returns the scene and
/// their exact starts (px).
pub fn head_on(cfg: &PlannerConfig) -> (Scene, Vec<Vec2>) {
    let (east, west) = (3.0, 3.0 + HEAD_ON_OFFSET_M);
    let mut s = world("validate-head-on", 20.0, 6.0);
    s.goals.push(goal([18.0, east], 0.5));
    s.goals.push(goal([2.0, west], 0.5));
    s.groups.push(walkers("east", 0, 1, [1.5, 2.5], [2.5, 3.5], 0, cfg));
    s.groups.push(walkers("west", 1, 1, [17.5, 2.5], [18.5, 3.5], 1, cfg));
    (s, vec![Vec2::new(px(2.0), px(east)), Vec2::new(px(18.0), px(west))])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_scene_is_valid_and_spawns() {
        let cfg = PlannerKind::Boids.default_config();
        let mut scenes = vec![
            free_walking(&cfg),
            periodic_corridor("t4", &cfg, 240, 20.0, 2.0).0,
            periodic_corridor("t16", &cfg, 50, 20.0, 0.5).0,
            counter_flow(&cfg, 40).0,
            Corner { leg: 12.0, width: 2.0 }.scene("t6", &cfg, 20, 6.0),
            straight("t15", &cfg, 100, 27.0, 3.0, 8.0),
            large_room(&cfg, true, 1000).0,
            large_room(&cfg, false, 1000).0,
            small_room(&cfg, 40).0,
            bottleneck(&cfg, 150),
            demographics(PlannerKind::Boids).expect("speeds").0,
            turned_walk(&cfg, 0.7).0,
            head_on(&cfg).0,
        ];
        for s in scenes.drain(..) {
            let name = s.name.clone();
            crate::sim::world::World::new_beyond_cost_limit(s).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }

    #[test]
    fn every_t7_walker_starts_before_the_measured_section() {
        // T7 measures each walker's speed from x = 5 m: one that starts beyond it is never
        // measured and fails the test whatever its planner does.
        let (scene, _) = demographics(PlannerKind::Boids).expect("speeds");
        let world = crate::sim::world::World::new_beyond_cost_limit(scene).expect("valid");
        let beyond: Vec<f32> = world
            .positions()
            .iter()
            .map(|p| p.x / PX_PER_METRE)
            .filter(|&x| x + BODY_RADIUS_M >= 5.0)
            .collect();
        assert!(beyond.is_empty(), "starts at x ≥ 5 m: {beyond:?}");
    }

    #[test]
    fn rooms_have_their_doors() {
        let room = Room { side: 10.0, margin: 4.0, door: 1.5 };
        // Four walls, one split by the door: five rectangles.
        assert_eq!(room.walls(&[Side::Right]).len(), 5);
        let walls = room.walls(&[Side::Right]);
        let solid = |p: Vec2| walls.iter().any(|o| o.contains(p * PX_PER_METRE));
        assert!(!solid(Vec2::new(14.2, 9.0)), "the door is open");
        assert!(solid(Vec2::new(14.2, 6.0)) && solid(Vec2::new(3.8, 9.0)), "the walls are closed");
        assert!(room.inside(Vec2::new(9.0, 9.0)) && !room.inside(Vec2::new(15.0, 9.0)));
    }
}
