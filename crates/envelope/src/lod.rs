//! Levels of detail (Cohen et al. 7.2): each level simplified from the one before within its
//! step, bounded against the original by the sum of the steps, with switching distances.

use envelope_simplify::{Level, LodOptions, LodRule, Screen, Stage, lod_chain};

use crate::progress::{Callback, Relay};
use crate::{EnvelopeMethod, Epsilon, Error, Event, HoleFilling, Mesh, defaults, threads};

/// A chain of levels of detail with nested vertex sets.
///
/// ```
/// use envelope::{Epsilon, Lod};
/// let cup = envelope::Mesh::demo();
/// let levels = Lod::new(vec![Epsilon::percent(0.5), Epsilon::percent(1.0)]).run(&cup)?;
/// assert_eq!(levels.len(), 2);
/// assert!(levels[1].mesh.num_faces() <= levels[0].mesh.num_faces());
/// assert!(levels.iter().all(|l| l.certified.as_ref().is_some_and(|c| c.certificate.holds())));
/// # Ok::<(), envelope::Error>(())
/// ```
pub struct Lod<'a> {
    epsilons: Vec<Epsilon>,
    rule: LodRule,
    envelope_method: EnvelopeMethod,
    hole_filling: HoleFilling,
    tube_segments: Option<u32>,
    certify: bool,
    correspondences: bool,
    screen: Screen,
    threads: Option<usize>,
    progress: Option<Box<Callback<'a>>>,
}

impl<'a> Lod<'a> {
    /// A chain at these epsilons: with the default [`LodRule::Cumulative`] each is a level's
    /// bound to the original, and they must increase.
    #[must_use]
    pub fn new(epsilons: Vec<Epsilon>) -> Self {
        Lod {
            epsilons,
            rule: LodRule::default(),
            envelope_method: defaults::ENVELOPE_METHOD,
            hole_filling: defaults::hole_filling(),
            tube_segments: Some(defaults::TUBE_SEGMENTS),
            certify: defaults::CERTIFY,
            correspondences: false,
            screen: Screen::default(),
            threads: None,
            progress: None,
        }
    }

    /// Whether the epsilons are bounds (cumulative) or steps (summed, the paper's 7.2).
    #[must_use]
    pub fn rule(mut self, rule: LodRule) -> Self {
        self.rule = rule;
        self
    }

    /// Whether each level gets its [`Correspondence`](crate::Correspondence) to the level
    /// before (Cohen et al. 8.1: which faces of the finer level each face covers), in
    /// [`Level::correspondence`]; costs one more envelope build per level. Off by default.
    ///
    /// ```
    /// use envelope::{Epsilon, Lod};
    /// let cup = envelope::Mesh::demo();
    /// let levels = Lod::new(vec![Epsilon::percent(0.5), Epsilon::percent(1.0)])
    ///     .correspondences(true)
    ///     .run(&cup)?;
    /// let c = levels[1].correspondence.as_ref().unwrap();
    /// assert_eq!(c.coarse_faces, levels[1].mesh.num_faces());
    /// assert_eq!(c.fine_faces, levels[0].mesh.num_faces());
    /// assert!(c.is_onto());
    /// # Ok::<(), envelope::Error>(())
    /// ```
    #[must_use]
    pub fn correspondences(mut self, on: bool) -> Self {
        self.correspondences = on;
        self
    }

    /// How the envelopes find their offsets.
    #[must_use]
    pub fn envelope_method(mut self, method: EnvelopeMethod) -> Self {
        self.envelope_method = method;
        self
    }

    /// How holes are filled.
    #[must_use]
    pub fn hole_filling(mut self, hole_filling: HoleFilling) -> Self {
        self.hole_filling = hole_filling;
        self
    }

    /// Certify each level against the original at its bound (on by default).
    #[must_use]
    pub fn certify(mut self, certify: bool) -> Self {
        self.certify = certify;
        self
    }

    /// The display switching distances are computed for.
    #[must_use]
    pub fn screen(mut self, screen: Screen) -> Self {
        self.screen = screen;
        self
    }

