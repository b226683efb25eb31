//! The flockpath command line (placeholder until the CLI lands; this branch adds only `tune`).

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.split_first() {
        Some((command, rest)) if command == "tune" => {
            // The clock lives here: the core has none; it only feeds the evaluations/s figure.
            let start = std::time::Instant::now();
            ExitCode::from(flockpath::tune_cli::main(rest, &|| start.elapsed().as_secs_f64()))
        }
        _ => ExitCode::SUCCESS,
    }
}
