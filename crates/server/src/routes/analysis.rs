//! A sample loaded and analysed on a worker, its answer written there, and the result
//! cached under its key: what every analysing route (an upload, a listed sample, a plan's
//! state) goes through.

use std::sync::Arc;

use super::json::to_json;
use crate::answer::{AnalyzeAnswer, ListedFields};
use crate::state::{Analyzed, AppState, Drawing, Lane};
use crate::ApiError;
use close_core::analysis::{analyze_with, FrameRange, Options};
use close_core::border::{to_xyz, BorderFrames};
use close_core::budget::{Budget, Deadline};
use close_io::formats::{Sample, Truth};
use close_render::mesh_picture::MeshView;
use close_render::{Picture, DEFAULT_SIZE};

/// A sample that `GET /api/samples` lists, by id: built-in, or from one of the user's
/// datasets (`--dataset`). Both are answered, pictured and planned alike.
pub(super) enum Listed {
    Builtin(String),
    Dataset { id: String, sample: Arc<Sample> },
}

/// Where a sample comes from, as rows and analyses name it: `"builtin"`, the dataset
/// folder or store, or `"upload"`.
pub(super) const BUILTIN: &str = "builtin";
pub(super) const UPLOAD: &str = "upload";

/// A sample read and validated, ready to be analysed.
pub(super) struct Loaded {
    pub(super) key: String,
    pub(super) name: String,
    pub(super) category: String,
    pub(super) frames: usize,
    pub(super) border: BorderFrames,
    pub(super) range: FrameRange,
    /// Most folds one step may hold ([`Options::max_folds`]).
    pub(super) max_folds: usize,
    pub(super) source: String,
    pub(super) truth: Option<Truth>,
    /// A listed sample, whose answer includes the sample.
    pub(super) listed: Option<Listed>,
    /// A mesh sample's mesh at the frames the range asks (the analysis's by default).
    pub(super) mesh: Option<MeshView>,
}

impl Loaded {
    /// Validate `sample`, refused over the cell budget before its border is prepared when
    /// that is known ([`Sample::check_budget`]).
    pub(super) fn of(
        key: String,
        sample: &Sample,
        range: FrameRange,
        source: &str,
        listed: Option<Listed>,
        budget: &Budget,
    ) -> Result<Loaded, ApiError> {
        sample.check_budget(range, budget)?;
        Ok(Loaded {
            key,
            name: sample.name.clone(),
            category: sample.category.clone(),
            frames: frame_count(sample),
            border: sample.border_frames()?,
            range,
            max_folds: close_core::DEFAULT_MAX_FOLDS,
            source: source.to_string(),
            truth: sample.truth.clone(),
            listed,
            mesh: sample.mesh.as_ref().and_then(|m| {
                MeshView::new(
                    m,
                    (
                        range.start.unwrap_or(0),
                        range.end.unwrap_or(m.frames.len().saturating_sub(1)),
                    ),
                )
            }),
        })
    }

    /// dGLI cells of every frame: at least what the analysis of any range costs.
    fn cells(&self) -> u64 {
        let n = self.border.len() as u64;
        (self.border.frames.len() as u64).saturating_mul(n * n)
    }

    /// Analyse, with the server's budget and the job's deadline, and write the response.
    fn analyze(self, state: &AppState, deadline: &Deadline) -> Result<Analyzed, ApiError> {
        let options = Options {
            frames: self.range,
            max_folds: self.max_folds,
            budget: state.config().budget,
            deadline: deadline.clone(),
            ..Options::default()
        };
        let analysis = analyze_with(&self.border, options)?;
        let key = self.key;
        // The view of other frames than the analysis's is no view of it.
        let mesh = self.mesh.filter(|m| m.frames == (analysis.start_frame, analysis.end_frame));
        let listed_pictures =
            Picture::ALL.into_iter().chain(mesh.is_some().then_some(Picture::Mesh));
        let images = listed_pictures
            .map(|p| (p.name(), format!("/api/images/{key}/{}.png?size={DEFAULT_SIZE}", p.name())))
            .collect();
        let listed = match &self.listed {
            Some(Listed::Builtin(id)) => state.entry(id).map(|entry| ListedFields {
                id: &entry.id,
                sample: &entry.sample,
                recording: cfg!(feature = "rerun")
                    .then(|| format!("/api/samples/{}/recording.rrd", entry.id)),
            }),
            Some(Listed::Dataset { id, sample }) => {
                Some(ListedFields { id, sample, recording: None })
            }
            None => None,
        };
        let response = to_json(&AnalyzeAnswer {
            key: &key,
            name: &self.name,
            category: &self.category,
            frames: self.frames,
            analysis: &analysis,
            start_border: analysis.start_border().iter().map(to_xyz).collect(),
            end_border: analysis.end_border().iter().map(to_xyz).collect(),
            images,
            source: &self.source,
            truth: self.truth.as_ref(),
            listed,
        })?;
        let truth = self.truth.as_ref().map(close_render::truth::Truth::of).unwrap_or_default();
        Ok(Analyzed { key, drawing: Arc::new(Drawing::new(analysis, truth, mesh)), response })
    }
}

/// The cached analysis under `key`, or `load` the sample (within the job's deadline) and
/// analyse it. Both run on a worker: a light analysis in the same job as its loading, a heavy one (over
/// [`Lane::of`]'s threshold) in the heavy lane, so it never holds the light workers.
pub(super) async fn analysis(
    state: &AppState,
    key: String,
    load: impl FnOnce(String, &Deadline) -> Result<Loaded, ApiError> + Send + 'static,
) -> Result<Arc<Analyzed>, ApiError> {
    if let Some(hit) = state.cached_analysis(&key) {
        return Ok(hit);
    }
    let job = state.clone();
    let loaded = state
        .run_cpu(Lane::Light, move |deadline| {
            let loaded = load(key, deadline)?;
            // A request gone while its sample was read hands nothing on to the heavy lane.
            deadline.check()?;
            match Lane::of(loaded.cells()) {
                Lane::Light => loaded.analyze(&job, deadline).map(Ok),
                Lane::Heavy => Ok(Err(loaded)),
            }
        })
        .await?;
    let analyzed = match loaded {
        Ok(done) => done,
        Err(heavy) => {
            let job = state.clone();
            state.run_cpu(Lane::Heavy, move |deadline| heavy.analyze(&job, deadline)).await?
        }
    };
    let analyzed = Arc::new(analyzed);
    state.cache_analysis(&analyzed);
    Ok(analyzed)
}

/// Frames of a border or mesh sample.
pub(super) fn frame_count(sample: &Sample) -> usize {
    sample.mesh.as_ref().map_or(sample.frames.len(), |m| m.frames.len())
}
