//! `close`: the command line (SPEC §3).

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use close::formats::{read_files, Sample};
use close::{analyze, analyze_with, eval, FoldMethod, FrameRange, Options};

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
        /// How fold points are chosen.
        #[arg(long, value_enum, default_value_t = Method::Cut)]
        method: Method,
    },
    /// Evaluate every sample under the given files or folders.
    Eval {
        #[arg(required_unless_present = "builtin")]
        paths: Vec<PathBuf>,
        /// Evaluate the built-in dataset (with any given paths).
        #[arg(long)]
        builtin: bool,
        /// Print the full report as JSON instead of a table.
        #[arg(long)]
        json: bool,
        /// How fold points are chosen.
        #[arg(long, value_enum, default_value_t = Method::Cut)]
        method: Method,
    },
    /// Write the built-in dataset as Sample JSON files into a folder.
    Dataset {
        out: PathBuf,
    },
    /// Plan how to reach a goal fold from a sample's end state (SPEC "Planning").
    Plan {
        /// One Sample JSON, or one text/CSV file per frame.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// The goal fold as two angles in radians, e.g. `--goal 0.5,3.6`.
        #[arg(long, required = true, value_delimiter = ',', num_args = 1, allow_hyphen_values = true)]
        goal: Vec<f64>,
        /// Print the plan as JSON instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Write a recording of the analysis for the Rerun viewer (open it with `rerun FILE.rrd`).
    #[cfg(feature = "rerun")]
    Record {
        /// One Sample JSON, or one text/CSV file per frame.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Where to write the .rrd file.
        #[arg(long)]
        out: PathBuf,
    },
    /// Serve the web app (the default when no command is given).
    Serve {
        /// Address to listen on.
        #[arg(long, default_value = DEFAULT_ADDR)]
        addr: String,
        #[command(flatten)]
        limits: ServeFlags,
    },
}

/// Who may reach the server and what it may spend; unset flags keep the server's defaults.
#[derive(clap::Args)]
struct ServeFlags {
    /// Also answer requests whose Host header names NAME (repeatable). Loopback names and
    /// the address listened on are always answered; others are refused (DNS rebinding).
    #[arg(long = "allow-host", value_name = "NAME")]
    allow_host: Vec<String>,
    /// Let pages from ORIGIN (e.g. https://example.org) call the API (repeatable). Off by
    /// default: state-changing requests from other origins are refused.
    #[arg(long, value_name = "ORIGIN")]
    cors: Vec<String>,
    /// Seconds a request may take before it is answered 408 and its work stopped [default: 30].
    #[arg(long, value_name = "SECS")]
    timeout: Option<u64>,
    /// Seconds a connection may take to send its request headers, or stay idle [default: 10].
    #[arg(long, value_name = "SECS")]
    header_timeout: Option<u64>,
    /// Connections served at once [default: 256].
    #[arg(long, value_name = "N")]
    max_connections: Option<usize>,
    /// Most dGLI cells (analysed frames × N²) one analysis may cost [default: 100000000].
    #[arg(long, value_name = "N")]
    max_cells: Option<u64>,
    /// MiB of request bodies held at once across all requests [default: 256].
    #[arg(long, value_name = "MIB")]
    upload_budget: Option<usize>,
}

impl ServeFlags {
    fn config(self) -> close::server::Config {
        let mut config = close::server::Config { allowed_hosts: self.allow_host, cors_origins: self.cors, ..Default::default() };
        let secs = std::time::Duration::from_secs;
        config.timeout = self.timeout.map_or(config.timeout, secs);
        config.header_timeout = self.header_timeout.map_or(config.header_timeout, secs);
        config.max_connections = self.max_connections.unwrap_or(config.max_connections);
        config.budget.max_cells = self.max_cells.unwrap_or(config.budget.max_cells);
        config.upload_budget = self.upload_budget.map_or(config.upload_budget, |mib| mib.saturating_mul(1 << 20));
        config
    }
}

/// Fold point methods, as the command line names them.
#[derive(Clone, Copy, clap::ValueEnum)]
enum Method {
    /// Least same-side change of the diff disk, refined on the rim (default).
    Cut,
    /// The paper's fitted curves alone.
    Paper,
}

impl From<Method> for FoldMethod {
    fn from(m: Method) -> FoldMethod {
        match m {
            Method::Cut => FoldMethod::Cut,
            Method::Paper => FoldMethod::Paper,
        }
    }
}

const DEFAULT_ADDR: &str = "127.0.0.1:8080";

/// Print a result and a newline; a closed pipe (`close … | head`) is not an error.
fn emit(text: &str) -> Result<(), String> {
    let mut out = std::io::stdout().lock();
    match writeln!(out, "{text}").and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(format!("writing the output: {e}")),
        _ => Ok(()),
    }
}

fn read(path: &Path) -> Result<(String, Vec<u8>), String> {
    std::fs::read(path).map(|b| (path.display().to_string(), b)).map_err(|e| format!("{}: {e}", path.display()))
}

fn load_sample(paths: &[PathBuf]) -> Result<Sample, String> {
    let files = paths.iter().map(|p| read(p)).collect::<Result<Vec<_>, _>>()?;
    read_files(&files).map_err(|e| e.to_string())
}

