//! Certified two-sided Hausdorff, self-intersection and topology verdicts for any pair of triangle meshes.
#![forbid(unsafe_code)]
