//! `close`: the command line: analyze, eval, dataset, plan, verify, record, serve.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use serde::Serialize;

use close::formats::{read_files, Sample};
use close::{analyze, analyze_with, eval, FoldMethod, FrameRange, Options};

#[derive(Parser)]
#[command(
    name = "close",
    version,
    about = "CloSE cloth-state representation: analyse folds, evaluate, serve the web app"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Analyse a sample: one Sample JSON, or one text/CSV file per frame; or one fold of a
    /// video of a VR-Folding Zarr store (`close analyze STORE --video ID --fold 2`).
    Analyze {
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// The video to analyse, when the path is a VR-Folding store (`ID` or `Category/ID`).
        #[arg(long)]
        video: Option<String>,
        /// Which fold of the video: 1 (start → end of action 1) or 2 (start → end of
        /// action 1 → end of action 2; the fold is its second step).
        #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(1..=2))]
        fold: u8,
        /// First frame (default: the first).
        #[arg(long)]
        start: Option<usize>,
        /// Last frame (default: the last).
        #[arg(long)]
        end: Option<usize>,
        /// Print JSON (the only output form; accepted so scripts may say so).
        #[arg(long)]
        json: bool,
        /// Add the start and end dGLI disks as condensed pair vectors.
        #[arg(long)]
        disks: bool,
        /// How fold points are chosen.
        #[arg(long, value_enum, default_value_t = Method::Cut)]
        method: Method,
        /// Most folds one step may hold: a step whose end disk one fold cannot explain is
        /// read as a sequence of up to K folds (1: one fold per step).
        #[arg(long, value_name = "K", default_value_t = close::DEFAULT_MAX_FOLDS as u8,
              value_parser = clap::value_parser!(u8).range(1..=close::fold::sequence::MAX_FOLDS as i64))]
        max_folds: u8,
    },
    /// Evaluate every sample under the given files or folders, and every fold of every video
    /// of a VR-Folding Zarr store (or of one category folder of it).
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
    /// Write the built-in dataset as Sample JSON files into a folder; with `--from STORE`,
    /// the folds of a VR-Folding store instead (one file per video and fold).
    Dataset {
        out: PathBuf,
        /// A VR-Folding Zarr store (or category folder) to export instead of the built-in set.
        #[arg(long)]
        from: Vec<PathBuf>,
        /// Write into OUT even when it already holds files (those of the same name are replaced).
        #[arg(long)]
        force: bool,
    },
    /// Plan how to reach a goal fold from a sample's end state (the paper's planning).
    Plan {
        /// One Sample JSON, or one text/CSV file per frame.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// The goal folds in order, each two angles in radians: `--goal 0.5,3.6` or
        /// `--goal '0.5,3.6;1.2,4.0'` (made in order, each on the state the ones before left).
        #[arg(long, required = true, allow_hyphen_values = true)]
        goal: String,
        /// Print the plan as JSON instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Check a sample's end state against a goal sequence of folds: reached or not, how far,
    /// which folds are missing, extra or misplaced, and the plan that corrects it.
    Verify {
        /// One Sample JSON, or one text/CSV file per frame (the flat start first).
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// The goal folds in order, each two angles in radians: `--goal 0.5,3.6` or
        /// `--goal '0.5,3.6;1.2,4.0'`.
        #[arg(long, required = true, allow_hyphen_values = true)]
        goal: String,
        /// Each fold point within this many edges of the goal's.
        #[arg(long, default_value_t = close::verify::Tolerance::default().edges)]
        tolerance_edges: f64,
        /// The aligned RMSE between the predicted borders at most this (normalised units).
        #[arg(long, default_value_t = close::verify::Tolerance::default().aligned_rmse)]
        tolerance_rmse: f64,
        /// Print the answer as JSON instead of text.
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
        /// Replace the file at OUT when there is one.
        #[arg(long)]
        force: bool,
    },
    /// Serve the web app (the default when no command is given).
    Serve {
        /// Address to listen on.
        #[arg(long, default_value = DEFAULT_ADDR)]
        addr: String,
        /// A folder of the user's own samples (Sample JSON, CSV, OBJ, PLY, .mat; one sample
        /// per file or per sub-folder of frames) or a VR-Folding Zarr store, shown in Browse
        /// next to the built-in set. Repeatable.
        #[arg(long = "dataset")]
        datasets: Vec<PathBuf>,
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
    /// Keep uploads on disk in DIR (the 1000 most recent, 1 GiB at most; the oldest go
    /// first), so their links survive a reload of the page and a restart of the server.
    #[arg(long, value_name = "DIR")]
    data_dir: Option<PathBuf>,
}

impl ServeFlags {
    fn config(self) -> close::server::Config {
        let mut config = close::server::Config {
            allowed_hosts: self.allow_host,
            cors_origins: self.cors,
            data_dir: self.data_dir,
            ..Default::default()
        };
        let secs = std::time::Duration::from_secs;
        config.timeout = self.timeout.map_or(config.timeout, secs);
        config.header_timeout = self.header_timeout.map_or(config.header_timeout, secs);
        config.max_connections = self.max_connections.unwrap_or(config.max_connections);
        config.budget.max_cells = self.max_cells.unwrap_or(config.budget.max_cells);
        config.upload_budget =
            self.upload_budget.map_or(config.upload_budget, |mib| mib.saturating_mul(1 << 20));
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

/// Why a command failed, printed as `error: …`: the library's own error (it names the
/// problem), a file that could not be read or written, or a command line that does not fit.
#[derive(Debug, thiserror::Error)]
enum CliError {
    #[error(transparent)]
    Library(#[from] close::Error),
    #[error(transparent)]
    Read(#[from] close::io_error::Error),
    #[error(transparent)]
    Picture(#[from] close::render::error::Error),
    #[error("{}: {source}", path.display())]
    File { path: PathBuf, source: std::io::Error },
    #[error("writing the output: {0}")]
    Output(std::io::Error),
    #[error("could not write JSON: {0}")]
    Json(#[from] serde_json::Error),
    /// A command line that does not fit what the command takes.
    #[error("{0}")]
    Usage(String),
    /// The server could not start (its address taken, say) or stopped serving.
    #[error(transparent)]
    Serve(close::server::ServeError),
    /// Some of the files of an export could not be written (each was reported).
    #[error("{0}")]
    Incomplete(String),
}

impl CliError {
    /// 2 for a command line that does not fit (as clap's own errors), 1 for every other
    /// failure: a server that cannot start is not the caller's typing.
    fn exit_code(&self) -> ExitCode {
        match self {
            CliError::Usage(_) => ExitCode::from(2),
            _ => ExitCode::FAILURE,
        }
    }
}

type CliResult<T = ()> = Result<T, CliError>;

/// The error of an I/O call on `path`.
fn file_error(path: &Path) -> impl FnOnce(std::io::Error) -> CliError + '_ {
    move |source| CliError::File { path: path.to_path_buf(), source }
}

/// Print a result and a newline; a closed pipe (`close … | head`) is not an error.
fn emit(text: &str) -> CliResult {
    let mut out = std::io::stdout().lock();
    match writeln!(out, "{text}").and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(CliError::Output(e)),
        _ => Ok(()),
    }
}

/// A user's file, read as a regular file through the readers' byte cap.
fn read(path: &Path) -> CliResult<(String, Vec<u8>)> {
    Ok((path.display().to_string(), close::formats::read_file(path)?))
}

/// Write `bytes` to `path` whole or not at all ([`close::formats::write_atomic`]: a temporary
/// file beside it, synced, renamed over it; a link at `path` is replaced, not followed). An
/// existing `path` is refused unless `force`.
fn write_file(path: &Path, bytes: &[u8], force: bool) -> CliResult {
    if !force && std::fs::symlink_metadata(path).is_ok() {
        return Err(CliError::Usage(format!(
            "{} already exists: give --force to replace it",
            path.display()
        )));
    }
    close::formats::write_atomic(path, bytes).map_err(CliError::Output)
}

fn load_sample(paths: &[PathBuf]) -> CliResult<Sample> {
    let files = paths.iter().map(|p| read(p)).collect::<Result<Vec<_>, _>>()?;
    Ok(read_files(&files)?)
}

fn run_analyze(
    files: &[PathBuf],
    video: Option<&str>,
    fold: usize,
    options: Options,
    disks: bool,
) -> CliResult {
    let (sample, mesh_indices, video) = match video {
        Some(id) => store_fold(files, id, fold)?,
        None if files.len() == 1 && files[0].join(".zgroup").is_file() => {
            return Err(CliError::Usage(format!(
                "{} is a Zarr store: choose a video with --video ID (and --fold 1|2)",
                files[0].display()
            )));
        }
        None => (load_sample(files)?, None, None),
    };
    let frames = sample.border_frames()?;
    let mut analysis = analyze_with(&frames, options)?;
    if let Some(mesh) = mesh_indices {
        // The border was gathered from the mesh: report mesh vertex ids.
        analysis.border_indices = analysis.border_indices.iter().map(|&k| mesh[k]).collect();
    }
    let disk =
        |k: usize| disks.then(|| analysis.disk(k).map(|d| d.values().to_vec()).unwrap_or_default());
    let out = AnalyzeOutput {
        analysis: &analysis,
        video,
        disk_start: disk(0),
        disk_end: disk(analysis.frames.len().saturating_sub(1)),
    };
    emit(&serde_json::to_string(&out)?)?;
    Ok(())
}

/// `close analyze`'s JSON: the analysis, with the keys of the video fold it is (`--video`)
/// and, with `--disks`, the values of its first and last disks beside its own.
#[derive(Serialize)]
struct AnalyzeOutput<'a> {
    #[serde(flatten)]
    analysis: &'a close::Analysis,
    #[serde(flatten)]
    video: Option<VideoFold>,
    #[serde(skip_serializing_if = "Option::is_none")]
    disk_start: Option<Vec<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    disk_end: Option<Vec<f64>>,
}

/// Which fold of which VR-Folding video an analysis is, and the video's fold actions.
#[derive(Serialize)]
#[cfg_attr(not(feature = "vrfolding"), allow(dead_code))]
struct VideoFold {
    video: String,
    category: String,
    fold: usize,
    #[cfg(feature = "vrfolding")]
    actions: Vec<close::vrfolding::bifold::Action>,
}

/// Fold `fold` of video `id` of the store at `files[0]`: the border sample, the mesh vertex of
/// each border vertex, and what to add to the output (video, fold, actions).
#[cfg(feature = "vrfolding")]
fn store_fold(
    files: &[PathBuf],
    id: &str,
    fold: usize,
) -> CliResult<(Sample, Option<Vec<usize>>, Option<VideoFold>)> {
    let [path] = files else {
        return Err(CliError::Usage(
            "--video takes one VR-Folding store (or category folder)".into(),
        ));
    };
    let store = close::vrfolding::Store::open(path)?;
    let (videos, _) = store.videos()?;
    let video = videos
        .iter()
        .find(|v| v.id == id || format!("{}/{}", v.category, v.id) == id)
        .ok_or_else(|| {
            CliError::Usage(format!(
                "no video {id:?} in {} (videos are named by video_id, or Category/video_id)",
                path.display()
            ))
        })?;
    let folds = store.folds(video)?;
    let sample = folds.sample(video, fold).ok_or_else(|| {
        CliError::Usage(if fold <= folds.broken.len() {
            format!("fold {fold} of video {id} is dropped: a mesh it uses is broken (BiFold's z-score test)")
        } else {
            format!("video {id} has {} fold action(s), not {fold}", folds.actions.len())
        })
    })?;
    let extra = VideoFold {
        video: video.id.clone(),
        category: video.category.clone(),
        fold,
        actions: folds.actions,
    };
    Ok((sample, Some(folds.border_indices), Some(extra)))
}

#[cfg(not(feature = "vrfolding"))]
fn store_fold(
    _: &[PathBuf],
    _: &str,
    _: usize,
) -> CliResult<(Sample, Option<Vec<usize>>, Option<VideoFold>)> {
    Err(CliError::Usage(NO_VRFOLDING.into()))
}

#[cfg(not(feature = "vrfolding"))]
use close::batch::NO_VRFOLDING;

/// One unit of evaluation work (one progress-bar tick).
enum Work<'a> {
    Unit(close::batch::Unit),
    Builtin(&'a close::dataset::BuiltinSample),
}

impl Work<'_> {
    fn evaluate(&self, method: FoldMethod) -> Vec<eval::SampleResult> {
        match self {
            Work::Unit(unit) => unit.evaluate(method),
            Work::Builtin(entry) => vec![eval::evaluate_with(&entry.sample, method)],
        }
    }
}

fn run_eval(paths: &[PathBuf], builtin: bool, json: bool, method: FoldMethod) -> CliResult {
    let dataset = close::dataset::Dataset::builtin();
    let mut work: Vec<Work> = close::batch::units(paths)?.into_iter().map(Work::Unit).collect();
    if builtin {
        work.extend(dataset.entries().iter().map(Work::Builtin));
    }
    if work.is_empty() {
        return Err(CliError::Usage("no Sample JSON file or VR-Folding video found".into()));
    }
    let bar = if std::io::stderr().is_terminal() {
        ProgressBar::new(work.len() as u64)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} samples/videos {elapsed} eta {eta}")
            .expect("valid template"),
    );
    let results: Vec<eval::SampleResult> = work
        .par_iter()
        .flat_map_iter(|w| {
            let rows = w.evaluate(method);
            bar.inc(1);
            rows
        })
        .collect();
    bar.finish_and_clear();
    let report = eval::report(results);
    if json {
        emit(&serde_json::to_string_pretty(&report)?)?;
    } else {
        emit(report.table().trim_end())?;
        for r in report.samples.iter().filter(|r| r.error.is_some()) {
            eprintln!("error: {}: {}", r.name, r.error.as_deref().unwrap_or_default());
        }
    }
    Ok(())
}

/// Write the samples into folder `out`, created when missing; one that already holds
/// anything is refused unless `force`. Each file is written by [`write_file`], named by
/// [`file_name`]; a file that cannot be written is reported and the others are written.
fn run_dataset(out: &Path, from: &[PathBuf], force: bool) -> CliResult {
    std::fs::create_dir_all(out).map_err(file_error(out))?;
    let held = std::fs::read_dir(out).map_err(file_error(out))?.next().is_some();
    if held && !force {
        return Err(CliError::Usage(format!(
            "{} is not empty: give --force to write into it",
            out.display()
        )));
    }
    if !from.is_empty() {
        return export_stores(out, from);
    }
    let dataset = close::dataset::Dataset::builtin();
    let samples: Vec<(String, &Sample)> =
        dataset.entries().iter().map(|e| (e.id.clone(), &e.sample)).collect();
    let written = write_samples(out, &samples);
    eprintln!("wrote {written} samples to {}", out.display());
    finish(written, samples.len())
}

/// Most bytes of a written file's name before its extension: well inside every file
/// system's 255.
const MAX_NAME: usize = 100;

/// The file name of sample `id`: the id itself when it is plain (ASCII letters, digits,
/// `-`, `_`, `.`, not leading with a dot) and at most [`MAX_NAME`] bytes; otherwise its
/// plain characters (others made `_`), cut to fit, then `-` and a hash of the whole id, so
/// that two ids never share a name (`a/b` and `a_b`, two long ids alike at the start).
fn file_name(id: &str) -> String {
    let plain: String = id
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() || "-_.".contains(c) { c } else { '_' })
        .collect();
    if plain == id && !id.is_empty() && !id.starts_with('.') && id.len() <= MAX_NAME {
        return format!("{id}.json");
    }
    // FNV-1a, 64 bits: the same name for the same id in every build.
    let hash = id.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    });
    let kept = plain.trim_start_matches('.');
    format!("{}-{hash:016x}.json", &kept[..kept.len().min(MAX_NAME - 17)])
}

