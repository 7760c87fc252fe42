//! The case generators, one function per family. Expected exit codes are the TARGET
//! behaviour of the "hostile input" issue (see `tests/hostile.rs`).
//!
//! Files by family of defect: `controls` (valid inputs), `file_structure` (truncations, lying
//! counts, bombs, BOM/CRLF), `file_contents` (numbers, indices, polygons), `geometry`
//! (degenerate meshes, scales), `epsilons`, `paths`, `flags`.

mod controls;
mod epsilons;
mod file_contents;
mod file_structure;
mod flags;
mod geometry;
mod paths;

use super::files::*;
use super::harness::Case;
use controls::controls;
use envelope_io::Format;
use epsilons::{epsilons, large_epsilons};
use file_contents::{indices, numbers, polygons};
use file_structure::{bom_crlf, bombs, lying_counts, truncations};
use flags::flags;
use geometry::{degenerate, scales};
use paths::paths;

/// Every family, in order.
pub fn all() -> Vec<(&'static str, Vec<Case>)> {
    vec![
        ("controls", controls()),
        ("truncate", truncations()),
        ("counts", lying_counts()),
        ("bomb", bombs()),
        ("bom-crlf", bom_crlf()),
        ("numbers", numbers()),
        ("index", indices()),
        ("polygon", polygons()),
        ("degenerate", degenerate()),
        ("scale", scales()),
        ("epsilon", epsilons()),
        ("path", paths()),
        ("flag", flags()),
        ("large-epsilon", large_epsilons()),
    ]
}

/// The small sphere every command-level case runs on.
fn sphere_obj() -> Vec<u8> {
    encode(&ico(1), Format::Obj)
}

impl Case {
    /// Appends whitespace-separated `args` (for builders that start from an empty command).
    fn with_args(mut self, args: &str) -> Case {
        self.args.extend(args.split_whitespace().map(str::to_owned));
        self
    }
}