fn run_analyze(files: &[PathBuf], options: Options, disks: bool) -> Result<(), String> {
    let sample = load_sample(files)?;
    let frames = sample.border_frames().map_err(|e| e.to_string())?;
    let analysis = analyze_with(&frames, options).map_err(|e| e.to_string())?;
    let mut out = serde_json::to_value(&analysis).map_err(|e| e.to_string())?;
    if disks {
        let last = analysis.frames.len() - 1;
        for (key, k) in [("disk_start", 0), ("disk_end", last)] {
            out[key] = analysis.disk(k).map(|d| d.values().to_vec()).unwrap_or_default().into();
        }
    }
    emit(&out.to_string())?;
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

fn run_eval(paths: &[PathBuf], builtin: bool, json: bool, method: FoldMethod) -> Result<(), String> {
    let files = sample_files(paths)?;
    let mut samples: Vec<(String, Result<Sample, String>)> = files
        .iter()
        .map(|path| {
            let sample = read(path).and_then(|f| close::formats::json::parse_sample(&f.1).map_err(|e| e.to_string()));
            (path.display().to_string(), sample)
        })
        .collect();
    if builtin {
        samples.extend(close::dataset::builtin().iter().map(|e| (e.id.clone(), Ok(e.sample.clone()))));
    }
    if samples.is_empty() {
        return Err("no Sample JSON file found".into());
    }
    let bar = if std::io::stderr().is_terminal() { ProgressBar::new(samples.len() as u64) } else { ProgressBar::hidden() };
    bar.set_style(ProgressStyle::with_template("{bar:40} {pos}/{len} samples {elapsed} {msg}").expect("valid template"));
    let results: Vec<eval::SampleResult> = samples
        .par_iter()
        .map(|(name, sample)| {
            let result = match sample {
                Ok(sample) => eval::evaluate_with(sample, method),
                Err(e) => eval::SampleResult::unreadable(name, e),
            };
            bar.inc(1);
            result
        })
        .collect();
    bar.finish_and_clear();
    let report = eval::report(results);
    if json {
        emit(&serde_json::to_string_pretty(&report).map_err(|e| e.to_string())?)?;
    } else {
        emit(report.table().trim_end())?;
        for r in report.samples.iter().filter(|r| r.error.is_some()) {
            eprintln!("error: {}: {}", r.name, r.error.as_deref().unwrap_or_default());
        }
    }
    Ok(())
}

fn run_dataset(out: &Path) -> Result<(), String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let entries = close::dataset::builtin();
    for entry in entries {
        let path = out.join(format!("{}.json", entry.id));
        std::fs::write(&path, close::formats::json::to_json(&entry.sample)).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    eprintln!("wrote {} samples to {}", entries.len(), out.display());
    Ok(())
}

/// Analyse the sample, then plan from its start border, corners and folds to `goal`;
/// vertices are reported as input indices.
fn run_plan(files: &[PathBuf], goal: &[f64], json: bool) -> Result<(), String> {
    let &[g1, g2] = goal else {
        return Err(format!("--goal takes two angles f1,f2 (got {} values)", goal.len()));
    };
    let sample = load_sample(files)?;
    let frames = sample.border_frames().map_err(|e| e.to_string())?;
    let analysis = analyze(&frames, FrameRange::default()).map_err(|e| e.to_string())?;
    let mut plan = close::plan::plan(analysis.start_border(), &analysis.corner_vertices, &analysis.folds, [g1, g2])
        .map_err(|e| e.to_string())?;
    for pick in plan.steps.iter_mut().flat_map(|s| s.picks.iter_mut()) {
        pick.vertex = analysis.border_indices[pick.vertex];
    }
    if json {
        return emit(&serde_json::to_string(&plan).map_err(|e| e.to_string())?);
    }
    let mut text = plan.case.clone();
    for (k, step) in plan.steps.iter().enumerate() {
        text += &format!("\n{}. {} ({:.4}, {:.4}), corners {:?}", k + 1, step.action, step.fold[0], step.fold[1], step.corners);
        for p in &step.picks {
            let xyz = |v: [f64; 3]| format!("({:.4}, {:.4}, {:.4})", v[0], v[1], v[2]);
            text += &format!("\n   vertex {}: {} -> {}", p.vertex, xyz(p.from), xyz(p.to));
        }
    }
    emit(&text)
}

#[cfg(feature = "rerun")]
fn run_record(files: &[PathBuf], out: &Path) -> Result<(), String> {
    let sample = load_sample(files)?;
    let frames = sample.border_frames().map_err(|e| e.to_string())?;
    let analysis = analyze(&frames, FrameRange::default()).map_err(|e| e.to_string())?;
    let rrd = close::record::record(&analysis, &frames).map_err(|e| e.to_string())?;
    std::fs::write(out, &rrd).map_err(|e| format!("{}: {e}", out.display()))?;
    eprintln!("wrote {} ({} bytes); open it with `rerun {}`", out.display(), rrd.len(), out.display());
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let outcome = match cli.command {
        Some(Command::Analyze { files, start, end, json: _, disks, method }) => {
            run_analyze(&files, Options { frames: FrameRange { start, end }, method: method.into(), ..Options::default() }, disks)
        }
        Some(Command::Eval { paths, builtin, json, method }) => run_eval(&paths, builtin, json, method.into()),
        Some(Command::Dataset { out }) => run_dataset(&out),
        Some(Command::Plan { files, goal, json }) => run_plan(&files, &goal, json),
        #[cfg(feature = "rerun")]
        Some(Command::Record { files, out }) => run_record(&files, &out),
        Some(Command::Serve { addr, limits }) => close::server::run(&addr, limits.config()),
        None => close::server::run(DEFAULT_ADDR, close::server::Config::default()),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::FAILURE
        }
    }
}
