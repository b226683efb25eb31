//! Budgets and limits of a run and of the front-ends, in one place: each a constant, with why a
//! front-end's value differs where it does (one value where nothing calls for two).
//!
//! The page runs in one browser tab: wasm32 memory (at most 4 GiB, often much less on a phone),
//! shared by the world, the renderer's pixmaps, the timeline and the recording, and every call
//! must fit in a frame. The command line runs natively with the machine's memory, writes files
//! and may take minutes. The scene's own limits (agents, size, obstacles) are the same everywhere
//! and live with the scene (`crate::model::scene`, stated in the README's limits table); the
//! flow fields' memory and the planning limit are [`crate::sim::cost`].

/// The page's recording of a run (the exports: paths CSV/JSON, MEL, Python, SVG): 32 MiB, for
/// example 1,000 agents × 2,000 steps at every step. Smaller than the command line's because it
/// shares the tab's memory with the timeline ([`REPLAY_FRAME_BUDGET_BYTES`] +
/// [`REPLAY_CHECKPOINT_BUDGET_BYTES`]) and the pixmaps; the page states the budget and any
/// thinning on screen.
pub const PAGE_RECORDING_BUDGET_BYTES: usize = 32 << 20;
/// `flockpath run`'s recording: 1 GiB (for example 10,000 agents × 6,700 steps). Native memory,
/// and the files written are the point of the run, so it keeps every step far longer; thinning
/// is noted on stderr.
pub const CLI_RECORDING_BUDGET_BYTES: usize = 1 << 30;

/// The timeline's quantised positions (the page only; the command line does not seek):
/// 80 MB = 10,000 agents × 2,000 steps × 4 bytes, at every step.
pub const REPLAY_FRAME_BUDGET_BYTES: usize = 80_000_000;
/// The timeline's checkpoints (estimated world sizes): 48 MiB, enough for 10,000 agents ×
/// 2,000 steps at the default interval.
pub const REPLAY_CHECKPOINT_BUDGET_BYTES: usize = 48 << 20;
/// Agent-steps a jump on the timeline may re-simulate: sets the checkpoint interval from the
/// agent count (20,000 agent-steps take a few milliseconds: a jump fits in a frame).
pub const REPLAY_JUMP_AGENT_STEPS: u32 = 20_000;
/// Shortest and longest automatic checkpoint interval (steps).
pub const REPLAY_CHECKPOINT_EVERY_RANGE: (u32, u32) = (20, 200);

/// Steps between metric samples at the start of a run, in the page and the command line alike.
pub const METRIC_SERIES_EVERY: u32 = 5;
/// Most metric samples the page keeps (then halves): its plots are a few hundred pixels wide
/// and read every series again on each refresh, so more samples would cost time, not detail.
pub const PAGE_METRIC_SERIES_CAP: usize = 512;
/// Most metric samples `flockpath run --metrics-history` keeps (then halves): a CSV for
/// analysis, where resolution is wanted and the cost is paid once.
pub const CLI_METRIC_SERIES_CAP: usize = 4096;

/// Steps between samples of a comparison pane's series at the start (the compare page only).
pub const COMPARE_SERIES_EVERY: u32 = 10;
/// Most samples a comparison pane's series keeps (then halves).
pub const COMPARE_SERIES_CAP: usize = 1000;

/// Most steps one `flockpath run` may ask for (about 4.6 hours of simulated time at 60
/// steps/s). The page has no such limit: it steps a few at a time, frame by frame, and the
/// recording and timeline budgets above bound what it keeps.
pub const CLI_MAX_STEPS: u32 = 1_000_000;

/// The optimizer lab page's largest population: its form's maximum, enforced here because a
/// typed number passes the form (issue 24: 500 particles at d = 200 with all five algorithms is
/// already a 7.7 s task in the page's worker). GSA and IGSA cost O(N²·d) per iteration
/// (`docs/optimizers.md` measures 50 ns per pair at d = 30). `flockpath optimize` allows
/// [`CLI_LAB_POPULATION`].
pub const PAGE_LAB_POPULATION: u32 = 500;
/// `flockpath optimize`'s largest population: batch runs natively, where a slow O(N²)
/// iteration (100,000 agents ≈ 8 minutes at d = 30) is a choice, not a frozen tab.
pub const CLI_LAB_POPULATION: usize = 100_000;
/// The lab page's largest dimension, its form's maximum (the command line: 10,000).
pub const PAGE_LAB_DIMENSION: u32 = 200;
/// `flockpath optimize`'s largest dimension.
pub const CLI_LAB_DIMENSION: usize = 10_000;
/// The lab page's most iterations per run, its form's maximum (the command line: 10,000,000,
/// a batch job).
pub const PAGE_LAB_ITERATIONS: u32 = 10_000;
/// `flockpath optimize`'s most iterations per run.
pub const CLI_LAB_ITERATIONS: u32 = 10_000_000;

// Not here, and why: the lab page's form (`www/lab.html`) repeats the three `PAGE_LAB_*`
// values above as its inputs' `max` (a test reads them back: tests/web_lab.rs), and the
// tuning page's form caps its population at 2,000 where `crate::tune` accepts 100,000 (the
// command line's limit). The playground's agent-count field repeats the scene's `MAX_AGENTS`
// (200,000). These are inputs' `max` attributes in HTML/JS, which cannot name a Rust constant.
