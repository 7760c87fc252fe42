//! Levels of detail with nested vertex sets (section 7.2): level `i` simplifies level
//! `i - 1`, so its vertices are a subset of level `i - 1`'s.
//!
//! **The cumulative bound.** The envelopes of level `i` are built around level `i - 1`, so
//! the guarantee of one step is relative to the previous level. The directed Hausdorff
//! distance obeys the triangle inequality, `h(A, C) <= h(A, B) + h(B, C)`, in each direction;
//! so if every step `j` is within `delta_j` of its predecessor both ways, level `i` is within
//! `delta_1 + ... + delta_i` of the original both ways. Two rules ([`LodRule`]):
//!
//! | rule | step epsilon `delta_i` | cumulative bound of level `i` |
//! |---|---|---|
//! | [`LodRule::Cumulative`] (default) | `eps_i - eps_{i-1}` (`delta_1 = eps_1`) | `eps_i`: the requested epsilon is the bound to the original |
//! | [`LodRule::Sum`] (the paper's 7.2) | `eps_i` | `eps_1 + ... + eps_i` (1, 2, 4, 8 % give 1, 3, 7, 15 %) |
//!
//! With doubling epsilons (`1/64 %, 1/32 %, ...`) the default rule simplifies each level with
//! the previous level's epsilon as increment. Whatever the rule, [`Level::certified`] checks
//! the cumulative bound against the **original** directly when asked.
//!
//! **Switching distances.** A viewer at distance `d` with a horizontal field of view `fov`
//! sees a slab `2 d tan(fov / 2)` wide across `W` pixels, so a length `eps` there covers
//! `eps W / (2 d tan(fov / 2))` pixels. Level `i` may be shown from the distance where its
//! cumulative bound covers `P` pixels: `d_i = eps_i W / (2 P tan(fov / 2))` ([`Screen`]).
//! Closer than `d_1` the original (level 0) is shown.

use envelope_mesh::TriangleSoup;
use envelope_offset::{EnvelopeMethod, EpsilonField};
use serde_json::{Value, json};

use crate::correspond::{Correspondence, correspondence};
use crate::driver::{DriverError, Progress, SimplifyOptions, SimplifyReport, VerifyReport};
use crate::driver::{envelopes_for, simplify};
use crate::local::HoleFilling;

/// How each level's step epsilon relates to the requested epsilons (see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LodRule {
    /// Requested epsilons are cumulative bounds; steps are their differences.
    #[default]
    Cumulative,
    /// Requested epsilons are steps; bounds are their running sums (the paper's 7.2).
    Sum,
}

/// The display that switching distances are computed for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Screen {
    /// Tolerated error in pixels (`P`).
    pub pixels: f64,
    /// Screen width in pixels (`W`).
    pub resolution: f64,
    /// Horizontal field of view in degrees.
    pub fov_degrees: f64,
}

impl Default for Screen {
    /// One pixel on a 1920-pixel-wide screen with a 60-degree field of view.
    fn default() -> Self {
        Screen {
            pixels: 1.0,
            resolution: 1920.0,
            fov_degrees: 60.0,
        }
    }
}

impl Screen {
    /// The viewing distance at which a length `eps` projects to `pixels` pixels:
    /// `eps W / (2 P tan(fov / 2))`.
    #[must_use]
    pub fn switching_distance(&self, eps: f64) -> f64 {
        eps * self.resolution / (2.0 * self.pixels * (self.fov_degrees.to_radians() / 2.0).tan())
    }
}

/// Options of [`lod_chain`].
#[derive(Clone, Debug)]
pub struct LodOptions {
    /// Requested epsilons (absolute), strictly increasing for [`LodRule::Cumulative`].
    pub epsilons: Vec<f64>,
    /// How steps and bounds follow from them.
    pub rule: LodRule,
    /// Envelope method of every step.
    pub method: EnvelopeMethod,
    /// Hole filling of every step.
    pub hole_filling: HoleFilling,
    /// Border tubes (`None`: border vertices are kept).
    pub tube_segments: Option<u32>,
    /// Certify each level against the original at its cumulative bound.
    pub verify: bool,
    /// For switching distances.
    pub screen: Screen,
    /// Vertices of the original no level may remove or move, by id (empty: none), as
    /// [`SimplifyOptions::keep`]; each level's own ids are found by position (levels keep
    /// the original's positions bitwise).
    pub keep: Vec<bool>,
    /// Compute each level's [`Correspondence`] to the level before (section 8.1), on the
    /// step's envelopes built again (the cost of one more envelope build per level).
    pub correspondences: bool,
}

impl LodOptions {
    /// Defaults for a list of epsilons (cumulative rule, auto envelopes, greedy, tubes, verify).
    #[must_use]
    pub fn new(epsilons: Vec<f64>) -> Self {
        LodOptions {
            epsilons,
            rule: LodRule::default(),
            method: EnvelopeMethod::Auto,
            hole_filling: HoleFilling::default(),
            tube_segments: Some(8),
            verify: true,
            screen: Screen::default(),
            keep: Vec::new(),
            correspondences: false,
        }
    }
}

