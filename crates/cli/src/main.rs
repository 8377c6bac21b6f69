//! `roughcontact`: the command-line tool. The only place that uses clap and anyhow.

use clap::{Parser, Subcommand};
use roughcontact::{bench, solve, study, surface, sweep, theory_cmd};
use std::process::ExitCode;

/// Deterministic contact mechanics of rough surfaces with adhesion.
///
/// All quantities are SI: lengths and heights in metres, pressures and moduli in pascals,
/// energies per area in J/m^2, wavevectors in rad/m.
#[derive(Parser, Debug)]
#[command(name = "roughcontact", version, about, long_about = None)]
struct Cli {
    /// Worker threads (default: all cores). Results do not depend on it beyond round-off,
    /// and generated surfaces not at all.
    #[arg(long, global = true, value_name = "N")]
    threads: Option<usize>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Generate a periodic self-affine rough surface from its power spectrum (Eq. 13).
    #[command(allow_hyphen_values = true)]
    Generate(surface::GenerateArgs),
    /// List what a surface file holds: its channels (grid, size, unit), the channel read as
    /// heights, and the points the instrument did not measure.
    Info(surface::InfoArgs),
    /// Print a surface's statistics (heights, slopes, curvatures, Hurst exponent).
    Stats(surface::StatsArgs),
    /// Write a surface's radially averaged power spectrum as CSV and a log-log plot.
    Psd(surface::PsdArgs),
    /// Solve one normal contact, with or without adhesion (rough flat, sphere, rough sphere).
    #[command(allow_hyphen_values = true)]
    Solve(Box<solve::SolveArgs>),
    /// An approach-retraction cycle (or a list of approaches, loads or central gaps) with
    /// continuation: load-approach curve, pull-off, jumps and hysteresis.
    #[command(allow_hyphen_values = true)]
    Sweep(Box<sweep::SweepArgs>),
    /// A parameter study: a base case and axes to vary (seeds, Tabor parameters, any case key),
    /// each run a solve or a sweep in its own directory, run side by side, resumable, merged
    /// into one table (study.csv) with a mean and standard error per group.
    Study(study::StudyArgs),
    /// Time the non-adhesive solver on one self-affine problem at several grid sizes.
    Bench(bench::BenchArgs),
    /// Reference curves (Maugis-Dugdale, JKR, DMT, Greenwood's Lennard-Jones sphere) as CSV,
    /// or their pull-off forces.
    #[command(allow_hyphen_values = true)]
    Theory(theory_cmd::TheoryArgs),
}

fn main() -> ExitCode {
    // Rust ignores SIGPIPE, so printing into a closed pipe (`| head`) would panic; with the
    // default action the process ends quietly, as Unix tools do.
    #[cfg(unix)]
    // SAFETY: called first, before any other thread exists; SIG_DFL is a valid handler.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    // Help, the version and clap's own errors are printed here, so that one that cannot be
    // written ends the command with status 1 too.
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let status = if e.use_stderr() { 2 } else { 0 };
            return match e.print() {
                Ok(()) => ExitCode::from(status),
                Err(_) => ExitCode::FAILURE,
            };
        }
    };
    if let Some(n) = cli.threads
        && let Err(e) = case::memory::check_threads("--threads", n)
            .map_err(anyhow::Error::from)
            .and_then(|()| Ok(rayon::ThreadPoolBuilder::new().num_threads(n).build_global()?))
    {
        roughcontact::note_err(format_args!("error: {e:#}"));
        return ExitCode::FAILURE;
    }
    let result = match cli.command {
        Command::Generate(args) => surface::generate(args),
        Command::Info(args) => surface::info(args),
        Command::Stats(args) => surface::stats(args),
        Command::Psd(args) => surface::psd(args),
        Command::Solve(args) => solve::solve(*args),
        Command::Sweep(args) => sweep::sweep(*args),
        Command::Study(args) => study::study(args, cli.threads),
        Command::Bench(args) => bench::bench(args),
        Command::Theory(args) => theory_cmd::theory(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // A standard error that cannot be written to still ends the command with status 1.
            roughcontact::note_err(format_args!("error: {e:#}"));
            ExitCode::FAILURE
        }
    }
}
