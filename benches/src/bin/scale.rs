//! `scale`: the scale series of issue 36. One input family at growing sizes, `envelope
//! simplify` (default settings, its certificate included) at each size and epsilon, one row
//! per run with the time of each stage, and the log-log slope of each stage between
//! consecutive sizes (1 is linear, 2 quadratic). meshoptimizer (no guarantee, f32) runs on the
//! same input in this process for the speed ratio.
//!
//! ```text
//! scale [--mesh bunny00|armadillo|...|torus] [--levels 0,1,2] [--sizes 100k,1M]
//!       [--epsilons 1/64%,1%] [--envelope PATH] [--dir DIR] [--threads N] [--timeout S]
//!       [--json PATH] [--quick]
//! ```
//!
//! * A corpus mesh (`.corpus/data/meshes/NAME.off`) is refined by Loop subdivision
//!   (`envelope_benches::loop_subdivide`, as the issue's 1,074,744-face head was made); each
//!   level multiplies the faces by four (`--levels`, default 0..=2).
//! * `torus` is a generated smooth bumpy torus of about each of `--sizes` faces (default
//!   100k, 300k, 1M): a stand-in for a scan that needs no corpus.
//! * `--quick` (CI smoke): the torus at 20k and 80k faces at 1 %.
//!
//! The inputs are written as binary PLY into `--dir` and kept there (default a temporary
//! directory, removed at the end). Each run is a child process under `/usr/bin/time -f %M` (peak RSS); the
//! stage times come from the report (`envelope.seconds`, `simplify_seconds`,
//! `verify.seconds`, `seconds`); `cpu/wall` is the process's user and system time over its
//! wall time (2 when both cores of this machine work throughout).
#![forbid(unsafe_code)]

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::time::Instant;

use envelope_benches::{loop_subdivide, meshopt_simplify, parse_epsilon};
use envelope_io::{Format, PlyEncoding, read_path, write};
use envelope_mesh::{TriangleSoup, VertexId};
use glam::DVec3;

struct Args {
    mesh: String,
    levels: Vec<u32>,
    sizes: Vec<usize>,
    epsilons: Vec<(String, f64)>,
    envelope: Option<PathBuf>,
    dir: Option<PathBuf>,
    threads: Option<String>,
    timeout: f64,
    json: Option<PathBuf>,
}

#[derive(Default, Clone)]
struct Row {
    input: String,
    faces: usize,
    eps: String,
    out_faces: Option<u64>,
    envelopes: Option<f64>,
    simplify: Option<f64>,
    certificate: Option<f64>,
    total: Option<f64>,
    wall: Option<f64>,
    peak_mib: Option<f64>,
    /// User plus system seconds of the whole process.
    cpu: Option<f64>,
    meshopt: Option<f64>,
    status: String,
}

fn usage() -> ExitCode {
    eprintln!(
        "usage: scale [--mesh NAME|torus] [--levels 0,1,2] [--sizes 100k,300k,1M] \
         [--epsilons 1/64%,1%] [--envelope PATH] [--dir DIR] [--threads N] [--timeout S] \
         [--json PATH] [--quick]"
    );
    ExitCode::from(2)
}

fn parse_size(s: &str) -> Option<usize> {
    let (num, mul) = match s.as_bytes().last()? {
        b'k' | b'K' => (&s[..s.len() - 1], 1e3),
        b'm' | b'M' => (&s[..s.len() - 1], 1e6),
        _ => (s, 1.0),
    };
    let v = num.parse::<f64>().ok()? * mul;
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    (8.0..=1e9).contains(&v).then_some(v as usize)
}

