//! Paths: missing, wrong-kind and colliding.

use super::super::harness::Case;
use super::sphere_obj;

/// Missing, wrong-kind and colliding paths.
pub(super) fn paths() -> Vec<Case> {
    let s = sphere_obj();
    let c =
        |name: &str, args: &str| Case::new(format!("path/{name}"), args).file("in.obj", s.clone());
    let mut v = vec![
        c("missing/check", "check missing.obj")
            .codes(&[2])
            .names("missing.obj"),
        c(
            "missing/simplify",
            "simplify missing.obj out.obj --epsilon 1%",
        )
        .codes(&[2])
        .names("missing.obj")
        .keep("out.obj"),
        c("missing/envelopes", "envelopes missing.obj --epsilon 1%")
            .codes(&[2])
            .names("missing.obj"),
        c(
            "missing/verify-orig",
            "verify missing.obj in.obj --epsilon 1%",
        )
        .codes(&[2])
        .names("missing.obj"),
        c(
            "missing/verify-approx",
            "verify in.obj missing.obj --epsilon 1%",
        )
        .codes(&[2])
        .names("missing.obj"),
        c("missing/lod", "lod missing.obj lod")
            .codes(&[2])
            .names("missing.obj"),
        c("missing/genus", "genus missing.obj out.obj --alpha 1%")
            .codes(&[2])
            .names("missing.obj")
            .keep("out.obj"),
        c("missing/pipeline", "pipeline missing.obj pipe")
            .codes(&[2])
            .names("missing.obj"),
        c(
            "missing/epsilon-file",
            "simplify in.obj out.obj --epsilon-file none.txt",
        )
        .codes(&[2])
        .names("none.txt")
        .keep("out.obj"),
        c("directory/check", "check d.obj")
            .dir("d.obj")
            .codes(&[2])
            .names("d.obj"),
        c(
            "directory/simplify-in",
            "simplify d.obj out.obj --epsilon 1%",
        )
        .dir("d.obj")
        .codes(&[2])
        .names("d.obj")
        .keep("out.obj"),
        c(
            "directory/simplify-out",
            "simplify in.obj d.obj --epsilon 1% --quiet",
        )
        .dir("d.obj")
        .codes(&[2])
        .names("d.obj"),
        c(
            "directory/epsilon-file",
            "simplify in.obj out.obj --epsilon-file d.txt",
        )
        .dir("d.txt")
        .codes(&[2])
        .names("d.txt")
        .keep("out.obj"),
        c(
            "out-dir-missing/simplify",
            "simplify in.obj nodir/out.obj --epsilon 1% --quiet",
        )
        .codes(&[2])
        .names("nodir"),
        c(
            "out-dir-missing/genus",
            "genus in.obj nodir/out.obj --alpha 1%",
        )
        .codes(&[2])
        .names("nodir"),
        c(
            "report-dir-missing/simplify",
            "simplify in.obj out.obj --epsilon 1% --quiet --report nodir/r.json",
        )
        .codes(&[2])
        .names("nodir")
        .keep("out.obj"),
        c(
            "report-dir-missing/genus",
            "genus in.obj out.obj --alpha 1% --report nodir/r.json",
        )
        .codes(&[2])
        .names("nodir")
        .keep("out.obj"),
        c(
            "report-is-directory/simplify",
            "simplify in.obj out.obj --epsilon 1% --quiet --report rd",
        )
        .dir("rd")
        .codes(&[2])
        .names("rd")
        .keep("out.obj"),
        c(
            "out-is-in/simplify",
            "simplify in.obj in.obj --epsilon 1% --quiet",
        )
        .codes(&[0, 2])
        .names("in.obj")
        .keep("in.obj"),
        c("out-is-in/genus", "genus in.obj in.obj --alpha 1%")
            .codes(&[0, 2])
            .names("in.obj")
            .keep("in.obj"),
        c(
            "out-is-in/simplify-dotted",
            "simplify in.obj ./in.obj --epsilon 1% --quiet",
        )
        .codes(&[0, 2])
        .names("in.obj")
        .keep("in.obj"),
        c(
            "unknown-ext/simplify-out",
            "simplify in.obj out.xyz --epsilon 1% --quiet",
        )
        .codes(&[2])
        .names("out.xyz")
        .keep("out.xyz"),
        c("unknown-ext/genus-out", "genus in.obj out.xyz --alpha 1%")
            .codes(&[2])
            .names("out.xyz")
            .keep("out.xyz"),
        c(
            "no-ext/simplify-out",
            "simplify in.obj out --epsilon 1% --quiet",
        )
        .codes(&[2])
        .names("out")
        .keep("out"),
        c("unknown-ext/check-obj-text", "check m.txt")
            .file("m.txt", s.clone())
            .codes(&[0, 2])
            .names("m.txt"),
        c("unknown-ext/check-junk", "check m.dat")
            .file("m.dat", b"hello world\n".to_vec())
            .codes(&[2])
            .names("m.dat"),
        c("out-dir-is-file/lod", "lod in.obj f.txt --epsilons 1%")
            .codes(&[2])
            .names("f.txt")
            .keep("f.txt"),
        c(
            "out-dir-is-file/pipeline",
            "pipeline in.obj f.txt --steps e1%",
        )
        .codes(&[2])
        .names("f.txt")
        .keep("f.txt"),
        c(
            "out-dir-is-file/envelopes",
            "envelopes in.obj --epsilon 1% --out-dir f.txt",
        )
        .codes(&[2])
        .names("f.txt")
        .keep("f.txt"),
        c("out-dir-is-file/demo", "demo --out-dir f.txt")
            .codes(&[2])
            .names("f.txt")
            .keep("f.txt"),
        c(
            "epsilon-file/too-few",
            "simplify in.obj out.obj --epsilon-file e.txt",
        )
        .file("e.txt", "1%\n".repeat(41))
        .codes(&[2])
        .names("e.txt")
        .keep("out.obj"),
        c(
            "epsilon-file/too-many",
            "simplify in.obj out.obj --epsilon-file e.txt",
        )
        .file("e.txt", "1%\n".repeat(43))
        .codes(&[2])
        .names("e.txt")
        .keep("out.obj"),
        c(
            "epsilon-file/empty",
            "envelopes in.obj --epsilon-file e.txt",
        )
        .file("e.txt", "")
        .codes(&[2])
        .names("e.txt"),
        c(
            "epsilon-file/binary",
            "envelopes in.obj --epsilon-file e.txt",
        )
        .file("e.txt", vec![0xFFu8, 0xFE, 0, 1, 2])
        .codes(&[2])
        .names("e.txt"),
    ];
    let out_in_read_only = c(
        "existing-out-untouched-on-bad-input",
        "simplify bad.obj out.obj --epsilon 1%",
    )
    .file("bad.obj", b"v 0 0 0\nf 1 2 3\n".to_vec())
    .codes(&[2])
    .names("bad.obj")
    .keep("out.obj");
    v.push(out_in_read_only);
    v
}
