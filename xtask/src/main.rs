//! `cargo xtask figures [--quick] [--only N,...] [--out DIR]`; `cargo xtask study NAME`.

use anyhow::Result;
use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "xtask", about = "Project automation for roughcontact")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum RoughLaw {
    Point,
    Surface,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum ChallengeLaw {
    Surface,
    Exponential,
}

/// The flags of `figures`.
#[derive(clap::Args)]
struct FiguresArgs {
    /// Small grids and few points (a few minutes); what CI runs.
    #[arg(long)]
    quick: bool,
    /// Only these figures, e.g. --only 5,6,11.
    #[arg(long, value_delimiter = ',')]
    only: Vec<u32>,
    /// Output directory (default: figures, or figures-quick with --quick).
    #[arg(long)]
    out: Option<PathBuf>,
    /// The contact-mechanics challenge's own topography (any format `roughcontact`
    /// reads; a bare .npy is taken as 100 um square) for Figs. 8-10.
    #[arg(long, value_name = "FILE")]
    challenge_surface: Option<PathBuf>,
    /// Recompute every run instead of reusing the cache in OUT/cache and the finished
    /// runs of the studies in OUT/studies.
    #[arg(long)]
    fresh: bool,
    /// Only write the study files of the figures' series into OUT/studies, to run them
    /// elsewhere (`mpirun -n K roughcontact study FILE --out DIR`, or a job array with
    /// --shard); building the figures afterwards draws from their finished runs.
    #[arg(long)]
    studies_only: bool,
    /// The Lennard-Jones law of the rough spheres (Figs. 11-14): `point` (by the energy
    /// descent) or the paper's `surface` law, Eq. 11 (by the flow, about 2.5 times the
    /// time).
    #[arg(long, value_enum, default_value = "point")]
    rough_law: RoughLaw,
    /// The adhesive law of the challenge's figures (Figs. 8-10): the paper's `surface` law,
    /// Eq. 11 with z0 = 2.071 nm (by the flow), or the challenge's `exponential` law of
    /// range 2.071 nm.
    #[arg(long, value_enum, default_value = "surface")]
    challenge_law: ChallengeLaw,
}

#[derive(Subcommand)]
enum Command {
    /// Regenerate Figures 5-14 of Ghanbarzadeh, Faraji & Neville (2020) as PNG + SVG + CSV,
    /// with FIGURES.md reporting the agreement with each reference.
    Figures(FiguresArgs),
    /// Run a study that prints a table of docs/validation.md (`--list` names them).
    Study {
        /// The study's name.
        #[arg(required_unless_present = "list")]
        name: Option<String>,
        /// List the studies.
        #[arg(long)]
        list: bool,
    },
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<()> {
    let FiguresArgs {
        quick,
        only,
        out,
        challenge_surface,
        fresh,
        studies_only,
        rough_law,
        challenge_law,
    } = match Cli::parse().command {
        Command::Figures(args) => args,
        Command::Study { name, list } => {
            if list {
                let width = xtask::study::STUDIES
                    .iter()
                    .map(|(n, _)| n.len())
                    .max()
                    .unwrap_or(0);
                for (name, what) in xtask::study::STUDIES {
                    println!("{name:width$}  {what}");
                }
                return Ok(());
            }
            return xtask::study::run(name.as_deref().unwrap_or_default());
        }
    };
    let out = out.unwrap_or_else(|| PathBuf::from(if quick { "figures-quick" } else { "figures" }));
    let options = xtask::Options {
        quick,
        only,
        out: out.clone(),
        challenge_surface,
        fresh,
        progress: true,
        rough_law: match rough_law {
            RoughLaw::Point => case::LawKind::Point,
            RoughLaw::Surface => case::LawKind::Surface,
        },
        challenge_law: match challenge_law {
            ChallengeLaw::Surface => case::LawKind::Surface,
            ChallengeLaw::Exponential => case::LawKind::Exponential,
        },
    };
    if studies_only {
        for (file, dir, runs) in xtask::write_studies(options)? {
            println!(
                "{} ({runs} runs): roughcontact study {} --out {}",
                file.display(),
                file.display(),
                dir.display()
            );
        }
        return Ok(());
    }
    let reports = xtask::figures(options)?;
    eprintln!(
        "wrote {} figure(s) and {}",
        reports.len(),
        out.join("FIGURES.md").display()
    );
    Ok(())
}