/// Write each `(id, sample)` into `out` as [`file_name`]`(id)`, in parallel; each failure
/// is reported (`error: …`) and the rest are written. Returns how many were written.
fn write_samples(out: &Path, samples: &[(String, &Sample)]) -> usize {
    let mut names = std::collections::HashSet::new();
    let named: Vec<(PathBuf, &Sample, bool)> = samples
        .iter()
        .map(|(id, sample)| {
            let name = file_name(id);
            let fresh = names.insert(name.clone());
            (out.join(name), *sample, fresh)
        })
        .collect();
    named
        .par_iter()
        .filter(|(path, sample, fresh)| {
            let written = if *fresh {
                write_file(path, close::formats::json::to_json(sample).as_bytes(), true)
            } else {
                Err(CliError::Usage(format!(
                    "{}: two samples map to this name; the second is not written",
                    path.display()
                )))
            };
            written.map_err(|e| eprintln!("error: {e}")).is_ok()
        })
        .count()
}

/// Success when all `total` files were written, else the failure that says how many were.
fn finish(written: usize, total: usize) -> CliResult {
    if written == total {
        return Ok(());
    }
    Err(CliError::Incomplete(format!(
        "{} of {total} files could not be written (see the errors above)",
        total - written
    )))
}

/// Every usable fold of every video of the stores as Sample JSON (`<Category>_<video>_fold<k>`,
/// category `<Category>/fold<k>`); broken folds and unreadable videos are reported and skipped.
#[cfg(feature = "vrfolding")]
fn export_stores(out: &Path, from: &[PathBuf]) -> CliResult {
    let mut work = Vec::new();
    for path in from {
        if !close::catalog::walk::looks_like_store(path) {
            return Err(CliError::Usage(format!(
                "{}: --from takes VR-Folding Zarr stores (a folder with .zgroup)",
                path.display()
            )));
        }
        work.extend(close::batch::store_units(path)?);
    }
    let read: Vec<Result<(close::vrfolding::VideoFolds, &close::vrfolding::Video), String>> = work
        .par_iter()
        .filter_map(|w| match w {
            close::batch::Unit::Video(store, video) => {
                Some(store.folds(video).map(|f| (f, video)).map_err(|e| e.to_string()))
            }
            close::batch::Unit::Failed(name, why) => Some(Err(format!("{name}: {why}"))),
            _ => None,
        })
        .collect();
    let mut samples = Vec::new();
    let (mut dropped, mut unreadable) = (0, 0);
    for found in &read {
        match found {
            Ok((folds, video)) => {
                dropped += folds.dropped();
                samples.extend((1..=folds.usable()).filter_map(|k| {
                    let id = format!("{}_{}_fold{k}", video.category, video.id);
                    folds.sample(video, k).map(|s| (id, s))
                }));
            }
            Err(e) => {
                eprintln!("error: {e}");
                unreadable += 1;
            }
        }
    }
    let borrowed: Vec<(String, &Sample)> = samples.iter().map(|(id, s)| (id.clone(), s)).collect();
    let written = write_samples(out, &borrowed);
    eprintln!(
        "wrote {written} folds of {} videos to {} ({dropped} dropped: broken mesh; {unreadable} videos unreadable)",
        work.len(),
        out.display(),
    );
    finish(written, borrowed.len())
}

