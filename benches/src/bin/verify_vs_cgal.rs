//! `envelope_verify::certify` against CGAL on the same pairs in one run: CGAL's
//! `PMP::bounded_error_Hausdorff_distance` in both directions plus `PMP::does_self_intersect`
//! on the approximation, against our two-sided certified decision plus our exhaustive
//! self-intersection list (topology off: CGAL does not compute it here).
//!
//! Pairs: `bunny00.off` (72k faces) against approximations at tolerances `t` = 1/64 %, 1/16 %,
//! 1/4 % and 1 % of its bounding-box diagonal `D`:
//! * `noise`: every vertex moved by a random vector of length < `t D` (same connectivity, so
//!   CGAL reads it as a mesh); epsilon = `t D`, which the pair provably meets;
//! * `cluster`: vertex clustering on a grid of cell `t D / sqrt(3)` (every vertex moves less
//!   than `t D`, faces collapse: a real decimation); epsilon = `2 t D`. Skipped for CGAL when it
//!   does not load as a polygon mesh.
//!
//! And a 1-million-face pair: a torus against its `noise` approximation at `t` = 1e-4.
//!
//! Timing: ours best of 3 on the in-memory soups (all rayon threads, and one thread), file
//! loading excluded, twice: listing every self-intersecting pair (the default, a certificate
//! names them) and stopping at the first (`first_intersection_only`, what CGAL's
//! `does_self_intersect` does: the like-for-like comparison). CGAL is sequential, timed around the oracle call minus the two files'
//! load times that the oracle measures itself; CGAL's error bound is `--cgal-bound` times
//! epsilon (default 1e-3). Our interval must contain CGAL's value in both directions (within
//! CGAL's error bound); the run fails otherwise.
//!
//! `cargo run --release -p envelope-benches --bin verify_vs_cgal [-- --cgal-bound R] [--no-big] [--only NAME] [--ours-only]`
//!
//! `--ours-only` skips CGAL (for profiling).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use envelope_io::{Format, read_path, write_path};
use envelope_mesh::{TriangleSoup, VertexId, generate};
use envelope_tests::oracle::{Oracle, corpus_dir};
use envelope_verify::{Options, certify};
use glam::DVec3;

const RUNS: usize = 3;

