//! Output faces and seconds of [`envelope_simplify::simplify`] on one mesh at several epsilons
//! (fractions of the bounding-box diagonal), each run from the input.
//!
//! `cargo run --release -p envelope-simplify --example simplify_table -- MESH.off [auto|analytical|numerical] [verify] [PERCENT...]`

use envelope_offset::{EnvelopeMethod, EpsilonField};
use envelope_simplify::{SimplifyOptions, simplify};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args
        .first()
        .expect("usage: simplify_table MESH [method] [verify] [percent...]");
    let (soup, _) = envelope_io::read_path(std::path::Path::new(path)).expect("readable mesh");
    let method = match args.get(1).map(String::as_str) {
        Some("numerical") => EnvelopeMethod::Numerical,
        Some("analytical") => EnvelopeMethod::Analytical,
        _ => EnvelopeMethod::Auto,
    };
    let verify = args.iter().any(|a| a == "verify");
    let mut percents: Vec<f64> = args.iter().skip(2).filter_map(|a| a.parse().ok()).collect();
    if percents.is_empty() {
        percents = vec![
            1.0 / 64.0,
            1.0 / 32.0,
            1.0 / 16.0,
            1.0 / 8.0,
            0.25,
            0.5,
            1.0,
        ];
    }
    println!("{path}: {} faces, method {method:?}", soup.num_faces());
    println!("| eps (% diag) | output faces | total s | envelopes s | simplify s | verify |");
    println!("|---|---|---|---|---|---|");
    for p in percents {
        let mut o = SimplifyOptions::new(EpsilonField::Constant(p / 100.0 * soup.diagonal()));
        o.method = method;
        o.verify = verify;
        let (out, r) = simplify(&soup, &o, &mut ()).expect("simplify");
        let v = r.verify.as_ref().map_or("-".to_string(), |v| {
            format!(
                "{} (a->o {:.3e}, o->a {:.3e}, {:.1} s)",
                v.verdict.as_str(),
                v.approx_to_orig_upper / r.diagonal,
                v.orig_to_approx_upper / r.diagonal,
                v.seconds
            )
        });
        println!(
            "| {p} | {} | {:.2} | {:.2} | {:.2} | {v} |",
            out.num_faces(),
            r.seconds,
            r.envelope.seconds,
            r.simplify_seconds
        );
    }
}
