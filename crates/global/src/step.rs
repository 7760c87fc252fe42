//! The three methods as steps of the `envelope-simplify` driver ([`SimplifyStep`]):
//! `local` (5.2), `global` (5.3) and `hybrid` (5.4: "choose nearby groups of vertices to
//! remove simultaneously": the global algorithm within bounded regions where the local one is
//! stuck, see [`HybridStep`]).

use crate::candidates::Fibers;
use crate::global::{GlobalError, GlobalOptions, GlobalStats, simplify_global};
use envelope_mesh::HalfEdgeMesh;
use envelope_simplify::{
    LocalStep, Progress, SimplifyError, SimplifyStep, Stats, StepInput, StepOutcome,
};
use serde_json::json;

/// Which simplification algorithm runs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Method {
    /// Vertex removal one at a time (5.2).
    #[default]
    Local,
    /// Greedy set cover by candidate triangles (5.3), border vertices in open regions.
    Global,
    /// Local, then global within bounded regions, then local again (5.4, [`HybridStep`]).
    Hybrid,
}

impl Method {
    /// `"local"`, `"global"` or `"hybrid"`.
    #[must_use]
    pub fn as_str(self) -> &'static str {
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
        [Method::Local, Method::Global, Method::Hybrid]
            .into_iter()
            .find(|m| m.as_str() == s)
    }

    /// The driver step of this method (with the default options of each stage).
    #[must_use]
    pub fn step(self) -> Box<dyn SimplifyStep + Send + Sync> {
        match self {
            Method::Local => Box::new(LocalStep),
            Method::Global => Box::new(GlobalStep {
                options: GlobalOptions::default(),
                then_local: false,
            }),
            Method::Hybrid => Box::new(HybridStep::default()),
        }
    }
}

/// The global algorithm as a driver step, optionally followed by the local one (hybrid).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GlobalStep {
    /// Options of the global stage.
    pub options: GlobalOptions,
    /// Run the local algorithm afterwards (the hybrid method).
    pub then_local: bool,
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
        add_local(&mut stats, &local);
        Ok(StepOutcome {
            stats,
            method: "global+local",
            details: json!({ "global": g.to_json(), "local": local_json(&local) }),
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
    pub fn as_str(self) -> &'static str {
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
}

impl Default for HybridStep {
    /// Bounded global options, local first.
    fn default() -> Self {
        HybridStep {
            options: GlobalOptions::bounded(),
            order: HybridOrder::default(),
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
        let first = match self.order {
            HybridOrder::LocalFirst => Some(LocalStep.run(mesh, input, progress)?.stats),
            HybridOrder::GlobalFirst => None,
        };
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
            let l = LocalStep.run(mesh, input, progress)?.stats;
            add_local(&mut stats, &l);
            Some(l)
        } else {
            None
        };
        Ok(StepOutcome {
            stats,
            method: "hybrid",
            details: json!({
                "order": self.order.as_str(),
                "local": first.as_ref().map(local_json),
                "global": g.to_json(),
                "local_again": second.as_ref().map(local_json),
            }),
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
    simplify_global(mesh, input.barriers, &fibers, options, progress).map_err(to_simplify_error)
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
        refused: g.overlapping,
        candidate_tests: g.filter_tests,
    }
}

fn add_local(stats: &mut Stats, local: &Stats) {
    stats.vertices_after = local.vertices_after;
    stats.faces_after = local.faces_after;
    stats.attempts += local.attempts;
    stats.removed += local.removed;
    stats.no_valid_fill += local.no_valid_fill;
    stats.refused += local.refused;
    stats.candidate_tests += local.candidate_tests;
}

fn local_json(l: &Stats) -> serde_json::Value {
    json!({
        "attempts": l.attempts,
        "removed_vertices": l.removed,
        "faces_after": l.faces_after,
    })
}
