//! Epsilons: malformed, tiny and huge ones through every flag, and large ones through every
//! method.

use super::super::files::*;
use super::super::harness::Case;
use super::sphere_obj;
use envelope_io::Format;

/// Malformed, tiny and huge epsilons through every flag that takes one.
pub(super) fn epsilons() -> Vec<Case> {
    let mut v = Vec::new();
    let s = sphere_obj();
    for e in [
        "abc", "-1", "0", "1%%", "1/0%", "nan", "inf", "1e-315", "1e20",
    ] {
        let extreme = matches!(e, "1e-315" | "1e20");
        let codes: &[i32] = if extreme { &[0, 2] } else { &[2] };
        let tag = e.replace('/', "over").replace('%', "pct");
        let mk = |cmd: &str, args: String, flag: &str| {
            Case::new(format!("epsilon/{tag}/{cmd}"), "")
                .file("in.obj", s.clone())
                .codes(codes)
                .names(flag)
                .with_args(&args)
        };
        v.push(
            mk(
                "simplify",
                format!("simplify in.obj out.obj --quiet --epsilon={e}"),
                "--epsilon",
            )
            .keep("out.obj")
            .recert("in.obj", "out.obj", e),
        );
        v.push(
            mk(
                "simplify-no-verify",
                format!("simplify in.obj out.obj --quiet --no-verify --epsilon={e}"),
                "--epsilon",
            )
            .keep("out.obj")
            .recert("in.obj", "out.obj", e),
        );
        v.push(
            mk(
                "simplify-epsilon-far",
                format!(
                    "simplify in.obj out.obj --quiet --viewpoint 0,0,3 --epsilon 1% --epsilon-far={e}"
                ),
                "--epsilon-far",
            )
            .keep("out.obj"),
        );
        v.push(
            mk(
                "simplify-epsilon-file",
                "simplify in.obj out.obj --quiet --epsilon-file eps.txt".into(),
                "eps.txt",
            )
            .file("eps.txt", format!("{e}\n").repeat(42))
            .keep("out.obj"),
        );
        v.push(mk(
            "envelopes",
            format!("envelopes in.obj --out-dir env --epsilon={e}"),
            "--epsilon",
        ));
        v.push(mk(
            "verify",
            format!("verify in.obj in.obj --epsilon={e}"),
            "--epsilon",
        ));
        v.push(mk(
            "lod",
            format!("lod in.obj lod --quiet --epsilons={e}"),
            "--epsilons",
        ));
        v.push(
            mk(
                "genus",
                format!("genus in.obj out.obj --alpha={e}"),
                "--alpha",
            )
            .keep("out.obj"),
        );
        v.push(mk(
            "pipeline",
            format!("pipeline in.obj pipe --steps=e{e}"),
            "--steps",
        ));
    }
    v
}

/// Large epsilons (a fifth of the diagonal and more) through every method: the output must
/// still be certified (the fuzz target `command_path` found violated certificates there).
pub(super) fn large_epsilons() -> Vec<Case> {
    let mut v = Vec::new();
    let (op, of) = octasphere();
    let meshes = [
        ("octasphere", obj(&rows_of(&op), &one_based(&of))),
        ("ico80", encode(&ico(1), Format::Obj)),
        ("cube", encode(&cube(), Format::Obj)),
        ("torus", encode(&torus(), Format::Obj)),
    ];
    for (mesh, bytes) in meshes {
        for eps in ["20%", "25%", "40%"] {
            for method in ["local", "global", "hybrid"] {
                v.push(
                    Case::new(
                        format!("large-epsilon/{mesh}/{eps}/{method}"),
                        &format!(
                            "simplify m.obj out.obj --quiet --epsilon {eps} --method {method}"
                        ),
                    )
                    .file("m.obj", bytes.clone())
                    .codes(&[0, 3])
                    .recert("m.obj", "out.obj", eps),
                );
            }
        }
    }
    v
}
