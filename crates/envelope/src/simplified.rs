//! What a simplification made: the output, its report and its certificate.

use envelope_simplify::SimplifyReport;
use envelope_verify::Certificate;

use crate::Mesh;

/// What `Simplifier::run` made: the output, the report, and the certificate.
#[derive(Clone, Debug)]
pub struct Simplified {
    mesh: Mesh,
    report: SimplifyReport,
}

impl Simplified {
    pub(crate) fn new(mesh: Mesh, report: SimplifyReport) -> Self {
        Simplified { mesh, report }
    }

    /// The simplified mesh.
    #[must_use]
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The simplified mesh, taken.
    #[must_use]
    pub fn into_mesh(self) -> Mesh {
        self.mesh
    }

    /// Counts, epsilons, envelope statistics and times (`to_json` gives the command line's
    /// JSON report).
    #[must_use]
    pub fn report(&self) -> &SimplifyReport {
        &self.report
    }

    /// The certificate of the output against the input (`None` when certification was turned
    /// off).
    #[must_use]
    pub fn certificate(&self) -> Option<&Certificate> {
        self.report.verify.as_ref().map(|v| &v.certificate)
    }

    /// The output is certified: within epsilon both ways, no self-intersection, same
    /// topology, all proved.
    #[must_use]
    pub fn is_certified(&self) -> bool {
        self.certificate().is_some_and(Certificate::holds)
    }

    /// The names of the violated properties (empty unless certified and violated).
    #[must_use]
    pub fn violations(&self) -> Vec<&'static str> {
        self.certificate()
            .map(Certificate::violations)
            .unwrap_or_default()
    }
}
