//! Controlled simplification of genus (El-Sana and Varshney 1997): holes and tunnels an
//! L-infinity cube of side `2 alpha` cannot pass are filled.

use envelope_genus::{GenusOptions, GenusReport, TessellationSource, reduce_genus_with};

use crate::{Epsilon, Error, Mesh, defaults, threads};

/// The genus reduction.
///
/// ```
/// use envelope::{Epsilon, Genus};
/// let cup = envelope::Mesh::demo();
/// let (out, report) = Genus::new(Epsilon::percent(1.0)).run(&cup)?;
/// assert_eq!(report.genus_out, Some(0));
/// assert!(out.num_faces() > 0);
/// # Ok::<(), envelope::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Genus {
    alpha: Epsilon,
    beta_degrees: f64,
    source: TessellationSource,
    threads: Option<usize>,
}

impl Genus {
    /// Fills what a cube of side `2 alpha` cannot pass (a relative alpha is a part of the
    /// diagonal).
    #[must_use]
    pub fn new(alpha: Epsilon) -> Self {
        Genus {
            alpha,
            beta_degrees: defaults::GENUS_BETA_DEGREES,
            source: TessellationSource::default(),
            threads: None,
        }
    }

    /// The sharp-edge angle between face normals, in degrees, `(0, 180)`.
    #[must_use]
    pub fn beta_degrees(mut self, beta: f64) -> Self {
        self.beta_degrees = beta;
        self
    }

    /// Where the rims of the filled regions come from (default: the sharp-edge step, then the
    /// regions the L-infinity closing swallows).
    #[must_use]
    pub fn source(mut self, source: TessellationSource) -> Self {
        self.source = source;
        self
    }

    /// Worker threads (default: one per core).
    #[must_use]
    pub fn threads(mut self, threads: usize) -> Self {
        self.threads = Some(threads);
        self
    }

    /// Reduces the genus of `mesh`.
    ///
    /// # Errors
    /// [`Error::Genus`] when the input has a degeneracy the method does not handle or an
    /// argument is out of range; [`Error::InvalidEpsilon`] for alpha.
    pub fn run(&self, mesh: &Mesh) -> Result<(Mesh, GenusReport), Error> {
        let options = GenusOptions {
            alpha: self.alpha.validate()?.resolve(mesh),
            beta_degrees: self.beta_degrees,
        };
        let (out, report) = threads::run(self.threads, || {
            reduce_genus_with(mesh.soup(), &options, self.source)
        })??;
        Ok((Mesh::from_soup(out), report))
    }
}
