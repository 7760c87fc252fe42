//! The three methods as steps of the `envelope-simplify` driver ([`SimplifyStep`]):
//! `local` (5.2), `global` (5.3) and `hybrid` (5.4: "choose nearby groups of vertices to
//! remove simultaneously": the global algorithm within bounded regions where the local one is
//! stuck, see [`HybridStep`]).

use crate::candidates::Fibers;
use crate::global::{GlobalError, GlobalOptions, GlobalStats, simplify_global};
use envelope_mesh::{HalfEdgeMesh, VertexId};
use envelope_simplify::policy::{
    Options as LocalOptions, SimplifyError, Stats, simplify_local_from,
};
use envelope_simplify::{
    HoleFilling, LocalStep, Placement, Progress, SimplifyStep, StepInput, StepOutcome,
};
use serde_json::{Value, json};
use std::collections::HashSet;

/// Which simplification algorithm runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// Vertex removal one at a time (5.2).
    #[default]
    Local,
    /// Greedy set cover by candidate triangles from the whole surface with maximal holes
    /// (5.3), on what the local algorithm leaves, then local again ([`HybridStep::global`]).
    Global,
    /// Local, then global within bounded regions, then local again (5.4, [`HybridStep`]).
    Hybrid,
}

impl Method {
    /// Every method, in the order of [`Method::as_str`]'s names.
    pub const ALL: [Method; 3] = [Method::Local, Method::Global, Method::Hybrid];

    /// `"local"`, `"global"` or `"hybrid"`.
    #[must_use]
    pub const fn as_str(self) -> &'static str {
        match self {
            Method::Local => "local",
            Method::Global => "global",
            Method::Hybrid => "hybrid",
        }
    }

    /// Parses [`Method::as_str`].
    ///
    /// ```
    /// use envelope_global::Method;
    /// assert_eq!(Method::parse("hybrid"), Some(Method::Hybrid));
    /// assert_eq!(Method::parse("fast"), None);
    /// ```
    #[must_use]
    pub fn parse(s: &str) -> Option<Method> {
        Method::ALL.into_iter().find(|m| m.as_str() == s)
    }

    /// The driver step of this method (with the default options of each stage).
    #[must_use]
    pub fn step(self) -> Box<dyn SimplifyStep + Send + Sync> {
        match self {
            Method::Local => Box::new(LocalStep),
            Method::Global => Box::new(HybridStep::global()),
            Method::Hybrid => Box::new(HybridStep::default()),
        }
    }
}

/// The global algorithm as a driver step on the input, optionally followed by the local one
/// (`"global-first"` in the report; [`Method::Global`] runs it after local instead,
/// [`HybridStep::global`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GlobalStep {
    /// Options of the global stage.
    pub options: GlobalOptions,
    /// Run the local algorithm afterwards, over every remaining vertex (a finishing pass:
    /// single removals the global stage's candidates did not reach).
    pub then_local: bool,
}

impl Default for GlobalStep {
    /// The global stage on the input with the region candidates
    /// ([`GlobalOptions::default`]), then the local algorithm to finish.
    fn default() -> Self {
        GlobalStep {
            options: GlobalOptions::default(),
            then_local: true,
        }
    }
}

fn to_simplify_error(e: GlobalError) -> SimplifyError {
    match e {
        GlobalError::NonManifoldVertex(v) => SimplifyError::NonManifoldVertex(v),
        GlobalError::SanityCheck(message) => SimplifyError::SanityCheck {
            after: envelope_mesh::VertexId(u32::MAX),
            message,
        },
    }
}

impl SimplifyStep for GlobalStep {
    fn run(
        &self,
        mesh: &mut HalfEdgeMesh,
        input: &StepInput<'_>,
        progress: &mut dyn Progress,
    ) -> Result<StepOutcome, SimplifyError> {
        let g = run_global(mesh, input, &self.options, progress)?;
        let mut stats = global_stats(&g);
        if !self.then_local {
            return Ok(StepOutcome {
                stats,
                method: "global",
                details: g.to_json(),
            });
        }
        let local = LocalStep.run(mesh, input, progress)?.stats;
        stats.add_later(&local);
        let mut details = g.to_json();
        if let Some(d) = details.as_object_mut() {
            d.insert("local_finish".into(), local_json(&local));
        }
        Ok(StepOutcome {
            stats,
            method: "global-first",
            details,
        })
    }
}

/// The order of the hybrid's stages ([`HybridStep`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum HybridOrder {
    /// Local, then global within bounded regions on what local left, then local again if
    /// global removed anything (the default: measured better, see the crate README).
    #[default]
    LocalFirst,
    /// Global within bounded regions, then local (the issue's wording of 5.4).
    GlobalFirst,
}

