//! Self-intersection timing: our `envelope_predicates::self_intersections` against CGAL's
//! `PMP::does_self_intersect` (through the oracle), on the same OFF files in the same run.
//!
//! Meshes: a clean torus of about N faces (`generate::torus`; default N = 1,000,000, i.e.
//! `torus(1.0, 0.3, 1000, 500)`), two interpenetrating icospheres (many intersecting pairs),
//! and with `--corpus` the largest triangle-only corpus meshes. Each is written to a temporary
//! OFF file; ours is timed on the in-memory soup (file loading excluded), best of 3, once on
//! all rayon threads and once on a one-thread pool; CGAL's time is the oracle's own
//! measurement of `does_self_intersect` alone (loading excluded), best of 3, sequential.
//!
//! Not like for like: `does_self_intersect` may stop at the first intersecting pair, while
//! ours always lists **every** pair. On clean meshes both must examine every candidate pair.
//! The pair counts come from one extra (untimed) `self_intersections` call on each side.
//!
//! `cargo run --release -p envelope-benches --bin selfint_vs_cgal [-- --faces N] [--corpus]`

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use envelope_io::{Format, read_path, write_path};
use envelope_mesh::{TriangleSoup, VertexId, generate};
use envelope_predicates::self_intersections;
use envelope_tests::oracle::{Oracle, corpus_meshes};

const RUNS: usize = 3;

struct Args {
    faces: u64,
    corpus: bool,
}

fn parse_args() -> Option<Args> {
    let mut a = Args {
        faces: 1_000_000,
        corpus: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(x) = it.next() {
        match x.as_str() {
            "--faces" => a.faces = it.next()?.parse().ok().filter(|&n: &u64| n >= 18)?,
            "--corpus" => a.corpus = true,
            _ => return None,
        }
    }
    Some(a)
}

fn main() -> ExitCode {
    let Some(args) = parse_args() else {
        eprintln!("usage: selfint_vs_cgal [--faces N (>= 18, default 1000000)] [--corpus]");
        return ExitCode::FAILURE;
    };
    let oracle = match Oracle::locate() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let dir = std::env::temp_dir().join(format!("selfint_vs_cgal-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("create temp dir");

    // (name, file, soup as both sides read it)
    let mut meshes: Vec<(String, PathBuf, TriangleSoup)> = Vec::new();
    let nu = ((args.faces as f64 / 2.0).sqrt() * 2f64.sqrt())
        .round()
        .max(3.0) as u32;
    let nv = ((args.faces / (2 * u64::from(nu))) as u32).max(3);
    let torus = generate::torus(1.0, 0.3, nu, nv);
    meshes.push(written(&dir, &format!("torus({nu}x{nv})"), &torus));
    // Two interpenetrating spheres of about a sixth of N faces in all.
    let mut sub = 0;
    while 40 * 4u64.pow(sub + 1) <= args.faces / 6 {
        sub += 1;
    }
    let s = generate::icosphere(sub, 1.0);
    let mut shifted = s.clone();
    shifted.positions.iter_mut().for_each(|p| p.x += 1.0);
    meshes.push(written(
        &dir,
        &format!("two_spheres(ico{sub})"),
        &merge(&s, &shifted),
    ));
    if args.corpus {
        let mut files: Vec<(u64, PathBuf)> = corpus_meshes()
            .into_iter()
            .map(|p| (std::fs::metadata(&p).map_or(0, |m| m.len()), p))
            .collect();
        files.sort_by_key(|f| std::cmp::Reverse(f.0));
        for (_, p) in files.into_iter().take(8) {
            match read_path(&p) {
                Ok((soup, r)) if r.polygons_triangulated == 0 => {
                    let n = p.file_name().unwrap().to_string_lossy().into_owned();
                    meshes.push((n, p, soup));
                }
                _ => {}
            }
        }
    }

    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("one-thread pool");
    println!(
        "self-intersection: ours = all pairs listed (best of {RUNS}, load excluded); \
         CGAL = PMP::does_self_intersect, may stop at the first pair (best of {RUNS}, load excluded)"
    );
    println!(
        "{:<26} {:>9} {:>12} {:>12} {:>12} {:>10} {:>10} {:>11} {:>11}",
        "mesh",
        "faces",
        format!("ours {}t (s)", rayon::current_num_threads()),
        "ours 1t (s)",
        "CGAL dsi (s)",
        "CGAL/ours",
        "CGAL/1t",
        "pairs ours",
        "pairs CGAL"
    );
    for (name, path, soup) in &meshes {
        let faces: Vec<[u32; 3]> = soup.faces.iter().map(|f| f.map(|v| v.0)).collect();
        let (ours, pairs) = best_of(|| self_intersections(&soup.positions, &faces));
        let (ours1, _) =
            best_of(|| one_thread.install(|| self_intersections(&soup.positions, &faces)));
        let mut cgal = f64::INFINITY;
        let mut intersects = false;
        for _ in 0..RUNS {
            match oracle.time_does_self_intersect(path) {
                Ok(t) => {
                    cgal = cgal.min(t.seconds);
                    intersects = t.intersects;
                }
                Err(e) => {
                    eprintln!("{name}: oracle failed: {e}");
                    break;
                }
            }
        }
        let cgal_pairs = oracle
            .try_self_intersections(path, false)
            .map(|r| r.pairs.iter().filter(|p| p.0 != p.1).count().to_string())
            .unwrap_or_else(|e| format!("err: {e}"));
        assert_eq!(
            intersects,
            !pairs.is_empty(),
            "{name}: does_self_intersect says {intersects}, we found {} pairs",
            pairs.len()
        );
        println!(
            "{:<26} {:>9} {:>12.3} {:>12.3} {:>12.3} {:>10.2} {:>10.2} {:>11} {:>11}",
            name,
            faces.len(),
            ours,
            ours1,
            cgal,
            cgal / ours,
            cgal / ours1,
            pairs.len(),
            cgal_pairs
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
    ExitCode::SUCCESS
}

/// Writes `soup` as OFF and reads it back, so ours runs on exactly the doubles CGAL reads.
fn written(dir: &Path, name: &str, soup: &TriangleSoup) -> (String, PathBuf, TriangleSoup) {
    let file: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    let path = dir.join(format!("{file}.off"));
    write_path(&path, soup, Format::Off).expect("write OFF");
    let (back, _) = read_path(&path).expect("read OFF back");
    (name.to_string(), path, back)
}

fn merge(a: &TriangleSoup, b: &TriangleSoup) -> TriangleSoup {
    let off = a.positions.len() as u32;
    let mut positions = a.positions.clone();
    positions.extend_from_slice(&b.positions);
    let mut faces = a.faces.clone();
    faces.extend(b.faces.iter().map(|f| f.map(|v| VertexId(v.0 + off))));
    TriangleSoup::new(positions, faces)
}

fn best_of<T>(mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..RUNS {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    (best, out.expect("RUNS > 0"))
}
