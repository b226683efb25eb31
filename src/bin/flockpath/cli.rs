//! The command line's clap definition, its typed error and the helpers every command uses.

use crate::{bench, bench_cli, optimize, run, scenes, scorm, tune, validate};
use clap::{CommandFactory as _, Parser, Subcommand};
use std::io::Write as _;
use std::process::ExitCode;

/// The end of `flockpath --help`: where to look next and what the exit codes mean.
const AFTER_HELP: &str = "\
Run `flockpath <COMMAND> --help` or `flockpath help <COMMAND>` for a command's options.

Exit codes: 0 done; 2 usage mistake (unknown command or option, missing or bad value);
1 failure (unreadable or unwritable file, invalid scene). Errors go to stderr.";

/// `flockpath`: one subcommand per task.
#[derive(Parser, Debug)]
#[command(
    name = "flockpath",
    version,
    about = "flockpath — swarm-intelligence crowd planners on the command line",
    after_help = AFTER_HELP
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand, Debug)]
pub(crate) enum Command {
    /// List the preset scenes (name and description)
    #[command(long_about = "List the preset scenes, one per line: name, then description")]
    Presets,
    /// Print a preset scene as JSON
    Preset(scenes::PresetArgs),
    /// Run a scene for N steps and report its metrics
    Run(run::RunArgs),
    /// Print the URL fragment value (the part after #s=) for a scene JSON file
    Url(scenes::UrlArgs),
    /// Print the scene JSON for a URL fragment value, #s= fragment or URL
    Scene(scenes::SceneArgs),
    /// Measure step and render speed (prints figures)
    Bench(bench_cli::BenchArgs),
    /// Run swarm optimizers on benchmark functions (table, JSON, curves)
    Optimize(optimize::OptimizeArgs),
    /// Tune the five virtual-force weights with the genetic algorithm (one pair, or the table)
    Tune(tune::TuneArgs),
    /// Run the validation suite (RiMEA tests, Jülich checks, lanes): table, JSON, CSV curves
    Validate(validate::ValidateArgs),
    /// Package an activity link as a SCORM 1.2 zip an LMS can grade
    Scorm(scorm::ScormArgs),
    /// The scene the benchmarks use, for the browser bench page (scripts/bench.sh)
    #[command(hide = true)]
    DensityScene(bench_cli::DensitySceneArgs),
}

/// Why a command did not finish.
#[derive(Debug)]
pub enum CliError {
    /// The command line did not parse (clap's message names the argument): exit code 2.
    Parse(clap::Error),
    /// The command line parsed but asks for something impossible (unknown preset, value out of
    /// range, missing option): exit code 2.
    Usage(String),
    /// The command line was fine but the work failed (missing file, invalid scene): exit code 1.
    Failed(String),
}

impl CliError {
    /// The process exit code: 2 for a usage mistake, 1 for a failure.
    fn exit_code(&self) -> u8 {
        match self {
            CliError::Parse(_) | CliError::Usage(_) => 2,
            CliError::Failed(_) => 1,
        }
    }
}

impl std::fmt::Display for CliError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            // clap's own text: `error: …`, the usage line and where to look for help.
            CliError::Parse(e) => write!(f, "{}", e.render()),
            CliError::Usage(msg) => {
                write!(f, "flockpath: {msg}\nRun `flockpath --help` for usage.")
            }
            CliError::Failed(msg) => write!(f, "flockpath: {msg}"),
        }
    }
}

impl std::error::Error for CliError {}

/// A usage mistake found after parsing (a message, or a library's typed error).
pub fn usage(msg: impl std::fmt::Display) -> CliError {
    CliError::Usage(msg.to_string())
}

/// A failure of the work itself (a message, or a library's typed error).
pub fn failed(msg: impl std::fmt::Display) -> CliError {
    CliError::Failed(msg.to_string())
}

pub fn main() -> ExitCode {
    match dispatch() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let text = e.to_string();
            eprintln!("{}", text.trim_end());
            ExitCode::from(e.exit_code())
        }
    }
}

