//! The simplifier of both papers' guarantee behind one builder: the input checked, the
//! envelopes built and proved, the surface simplified between them, the output certified.

use envelope_offset::{EnvelopeMethod, EpsilonField};
use envelope_simplify::{HoleFilling, Placement, SimplifyOptions, simplify_with};
use envelope_verify::Verdict;

use crate::progress::{Callback, Relay};
use crate::{Epsilon, Error, Event, Mesh, Method, Simplified, defaults, threads};

/// Simplifies a mesh within epsilon of it, both ways, keeping its topology and making no
/// self-intersection (Cohen et al. 1996), and certifies the output.
///
/// Every setting has the command line's default ([`defaults`]).
///
/// ```
/// use envelope::{Epsilon, Placement, Simplifier};
/// let cup = envelope::Mesh::demo();
/// let done = Simplifier::new(Epsilon::percent(1.0))
///     .placement(Placement::Subset)
///     .threads(1)
///     .run(&cup)?;
/// assert!(done.is_certified());
/// assert!(done.mesh().num_faces() < cup.num_faces() / 4);
/// # Ok::<(), envelope::Error>(())
/// ```
pub struct Simplifier<'a> {
    epsilon: EpsilonChoice,
    method: Method,
    envelope_method: EnvelopeMethod,
    placement: Placement,
    hole_filling: HoleFilling,
    tube_segments: Option<u32>,
    target_faces: Option<usize>,
    certify: bool,
    tolerance_phase: bool,
    threads: Option<usize>,
    progress: Option<Box<Callback<'a>>>,
}

/// Where the epsilon of each vertex comes from.
#[derive(Clone, Debug)]
enum EpsilonChoice {
    Uniform(Epsilon),
    PerVertex(Vec<Epsilon>),
}

impl<'a> Simplifier<'a> {
    /// A simplifier holding every point of the output within `epsilon` of the input and back.
    #[must_use]
    pub fn new(epsilon: Epsilon) -> Self {
        Self::with(EpsilonChoice::Uniform(epsilon))
    }

    /// Per-vertex epsilons (section 6.3), one per vertex of the mesh it will run on, in vertex
    /// order; the output is held to the largest.
    #[must_use]
    pub fn per_vertex(epsilons: Vec<Epsilon>) -> Self {
        Self::with(EpsilonChoice::PerVertex(epsilons))
    }

    fn with(epsilon: EpsilonChoice) -> Self {
        Simplifier {
            epsilon,
            method: defaults::METHOD,
            envelope_method: defaults::ENVELOPE_METHOD,
            placement: defaults::PLACEMENT,
            hole_filling: defaults::hole_filling(),
            tube_segments: Some(defaults::TUBE_SEGMENTS),
            target_faces: None,
            certify: defaults::CERTIFY,
            tolerance_phase: defaults::TOLERANCE_PHASE,
            threads: None,
            progress: None,
        }
    }

    /// The simplification algorithm: local (5.2), global (5.3) or hybrid (5.4).
    #[must_use]
    pub fn method(mut self, method: Method) -> Self {
        self.method = method;
        self
    }

    /// How the envelopes find their offsets (4.1, 4.2, or both).
    #[must_use]
    pub fn envelope_method(mut self, method: EnvelopeMethod) -> Self {
        self.envelope_method = method;
        self
    }

    /// Where output vertices may lie: input vertices only, or moved between the envelopes.
    #[must_use]
    pub fn placement(mut self, placement: Placement) -> Self {
        self.placement = placement;
        self
    }

    /// How holes left by removed vertices are filled.
    #[must_use]
    pub fn hole_filling(mut self, hole_filling: HoleFilling) -> Self {
        self.hole_filling = hole_filling;
        self
    }

    /// Vertices per border-tube ring (6.2), `3..=64`; `None` keeps every border vertex.
    #[must_use]
    pub fn tube_segments(mut self, segments: Option<u32>) -> Self {
        self.tube_segments = segments;
        self
    }

    /// Stop once at most this many faces remain.
    #[must_use]
    pub fn target_faces(mut self, faces: usize) -> Self {
        self.target_faces = Some(faces);
        self
    }

    /// Certify the output against the input (on by default). Without a certificate the
    /// guarantee rests on the envelopes' proof and the exact validity tests alone.
    #[must_use]
    pub fn certify(mut self, certify: bool) -> Self {
        self.certify = certify;
        self
    }