/// One level of detail (level 0 is the input itself and is not listed).
#[derive(Clone, Debug)]
pub struct Level {
    /// 1, 2, ...
    pub index: usize,
    /// The mesh.
    pub mesh: TriangleSoup,
    /// The requested epsilon (absolute).
    pub requested: f64,
    /// The epsilon of this step's envelopes, around the previous level.
    pub step: f64,
    /// The bound to the original, both ways (see the module docs).
    pub cumulative: f64,
    /// The step's report (input = the previous level).
    pub report: SimplifyReport,
    /// This level against the original at `cumulative`, when asked.
    pub certified: Option<VerifyReport>,
    /// Viewing distance from which this level may be shown ([`Screen::switching_distance`]).
    pub switching_distance: f64,
    /// Which faces of the level before each face of this one covers, when asked
    /// ([`LodOptions::correspondences`]).
    pub correspondence: Option<Correspondence>,
}

impl Level {
    /// Stable JSON keys; relative values are over `diagonal` (the original's).
    #[must_use]
    pub fn to_json(&self, diagonal: f64) -> Value {
        json!({
            "level": self.index,
            "faces": self.mesh.num_faces(),
            "vertices": self.mesh.num_vertices(),
            "epsilon_requested": self.requested,
            "epsilon_requested_fraction": self.requested / diagonal,
            "epsilon_step": self.step,
            "cumulative_bound": self.cumulative,
            "cumulative_bound_fraction": self.cumulative / diagonal,
            "switching_distance": self.switching_distance,
            "seconds": self.report.seconds,
            "genus": self.report.genus_out,
            "border_loops": self.report.border_loops_out,
            "envelope_proved": self.report.envelope.proved,
            "certified_vs_original": self.certified.as_ref().map(VerifyReport::to_json),
        })
    }
}

/// The chain of levels for `options.epsilons` (see the module docs). `progress` hears each
/// level's stages in turn; `on_level` is called after each level.
pub fn lod_chain(
    original: &TriangleSoup,
    options: &LodOptions,
    progress: &mut dyn Progress,
    on_level: &mut dyn FnMut(&Level),
) -> Result<Vec<Level>, DriverError> {
    let eps = &options.epsilons;
    if eps.is_empty() || eps.iter().any(|e| !(e.is_finite() && *e > 0.0)) {
        return Err(DriverError::Epsilons(
            "the epsilons must be finite and positive",
        ));
    }
    if options.rule == LodRule::Cumulative && eps.windows(2).any(|w| w[1] <= w[0]) {
        return Err(DriverError::Epsilons(
            "cumulative epsilons must be strictly increasing",
        ));
    }
    let mut levels: Vec<Level> = Vec::new();
    let mut cumulative = 0.0;
    // The kept vertices' positions (bits), to find them again in each level.
    let kept: std::collections::HashSet<[u64; 3]> = options
        .keep
        .iter()
        .zip(&original.positions)
        .filter(|(k, _)| **k)
        .map(|(_, p)| p.to_array().map(f64::to_bits))
        .collect();
    for (i, &requested) in eps.iter().enumerate() {
        let step = match (options.rule, i) {
            (LodRule::Cumulative, 0) | (LodRule::Sum, _) => requested,
            (LodRule::Cumulative, _) => requested - eps[i - 1],
        };
        cumulative = match options.rule {
            LodRule::Cumulative => requested,
            LodRule::Sum => cumulative + requested,
        };
        let previous = levels.last().map_or(original, |l| &l.mesh);
        let keep = if i == 0 || kept.is_empty() {
            options.keep.clone()
        } else {
            previous
                .positions
                .iter()
                .map(|p| kept.contains(&p.to_array().map(f64::to_bits)))
                .collect()
        };
        let step_options = SimplifyOptions {
            method: options.method,
            hole_filling: options.hole_filling,
            tube_segments: options.tube_segments,
            keep,
            ..SimplifyOptions::new(EpsilonField::Constant(step))
        };
        let (mesh, report) = simplify(previous, &step_options, progress)?;
        let correspondence = if options.correspondences {
            // The driver's envelopes are gone with its working state; the build is
            // deterministic, so building them again gives the same prisms.
            let envelopes = envelopes_for(previous, &step_options, None)?;
            let mut c = correspondence(previous, &envelopes, &mesh);
            if report.kept.is_some() {
                // Made within the envelopes of the part not kept, not these: no bound.
                c.error.clear();
            }
            Some(c)
        } else {
            None
        };
        let certified = options.verify.then(|| {
            let t = std::time::Instant::now();
            let c = envelope_verify::certify(
                original,
                &mesh,
                // A self-intersecting input's own crossings are kept as they are.
                &envelope_verify::Options {
                    allow_input_intersections: true,
                    ..envelope_verify::Options::new(cumulative)
                },
            );
            VerifyReport::from_certificate(c, t.elapsed().as_secs_f64())
        });
        let level = Level {
            index: i + 1,
            mesh,
            requested,
            step,
            cumulative,
            report,
            certified,
            switching_distance: options.screen.switching_distance(cumulative),
            correspondence,
        };
        on_level(&level);
        levels.push(level);
    }
    Ok(levels)
}
