//! The case generators, one function per family. Expected exit codes are the TARGET
//! behaviour of the "hostile input" issue (see `tests/hostile.rs`).

use super::files::*;
use super::harness::Case;
use envelope_io::{Format, PlyEncoding};

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

/// Valid inputs in every encoding through every subcommand: the suite's positive controls
/// (a harness that passes everything would fail these only if the program is broken, so
/// they also show the post-conditions hold on the good path).
fn controls() -> Vec<Case> {
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

/// Valid tetrahedron files cut at many byte offsets, run through the reading commands.
fn truncations() -> Vec<Case> {
    let mut v = Vec::new();
    for (label, format, ext) in ENCODINGS {
        let full = encode(&tet(), format);
        let counted = !matches!(
            format,
            Format::Obj | Format::Stl(envelope_io::StlEncoding::Ascii)
        );
        let n = full.len();
        let mut cuts: Vec<usize> = (1..=8).map(|k| n * k / 9).collect();
        cuts.extend([0, n - 1]);
        cuts.sort_unstable();
        cuts.dedup();
        for (i, &at) in cuts.iter().enumerate() {
            let cut = full[..at].to_vec();
            let f = format!("t.{ext}");
            let rest_blank = full[at..].iter().all(u8::is_ascii_whitespace);
            // Counted formats must refuse any cut that loses data; OBJ and ASCII STL have no
            // counts, so a cut at a statement boundary is a smaller valid mesh.
            let (check, run): (&[i32], &[i32]) = if rest_blank {
                (&[0], &[0])
            } else if counted || at == 0 {
                (&[2], &[2])
            } else {
                (&[0, 1, 2], &[0, 1, 2])
            };
            let case = match i % 4 {
                0 => Case::new(
                    format!("truncate/{label}/@{at}/check"),
                    &format!("check {f}"),
                )
                .codes(check),
                1 => Case::new(
                    format!("truncate/{label}/@{at}/simplify"),
                    &format!("simplify {f} out.off --epsilon 1% --quiet"),
                )
                .codes(&run.iter().copied().filter(|&c| c != 1).collect::<Vec<_>>())
                .keep("out.off")
                .recert(&f, "out.off", "1%"),
                2 => Case::new(
                    format!("truncate/{label}/@{at}/verify"),
                    &format!("verify full.{ext} {f} --epsilon 1%"),
                )
                .file(format!("full.{ext}"), full.clone())
                .codes(if rest_blank { &[0] } else { &[1, 2] }),
                _ => Case::new(
                    format!("truncate/{label}/@{at}/envelopes"),
                    &format!("envelopes {f} --epsilon 1% --out-dir env"),
                )
                .codes(run),
            };
            v.push(case.file(&f, cut).names(&f));
        }
    }
    v
}

/// Headers whose counts disagree with the data.
fn lying_counts() -> Vec<Case> {
    let s = tet();
    let (r, p) = (rows(&s), polys(&s));
    let pts: Vec<[f64; 3]> = s.positions.iter().map(|q| q.to_array()).collect();
    let (nv, nf) = (4u64, 4u64);
    let mut files: Vec<(String, &str, Vec<u8>)> = Vec::new();
    for (dv, df) in [(1i64, 0i64), (-1, 0), (0, 1), (0, -1), (5, 5)] {
        let (cv, cf) = ((nv as i64 + dv) as u64, (nf as i64 + df) as u64);
        let tag = format!("v{dv:+}f{df:+}");
        files.push((format!("off/{tag}"), "off", off_counts(&r, &p, cv, cf)));
        files.push((
            format!("ply-ascii/{tag}"),
            "ply",
            ply_ascii_counts(&r, &p, cv, cf),
        ));
        files.push((
            format!("ply-le/{tag}"),
            "ply",
            ply_binary(false, &pts, &p, (cv, cf), None),
        ));
        files.push((
            format!("ply-be/{tag}"),
            "ply",
            ply_binary(true, &pts, &p, (cv, cf), None),
        ));
    }
    let tris = stl_tris(&s);
    for c in [0u32, 3, 5, 100] {
        files.push((format!("stl-bin/count{c}"), "stl", stl_binary(&tris, c)));
    }
    // A face list count that differs from the indices that follow.
    files.push((
        "ply-le/list-count4".into(),
        "ply",
        ply_binary(false, &pts, &p, (nv, nf), Some(4)),
    ));
    files.push((
        "ply-be/list-count2".into(),
        "ply",
        ply_binary(true, &pts, &p, (nv, nf), Some(2)),
    ));
    files.push((
        "off/face-count-lies".into(),
        "off",
        replace_once(&off(&r, &p), "3 0 2 1", "4 0 2 1"),
    ));
    files
        .into_iter()
        .map(|(tag, ext, bytes)| {
            let f = format!("c.{ext}");
            Case::new(format!("counts/{tag}"), &format!("check {f}"))
                .file(&f, bytes)
                .codes(&[2])
                .names(&f)
        })
        .collect()
}

/// Huge counts that must not be trusted for allocation, and inputs that are big for real.
fn bombs() -> Vec<Case> {
    let s = tet();
    let (r, p) = (rows(&s), polys(&s));
    let pts: Vec<[f64; 3]> = s.positions.iter().map(|q| q.to_array()).collect();
    let mut v = Vec::new();
    let mut refuse = |tag: &str, ext: &str, bytes: Vec<u8>| {
        let f = format!("b.{ext}");
        v.push(
            Case::new(format!("bomb/{tag}"), &format!("check {f}"))
                .file(&f, bytes)
                .codes(&[2])
                .names(&f),
        );
    };
    refuse(
        "off-counts-4e9",
        "off",
        off_counts(&r, &p, 4_000_000_000, 4_000_000_000),
    );
    refuse("off-vertices-u64", "off", off_counts(&r, &p, u64::MAX, 4));
    refuse(
        "off-polygon-4e9-corners",
        "off",
        replace_once(&off(&r, &p), "3 0 2 1", "4000000000 0 2 1"),
    );
    refuse(
        "ply-ascii-vertex-u32max",
        "ply",
        ply_ascii_counts(&r, &p, u32::MAX.into(), 4),
    );
    refuse(
        "ply-ascii-face-1e12",
        "ply",
        ply_ascii_counts(&r, &p, 4, 1_000_000_000_000),
    );
    refuse(
        "ply-ascii-list-u32max",
        "ply",
        replace_once(&ply_ascii(&r, &p), "\n3 0 2 1", "\n4294967295 0 2 1"),
    );
    refuse(
        "ply-le-vertex-u32max",
        "ply",
        ply_binary(false, &pts, &p, (u32::MAX.into(), 4), None),
    );
    refuse(
        "ply-be-face-1e9",
        "ply",
        ply_binary(true, &pts, &p, (4, 1_000_000_000), None),
    );
    refuse(
        "ply-le-list-u32max",
        "ply",
        ply_binary(false, &pts, &p, (4, 4), Some(u32::MAX)),
    );
    refuse(
        "stl-bin-count-u32max",
        "stl",
        stl_binary(&stl_tris(&s), u32::MAX),
    );
    // Real size: 3 vertices and 300,000 copies of one face (the 19 GB report).
    let three = rows_of(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let many = vec![vec![1i64, 2, 3]; 300_000];
    v.push(
        Case::new("bomb/obj-300k-duplicate-faces", "check b.obj")
            .file("b.obj", obj(&three, &many))
            .codes(&[1]),
    );
    let many0 = vec![vec![0i64, 1, 2]; 300_000];
    v.push(
        Case::new(
            "bomb/off-300k-duplicate-faces-simplify",
            "simplify b.off out.off --epsilon 1%",
        )
        .file("b.off", off(&three, &many0))
        .codes(&[2])
        .names("b.off")
        .keep("out.off"),
    );
    let (bp, bf) = big_polygon(5000);
    v.push(
        Case::new("bomb/obj-5000-gon", "check b.obj")
            .file("b.obj", obj(&rows_of(&bp), &one_based(&bf)))
            .codes(&[0, 1]),
    );
    v
}

/// A BOM or CRLF line ends must not change what a text file means.
fn bom_crlf() -> Vec<Case> {
    let mut v = Vec::new();
    for (label, format, ext) in TEXT_ENCODINGS {
        // The writer's files start with a comment (OBJ) or keyword; the hand-written ones
        // start with data (`v ...` on the first line of the OBJ).
        let t = tet();
        let hand = match format {
            Format::Obj => obj(&rows(&t), &one_based(&polys(&t))),
            Format::Off => off(&rows(&t), &polys(&t)),
            Format::Ply(_) => ply_ascii(&rows(&t), &polys(&t)),
            Format::Stl(_) => stl_ascii(&stl_rows(&t)),
        };
        for (mesh, plain) in [
            ("tet", encode(&t, format)),
            ("ico", encode(&ico(1), format)),
            ("hand-tet", hand),
        ] {
            let a = format!("plain.{ext}");
            let b = format!("odd.{ext}");
            let variants = [
                ("bom", [BOM, &plain].concat()),
                ("crlf", crlf(&plain)),
                ("bom-crlf", [BOM, &crlf(&plain)].concat()),
            ];
            for (kind, bytes) in variants {
                v.push(
                    Case::new(format!("{kind}/{label}/{mesh}"), &format!("check {b}"))
                        .file(&a, plain.clone())
                        .file(&b, bytes)
                        .codes(&[0])
                        .same_check(&a, &b),
                );
            }
        }
        let bom = [BOM, &encode(&ico(1), format)].concat();
        v.push(
            Case::new(
                format!("bom/{label}/simplify"),
                &format!("simplify in.{ext} out.off --epsilon 1% --quiet"),
            )
            .file(format!("in.{ext}"), bom)
            .codes(&[0])
            .recert(&format!("in.{ext}"), "out.off", "1%"),
        );
    }
    // The worst case of a dropped first `v`: the indices still fit, so a different mesh
    // would be read without a word (an unused fifth vertex becomes the fourth).
    let t = tet();
    let mut r = rows(&t);
    r.push(["9.0".into(), "9.0".into(), "9.0".into()]);
    let plain = obj(&r, &one_based(&polys(&t)));
    v.push(
        Case::new("bom/obj/indices-still-fit", "check odd.obj")
            .file("plain.obj", plain.clone())
            .file("odd.obj", [BOM, &plain].concat())
            .codes(&[0])
            .same_check("plain.obj", "odd.obj"),
    );
    // A binary PLY whose header lines end in CRLF (Windows tools write these).
    let le = encode(&tet(), Format::Ply(PlyEncoding::BinaryLittleEndian));
    let end = le.windows(11).position(|w| w == b"end_header\n").unwrap() + 11;
    let mut crlf_header = crlf(&le[..end]);
    crlf_header.extend_from_slice(&le[end..]);
    v.push(
        Case::new("crlf/ply-le-header", "check odd.ply")
            .file("odd.ply", crlf_header)
            .codes(&[0, 2])
            .names("odd.ply"),
    );
    v
}

/// Coordinates that are not finite or outside the exact range, in every format.
fn numbers() -> Vec<Case> {
    let s = tet();
    let p = polys(&s);
    let mut v = Vec::new();
    let bad = [
        "nan", "NaN", "inf", "-inf", "1e400", "-1e400", "4.9e-324", "1e-310", "1e-40", "1e40",
        "0x10", "1,5",
    ];
    for (k, tok) in bad.iter().enumerate() {
        let mut r = rows(&s);
        r[1][k % 3] = (*tok).to_string();
        let stl = {
            let mut t = stl_rows(&s);
            t[0][1][k % 3] = (*tok).to_string();
            stl_ascii(&t)
        };
        let per_format: [(&str, &str, Vec<u8>); 4] = [
            ("obj", "obj", obj(&r, &one_based(&p))),
            ("off", "off", off(&r, &p)),
            ("ply-ascii", "ply", ply_ascii(&r, &p)),
            ("stl-ascii", "stl", stl),
        ];
        for (label, ext, bytes) in per_format {
            // Spread the formats over the commands that read meshes.
            let f = format!("n.{ext}");
            let case = match (k + label.len()) % 3 {
                0 => Case::new(
                    format!("numbers/{label}/{tok}/check"),
                    &format!("check {f}"),
                ),
                1 => Case::new(
                    format!("numbers/{label}/{tok}/simplify"),
                    &format!("simplify {f} out.obj --epsilon 1%"),
                )
                .keep("out.obj"),
                _ => Case::new(
                    format!("numbers/{label}/{tok}/genus"),
                    &format!("genus {f} out.obj --alpha 1%"),
                )
                .keep("out.obj"),
            };
            // ASCII STL holds f32: a decimal that rounds to zero there is read as zero (then
            // welded, or a degenerate face), which is rounding, not misreading.
            let underflow = label == "stl-ascii" && matches!(*tok, "4.9e-324" | "1e-310");
            let case = case.file(&f, bytes);
            v.push(if underflow {
                case.codes(&[0, 1, 2])
            } else {
                case.codes(&[2]).names(&f)
            });
        }
    }
    // Binary formats carry any bit pattern.
    let pts: Vec<[f64; 3]> = s.positions.iter().map(|q| q.to_array()).collect();
    for (tag, x) in [
        ("nan", f64::NAN),
        ("inf", f64::INFINITY),
        ("subnormal", 5e-324),
        ("tiny", 1e-300),
        ("huge", 1e300),
        ("neg-huge", -1e200),
    ] {
        let mut q = pts.clone();
        q[2][1] = x;
        for be in [false, true] {
            let label = if be { "ply-be" } else { "ply-le" };
            v.push(
                Case::new(format!("numbers/{label}/{tag}"), "check n.ply")
                    .file("n.ply", ply_binary(be, &q, &p, (4, 4), None))
                    .codes(&[2])
                    .names("n.ply"),
            );
        }
    }
    for (tag, x) in [
        ("nan", f32::NAN),
        ("inf", f32::NEG_INFINITY),
        ("subnormal", 1e-40f32),
        ("huge", 3e38f32),
    ] {
        let mut t = stl_tris(&s);
        t[1][2][0] = x;
        v.push(
            Case::new(format!("numbers/stl-bin/{tag}"), "check n.stl")
                .file("n.stl", stl_binary(&t, 4))
                .codes(&[2])
                .names("n.stl"),
        );
    }
    v
}

/// Vertex indices naming no vertex; the error must quote the index as written.
fn indices() -> Vec<Case> {
    let s = tet();
    let r = rows(&s);
    let pts: Vec<[f64; 3]> = s.positions.iter().map(|q| q.to_array()).collect();
    let mut v = Vec::new();
    let base = one_based(&polys(&s));
    for (tag, face, word) in [
        ("past-end", vec![1i64, 2, 7], "7"),
        ("zero", vec![0, 1, 2], "0"),
        ("negative-past-start", vec![-5, 1, 2], "-5"),
        ("huge", vec![1, 2, 99_999_999_999], "99999999999"),
        ("beyond-i64", vec![1, 2, i64::MAX], "9223372036854775807"),
    ] {
        let mut f = base.clone();
        f[3] = face;
        v.push(
            Case::new(format!("index/obj/{tag}"), "check i.obj")
                .file("i.obj", obj(&r, &f))
                .codes(&[2])
                .names("i.obj")
                .word(word),
        );
    }
    v.push(
        Case::new("index/obj/overflow-text", "check i.obj")
            .file(
                "i.obj",
                replace_once(
                    &obj(&r, &base),
                    "f 2 3 4",
                    "f 2 3 123456789012345678901234567890",
                ),
            )
            .codes(&[2])
            .names("i.obj")
            .word("123456789012345678901234567890"),
    );
    v.push(
        Case::new("index/obj/corner-forms", "check i.obj")
            .file(
                "i.obj",
                replace_once(
                    &obj(&r, &base),
                    "f 2 3 4",
                    "vt 0 0\nvn 0 0 1\nf 2/1/1 3//1 -1/1",
                ),
            )
            .codes(&[0]),
    );
    v.push(
        Case::new("index/obj/bad-corner-form", "check i.obj")
            .file(
                "i.obj",
                replace_once(&obj(&r, &base), "f 2 3 4", "f 2 3 4/x/y"),
            )
            .codes(&[2])
            .names("i.obj"),
    );
    let p0 = polys(&s);
    for (tag, face, word) in [
        ("past-end", vec![0i64, 1, 4], "4"),
        ("negative", vec![0, 1, -1], "-1"),
    ] {
        let mut f = p0.clone();
        f[3] = face;
        for (label, ext, bytes) in [
            ("off", "off", off(&r, &f)),
            ("ply-ascii", "ply", ply_ascii(&r, &f)),
            ("ply-le", "ply", ply_binary(false, &pts, &f, (4, 4), None)),
        ] {
            let name = format!("i.{ext}");
            v.push(
                Case::new(format!("index/{label}/{tag}"), &format!("check {name}"))
                    .file(&name, bytes)
                    .codes(&[2])
                    .names(&name)
                    .word(word),
            );
        }
    }
    for (tag, face) in [
        ("two-corners", vec![1i64, 2]),
        ("one-corner", vec![1]),
        ("empty", vec![]),
    ] {
        let mut f = base.clone();
        f[3] = face;
        v.push(
            Case::new(format!("index/obj/{tag}"), "check i.obj")
                .file("i.obj", obj(&r, &f))
                .codes(&[2])
                .names("i.obj"),
        );
    }
    // Statements that would change geometry or indices but are not understood: refused.
    // (`vp` only serves free-form geometry, refused below; `fo` is the old name of `f`.)
    for stmt in ["cstype bspline", "curv 0 1 1 2", "surf 0 1 0 1 1 2 3 4"] {
        let kw = stmt.split(' ').next().unwrap();
        v.push(
            Case::new(format!("index/obj/unknown-{kw}"), "check i.obj")
                .file(
                    "i.obj",
                    [obj(&r, &base), format!("{stmt}\n").into_bytes()].concat(),
                )
                .codes(&[2])
                .names("i.obj"),
        );
    }
    // `vp` alone is harmless; `fo` is read as `f` (here: a second copy of a face, exit 1).
    v.push(
        Case::new("index/obj/vp-alone", "check i.obj")
            .file("i.obj", [obj(&r, &base), b"vp 0.5 0.5\n".to_vec()].concat())
            .codes(&[0]),
    );
    v.push(
        Case::new("index/obj/fo-is-f", "check i.obj")
            .file("i.obj", [obj(&r, &base), b"fo 1 2 3\n".to_vec()].concat())
            .codes(&[1]),
    );
    // Statements that cannot change geometry are fine.
    v.push(
        Case::new("index/obj/harmless-statements", "check i.obj")
            .file(
                "i.obj",
                [
                    b"mtllib a.mtl\no thing\ng group\ns 1\nusemtl red\n".to_vec(),
                    obj(&r, &base),
                ]
                .concat(),
            )
            .codes(&[0]),
    );
    v
}

/// Polygons: convex, non-convex, self-intersecting, with repeated corners.
fn polygons() -> Vec<Case> {
    let mut v = Vec::new();
    let (lp, lf) = l_prism();
    let (cp, cf) = quad_cube();
    let (sp, sf) = pentagram();
    for (shape, pts, faces, codes) in [
        ("convex-quads", &cp, &cf, &[0][..]),
        ("non-convex-l-prism", &lp, &lf, &[0]),
    ] {
        let r = rows_of(pts);
        for (label, ext, bytes) in [
            ("obj", "obj", obj(&r, &one_based(faces))),
            ("off", "off", off(&r, faces)),
            ("ply-ascii", "ply", ply_ascii(&r, faces)),
            (
                "ply-be",
                "ply",
                ply_binary(
                    true,
                    pts,
                    faces,
                    (pts.len() as u64, faces.len() as u64),
                    None,
                ),
            ),
        ] {
            let f = format!("p.{ext}");
            v.push(
                Case::new(
                    format!("polygon/{shape}/{label}/check"),
                    &format!("check {f}"),
                )
                .file(&f, bytes)
                .codes(codes),
            );
        }
    }
    let lobj = obj(&rows_of(&lp), &one_based(&lf));
    v.push(
        Case::new(
            "polygon/non-convex-l-prism/simplify",
            "simplify p.obj out.obj --epsilon 5% --quiet",
        )
        .file("p.obj", lobj.clone())
        .codes(&[0])
        .recert("p.obj", "out.obj", "5%"),
    );
    v.push(
        Case::new(
            "polygon/non-convex-l-prism/envelopes",
            "envelopes p.obj --epsilon 1% --out-dir env",
        )
        .file("p.obj", lobj)
        .codes(&[0]),
    );
    // The pentagram: 5 vertex lines, then the face (OBJ line 6, OFF line 8, PLY line 15).
    let r = rows_of(&sp);
    for (label, ext, bytes, line) in [
        ("obj", "obj", obj(&r, &one_based(&sf)), 6),
        ("off", "off", off(&r, &sf), 8),
        ("ply-ascii", "ply", ply_ascii(&r, &sf), 15),
    ] {
        let f = format!("p.{ext}");
        v.push(
            Case::new(
                format!("polygon/self-intersecting/{label}"),
                &format!("check {f}"),
            )
            .file(&f, bytes)
            .codes(&[2])
            .names(&f)
            .names(format!("line {line}")),
        );
    }
    let cr = rows_of(&cp);
    let cube1 = one_based(&cf);
    let mut repeated = cube1.clone();
    repeated[0] = vec![1, 3, 3, 4, 2];
    v.push(
        Case::new("polygon/repeated-corner-in-quad", "check p.obj")
            .file("p.obj", obj(&cr, &repeated))
            .codes(&[0, 1, 2]),
    );
    let mut repeated = cube1.clone();
    repeated[0] = vec![1, 3, 4, 2, 1];
    v.push(
        Case::new("polygon/closing-corner-repeated", "check p.obj")
            .file("p.obj", obj(&cr, &repeated))
            .codes(&[0, 1, 2]),
    );
    let mut tri = one_based(&polys(&tet()));
    tri[3] = vec![2, 2, 3];
    v.push(
        Case::new("polygon/triangle-repeated-corner", "check p.obj")
            .file("p.obj", obj(&rows(&tet()), &tri))
            .codes(&[1, 2]),
    );
    // A quad whose corners are all on one line.
    v.push(
        Case::new("polygon/collinear-quad", "check p.obj")
            .file(
                "p.obj",
                obj(
                    &rows_of(&[
                        [0.0, 0.0, 0.0],
                        [1.0, 0.0, 0.0],
                        [2.0, 0.0, 0.0],
                        [3.0, 0.0, 0.0],
                    ]),
                    &[vec![1, 2, 3, 4]],
                ),
            )
            .codes(&[1, 2]),
    );
    v
}

/// Meshes the simplifier must refuse, with a message that blames the mesh.
fn degenerate() -> Vec<Case> {
    use envelope_mesh::generate;
    let mut v = Vec::new();
    let mut same = tet();
    for p in &mut same.positions {
        *p = glam::DVec3::splat(0.5);
    }
    let same_obj = encode(&same, Format::Obj);
    v.push(
        Case::new("degenerate/all-equal/check", "check d.obj")
            .file("d.obj", same_obj.clone())
            .codes(&[1]),
    );
    for (tag, eps) in [("relative", "1%"), ("absolute", "0.1")] {
        v.push(
            Case::new(
                format!("degenerate/all-equal/simplify-{tag}"),
                &format!("simplify d.obj out.obj --epsilon {eps}"),
            )
            .file("d.obj", same_obj.clone())
            .codes(&[2])
            .names("d.obj")
            .keep("out.obj")
            .lacks("epsilon"),
        );
    }
    v.push(
        Case::new(
            "degenerate/all-equal/envelopes",
            "envelopes d.obj --epsilon 1% --out-dir env",
        )
        .file("d.obj", same_obj.clone())
        .codes(&[2])
        .names("d.obj")
        .lacks("epsilon"),
    );
    v.push(
        Case::new("degenerate/all-equal/lod", "lod d.obj lod --epsilons 1%")
            .file("d.obj", same_obj.clone())
            .codes(&[2])
            .names("d.obj")
            .lacks("epsilon"),
    );
    v.push(
        Case::new(
            "degenerate/all-equal/genus",
            "genus d.obj out.obj --alpha 1%",
        )
        .file("d.obj", same_obj)
        .codes(&[2])
        .names("d.obj")
        .keep("out.obj")
        .lacks("alpha"),
    );
    let mut dup = tet();
    dup.faces.push(dup.faces[0]);
    let mut zero = tet();
    zero.positions.push(glam::DVec3::new(0.5, 0.0, 0.0));
    zero.faces.push([0, 1, 4].map(envelope_mesh::VertexId));
    let mut unref = tet();
    unref.positions.push(glam::DVec3::new(5.0, 5.0, 5.0));
    let mut single = tet();
    single.faces.truncate(1);
    for (tag, soup, check, simplify) in [
        ("duplicate-face", dup, &[1][..], &[2][..]),
        ("zero-area-face", zero, &[1], &[2]),
        (
            "non-manifold-edge",
            generate::three_triangles_on_edge(),
            &[1],
            &[2],
        ),
        ("bow-tie", generate::bow_tie(), &[1], &[2]),
        ("folded-vertex", generate::folded_vertex(), &[0], &[0]),
        ("moebius", generate::moebius_strip(8), &[1], &[2]),
        ("unreferenced-vertex", unref, &[0], &[0]),
        ("single-triangle", single, &[0], &[0]),
    ] {
        let bytes = encode(&soup, Format::Off);
        v.push(
            Case::new(format!("degenerate/{tag}/check"), "check d.off")
                .file("d.off", bytes.clone())
                .codes(check),
        );
        let c = Case::new(
            format!("degenerate/{tag}/simplify"),
            "simplify d.off out.off --epsilon 1% --quiet",
        )
        .file("d.off", bytes)
        .codes(simplify)
        .keep("out.off")
        .recert("d.off", "out.off", "1%");
        v.push(if simplify == [2] { c.names("d.off") } else { c });
    }
    for (tag, bytes) in [
        ("empty", Vec::new()),
        ("only-vertices", b"v 0 0 0\nv 1 0 0\nv 0 1 0\n".to_vec()),
        ("only-comments", b"# nothing\n\n   \n".to_vec()),
        ("binary-junk", (0..=255u8).cycle().take(1000).collect()),
    ] {
        v.push(
            Case::new(format!("degenerate/{tag}"), "check d.obj")
                .file("d.obj", bytes)
                .codes(&[2])
                .names("d.obj"),
        );
    }
    v
}

/// Tiny and huge scales and translations, with relative and absolute epsilons: each works
/// (and is certified) or is refused naming the file or flag.
fn scales() -> Vec<Case> {
    let mut v = Vec::new();
    let s = ico(1);
    for (tag, k, offset) in [
        ("1e-30", 1e-30, 0.0),
        ("1e-12", 1e-12, 0.0),
        ("1e12", 1e12, 0.0),
        ("1e30", 1e30, 0.0),
        ("offset-1e15", 1.0, 1e15),
        ("offset-1e8-size-1e-6", 1e-6, 1e8),
    ] {
        let bytes = encode(&scaled(&s, k, offset), Format::Obj);
        let abs = format!("{:e}", 0.01 * k);
        for (eps, name) in [("1%".to_string(), "relative"), (abs.clone(), "absolute")] {
            v.push(
                Case::new(
                    format!("scale/{tag}/simplify-{name}"),
                    &format!("simplify s.obj out.obj --epsilon {eps} --quiet"),
                )
                .file("s.obj", bytes.clone())
                .codes(&[0, 2])
                .one_of(&["s.obj", "--epsilon"])
                .lacks("barrier")
                .keep("out.obj")
                .recert("s.obj", "out.obj", &eps),
            );
        }
        v.push(
            Case::new(
                format!("scale/{tag}/envelopes"),
                "envelopes s.obj --epsilon 1% --out-dir env",
            )
            .file("s.obj", bytes.clone())
            .codes(&[0, 2])
            .one_of(&["s.obj", "--epsilon"])
            .lacks("barrier"),
        );
        v.push(
            Case::new(format!("scale/{tag}/check"), "check s.obj")
                .file("s.obj", bytes)
                .codes(&[0]),
        );
    }
    for (tag, k) in [("1e-40", 1e-40), ("1e40", 1e40)] {
        v.push(
            Case::new(format!("scale/{tag}/check"), "check s.obj")
                .file("s.obj", {
                    // The writer refuses such coordinates: write the text by hand.
                    let big = scaled(&s, k, 0.0);
                    obj(&rows(&big), &one_based(&polys(&big)))
                })
                .codes(&[2])
                .names("s.obj"),
        );
    }
    // The hang: a huge epsilon on a unit sphere.
    v.push(
        Case::new(
            "scale/sphere-320/epsilon-1e20",
            "simplify s.obj out.obj --epsilon 1e20 --quiet",
        )
        .file("s.obj", encode(&ico(2), Format::Obj))
        .codes(&[0, 2])
        .names("--epsilon")
        .keep("out.obj")
        .recert("s.obj", "out.obj", "1e20"),
    );
    v
}

/// Malformed, tiny and huge epsilons through every flag that takes one.
fn epsilons() -> Vec<Case> {
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

/// Missing, wrong-kind and colliding paths.
fn paths() -> Vec<Case> {
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

/// Numeric and enumerated flags out of range.
fn flags() -> Vec<Case> {
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

impl Case {
    /// Appends whitespace-separated `args` (for builders that start from an empty command).
    fn with_args(mut self, args: &str) -> Case {
        self.args.extend(args.split_whitespace().map(str::to_owned));
        self
    }
}

/// Large epsilons (a fifth of the diagonal and more) through every method: the output must
/// still be certified (the fuzz target `command_path` found violated certificates there).
fn large_epsilons() -> Vec<Case> {
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