impl HybridOrder {
    /// `"local-global-local"` or `"global-local"`.
    #[must_use]
    pub const fn as_str(self) -> &'static str {
        match self {
            HybridOrder::LocalFirst => "local-global-local",
            HybridOrder::GlobalFirst => "global-local",
        }
    }
}

/// The hybrid method (5.4): "choose nearby groups of vertices to remove simultaneously",
/// the global algorithm within bounded regions ([`GlobalOptions::bounded`]) combined with
/// the local one, in the [`HybridOrder`] chosen.
///
/// With [`HybridOrder::LocalFirst`]: local, then global on what local left (where single
/// removals are stuck, groups of vertices may still go together, figure 8), then local
/// again if global changed anything. Each stage only removes vertices (two faces fewer per
/// interior vertex, one per border vertex), so this order never ends with more faces than
/// the local algorithm alone reaches in its first stage. [`HybridOrder::GlobalFirst`] has no
/// such bound.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HybridStep {
    /// Options of the global stage.
    pub options: GlobalOptions,
    /// Which stage runs first.
    pub order: HybridOrder,
    /// A last stage: local again over every remaining vertex, with every triangulation of
    /// holes up to this many vertices tried ([`envelope_simplify::policy::Exhaustive`]) where the
    /// greedy filling of the first stages found none. Skipped when the job's own hole
    /// filling is already exhaustive.
    pub polish: Option<usize>,
    /// The report's method name (`"hybrid"`, or `"global"` for [`HybridStep::global`]).
    pub label: &'static str,
    /// Also run the global stage with these options on the input (then local and the
    /// polish) on a copy, and keep whichever of the two ends with fewer faces
    /// (`method_details.chosen`).
    pub global_first: Option<GlobalOptions>,
}

impl HybridStep {
    /// The report's `method_details`: for `hybrid`, the stages with the global stage under
    /// `"global"`; for `global`, the global stage's counts at the top (the keys of
    /// [`GlobalStats::to_json`]) beside the stages.
    fn details(&self, global: Value, mut stages: Value) -> Value {
        match (self.label, global, stages.as_object_mut()) {
            ("global", Value::Object(mut g), Some(stages)) => {
                g.append(stages);
                Value::Object(g)
            }
            (_, global, Some(map)) => {
                map.insert("global".into(), global);
                stages
            }
            (_, global, None) => global,
        }
    }

    /// The `global` method: local first (the candidates that cover one vertex, cheaply),
    /// then the global stage with whole-surface candidates and their maximal holes
    /// ([`GlobalOptions::surface`]) where single removals are stuck, then local again and
    /// the polish. Never more faces than local (every stage only removes vertices); the
    /// global stage started on the input instead ([`GlobalStep`]) ends with more faces than
    /// local on most of the benchmark (crate README).
    #[must_use]
    pub fn global() -> Self {
        HybridStep {
            options: GlobalOptions::surface(),
            label: "global",
            global_first: Some(GlobalOptions::default()),
            ..HybridStep::default()
        }
    }
}

impl Default for HybridStep {
    /// Bounded global options, local first, exhaustive polish of holes up to 10 vertices.
    fn default() -> Self {
        HybridStep {
            options: GlobalOptions::bounded(),
            order: HybridOrder::default(),
            polish: Some(10),
            label: "hybrid",
            global_first: None,
        }
    }
}

impl SimplifyStep for HybridStep {
    fn run(
        &self,
        mesh: &mut HalfEdgeMesh,
        input: &StepInput<'_>,
        progress: &mut dyn Progress,
    ) -> Result<StepOutcome, SimplifyError> {
        let Some(options) = self.global_first else {
            return self.run_stages(mesh, input, progress);
        };
        // The global stage on the input too (5.3 as the paper runs it), then local and the
        // polish, on a copy; the fewer faces wins (ties: the stages above).
        let mut other = mesh.clone();
        let mut outcome = self.run_stages(mesh, input, progress)?;
        let g = run_global(&mut other, input, &options, progress)?;
        let mut stats = global_stats(&g);
        let local = LocalStep.run(&mut other, input, progress)?.stats;
        stats.add_later(&local);
        let polish = self.run_polish(&mut other, input)?;
        if let Some(l) = &polish {
            stats.add_later(l);
        }
        let chosen = if other.num_faces() < mesh.num_faces() {
            *mesh = other;
            let mut total = stats;
            total.attempts += outcome.stats.attempts;
            total.candidate_tests += outcome.stats.candidate_tests;
            outcome.stats = total;
            "global-first"
        } else {
            outcome.stats.attempts += stats.attempts;
            outcome.stats.candidate_tests += stats.candidate_tests;
            self.order.as_str()
        };
        if let Some(d) = outcome.details.as_object_mut() {
            let mut first = g.to_json();
            if let Some(f) = first.as_object_mut() {
                f.insert("local_finish".into(), local_json(&local));
                f.insert(
                    "polish".into(),
                    polish.as_ref().map_or(Value::Null, local_json),
                );
            }
            d.insert("global_first".into(), first);
            d.insert("chosen".into(), chosen.into());
        }
        Ok(outcome)
    }
}