    /// Worker threads (default: one per core); the levels are the same for any number.
    #[must_use]
    pub fn threads(mut self, threads: usize) -> Self {
        self.threads = Some(threads);
        self
    }

    /// A callback told each level and its stages; it may cancel.
    #[must_use]
    pub fn progress(
        mut self,
        callback: impl Fn(Event) -> std::ops::ControlFlow<()> + Send + Sync + 'a,
    ) -> Self {
        self.progress = Some(Box::new(callback));
        self
    }

    /// The engine's options, epsilons resolved against `mesh`'s diagonal.
    fn options(&self, mesh: &Mesh) -> Result<LodOptions, Error> {
        let epsilons = self
            .epsilons
            .iter()
            .map(|e| Ok(e.validate()?.resolve(mesh)))
            .collect::<Result<Vec<f64>, Error>>()?;
        if self.rule == LodRule::Cumulative
            && let Some(i) = (1..epsilons.len()).find(|&i| epsilons[i] <= epsilons[i - 1])
        {
            return Err(Error::InvalidEpsilon(format!(
                "cumulative bounds must increase, but item {} ({}) is not larger than item {} ({})",
                i + 1,
                self.epsilons[i],
                i,
                self.epsilons[i - 1]
            )));
        }
        Ok(LodOptions {
            rule: self.rule,
            method: self.envelope_method,
            hole_filling: self.hole_filling,
            tube_segments: self.tube_segments,
            verify: self.certify,
            correspondences: self.correspondences,
            screen: self.screen,
            // Seam vertices stay where they are, so texture charts do not tear.
            keep: crate::seam_vertices(mesh),
            ..LodOptions::new(epsilons)
        })
    }

    /// Builds the chain (level 0, the input itself, is not listed); `on_level` hears each
    /// level as it is made. Vertices on texture-coordinate or colour seams are kept in every
    /// level ([`crate::seam_vertices`]); a level's attributes are
    /// [`crate::carry_attributes`]`(mesh, &level.mesh)` ([`Lod::level_mesh`]).
    ///
    /// # Errors
    /// As [`Simplifier::run`](crate::Simplifier::run) for each level; a level whose
    /// certificate is violated is returned, not refused: look at `certified`.
    pub fn run(&self, mesh: &Mesh) -> Result<Vec<Level>, Error> {
        self.run_with(mesh, &mut |_| {})
    }

    /// [`Lod::run`], calling `on_level` after each level.
    ///
    /// # Errors
    /// As [`Lod::run`].
    pub fn run_with(
        &self,
        mesh: &Mesh,
        on_level: &mut (dyn FnMut(&Level) + Send),
    ) -> Result<Vec<Level>, Error> {
        let options = self.options(mesh)?;
        let mut relay = Levels {
            relay: Relay::new(self.progress.as_deref()),
            index: 0,
            count: options.epsilons.len(),
        };
        Ok(threads::run(self.threads, || {
            lod_chain(mesh.soup(), &options, &mut relay, on_level)
        })??)
    }
}

impl Lod<'_> {
    /// A level as a [`Mesh`] with the attributes carried from `original`, the mesh the chain
    /// was built from ([`crate::carry_attributes`]).
    #[must_use]
    pub fn level_mesh(original: &Mesh, level: &Level) -> Mesh {
        let attributes = crate::carry_attributes(original, &level.mesh);
        Mesh::from_parts(level.mesh.clone(), attributes)
    }
}

/// Tells the callback which level begins before its stages.
struct Levels<'a> {
    relay: Relay<'a>,
    index: usize,
    count: usize,
}

impl envelope_simplify::Progress for Levels<'_> {
    fn stage(&mut self, stage: Stage) {
        if stage == Stage::Check {
            self.index += 1;
            self.relay.tell(Event::Level {
                index: self.index,
                count: self.count,
            });
        }
        self.relay.stage(stage);
    }

    fn step(&mut self, attempts: usize, removed: usize) {
        self.relay.step(attempts, removed);
    }

    fn cancelled(&mut self) -> bool {
        self.relay.cancelled()
    }
}