fn parse_args(argv: &[String]) -> Option<Args> {
    let mut a = Args {
        mesh: "bunny00".into(),
        levels: vec![0, 1, 2],
        sizes: vec![100_000, 300_000, 1_000_000],
        epsilons: ["1/64%", "1%"]
            .iter()
            .filter_map(|s| parse_epsilon(s))
            .collect(),
        envelope: None,
        dir: None,
        threads: None,
        timeout: 1800.0,
        json: None,
    };
    let mut it = argv.iter();
    while let Some(flag) = it.next() {
        if flag == "--quick" {
            a.mesh = "torus".into();
            a.sizes = vec![20_000, 80_000];
            a.epsilons = vec![parse_epsilon("1%")?];
            continue;
        }
        let v = it.next()?;
        match flag.as_str() {
            "--mesh" => a.mesh.clone_from(v),
            "--levels" => {
                a.levels = v
                    .split(',')
                    .map(|s| s.parse().ok())
                    .collect::<Option<_>>()?;
            }
            "--sizes" => a.sizes = v.split(',').map(parse_size).collect::<Option<_>>()?,
            "--epsilons" => a.epsilons = v.split(',').map(parse_epsilon).collect::<Option<_>>()?,
            "--envelope" => a.envelope = Some(v.into()),
            "--dir" => a.dir = Some(v.into()),
            "--threads" => a.threads = Some(v.clone()),
            "--timeout" => a.timeout = v.parse().ok().filter(|t: &f64| *t > 0.0)?,
            "--json" => a.json = Some(v.into()),
            _ => return None,
        }
    }
    Some(a)
}

/// A smooth torus with bumps of three wavelengths, `2 n n` faces for `n` rings of `2 n`
/// segments, closest to `faces`. Genus 1, closed, no two vertices equal.
fn torus(faces: usize) -> TriangleSoup {
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        clippy::cast_precision_loss
    )]
    let nv = ((faces as f64 / 4.0).sqrt().round() as u32).max(8);
    let nu = 2 * nv;
    let (big, small) = (1.0, 0.35);
    let mut positions = Vec::with_capacity((nu * nv) as usize);
    for i in 0..nu {
        let u = std::f64::consts::TAU * f64::from(i) / f64::from(nu);
        for j in 0..nv {
            let v = std::f64::consts::TAU * f64::from(j) / f64::from(nv);
            let d = 1.0
                + 0.08 * (7.0 * u + 3.0 * v).sin() * (5.0 * v).cos()
                + 0.02 * (13.0 * u - 5.0 * v).sin();
            let r = small * d;
            positions.push(DVec3::new(
                (big + r * v.cos()) * u.cos(),
                (big + r * v.cos()) * u.sin(),
                r * v.sin(),
            ));
        }
    }
    let id = |i: u32, j: u32| VertexId((i % nu) * nv + j % nv);
    let mut fs = Vec::with_capacity(2 * (nu * nv) as usize);
    for i in 0..nu {
        for j in 0..nv {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            fs.push([a, b, c]);
            fs.push([a, c, d]);
        }
    }
    TriangleSoup::new(positions, fs)
}

fn inputs(a: &Args) -> Result<Vec<(String, TriangleSoup)>, String> {
    if a.mesh == "torus" {
        return Ok(a
            .sizes
            .iter()
            .map(|&n| {
                let s = torus(n);
                (format!("torus-{}", s.faces.len()), s)
            })
            .collect());
    }
    let path = Path::new(".corpus/data/meshes").join(format!("{}.off", a.mesh));
    let (mut soup, _) =
        read_path(&path).map_err(|e| format!("{}: {e} (run scripts/corpus.sh)", path.display()))?;
    let mut out = Vec::new();
    let top = a.levels.iter().copied().max().unwrap_or(0);
    for level in 0..=top {
        if level > 0 {
            soup = loop_subdivide(&soup);
        }
        if a.levels.contains(&level) {
            out.push((format!("{}-L{level}", a.mesh), soup.clone()));
        }
    }
    Ok(out)
}

fn envelope_bin(a: &Args) -> Option<PathBuf> {
    if let Some(p) = &a.envelope {
        return Some(p.clone());
    }
    if let Some(p) = std::env::var_os("ENVELOPE_BIN") {
        return Some(p.into());
    }
    let dirs = [
        std::env::var("CARGO_TARGET_DIR").unwrap_or_default(),
        "target".into(),
    ];
    dirs.iter()
        .filter(|d| !d.is_empty())
        .map(|d| Path::new(d).join("release/envelope"))
        .filter(|p| p.exists())
        .max_by_key(|p| fs::metadata(p).and_then(|m| m.modified()).ok())
}

