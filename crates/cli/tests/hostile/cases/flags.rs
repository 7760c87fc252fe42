//! Numeric and enumerated flags out of range.

use super::super::files::*;
use super::super::harness::Case;
use super::sphere_obj;
use envelope_io::Format;

/// Numeric and enumerated flags out of range.
pub(super) fn flags() -> Vec<Case> {
    let s = sphere_obj();
    let c = |name: &str, args: &str, codes: &[i32], flag: &str| {
        Case::new(format!("flag/{name}"), args)
            .file("in.obj", s.clone())
            .codes(codes)
            .names(flag)
    };
    let tube = |v: &str, codes: &[i32]| {
        c(
            &format!("tube-segments-{v}"),
            &format!("envelopes in.obj --epsilon 1% --out-dir env --tube-segments={v}"),
            codes,
            "--tube-segments",
        )
        .file(
            "open.obj",
            encode(
                &envelope_mesh::generate::open_cylinder(1.0, 1.0, 12, 2),
                Format::Obj,
            ),
        )
    };
    let mut v = vec![
        tube("0", &[0]),
        tube("1", &[0, 2]),
        tube("2", &[0, 2]),
        tube("4294967295", &[0, 2]),
        tube("-1", &[2]),
        tube("abc", &[2]),
        tube("99999999999", &[2]),
        c(
            "examples-0",
            "check --examples 0 in.obj",
            &[0],
            "--examples",
        ),
        c(
            "examples-max",
            "check --examples 18446744073709551615 in.obj",
            &[2],
            "--examples",
        ),
        c(
            "examples-negative",
            "check --examples=-1 in.obj",
            &[2],
            "--examples",
        ),
        c(
            "examples-overflow",
            "check --examples 99999999999999999999 in.obj",
            &[2],
            "--examples",
        ),
    ];
    // Border tubes: an open cylinder exercises --tube-segments for real.
    for seg in ["3", "64", "4294967295"] {
        v.push(
            c(
                &format!("tube-segments-open-{seg}"),
                &format!("envelopes open.obj --epsilon 1% --out-dir env --tube-segments {seg}"),
                if seg == "4294967295" { &[0, 2] } else { &[0] },
                "--tube-segments",
            )
            .file(
                "open.obj",
                encode(
                    &envelope_mesh::generate::open_cylinder(1.0, 1.0, 12, 2),
                    Format::Obj,
                ),
            ),
        );
    }
    for (flag, val, codes) in [
        ("--pixels", "0", &[2][..]),
        ("--pixels", "-1", &[2]),
        ("--pixels", "nan", &[2]),
        ("--pixels", "inf", &[2]),
        ("--pixels", "1e308", &[0, 2]),
        ("--pixels", "1e-308", &[0, 2]),
        ("--resolution", "0", &[2]),
        ("--resolution", "nan", &[2]),
        ("--resolution", "abc", &[2]),
        ("--fov", "0", &[2]),
        ("--fov", "180", &[2]),
        ("--fov", "-30", &[2]),
        ("--fov", "nan", &[2]),
        ("--fov", "179.99999", &[0, 2]),
        ("--fov", "1e-300", &[0, 2]),
    ] {
        v.push(c(
            &format!("lod{flag}={val}"),
            &format!("lod in.obj lod --quiet --epsilons 1% {flag}={val}"),
            codes,
            flag,
        ));
    }
    for (val, codes) in [
        ("1%,0.5%", &[0, 2][..]),
        ("1%,,2%", &[2]),
        ("1%,1%", &[0, 2]),
        ("", &[2]),
        (",", &[2]),
        ("1%;2%", &[2]),
    ] {
        v.push(c(
            &format!("lod-epsilons={val}"),
            &format!("lod in.obj lod --quiet --epsilons={val}"),
            codes,
            "--epsilons",
        ));
    }
    for (val, codes) in [
        ("-1", &[0, 2][..]),
        ("0", &[0, 2]),
        ("180", &[0, 2]),
        ("360", &[0, 2]),
        ("nan", &[0, 2]),
        ("inf", &[0, 2]),
        ("1e308", &[0, 2]),
        ("abc", &[2]),
    ] {
        v.push(
            c(
                &format!("genus-beta={val}"),
                &format!("genus in.obj out.obj --alpha 2% --beta={val}"),
                codes,
                "--beta",
            )
            .keep("out.obj"),
        );
        v.push(c(
            &format!("pipeline-beta={val}"),
            &format!("pipeline in.obj pipe --steps a2% --beta={val}"),
            codes,
            "--beta",
        ));
    }
    for (val, codes) in [
        ("", &[2][..]),
        ("x1", &[2]),
        ("e", &[2]),
        ("e1%,", &[2]),
        ("E1%", &[2]),
        ("e1%,u2%", &[0]),
        ("a1e-300", &[0, 2]),
    ] {
        v.push(c(
            &format!("pipeline-steps={val}"),
            &format!("pipeline in.obj pipe --steps={val}"),
            codes,
            "--steps",
        ));
    }
    for (val, codes) in [
        ("-1", &[2][..]),
        ("nan", &[2]),
        ("inf", &[2]),
        ("1e300", &[0, 2, 3]),
        ("abc", &[2]),
    ] {
        v.push(c(
            &format!("verify-resolution={val}"),
            &format!("verify in.obj in.obj --epsilon 1% --resolution={val}"),
            codes,
            "--resolution",
        ));
    }
    for (val, codes) in [
        ("nan,0,0", &[2][..]),
        ("1,2", &[2]),
        ("1,2,3,4", &[2]),
        ("inf,0,0", &[2]),
        ("1e308,0,0", &[0, 2]),
        ("a,b,c", &[2]),
    ] {
        v.push(
            c(
                &format!("viewpoint={val}"),
                &format!("simplify in.obj out.obj --quiet --epsilon 1% --epsilon-far 2% --viewpoint={val}"),
                codes,
                "--viewpoint",
            )
            .keep("out.obj")
            .recert("in.obj", "out.obj", "2%"),
        );
    }
    for (name, args, flag) in [
        (
            "global-slide",
            "--method global --placement slide",
            "--placement",
        ),
        (
            "global-collapse",
            "--method global --placement collapse",
            "--placement",
        ),
        ("bad-method", "--method nope", "--method"),
        ("bad-envelope", "--envelope nope", "--envelope"),
        ("bad-placement", "--placement nope", "--placement"),
        ("bad-hole-filling", "--hole-filling nope", "--hole-filling"),
        ("epsilon-far-alone", "--epsilon-far 2%", "--viewpoint"),
        ("epsilon-and-file", "--epsilon-file e.txt", "--epsilon-file"),
        ("unknown-flag", "--frobnicate", "--frobnicate"),
    ] {
        v.push(
            c(
                &format!("simplify-{name}"),
                &format!("simplify in.obj out.obj --epsilon 1% {args}"),
                &[2],
                flag,
            )
            .file("e.txt", "1%\n".repeat(42))
            .keep("out.obj"),
        );
    }
    v.push(
        c(
            "simplify-no-epsilon",
            "simplify in.obj out.obj",
            &[2],
            "--epsilon",
        )
        .keep("out.obj"),
    );
    v.push(c(
        "verify-no-epsilon",
        "verify in.obj in.obj",
        &[2],
        "--epsilon",
    ));
    v.push(c("genus-no-alpha", "genus in.obj out.obj", &[2], "--alpha").keep("out.obj"));
    v.push(c(
        "envelopes-bad-format",
        "envelopes in.obj --epsilon 1% --format stl",
        &[2],
        "--format",
    ));
    v.push(c(
        "envelopes-ply",
        "envelopes in.obj --epsilon 1% --format ply --out-dir env",
        &[0],
        "--format",
    ));
    v.push(c(
        "lod-rule-sum",
        "lod in.obj lod --quiet --epsilons 1%,1% --rule sum",
        &[0],
        "--rule",
    ));
    v.push(c(
        "lod-bad-rule",
        "lod in.obj lod --epsilons 1% --rule nope",
        &[2],
        "--rule",
    ));
    v
}
