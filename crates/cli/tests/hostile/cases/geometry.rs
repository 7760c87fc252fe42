//! Meshes that are valid files but hard geometry: degenerate meshes and extreme scales.

use super::super::files::*;
use super::super::harness::Case;
use envelope_io::Format;

/// Meshes the simplifier must refuse, with a message that blames the mesh.
pub(super) fn degenerate() -> Vec<Case> {
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
pub(super) fn scales() -> Vec<Case> {
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