fn run_envelope(bin: &Path, a: &Args, input: &Path, dir: &Path, eps: &str, row: &mut Row) {
    let out = dir.join("out.ply");
    let report = dir.join("report.json");
    let _ = fs::remove_file(&report);
    let mut cmd = Command::new("/usr/bin/time");
    cmd.args([
        "-f",
        "peak_kib=%M cpu_s=%U+%S",
        "timeout",
        &format!("{}", a.timeout),
    ]);
    cmd.arg(bin);
    if let Some(t) = &a.threads {
        cmd.args(["--threads", t]);
    }
    cmd.arg("simplify").arg(input).arg(&out);
    cmd.args(["--epsilon", eps, "--quiet", "--report"])
        .arg(&report);
    let t = Instant::now();
    let res = cmd.stdout(Stdio::null()).stderr(Stdio::piped()).output();
    row.wall = Some(t.elapsed().as_secs_f64());
    let Ok(res) = res else {
        row.status = "spawn failed".into();
        return;
    };
    let stderr = String::from_utf8_lossy(&res.stderr);
    let last = stderr
        .lines()
        .rfind(|l| l.starts_with("peak_kib="))
        .unwrap_or("");
    let field = |key: &str| last.split(' ').find_map(|w| w.strip_prefix(key));
    row.peak_mib = field("peak_kib=")
        .and_then(|v| v.parse::<f64>().ok())
        .map(|k| k / 1024.0);
    row.cpu = field("cpu_s=").and_then(|v| {
        let (u, s) = v.split_once('+')?;
        Some(u.parse::<f64>().ok()? + s.parse::<f64>().ok()?)
    });
    row.status = if res.status.success() {
        "ok".into()
    } else {
        format!("exit {}", res.status.code().unwrap_or(-1))
    };
    let Ok(text) = fs::read_to_string(&report) else {
        return;
    };
    let Ok(r) = serde_json::from_str::<serde_json::Value>(&text) else {
        return;
    };
    row.out_faces = r["output_faces"].as_u64();
    row.envelopes = r["envelope"]["seconds"].as_f64();
    row.simplify = r["simplify_seconds"].as_f64();
    row.certificate = r["verify"]["seconds"].as_f64();
    row.total = r["seconds"].as_f64();
    if r["verify"]["verdict"].as_str() != Some("holds") {
        row.status = format!("certificate {}", r["verify"]["verdict"]);
    }
    let _ = fs::remove_file(&out);
}

fn cell(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(|| "-".into(), |x| format!("{x:.digits$}"))
}

#[allow(clippy::cast_precision_loss)]
fn slope(a: &Row, b: &Row, f: impl Fn(&Row) -> Option<f64>) -> String {
    match (f(a), f(b)) {
        (Some(x), Some(y)) if x > 0.0 && y > 0.0 && b.faces != a.faces => {
            format!(
                "{:.2}",
                (y / x).ln() / (b.faces as f64 / a.faces as f64).ln()
            )
        }
        _ => "-".into(),
    }
}