impl HybridStep {
    /// The polish stage ([`HybridStep::polish`]), when it applies.
    fn run_polish(
        &self,
        mesh: &mut HalfEdgeMesh,
        input: &StepInput<'_>,
    ) -> Result<Option<Stats>, SimplifyError> {
        match (self.polish, input.options.hole_filling) {
            (Some(max_vertices), HoleFilling::Greedy { .. }) => {
                let options = LocalOptions {
                    order: input.options.order,
                    hole_filling: HoleFilling::Exhaustive { max_vertices },
                    target_faces: input.options.target_faces,
                    check_each_step: false,
                    placement: Placement::Subset,
                };
                simplify_local_from(mesh, input.barriers, &options, None, None, None, &mut ())
                    .map(Some)
            }
            _ => Ok(None),
        }
    }

    /// The stages in [`HybridStep::order`], then the polish.
    fn run_stages(
        &self,
        mesh: &mut HalfEdgeMesh,
        input: &StepInput<'_>,
        progress: &mut dyn Progress,
    ) -> Result<StepOutcome, SimplifyError> {
        let first = match self.order {
            HybridOrder::LocalFirst => Some(LocalStep.run(mesh, input, progress)?.stats),
            HybridOrder::GlobalFirst => None,
        };
        let before: HashSet<[VertexId; 3]> = mesh
            .faces()
            .map(|f| canonical(mesh.face_vertices(f)))
            .collect();
        let g = run_global(mesh, input, &self.options, progress)?;
        let mut stats = match &first {
            Some(l) => {
                let mut s = *l;
                s.candidate_tests += g.filter_tests;
                s.attempts += g.attempts;
                s.removed += g.removed;
                s.no_valid_fill += g.no_valid_fill;
                s.vertices_after = g.vertices_after;
                s.faces_after = g.faces_after;
                s
            }
            None => global_stats(&g),
        };
        let second = if first.is_none() || g.removed > 0 {
            // After local, only the vertices of the faces global placed: the rest is as
            // local left it (as local re-queues only a hole's vertices after a removal).
            let changed = first.is_some().then(|| changed_vertices(mesh, &before));
            let l = LocalStep
                .run_from(mesh, input, changed.as_deref(), progress)?
                .stats;
            stats.add_later(&l);
            Some(l)
        } else {
            None
        };
        let polish = self.run_polish(mesh, input)?;
        if let Some(l) = &polish {
            stats.add_later(l);
        }
        Ok(StepOutcome {
            stats,
            method: self.label,
            details: self.details(
                g.to_json(),
                json!({
                    "order": self.order.as_str(),
                    "local": first.as_ref().map(local_json),
                    "local_again": second.as_ref().map(local_json),
                    "polish": polish.as_ref().map(local_json),
                }),
            ),
        })
    }
}

fn run_global(
    mesh: &mut HalfEdgeMesh,
    input: &StepInput<'_>,
    options: &GlobalOptions,
    progress: &mut dyn Progress,
) -> Result<GlobalStats, SimplifyError> {
    let fibers = Fibers {
        inner: input.inner,
        outer: input.outer,
    };
    let options = GlobalOptions {
        target_faces: input.options.target_faces,
        ..*options
    };
    simplify_global(mesh, input.barriers, &fibers, &options, progress).map_err(to_simplify_error)
}

fn global_stats(g: &GlobalStats) -> Stats {
    Stats {
        vertices_before: g.vertices_before,
        faces_before: g.faces_before,
        vertices_after: g.vertices_after,
        faces_after: g.faces_after,
        attempts: g.attempts,
        removed: g.removed,
        no_valid_fill: g.no_valid_fill,
        no_fill_across_fiber: 0,
        answered_ahead: 0,
        refused: g.overlapping,
        candidate_tests: g.filter_tests,
        slid: 0,
        collapsed: 0,
        moving_phase: false,
        moving_phase_light: false,
        light_gave_up: false,
        tolerance_removed: 0,
    }
}

fn local_json(l: &Stats) -> serde_json::Value {
    json!({
        "attempts": l.attempts,
        "removed_vertices": l.removed,
        "faces_after": l.faces_after,
    })
}

/// A face's vertices from its smallest id on, orientation kept.
fn canonical(t: [VertexId; 3]) -> [VertexId; 3] {
    let k = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
}

/// The vertices of the faces not in `before`, each once, in face order.
fn changed_vertices(mesh: &HalfEdgeMesh, before: &HashSet<[VertexId; 3]>) -> Vec<VertexId> {
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    for f in mesh.faces() {
        let t = mesh.face_vertices(f);
        if !before.contains(&canonical(t)) {
            out.extend(t.into_iter().filter(|&v| seen.insert(v)));
        }
    }
    out
}