#[cfg(not(feature = "vrfolding"))]
fn export_stores(_: &Path, _: &[PathBuf]) -> CliResult {
    Err(CliError::Usage(NO_VRFOLDING.into()))
}

/// Analyse the sample, then plan from its start border, corners and folds to `goal`;
/// vertices are reported as input indices. `--json` prints the plan as the server and Python
/// give it (schema/plan.json).
fn run_plan(files: &[PathBuf], goal: &str, json: bool) -> CliResult {
    let goal: Vec<close::Fold> = parse_goal(goal)?.into_iter().map(close::Fold::from).collect();
    let sample = load_sample(files)?;
    let frames = sample.border_frames()?;
    let analysis = analyze(&frames, FrameRange::default())?;
    // The answer of `POST /api/plan` and Python's `close.plan`: the plan and its start.
    let plan = close::plan::answer(&analysis, &goal)?;
    if json {
        return emit(&serde_json::to_string(&plan)?);
    }
    emit(&close::plan::Plan { case: plan.case, steps: plan.steps }.text())
}

/// The folds of `--goal`: pairs `f1,f2` separated by `;`.
fn parse_goal(text: &str) -> CliResult<Vec<[f64; 2]>> {
    text.split(';')
        .filter(|fold| !fold.trim().is_empty())
        .enumerate()
        .map(|(k, fold)| {
            let angles: Vec<f64> = fold
                .split(',')
                .map(|a| a.trim().parse::<f64>())
                .collect::<Result<_, _>>()
                .map_err(|e| CliError::Usage(format!("--goal, fold {}: {fold:?}: {e}", k + 1)))?;
            match angles[..] {
                [f1, f2] => Ok([f1, f2]),
                _ => Err(CliError::Usage(format!(
                    "--goal, fold {}: {fold:?} is not two angles f1,f2",
                    k + 1
                ))),
            }
        })
        .collect()
}

