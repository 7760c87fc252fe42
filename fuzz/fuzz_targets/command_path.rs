//! The command path of `envelope simplify` on arbitrary bytes: a selector byte picks the
//! format (OBJ, OFF, PLY ascii, PLY binary, STL ascii, STL binary), the simplification method,
//! the placement and whether the rest is a file or a recipe for one (`recipe`: a generated
//! mesh, scaled and with moved vertices, so that short runs from an empty corpus reach the
//! simplifier); two bytes give the epsilon (a fraction of the bounding-box diagonal or
//! an absolute length); the rest is the file. Whatever the reader accepts and the input check
//! finds acceptable (at most 200 faces, to keep runs short) goes through `simplify_with`
//! with the certificate on, as the CLI calls it. The simplifier must not panic, and when it
//! returns an output the certificate must not be violated. A failure prints the input as a
//! pasteable Rust byte string.
#![no_main]

use envelope_check::{CheckOptions, check};
use envelope_fuzz::input::Input;
use envelope_io::{Format, PlyEncoding, StlEncoding, read, write};
use envelope_mesh::generate;
use envelope_offset::EpsilonField;
use envelope_simplify::{Placement, SimplifyOptions, simplify_with};
use envelope_verify::Verdict;
use glam::DVec3;

/// Formats by the selector's low bits (the reader takes the encoding from the content; the
/// variant only names the family).
const FORMATS: [Format; 6] = [
    Format::Obj,
    Format::Off,
    Format::Ply(PlyEncoding::Ascii),
    Format::Ply(PlyEncoding::BinaryLittleEndian),
    Format::Stl(StlEncoding::Ascii),
    Format::Stl(StlEncoding::Binary),
];

/// The epsilon from two bytes: bit 7 of `a` chooses absolute (`(1 + b) / 16 * 10^k`, k in
/// -32..=31) or relative (`(1 + b) / 256 * 10^-k` of the diagonal, k in 0..=7).
fn epsilon(a: u8, b: u8, diagonal: f64) -> f64 {
    let m = 1.0 + f64::from(b);
    if a & 0x80 != 0 {
        m / 16.0 * 10f64.powi(i32::from(a & 0x3F) - 32)
    } else {
        m / 256.0 * 10f64.powi(-i32::from(a & 7)) * diagonal
    }
}

/// With selector bit 6 the rest is not a file but a recipe for one (so that a run from an
/// empty corpus reaches the simplifier): a generated mesh picked by the first byte, scaled
/// by a power of ten from the second, with vertices moved by the following bytes (vertex,
/// then a small scalar per axis), written in the selected format.
fn recipe(bytes: &[u8], format: Format) -> Vec<u8> {
    let mut input = Input(bytes);
    let mut soup = match input.u8() % 5 {
        0 => generate::tetrahedron(),
        1 => generate::box_mesh(DVec3::ONE, 1),
        2 => generate::icosphere(1, 1.0),
        3 => generate::torus(2.0, 0.5, 8, 6),
        _ => generate::open_cylinder(1.0, 1.0, 8, 2),
    };
    let scale = 10f64.powi(i32::from(input.u8() % 25) - 12);
    while !input.0.is_empty() {
        let v = usize::from(input.u8()) % soup.num_vertices();
        let d = DVec3::new(input.scalar(), input.scalar(), input.scalar());
        soup.positions[v] += d * 0.125;
    }
    for p in &mut soup.positions {
        *p *= scale;
    }
    let mut out = Vec::new();
    let _ = write(&mut out, &soup, format);
    out
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let [selector, a, b, file @ ..] = data else {
        return;
    };
    let format = FORMATS[usize::from(selector & 7) % FORMATS.len()];
    let made;
    let file = if selector & 0x40 != 0 {
        made = recipe(file, format);
        &made[..]
    } else {
        file
    };
    let Ok((soup, _)) = read(file, format) else {
        return;
    };
    if soup.num_faces() > 200 || !check(&soup, &CheckOptions::default()).acceptable() {
        return;
    }
    let eps = epsilon(*a, *b, soup.diagonal());
    if !(eps.is_finite() && eps > 0.0) {
        return;
    }
    let method = match (selector >> 3) & 3 {
        0 | 3 => envelope_global::Method::Local,
        1 => envelope_global::Method::Global,
        _ => envelope_global::Method::Hybrid,
    };
    let placement = if selector & 0x20 != 0 && method != envelope_global::Method::Global {
        Placement::Auto
    } else {
        Placement::Subset
    };
    let options = SimplifyOptions {
        verify: true,
        placement,
        ..SimplifyOptions::new(EpsilonField::Constant(eps))
    };
    let step = method.step();
    let Ok((out, report)) = simplify_with(&soup, &options, step.as_ref(), &mut ()) else {
        return;
    };
    if !out.indices_in_range() {
        envelope_fuzz::fail_with_input("output index out of range", data);
    }
    match report.verify.map(|v| (v.verdict, v.violations)) {
        Some((Verdict::Holds | Verdict::Undecided, _)) => {}
        Some((Verdict::Violated, why)) => envelope_fuzz::fail_with_input(
            &format!(
                "simplify returned an output whose certificate is violated ({}) at epsilon {eps:e}, {} method",
                why.join(", "),
                method.as_str()
            ),
            data,
        ),
        None => envelope_fuzz::fail_with_input("no certificate although verify was asked", data),
    }
});
