//! `close`: the command line (SPEC §3).

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use close::formats::{read_files, Sample};
use close::{analyze, eval, FrameRange};

#[derive(Parser)]
#[command(name = "close", version, about = "CloSE cloth-state representation: analyse folds, evaluate, serve the web app")]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Analyse a sample: one Sample JSON, or one text/CSV file per frame.
    Analyze {
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// First frame (default: the first).
        #[arg(long)]
        start: Option<usize>,
        /// Last frame (default: the last).
        #[arg(long)]
        end: Option<usize>,
        /// Print JSON (the only output form; accepted for the SPEC's command line).
        #[arg(long)]
        json: bool,
        /// Add the start and end dGLI disks as condensed pair vectors.
        #[arg(long)]
        disks: bool,
    },
    /// Evaluate every sample under the given files or folders.
    Eval {
        #[arg(required = true)]
        paths: Vec<PathBuf>,
        /// Print the full report as JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// Serve the web app (the default when no command is given).
    Serve {
        /// Address to listen on.
        #[arg(long, default_value = DEFAULT_ADDR)]
        addr: String,
    },
}

const DEFAULT_ADDR: &str = "127.0.0.1:8080";

fn read(path: &Path) -> Result<(String, Vec<u8>), String> {
    std::fs::read(path).map(|b| (path.display().to_string(), b)).map_err(|e| format!("{}: {e}", path.display()))
}

fn load_sample(paths: &[PathBuf]) -> Result<Sample, String> {
    let files = paths.iter().map(|p| read(p)).collect::<Result<Vec<_>, _>>()?;
    read_files(&files).map_err(|e| e.to_string())
}

fn run_analyze(files: &[PathBuf], range: FrameRange, disks: bool) -> Result<(), String> {
    let sample = load_sample(files)?;
    let frames = sample.border_frames().map_err(|e| e.to_string())?;
    let analysis = analyze(&frames, range).map_err(|e| e.to_string())?;
    let mut out = serde_json::to_value(&analysis).map_err(|e| e.to_string())?;
    if disks {
        out["disk_start"] = analysis.disk_start.values().into();
        out["disk_end"] = analysis.disk_end.values().into();
    }
    println!("{out}");
    Ok(())
}

/// Every `.json` file under the given files and folders, sorted.
fn sample_files(paths: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    let mut out = Vec::new();
    let mut stack: Vec<PathBuf> = paths.to_vec();
    while let Some(p) = stack.pop() {
        if p.is_dir() {
            let entries = std::fs::read_dir(&p).map_err(|e| format!("{}: {e}", p.display()))?;
            stack.extend(entries.filter_map(|e| e.ok()).map(|e| e.path()));
        } else if p.extension().is_some_and(|e| e == "json") {
            out.push(p);
        } else if paths.contains(&p) {
            return Err(format!("{}: not a folder or a Sample JSON file", p.display()));
        }
    }
    out.sort();
    Ok(out)
}

fn run_eval(paths: &[PathBuf], json: bool) -> Result<(), String> {
    let files = sample_files(paths)?;
    if files.is_empty() {
        return Err("no Sample JSON file found".into());
    }
    let bar = if std::io::stderr().is_terminal() { ProgressBar::new(files.len() as u64) } else { ProgressBar::hidden() };
    bar.set_style(ProgressStyle::with_template("{bar:40} {pos}/{len} samples {elapsed} {msg}").expect("valid template"));
    let results: Vec<eval::SampleResult> = files
        .par_iter()
        .map(|path| {
            let result = match read(path).and_then(|f| close::formats::json::parse_sample(&f.1).map_err(|e| e.to_string())) {
                Ok(sample) => eval::evaluate(&sample),
                Err(e) => eval::SampleResult {
                    name: path.display().to_string(),
                    category: "unreadable".into(),
                    folds: 0,
                    expected_folds: 0,
                    rmse: None,
                    frechet: None,
                    angle_error: None,
                    error: Some(e),
                },
            };
            bar.inc(1);
            result
        })
        .collect();
    bar.finish_and_clear();
    let report = eval::report(results);
    if json {
        println!("{}", serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?);
    } else {
        print!("{}", report.table());
        for r in report.samples.iter().filter(|r| r.error.is_some()) {
            eprintln!("error: {}: {}", r.name, r.error.as_deref().unwrap_or_default());
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let outcome = match cli.command {
        Some(Command::Analyze { files, start, end, json: _, disks }) => run_analyze(&files, FrameRange { start, end }, disks),
        Some(Command::Eval { paths, json }) => run_eval(&paths, json),
        Some(Command::Serve { addr }) => close::server::run(&addr),
        None => close::server::run(DEFAULT_ADDR),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}