    /// After the simplification, the tolerance phase: removals and edge collapses each
    /// proved against the contract itself (the new faces within epsilon of the input, the
    /// input near them within epsilon of the output, no intersection), which go on where
    /// the envelopes stop, in thin parts at large epsilons. Only for a uniform epsilon on an
    /// input that does not meet itself.
    #[must_use]
    pub fn tolerance_phase(mut self, on: bool) -> Self {
        self.tolerance_phase = on;
        self
    }

    /// Worker threads (default: rayon's, one per core). The output is the same for any
    /// number.
    #[must_use]
    pub fn threads(mut self, threads: usize) -> Self {
        self.threads = Some(threads);
        self
    }

    /// A callback told what happens; it may cancel by returning [`std::ops::ControlFlow::Break`].
    #[must_use]
    pub fn progress(
        mut self,
        callback: impl Fn(Event) -> std::ops::ControlFlow<()> + Send + Sync + 'a,
    ) -> Self {
        self.progress = Some(Box::new(callback));
        self
    }

    /// The engine's options for `mesh` (epsilons resolved against its diagonal).
    fn options(&self, mesh: &Mesh) -> Result<SimplifyOptions, Error> {
        if self.method == Method::Global
            && matches!(self.placement, Placement::Slide | Placement::Collapse)
        {
            return Err(Error::InvalidArgument(
                "placement slide and collapse move vertices in the local algorithm's phase, \
                 which the global method does not run (use the local or hybrid method)"
                    .into(),
            ));
        }
        if let Some(n) = self.tube_segments
            && !defaults::TUBE_SEGMENTS_RANGE.contains(&n)
        {
            return Err(Error::InvalidArgument(format!(
                "tube segments must be in {}..={}, got {n}",
                defaults::TUBE_SEGMENTS_RANGE.start(),
                defaults::TUBE_SEGMENTS_RANGE.end()
            )));
        }
        let field = match &self.epsilon {
            EpsilonChoice::Uniform(e) => EpsilonField::Constant(e.validate()?.resolve(mesh)),
            EpsilonChoice::PerVertex(es) => {
                if es.len() != mesh.num_vertices() {
                    return Err(Error::InvalidEpsilon(format!(
                        "{} per-vertex epsilons for {} vertices",
                        es.len(),
                        mesh.num_vertices()
                    )));
                }
                EpsilonField::PerVertex(
                    es.iter()
                        .map(|e| Ok(e.validate()?.resolve(mesh)))
                        .collect::<Result<_, Error>>()?,
                )
            }
        };
        Ok(SimplifyOptions {
            method: self.envelope_method,
            hole_filling: self.hole_filling,
            placement: self.placement,
            tube_segments: self.tube_segments,
            target_faces: self.target_faces,
            verify: self.certify,
            // Seam vertices stay where they are, so texture charts do not tear.
            keep: crate::seam_vertices(mesh),
            tolerance_phase: self.tolerance_phase,
            ..SimplifyOptions::new(field)
        })
    }

    /// Simplifies `mesh`. Its attributes are carried to the output ([`crate::carry_attributes`]):
    /// vertices on texture-coordinate or colour seams are kept where they are
    /// ([`crate::seam_vertices`]), so charts do not tear.
    ///
    /// # Errors
    /// [`Error::Simplify`] when the input is not acceptable (see [`check`](crate::check)) or
    /// the envelopes cannot be proved; [`Error::CertificateViolated`] (with the output, for
    /// inspection) when the certificate finds a violation; [`Error::Cancelled`];
    /// [`Error::InvalidEpsilon`] and [`Error::InvalidArgument`] before any work.
    pub fn run(&self, mesh: &Mesh) -> Result<Simplified, Error> {
        let options = self.options(mesh)?;
        let step = self.method.step();
        let mut relay = Relay::new(self.progress.as_deref());
        let (out, report) = threads::run(self.threads, || {
            simplify_with(mesh.soup(), &options, step.as_ref(), &mut relay)
        })??;
        let attributes = crate::carry_attributes(mesh, &out);
        let done = Simplified::new(Mesh::from_parts(out, attributes), report);
        match done.certificate().map(|c| c.verdict) {
            Some(Verdict::Violated) => Err(Error::CertificateViolated(Box::new(done))),
            _ => Ok(done),
        }
    }
}