fn dispatch() -> Result<(), CliError> {
    if std::env::args_os().len() <= 1 {
        eprint!("{}", Cli::command().render_help());
        return Err(usage("no command given"));
    }
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // --help, help COMMAND and --version are not mistakes: they print on stdout.
        Err(e) if e.exit_code() == 0 => return out(&e.render().to_string()),
        Err(e) => return Err(CliError::Parse(e)),
    };
    match cli.command {
        Command::Presets => scenes::presets(),
        Command::Preset(args) => scenes::preset(&args),
        Command::Run(args) => run::run(&args),
        Command::Url(args) => scenes::url(&args),
        Command::Scene(args) => scenes::scene(&args),
        Command::Bench(args) => bench::main(&args.options()),
        Command::Optimize(args) => optimize::optimize(&args),
        Command::Tune(args) => tune::tune(&args),
        Command::Validate(args) => validate::validate(&args),
        Command::Scorm(args) => scorm::scorm(&args),
        Command::DensityScene(args) => bench_cli::density_scene(&args),
    }
}

/// Writes to stdout; a closed pipe (`flockpath presets | head -1`) is not an error worth a panic.
pub fn out(text: &str) -> Result<(), CliError> {
    let mut stdout = std::io::stdout().lock();
    match stdout.write_all(text.as_bytes()).and_then(|()| stdout.flush()) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(failed(format!("cannot write to stdout: {e}"))),
    }
}

/// Writes `text` to `path`; a failure names `what` (such as `--paths file`) and the file.
pub fn write_file(what: &str, path: impl AsRef<std::path::Path>, text: &str) -> Result<(), CliError> {
    let path = path.as_ref();
    std::fs::write(path, text).map_err(|e| failed(format!("cannot write {what} {path:?}: {e}")))
}

/// A clap value parser for a whole number (spaces around it allowed).
pub fn whole_number<T: std::str::FromStr>(text: &str) -> Result<T, String> {
    text.trim().parse().map_err(|_| format!("must be a whole number, got {text:?}"))
}

/// A clap value parser for a number in `lo…hi`. Written as "inside" rather than "not outside"
/// so that NaN, which compares false with everything, is refused too (Rust's float parser
/// reads `NaN`, `inf` and `infinity`).
pub fn in_range<T>(lo: T, hi: T) -> impl Fn(&str) -> Result<T, String> + Clone + Send + Sync + 'static
where
    T: std::str::FromStr + PartialOrd + std::fmt::Display + Copy + Send + Sync + 'static,
{
    move |text: &str| {
        let x: T = text.trim().parse().map_err(|_| format!("needs a number in {lo}…{hi}, got {text:?}"))?;
        if !(lo <= x && x <= hi) {
            return Err(format!("{x} is outside {lo}…{hi}"));
        }
        Ok(x)
    }
}

/// A clap value parser for a finite number (the option's own range is checked where it is
/// used): `NaN` and `inf` parse as floats but are no setting.
pub fn finite<T>(text: &str) -> Result<T, String>
where
    T: std::str::FromStr + Into<f64> + Copy,
{
    let x: T = text.trim().parse().map_err(|_| format!("must be a number, got {text:?}"))?;
    if !x.into().is_finite() {
        return Err(format!("must be a finite number, got {text:?}"));
    }
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_command_line_definition_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn every_command_has_help_and_the_exit_codes_are_documented() {
        let help = Cli::command().render_long_help().to_string();
        for command in
            ["presets", "preset", "run", "url", "scene", "bench", "optimize", "tune", "validate", "scorm"]
        {
            assert!(help.contains(command), "{command} missing from --help:\n{help}");
            let e = Cli::try_parse_from(["flockpath", "help", command]).expect_err("help is an early exit");
            assert_eq!(e.exit_code(), 0, "help {command}");
            assert!(e.render().to_string().contains(&format!("flockpath {command}")), "help {command}");
        }
        assert!(help.contains("2 usage mistake") && help.contains("1 failure"), "{help}");
        assert!(!help.contains("density-scene"), "the bench page's helper stays hidden");
    }
}