/// Analyse the sample, then verify its end state against the goal folds.
fn run_verify(
    files: &[PathBuf],
    goal: &str,
    tolerance: close::verify::Tolerance,
    json: bool,
) -> CliResult {
    let goal = close::verify::Goal::folds(parse_goal(goal)?);
    let sample = load_sample(files)?;
    let analysis = analyze(&sample.border_frames()?, FrameRange::default())?;
    let answer = close::verify::verify(&analysis, &goal, tolerance)?;
    if json {
        return emit(&serde_json::to_string(&answer)?);
    }
    let mut text = answer.text.clone();
    let distance = answer.distance;
    text += &format!(
        "
distance: folds {:.4} of the border",
        distance.folds
    );
    if let Some(g) = distance.geometric {
        text += &format!(", shapes {g:.4} (aligned RMSE)");
    }
    for (k, f) in answer.folds.iter().enumerate() {
        let status = serde_json::to_value(f.status)?;
        text += &format!(
            "
fold {}: ({:.4}, {:.4}) {}",
            k + 1,
            f.goal[0],
            f.goal[1],
            status.as_str().unwrap_or_default()
        );
        if let (Some(e), Some(p)) = (f.error_edges, f.error_percent) {
            text += &format!(
                ", points off by {:+.2}, {:+.2} edges ({:+.2} %, {:+.2} %)",
                e[0], e[1], p[0], p[1]
            );
        }
    }
    for e in &answer.extra {
        text += &format!(
            "
extra fold: ({:.4}, {:.4})",
            e.fold[0], e.fold[1]
        );
    }
    emit(&text)
}