fn main() -> ExitCode {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let Some(args) = parse_args(&argv) else {
        return usage();
    };
    let Some(bin) = envelope_bin(&args) else {
        eprintln!(
            "error: no envelope binary (build `cargo build --release -p envelope-cli`, or pass --envelope)"
        );
        return ExitCode::FAILURE;
    };
    let inputs = match inputs(&args) {
        Ok(i) => i,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let (dir, temporary) = match &args.dir {
        Some(d) => (d.clone(), false),
        None => (
            std::env::temp_dir().join(format!("envelope-scale-{}", std::process::id())),
            true,
        ),
    };
    if let Err(e) = fs::create_dir_all(&dir) {
        eprintln!("error: {}: {e}", dir.display());
        return ExitCode::FAILURE;
    }
    let mut rows: Vec<Row> = Vec::new();
    println!(
        "{:<18} {:>9} {:>7} {:>7} {:>8} {:>8} {:>8} {:>8} {:>8} {:>9} {:>8} {:>8} {:>8} {:>8}",
        "input",
        "faces",
        "eps",
        "out",
        "env s",
        "simp s",
        "cert s",
        "total s",
        "wall s",
        "cert/simp",
        "cpu/wall",
        "peak MiB",
        "meshopt",
        "ours/mo"
    );
    for (name, soup) in &inputs {
        let path = dir.join(format!("{name}.ply"));
        let written = fs::File::create(&path)
            .map_err(|e| e.to_string())
            .and_then(|f| {
                write(
                    std::io::BufWriter::new(f),
                    soup,
                    Format::Ply(PlyEncoding::BinaryLittleEndian),
                )
                .map_err(|e| e.to_string())
            });
        if let Err(e) = written {
            eprintln!("error: {}: {e}", path.display());
            return ExitCode::FAILURE;
        }
        let diag = soup.diagonal();
        for (label, frac) in &args.epsilons {
            let mut row = Row {
                input: name.clone(),
                faces: soup.faces.len(),
                eps: label.clone(),
                ..Row::default()
            };
            run_envelope(&bin, &args, &path, &dir, label, &mut row);
            row.meshopt = meshopt_simplify(soup, frac * diag).ok().map(|r| r.seconds);
            println!(
                "{:<18} {:>9} {:>7} {:>7} {:>8} {:>8} {:>8} {:>8} {:>8} {:>9} {:>8} {:>8} {:>8} {:>8}{}",
                row.input,
                row.faces,
                row.eps,
                row.out_faces.map_or_else(|| "-".into(), |f| f.to_string()),
                cell(row.envelopes, 2),
                cell(row.simplify, 2),
                cell(row.certificate, 2),
                cell(row.total, 2),
                cell(row.wall, 2),
                cell(row.certificate.zip(row.simplify).map(|(c, s)| c / s), 2),
                cell(row.cpu.zip(row.wall).map(|(c, w)| c / w), 2),
                cell(row.peak_mib, 0),
                cell(row.meshopt, 3),
                cell(row.total.zip(row.meshopt).map(|(o, m)| o / m), 0),
                if row.status == "ok" {
                    String::new()
                } else {
                    format!("  {}", row.status)
                },
            );
            rows.push(row);
        }
        if temporary {
            let _ = fs::remove_file(&path);
        }
    }
    // Log-log slopes between consecutive sizes, per epsilon and stage.
    println!("\nlog-log slope of time against faces between consecutive sizes (1 = linear):");
    println!(
        "{:<7} {:>20} {:>7} {:>7} {:>7} {:>7} {:>7}",
        "eps", "faces", "env", "simp", "cert", "total", "peak"
    );
    let mut failed = false;
    for (label, _) in &args.epsilons {
        let of: Vec<&Row> = rows.iter().filter(|r| &r.eps == label).collect();
        for w in of.windows(2) {
            println!(
                "{:<7} {:>20} {:>7} {:>7} {:>7} {:>7} {:>7}",
                label,
                format!("{} -> {}", w[0].faces, w[1].faces),
                slope(w[0], w[1], |r| r.envelopes),
                slope(w[0], w[1], |r| r.simplify),
                slope(w[0], w[1], |r| r.certificate),
                slope(w[0], w[1], |r| r.total),
                slope(w[0], w[1], |r| r.peak_mib),
            );
        }
    }
    for r in &rows {
        failed |= r.status != "ok";
    }
    if let Some(p) = &args.json {
        let json: Vec<serde_json::Value> = rows
            .iter()
            .map(|r| {
                serde_json::json!({
                    "input": r.input, "faces": r.faces, "epsilon": r.eps,
                    "output_faces": r.out_faces, "envelopes": r.envelopes,
                    "simplify": r.simplify, "certificate": r.certificate, "total": r.total,
                    "wall": r.wall, "cpu": r.cpu, "peak_mib": r.peak_mib, "meshopt": r.meshopt,
                    "status": r.status,
                })
            })
            .collect();
        let text = serde_json::to_string_pretty(&json).unwrap_or_default();
        if let Err(e) = fs::write(p, text + "\n") {
            eprintln!("error: {}: {e}", p.display());
            failed = true;
        }
    }
    if temporary {
        let _ = fs::remove_dir_all(&dir);
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