fn main() -> ExitCode {
    let mut cgal_bound = 1e-3;
    let mut big = true;
    let mut only: Option<String> = None;
    let mut ours_only = false;
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--cgal-bound" => match it.next().and_then(|x| x.parse().ok()) {
                Some(x) => cgal_bound = x,
                None => return usage(),
            },
            "--no-big" => big = false,
            "--only" => only = it.next(),
            "--ours-only" => ours_only = true,
            _ => return usage(),
        }
    }
    let oracle = match Oracle::locate() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let Some(corpus) = corpus_dir() else {
        eprintln!("corpus missing (scripts/corpus.sh)");
        return ExitCode::FAILURE;
    };
    let dir = std::env::temp_dir().join(format!("verify_vs_cgal-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create temp dir");
    let bunny_path = corpus.join("bunny00.off");
    let (bunny, _) = read_path(&bunny_path).expect("read bunny00.off");
    let d = bunny.diagonal();

    // (name, orig path, orig, approx path, approx, epsilon)
    let mut pairs = Vec::new();
    for (label, t) in [
        ("1/64%", 1.0 / 6400.0),
        ("1/16%", 1.0 / 1600.0),
        ("1/4%", 0.0025),
        ("1%", 0.01),
    ] {
        let noisy = noise(&bunny, t * d, 7);
        let (p, s) = written(&dir, &format!("bunny_noise_{t}"), &noisy);
        pairs.push((
            format!("bunny noise {label}"),
            bunny_path.clone(),
            bunny.clone(),
            p,
            s,
            t * d,
        ));
        let clustered = cluster(&bunny, t * d / 3f64.sqrt());
        let (p, s) = written(&dir, &format!("bunny_cluster_{t}"), &clustered);
        pairs.push((
            format!("bunny cluster {label}"),
            bunny_path.clone(),
            bunny.clone(),
            p,
            s,
            2.0 * t * d,
        ));
    }
    if big {
        let torus = generate::torus(1.0, 0.3, 1000, 500);
        let (tp, ts) = written(&dir, "torus", &torus);
        let e = 1e-4 * ts.diagonal();
        let (np, ns) = written(&dir, "torus_noise", &noise(&ts, e, 11));
        pairs.push(("torus 1M noise 1e-4".into(), tp, ts, np, ns, e));
    }

    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    println!(
        "ours: certify both directions + all self-intersecting pairs (\"all\") or the first \
         (\"first\"), best of {RUNS}; CGAL: bounded_error_Hausdorff both directions (bound \
         {cgal_bound:e} eps) + does_self_intersect"
    );
    println!(
        "{:<22} {:>7} {:>7} {:>8} {:>8} {:>8} {:>8} {:>8} {:>7} {:>7} {:>7} {:<10} intervals A->O, O->A vs CGAL",
        "pair",
        "faces A",
        "faces B",
        "all (s)",
        "first",
        "first 1t",
        "CGAL (s)",
        "CGAL/all",
        "/first",
        "/1t",
        "H/eps",
        "verdict",
    );
    let mut ok = true;
    for (name, op, orig, ap, approx, eps) in &pairs {
        if only.as_ref().is_some_and(|o| !name.contains(o.as_str())) {
            continue;
        }
        let options = Options {
            topology: false,
            ..Options::new(*eps)
        };
        let (ours, cert) = best_of(RUNS, || certify(orig, approx, &options));
        let first = Options {
            first_intersection_only: true,
            ..options
        };
        let (ours_first, cert_first) = best_of(RUNS, || certify(orig, approx, &first));
        assert_eq!(
            cert.verdict, cert_first.verdict,
            "{name}: first-only changed the verdict"
        );
        let (ours1, _) = best_of(1, || one_thread.install(|| certify(orig, approx, &first)));
        let load = |p: &Path| {
            oracle
                .time_does_self_intersect(p)
                .map(|t| (t.load_seconds, t.seconds))
        };
        let cgal = (|| {
            if ours_only {
                return None;
            }
            let (lo, _) = load(op).ok()?;
            let (la, dsi) = load(ap).ok()?;
            let bound = cgal_bound * eps;
            let t = Instant::now();
            let h_ao = oracle.try_hausdorff(ap, op, bound).ok()?;
            let h_oa = oracle.try_hausdorff(op, ap, bound).ok()?;
            let secs = (t.elapsed().as_secs_f64() - 2.0 * (lo + la)).max(0.0) + dsi;
            Some((secs, h_ao, h_oa, bound))
        })();
        let fmt = |s: &envelope_verify::OneSided| format!("[{:.4e}, {:.4e}]", s.lower, s.upper);
        let (a, o) = (&cert.approx_to_orig, &cert.orig_to_approx);
        let hmax = a.lower.max(o.lower) / eps;
        match cgal {
            Some((secs, h_ao, h_oa, bound)) => {
                let inside = |s: &envelope_verify::OneSided, h: f64| {
                    s.lower <= h + bound && h - bound <= s.upper
                };
                let agree = inside(a, h_ao) && inside(o, h_oa);
                ok &= agree;
                println!(
                    "{:<22} {:>7} {:>7} {:>8.3} {:>8.3} {:>8.3} {:>8.3} {:>8.2} {:>7.2} {:>7.2} {:>7.3} {:<10} {} {} vs {:.4e} {:.4e}{}",
                    name,
                    approx.faces.len(),
                    orig.faces.len(),
                    ours,
                    ours_first,
                    ours1,
                    secs,
                    secs / ours,
                    secs / ours_first,
                    secs / ours1,
                    hmax,
                    verdict(&cert),
                    fmt(a),
                    fmt(o),
                    h_ao,
                    h_oa,
                    if agree { "" } else { "  DISAGREE" }
                );
            }
            None => println!(
                "{:<22} {:>7} {:>7} {:>8.3} {:>8.3} {:>8.3} {:>8} {:>8} {:>7} {:>7} {:>7.3} {:<10} {} {} ({})",
                name,
                approx.faces.len(),
                orig.faces.len(),
                ours,
                ours_first,
                ours1,
                "n/a",
                "",
                "",
                "",
                hmax,
                verdict(&cert),
                fmt(a),
                fmt(o),
                if ours_only {
                    "CGAL skipped"
                } else {
                    "CGAL cannot load as a mesh"
                }
            ),
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

fn verdict(c: &envelope_verify::Certificate) -> String {
    let v = c.violations();
    if v.is_empty() {
        c.verdict.as_str().to_string()
    } else {
        v.join("+").replace("self_intersections", "selfint")
    }
}

fn usage() -> ExitCode {
    eprintln!(
        "usage: verify_vs_cgal [--cgal-bound R (default 1e-3)] [--no-big] [--only NAME] [--ours-only]"
    );
    ExitCode::FAILURE
}

/// Every vertex moved by a pseudo-random vector of length below `r`.
pub fn noise(soup: &TriangleSoup, r: f64, seed: u64) -> TriangleSoup {
    let mut s = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut out = soup.clone();
    for p in &mut out.positions {
        let v = DVec3::new(next(), next(), next());
        // Inside the unit ball (length < 1 after scaling by 1/sqrt(3)), times 0.999 r.
        *p += v * (0.999 * r / 3f64.sqrt());
    }
    out
}

/// Vertex clustering on a grid of cell `h`: one kept input vertex per cell, degenerate and
/// duplicate faces dropped, unreferenced vertices removed.
pub fn cluster(soup: &TriangleSoup, h: f64) -> TriangleSoup {
    use std::collections::HashMap;
    let mut cells: HashMap<[i64; 3], u32> = HashMap::new();
    let mut rep = Vec::with_capacity(soup.positions.len());
    let mut positions = Vec::new();
    for p in &soup.positions {
        let key = (*p / h).floor().to_array().map(|x| x as i64);
        let id = *cells.entry(key).or_insert_with(|| {
            positions.push(*p);
            (positions.len() - 1) as u32
        });
        rep.push(id);
    }
    let mut seen = std::collections::HashSet::new();
    let faces = soup
        .faces
        .iter()
        .map(|f| f.map(|v| rep[v.index()]))
        .filter(|f| f[0] != f[1] && f[1] != f[2] && f[2] != f[0])
        .filter(|f| {
            let mut k = *f;
            k.sort_unstable();
            seen.insert(k)
        })
        .map(|f| f.map(VertexId))
        .collect();
    TriangleSoup::new(positions, faces)
}

/// Writes `soup` as OFF and reads it back, so ours runs on exactly the doubles CGAL reads.
fn written(dir: &Path, name: &str, soup: &TriangleSoup) -> (PathBuf, TriangleSoup) {
    let file: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let path: PathBuf = dir.join(format!("{file}.off"));
    write_path(&path, soup, Format::Off).expect("write OFF");
    let (back, _) = read_path(&path).expect("read OFF back");
    (path, back)
}

fn best_of<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..runs {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    (best, out.expect("runs > 0"))
}
