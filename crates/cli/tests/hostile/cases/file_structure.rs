//! Broken file structure: truncated files, headers whose counts lie, size bombs, and BOM or
//! CRLF variants of text files.

use super::super::files::*;
use super::super::harness::Case;
use envelope_io::{Format, PlyEncoding};

/// Valid tetrahedron files cut at many byte offsets, run through the reading commands.
pub(super) fn truncations() -> Vec<Case> {
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
pub(super) fn lying_counts() -> Vec<Case> {
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
pub(super) fn bombs() -> Vec<Case> {
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
pub(super) fn bom_crlf() -> Vec<Case> {
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