#[cfg(feature = "rerun")]
fn run_record(files: &[PathBuf], out: &Path, force: bool) -> CliResult {
    let sample = load_sample(files)?;
    let frames = sample.border_frames()?;
    let analysis = analyze(&frames, FrameRange::default())?;
    let rrd = close::record::record(&analysis, &frames)?;
    write_file(out, &rrd, force)?;
    eprintln!(
        "wrote {} ({} bytes); open it with `rerun {}`",
        out.display(),
        rrd.len(),
        out.display()
    );
    Ok(())
}

fn serve(addr: &str, config: close::server::Config) -> CliResult {
    close::server::run(addr, config).map_err(|e| match e {
        close::server::ServeError::Address { .. } => CliError::Usage(e.to_string()),
        e => CliError::Serve(e),
    })
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let outcome = match cli.command {
        Some(Command::Analyze {
            files,
            video,
            fold,
            start,
            end,
            json: _,
            disks,
            method,
            max_folds,
        }) => {
            let options = Options {
                frames: FrameRange { start, end },
                method: method.into(),
                max_folds: usize::from(max_folds),
                ..Options::default()
            };
            run_analyze(&files, video.as_deref(), usize::from(fold), options, disks)
        }
        Some(Command::Eval { paths, builtin, json, method }) => {
            run_eval(&paths, builtin, json, method.into())
        }
        Some(Command::Dataset { out, from, force }) => run_dataset(&out, &from, force),
        Some(Command::Plan { files, goal, json }) => run_plan(&files, &goal, json),
        Some(Command::Verify { files, goal, tolerance_edges, tolerance_rmse, json }) => {
            let tolerance =
                close::verify::Tolerance { edges: tolerance_edges, aligned_rmse: tolerance_rmse };
            run_verify(&files, &goal, tolerance, json)
        }
        #[cfg(feature = "rerun")]
        Some(Command::Record { files, out, force }) => run_record(&files, &out, force),
        Some(Command::Serve { addr, datasets, limits }) => {
            serve(&addr, close::server::Config { datasets, ..limits.config() })
        }
        None => serve(DEFAULT_ADDR, close::server::Config::default()),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error}");
            error.exit_code()
        }
    }
}
