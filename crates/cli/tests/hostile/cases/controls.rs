//! Positive controls: valid inputs in every encoding through every subcommand.

use super::super::files::*;
use super::super::harness::Case;
use super::sphere_obj;
use envelope_io::Format;

/// Valid inputs in every encoding through every subcommand: the suite's positive controls
/// (a harness that passes everything would fail these only if the program is broken, so
/// they also show the post-conditions hold on the good path).
pub(super) fn controls() -> Vec<Case> {
    let mut v = Vec::new();
    for (label, format, ext) in ENCODINGS {
        let f = format!("m.{ext}");
        for (mesh, soup) in [("tet", tet()), ("cube", cube()), ("cup", cup())] {
            v.push(
                Case::new(
                    format!("controls/{label}/{mesh}/check"),
                    &format!("check {f}"),
                )
                .file(&f, encode(&soup, format))
                .codes(&[0]),
            );
        }
        let sphere = encode(&ico(1), format);
        let out = format!("out.{ext}");
        v.push(
            Case::new(
                format!("controls/{label}/simplify"),
                &format!("simplify {f} {out} --epsilon 1% --quiet"),
            )
            .file(&f, sphere.clone())
            .codes(&[0])
            .recert(&f, &out, "1%"),
        );
        v.push(
            Case::new(
                format!("controls/{label}/verify"),
                &format!("verify {f} {f} --epsilon 0.1%"),
            )
            .file(&f, sphere.clone())
            .codes(&[0]),
        );
        v.push(
            Case::new(
                format!("controls/{label}/envelopes"),
                &format!("envelopes {f} --epsilon 1% --out-dir env"),
            )
            .file(&f, sphere.clone())
            .codes(&[0]),
        );
    }
    let s = sphere_obj();
    let simplify = |name: &str, extra: &str| {
        let eps = extra
            .strip_prefix("--epsilon ")
            .map_or("1%", |e| e.split(' ').next().unwrap_or("1%"));
        let args = if extra.starts_with("--epsilon ") {
            format!("simplify in.obj out.obj --quiet {extra}")
        } else {
            format!("simplify in.obj out.obj --epsilon 1% --quiet {extra}")
        };
        Case::new(format!("controls/simplify/{name}"), &args)
            .file("in.obj", s.clone())
            .codes(&[0])
            .recert("in.obj", "out.obj", eps)
    };
    for (name, extra) in [
        ("analytical", "--envelope analytical"),
        ("numerical", "--envelope numerical"),
        ("exhaustive", "--hole-filling exhaustive"),
        ("global", "--method global"),
        ("hybrid", "--method hybrid"),
        ("subset", "--placement subset"),
        ("slide", "--placement slide"),
        ("collapse", "--placement collapse"),
        ("report", "--report r.json"),
        ("no-verify", "--no-verify"),
        ("viewpoint", "--viewpoint 0,0,3 --epsilon-far 2%"),
        ("absolute", "--epsilon 0.01"),
        ("fraction", "--epsilon 1/64%"),
    ] {
        v.push(simplify(name, extra));
    }
    v.push(
        Case::new(
            "controls/simplify/epsilon-file",
            "simplify in.obj out.obj --epsilon-file eps.txt --quiet",
        )
        .file("in.obj", s.clone())
        .file(
            "eps.txt",
            "# one per vertex\n".to_string() + &"1%\n".repeat(42),
        )
        .codes(&[0])
        .recert("in.obj", "out.obj", "1%"),
    );
    v.push(
        Case::new(
            "controls/simplify/to-stl",
            "simplify in.obj out.stl --epsilon 2% --quiet",
        )
        .file("in.obj", s.clone())
        .codes(&[0])
        .recert("in.obj", "out.stl", "2%"),
    );
    v.push(
        Case::new("controls/lod", "lod in.obj lod --epsilons 1%,2% --quiet")
            .file("in.obj", s.clone())
            .codes(&[0]),
    );
    v.push(
        Case::new(
            "controls/genus",
            "genus in.obj out.off --alpha 2% --report r.json",
        )
        .file("in.obj", encode(&cube(), Format::Obj))
        .codes(&[0]),
    );
    v.push(
        Case::new(
            "controls/genus-union",
            "genus in.obj out.off --alpha 2% --union",
        )
        .file("in.obj", encode(&cube(), Format::Obj))
        .codes(&[0]),
    );
    v.push(
        Case::new(
            "controls/pipeline-torus",
            "pipeline in.obj pipe --steps e1%,a5%",
        )
        .file("in.obj", encode(&torus(), Format::Obj))
        .codes(&[0])
        .lacks("Some("),
    );
    v.push(
        Case::new(
            "controls/verify-flags",
            "verify in.obj in.obj --epsilon 0.001 --relative --resolution 0 --stop-at-first --json",
        )
        .file("in.obj", s.clone())
        .codes(&[0]),
    );
    v.push(
        Case::new(
            "controls/verify-envelope-of",
            "verify in.obj in.obj --epsilon 1% --envelope-of --no-topology --no-self-intersections",
        )
        .file("in.obj", s.clone())
        .codes(&[0]),
    );
    v.push(
        Case::new("controls/check-json", "check --json --examples 0 in.obj")
            .file("in.obj", s)
            .codes(&[0]),
    );
    v
}
