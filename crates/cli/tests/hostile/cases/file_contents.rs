//! Bad values inside well-formed files: coordinates, vertex indices, polygons.

use super::super::files::*;
use super::super::harness::Case;

/// Coordinates that are not finite or outside the exact range, in every format.
pub(super) fn numbers() -> Vec<Case> {
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
pub(super) fn indices() -> Vec<Case> {
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
pub(super) fn polygons() -> Vec<Case> {
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
