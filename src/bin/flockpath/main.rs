//! The flockpath command line: presets, batch runs with metrics, scene ↔ URL strings,
//! optimizer experiments, force-weight tuning, benchmarks, the validation suite, SCORM packages.
//!
//! A stable contract (DESIGN §5): output formats and flag names are scripted against. The
//! library computes; this binary parses the command line (clap), prints, writes files and draws
//! the progress bar. Every error goes to stderr naming the problem, with exit code 2 for a
//! usage mistake and 1 for a failure (unreadable file, invalid scene).

#[cfg(not(target_arch = "wasm32"))]
mod bench;
#[cfg(not(target_arch = "wasm32"))]
mod bench_cli;
#[cfg(not(target_arch = "wasm32"))]
mod cli;
#[cfg(not(target_arch = "wasm32"))]
mod optimize;
#[cfg(not(target_arch = "wasm32"))]
mod progress;
#[cfg(not(target_arch = "wasm32"))]
mod run;
#[cfg(not(target_arch = "wasm32"))]
mod scenes;
#[cfg(not(target_arch = "wasm32"))]
mod scorm;
#[cfg(not(target_arch = "wasm32"))]
mod tune;
#[cfg(not(target_arch = "wasm32"))]
mod validate;

#[cfg(not(target_arch = "wasm32"))]
pub use cli::{failed, finite, in_range, out, usage, whole_number, write_file, CliError};

#[cfg(not(target_arch = "wasm32"))]
fn main() -> std::process::ExitCode {
    cli::main()
}

/// The command line is native only; cargo still builds this binary when the wasm browser tests
/// are compiled, so on wasm32 it is an empty program.
#[cfg(target_arch = "wasm32")]
fn main() {}
