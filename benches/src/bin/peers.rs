//! `envelope simplify` against its peers on the same meshes and tolerances, in one run:
//! * `envelope`: `envelope simplify IN OUT --epsilon E --report R.json --quiet` (plus
//!   `--placement` and `--method` when given; the default placement is `auto`);
//! * `envelope-collapse`: the same with `--placement collapse` (local algorithm, edge
//!   collapses after the subset run), the configuration with the fewest faces for its time;
//! * `envelope-hybrid` (only when named in `--tools`): `--method hybrid --placement collapse`,
//!   slightly fewer faces than `envelope-collapse` for more time;
//! * `cgal`: CGAL 5.5 `edge_collapse` with `Polyhedral_envelope_filter` (`benches/peers`);
//! * `openmesh`: OpenMesh 9 `DecimaterT` with `ModQuadricT` + `ModHausdorffT` (`benches/peers`);
//! * `meshopt`: meshoptimizer's `simplify` (the `meshopt` crate), target 0 triangles,
//!   `ErrorAbsolute` target error epsilon: a speed ceiling with no guarantee.
//!
//! Every tool runs as a child process (meshopt: this program re-run with `--meshopt-child`)
//! under `/usr/bin/time` for its peak RSS, with a per-run timeout (the process group is killed).
//! Seconds are what the tool reports for the simplification alone (I/O excluded) when it does,
//! else wall seconds. Every output is then measured independently: the two-sided Hausdorff
//! distance over epsilon with CGAL (`envelope-oracle hausdorff`, both directions, error bound
//! 1% of epsilon), our certified decision (`envelope_verify::certify`, distance only) and CGAL's
//! self-intersection count (mesh, else soup semantics). Each oracle process runs under a CPU
//! time and address-space limit (`--oracle-cpu`, default 600 s; `--oracle-gib`, default 8): a
//! measurement that hits one shows as `limit` in the table, and an oracle left behind by a
//! killed `peers` ends at its CPU limit.
//!
//! Each `envelope` row at (mesh, E) also names the best valid peer: the fewest faces of any
//! peer output of that mesh in this run, at any epsilon, proved within E both ways (our
//! certificate's bounds, else CGAL's distance plus its error bound), free of
//! self-intersections and of the input's topology (`best_valid_peer`); then whether ours has
//! at most as many faces.
//!
//! ```sh
//! benches/peers/build.sh && cargo build --release -p envelope-cli
//! cargo run --release -p envelope-benches --bin peers -- [--quick] [--meshes a,b]
//!     [--epsilons 1/64%,1%] [--tools envelope,envelope-collapse,cgal,openmesh,meshopt] [--timeout S]
//!     [--repeat N] [--oracle-cpu S] [--oracle-gib G] [--json PATH] [--keep DIR] [--envelope PATH]
//!     [--plot PATH.svg]
//! ```
//! Prints one markdown table; writes the raw results as JSON (default
//! `benches/results/peers-<unix time>.json`) and, with `--plot`, faces against epsilon, one
//! line per mesh and tool (`envelope-render`). See `benches/README.md`.

use std::ffi::OsString;
use std::fmt::Write as _;
use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use envelope_benches::{meshopt_simplify, parse_epsilon};
use envelope_io::read_path;
use envelope_mesh::TriangleSoup;
use envelope_tests::oracle::{
    Limits, Oracle, OracleError, OracleTopology, TopoCounts, corpus_dir, repo_root,
};
use envelope_verify::{Options, Verdict, certify};
use serde_json::{Value, json};

const DEFAULT_MESHES: [&str; 4] = ["bunny00", "fandisk", "mech-holes-shark", "armadillo"];
const DEFAULT_EPSILONS: [&str; 7] = ["1/64%", "1/32%", "1/16%", "1/8%", "1/4%", "1/2%", "1%"];
/// CGAL's Hausdorff error bound, relative to epsilon.
const HAUSDORFF_BOUND: f64 = 0.01;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Tool {
    Envelope,
    /// Ours with the fewest faces for the time: `--placement collapse`.
    EnvelopeCollapse,
    /// Ours with `--method hybrid --placement collapse` (not run unless named).
    EnvelopeHybrid,
    Cgal,
    OpenMesh,
    Meshopt,
}

impl Tool {
    const ALL: [Tool; 6] = [
        Tool::Envelope,
        Tool::EnvelopeCollapse,
        Tool::EnvelopeHybrid,
        Tool::Cgal,
        Tool::OpenMesh,
        Tool::Meshopt,
    ];

    fn name(self) -> &'static str {
        match self {
            Tool::Envelope => "envelope",
            Tool::EnvelopeCollapse => "envelope-collapse",
            Tool::EnvelopeHybrid => "envelope-hybrid",
            Tool::Cgal => "cgal",
            Tool::OpenMesh => "openmesh",
            Tool::Meshopt => "meshopt",
        }
    }

    /// One of our configurations (the others are the peers).
    fn ours(self) -> bool {
        matches!(
            self,
            Tool::Envelope | Tool::EnvelopeCollapse | Tool::EnvelopeHybrid
        )
    }

    /// What runs without `--tools`.
    fn defaults() -> Vec<Tool> {
        Tool::ALL
            .into_iter()
            .filter(|&t| t != Tool::EnvelopeHybrid)
            .collect()
    }

    fn parse(s: &str) -> Option<Tool> {
        Tool::ALL.into_iter().find(|t| t.name() == s)
    }
}

struct Args {
    meshes: Vec<String>,
    /// With `--meshes all`: only meshes with at most this many faces.
    max_faces: Option<usize>,
    /// With `--meshes all`: only meshes whose name sorts at or after this one (resuming).
    from: Option<String>,
    /// With `--meshes all`: only meshes whose name sorts before this one (splitting a sweep).
    until: Option<String>,
    /// (label, fraction of the bounding-box diagonal)
    epsilons: Vec<(String, f64)>,
    tools: Vec<Tool>,
    timeout: f64,
    /// CPU seconds and GiB of address space for each oracle process (`Oracle::with_limits`).
    oracle_cpu: u64,
    oracle_gib: u64,
    json: Option<PathBuf>,
    keep: Option<PathBuf>,
    envelope: Option<PathBuf>,
    /// `--placement` for our simplifier (`auto`, the default, `subset`, `slide` or `collapse`).
    placement: Option<String>,
    /// `--method` for our simplifier (`local`, the default, `global` or `hybrid`).
    method: Option<String>,
    /// Runs of every tool per row, taken in turn (tool 1, tool 2, ..., tool 1, ...); the
    /// table shows the median seconds.
    repeat: usize,
    /// `--plot`: where to write faces against epsilon as SVG.
    plot: Option<PathBuf>,
}

fn main() -> ExitCode {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    if argv.first().map(String::as_str) == Some("--meshopt-child") {
        return match argv.as_slice() {
            [_, inp, out, eps] => match eps.parse() {
                Ok(e) => meshopt_child(Path::new(inp), Path::new(out), e),
                Err(_) => usage(),
            },
            _ => usage(),
        };
    }
    let Some(args) = parse_args(&argv) else {
        return usage();
    };
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn usage() -> ExitCode {
    eprintln!(
        "usage: peers [--quick] [--meshes a,b|all] [--max-faces N] [--from NAME] [--until NAME] [--epsilons 1/64%,...,1%] \
         [--tools envelope,envelope-collapse,envelope-hybrid,cgal,openmesh,meshopt] [--timeout S] [--repeat N] [--oracle-cpu S] [--oracle-gib G] \
         [--json PATH] [--keep DIR] [--envelope PATH] [--placement auto|subset|slide|collapse] \
         [--method local|global|hybrid] [--plot PATH.svg]\n\
         epsilons are percentages of the input's bounding-box diagonal (`1/64%`, `0.5%`)"
    );
    ExitCode::FAILURE
}

fn parse_args(argv: &[String]) -> Option<Args> {
    let mut a = Args {
        meshes: DEFAULT_MESHES.iter().map(|s| (*s).to_string()).collect(),
        epsilons: DEFAULT_EPSILONS
            .iter()
            .map(|s| parse_epsilon(s).expect("valid"))
            .collect(),
        tools: Tool::defaults(),
        timeout: 600.0,
        oracle_cpu: 600,
        oracle_gib: 8,
        json: None,
        keep: None,
        envelope: None,
        placement: None,
        method: None,
        max_faces: None,
        from: None,
        until: None,
        repeat: 1,
        plot: None,
    };
    let mut it = argv.iter();
    let list = |v: Option<&String>| -> Option<Vec<String>> {
        Some(
            v?.split(',')
                .filter(|s| !s.is_empty())
                .map(str::to_string)
                .collect(),
        )
    };
    while let Some(f) = it.next() {
        match f.as_str() {
            "--quick" => {
                a.meshes = vec!["mech-holes-shark".into()];
                a.epsilons = vec![parse_epsilon("1/4%")?, parse_epsilon("1%")?];
                a.timeout = 60.0;
            }
            "--meshes" => a.meshes = list(it.next())?,
            "--epsilons" => {
                a.epsilons = list(it.next())?
                    .iter()
                    .map(|s| parse_epsilon(s))
                    .collect::<Option<_>>()?;
            }
            "--tools" => {
                a.tools = list(it.next())?
                    .iter()
                    .map(|s| Tool::parse(s))
                    .collect::<Option<_>>()?;
            }
            "--timeout" => a.timeout = it.next()?.parse().ok().filter(|t: &f64| *t > 0.0)?,
            "--repeat" => a.repeat = it.next()?.parse().ok().filter(|&n: &usize| n > 0)?,
            "--oracle-cpu" => a.oracle_cpu = it.next()?.parse().ok().filter(|&t: &u64| t > 0)?,
            "--oracle-gib" => a.oracle_gib = it.next()?.parse().ok().filter(|&g: &u64| g > 0)?,
            "--json" => a.json = Some(PathBuf::from(it.next()?)),
            "--plot" => a.plot = Some(PathBuf::from(it.next()?)),
            "--keep" => a.keep = Some(PathBuf::from(it.next()?)),
            "--envelope" => a.envelope = Some(PathBuf::from(it.next()?)),
            "--placement" => {
                let p = it.next()?;
                a.placement = Some(p.clone())
                    .filter(|p| ["auto", "subset", "slide", "collapse"].contains(&p.as_str()));
                a.placement.as_ref()?;
            }
            "--method" => {
                let m = it.next()?;
                a.method =
                    Some(m.clone()).filter(|m| ["local", "global", "hybrid"].contains(&m.as_str()));
                a.method.as_ref()?;
            }
            "--max-faces" => a.max_faces = Some(it.next()?.parse().ok()?),
            "--from" => a.from = Some(it.next()?.clone()),
            "--until" => a.until = Some(it.next()?.clone()),
            _ => return None,
        }
    }
    (!a.meshes.is_empty() && !a.epsilons.is_empty() && !a.tools.is_empty()).then_some(a)
}

/// How one tool run ended.
#[derive(Clone, Debug, PartialEq)]
enum Status {
    Ok,
    Unavailable(String),
    Timeout,
    Failed(String),
}

/// One tool on one (mesh, epsilon).
#[derive(Clone, Debug)]
struct Run {
    status: Status,
    faces: Option<usize>,
    /// Tool-reported seconds (simplification only), else wall; with `--repeat`, the median
    /// of `samples`.
    seconds: Option<f64>,
    /// The seconds of every run (`--repeat`), in order.
    samples: Vec<f64>,
    seconds_source: &'static str,
    /// Ours: the seconds of the built-in certificate (`verify.seconds` in the report), not
    /// part of `seconds` (the peers have nothing like it).
    cert_seconds: Option<f64>,
    wall: Option<f64>,
    peak_mib: Option<f64>,
    /// CGAL: max of the two one-sided distances, over epsilon (with the two sides).
    dist: Option<(f64, f64, f64)>,
    dist_error: Option<String>,
    /// The distance failed because the oracle hit one of its limits.
    dist_limited: bool,
    /// Ours: certified verdict, and the larger lower bound over epsilon.
    cert: Option<(Verdict, f64, f64)>,
    /// Self-intersecting pairs (CGAL), with the semantics used.
    self_int: Option<(usize, &'static str)>,
    self_int_error: Option<String>,
    /// Genus, border loops and components of input and output by CGAL (OpenMesh when CGAL
    /// reads only a soup): `same`, or what changed.
    topo: Option<String>,
    topo_error: Option<String>,
}

impl Run {
    fn status(status: Status) -> Run {
        Run {
            status,
            faces: None,
            seconds: None,
            samples: Vec::new(),
            seconds_source: "",
            cert_seconds: None,
            wall: None,
            peak_mib: None,
            dist: None,
            dist_error: None,
            dist_limited: false,
            cert: None,
            self_int: None,
            self_int_error: None,
            topo: None,
            topo_error: None,
        }
    }
}

/// The peers' binaries and whether `envelope simplify` exists.
struct Programs {
    cgal: Option<PathBuf>,
    openmesh: Option<PathBuf>,
    envelope: Result<PathBuf, String>,
    /// Extra arguments of our `simplify` (`--placement`, `--method`).
    envelope_args: Vec<OsString>,
    me: PathBuf,
}

fn locate_programs(args: &Args) -> Programs {
    let root = repo_root();
    let peers = root.join("benches/peers/build");
    let needs_cpp = args.tools.contains(&Tool::Cgal) || args.tools.contains(&Tool::OpenMesh);
    if needs_cpp {
        let st = Command::new(root.join("benches/peers/build.sh"))
            .stdout(Stdio::null())
            .status();
        if !st.is_ok_and(|s| s.success()) {
            eprintln!("warning: benches/peers/build.sh failed; C++ peers unavailable");
        }
    }
    let exe = |p: PathBuf| p.is_file().then_some(p);
    Programs {
        cgal: exe(peers.join("cgal_envelope_collapse")),
        openmesh: exe(peers.join("openmesh_decimate")),
        envelope: locate_envelope(args.envelope.as_deref(), &root),
        envelope_args: args
            .placement
            .iter()
            .map(|p| ("--placement", p))
            .chain(args.method.iter().map(|m| ("--method", m)))
            .flat_map(|(k, v)| [k.into(), v.into()])
            .collect(),
        me: std::env::current_exe().expect("current exe"),
    }
}

/// `--envelope`, `$ENVELOPE_BIN`, then the newest `release/envelope` of `$CARGO_TARGET_DIR` and
/// `target/` that has a `simplify` subcommand.
fn locate_envelope(given: Option<&Path>, root: &Path) -> Result<PathBuf, String> {
    let mut cands: Vec<PathBuf> = Vec::new();
    if let Some(p) = given {
        cands.push(p.to_path_buf());
    } else if let Some(p) = std::env::var_os("ENVELOPE_BIN") {
        cands.push(PathBuf::from(p));
    } else {
        if let Some(t) = std::env::var_os("CARGO_TARGET_DIR") {
            let t = PathBuf::from(t);
            cands.push(if t.is_absolute() { t } else { root.join(t) }.join("release/envelope"));
        }
        cands.push(root.join("target/release/envelope"));
        let mtime = |p: &PathBuf| fs::metadata(p).and_then(|m| m.modified()).ok();
        cands.sort_by_key(|p| std::cmp::Reverse(mtime(p)));
    }
    for c in &cands {
        let ok = Command::new(c)
            .args(["simplify", "--help"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success());
        if ok {
            return Ok(c.clone());
        }
    }
    Err(format!(
        "no `envelope simplify` in {} (cargo build --release -p envelope-cli, or --envelope PATH)",
        cands
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    ))
}

/// Result of one measured child process.
struct Measured {
    status: Status,
    stdout: String,
    wall: f64,
    peak_mib: Option<f64>,
}

/// Runs `cmd` in its own process group under `/usr/bin/time -f %M` (when present), killing the
/// group after `timeout` seconds.
fn run_measured(cmd: &[OsString], timeout: f64, dir: &Path, tag: &str) -> Measured {
    let time_bin = Path::new("/usr/bin/time");
    let rss_file = dir.join(format!("{tag}.rss"));
    let out_file = dir.join(format!("{tag}.stdout"));
    let err_file = dir.join(format!("{tag}.stderr"));
    let mut c = if time_bin.is_file() {
        let mut c = Command::new(time_bin);
        c.arg("-f").arg("%M").arg("-o").arg(&rss_file).args(cmd);
        c
    } else {
        let mut c = Command::new(&cmd[0]);
        c.args(&cmd[1..]);
        c
    };
    let (Ok(o), Ok(e)) = (File::create(&out_file), File::create(&err_file)) else {
        return Measured {
            status: Status::Failed("cannot create log files".into()),
            stdout: String::new(),
            wall: 0.0,
            peak_mib: None,
        };
    };
    c.stdin(Stdio::null()).stdout(o).stderr(e).process_group(0);
    let start = Instant::now();
    let mut child = match c.spawn() {
        Ok(ch) => ch,
        Err(e) => {
            return Measured {
                status: Status::Failed(format!("spawn: {e}")),
                stdout: String::new(),
                wall: 0.0,
                peak_mib: None,
            };
        }
    };
    let exit = loop {
        match child.try_wait() {
            Ok(Some(s)) => break Some(s),
            Ok(None) if start.elapsed().as_secs_f64() > timeout => {
                let _ = Command::new("kill")
                    .args(["-KILL", "--", &format!("-{}", child.id())])
                    .status();
                let _ = child.wait();
                break None;
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(20)),
            Err(e) => {
                return Measured {
                    status: Status::Failed(format!("wait: {e}")),
                    stdout: String::new(),
                    wall: start.elapsed().as_secs_f64(),
                    peak_mib: None,
                };
            }
        }
    };
    let wall = start.elapsed().as_secs_f64();
    let stdout = fs::read_to_string(&out_file).unwrap_or_default();
    let stderr = fs::read_to_string(&err_file).unwrap_or_default();
    let peak_mib = fs::read_to_string(&rss_file)
        .ok()
        .and_then(|s| s.lines().last()?.trim().parse::<f64>().ok())
        .map(|kib| kib / 1024.0);
    let status = match exit {
        None => Status::Timeout,
        Some(s) if s.success() => Status::Ok,
        Some(s) => Status::Failed(format!(
            "{s}: {}",
            stderr
                .lines()
                .last()
                .unwrap_or("")
                .chars()
                .take(200)
                .collect::<String>()
        )),
    };
    Measured {
        status,
        stdout,
        wall,
        peak_mib,
    }
}

/// `key=value` from a peer's stdout.
fn field(stdout: &str, key: &str) -> Option<f64> {
    stdout
        .split_whitespace()
        .find_map(|w| w.strip_prefix(key)?.strip_prefix('=')?.parse().ok())
}

/// `envelope`'s report: its time without the built-in certificate (input check, envelopes,
/// simplification; I/O excluded), and the certificate's time.
fn report_seconds(report: &Path) -> Option<(f64, Option<f64>)> {
    let v: Value = serde_json::from_str(&fs::read_to_string(report).ok()?).ok()?;
    let total = v.get("seconds")?.as_f64()?;
    let cert = v.get("verify").and_then(|c| c.get("seconds")?.as_f64());
    Some((total - cert.unwrap_or(0.0), cert))
}

/// One tool on one input; the output goes to `out`.
fn run_tool(
    tool: Tool,
    progs: &Programs,
    input: &Path,
    out: &Path,
    eps: f64,
    timeout: f64,
    dir: &Path,
    tag: &str,
) -> Run {
    let e = format!("{eps:e}");
    let report = dir.join(format!("{tag}.report.json"));
    let cmd: Vec<OsString> = match tool {
        Tool::Envelope | Tool::EnvelopeCollapse | Tool::EnvelopeHybrid => match &progs.envelope {
            Ok(b) => [
                b.into(),
                "simplify".into(),
                input.into(),
                out.into(),
                "--epsilon".into(),
                e.into(),
                "--report".into(),
                report.clone().into(),
                "--quiet".into(),
            ]
            .into_iter()
            .chain(match tool {
                Tool::EnvelopeCollapse => vec!["--placement".into(), "collapse".into()],
                Tool::EnvelopeHybrid => ["--method", "hybrid", "--placement", "collapse"]
                    .map(OsString::from)
                    .to_vec(),
                _ => progs.envelope_args.clone(),
            })
            .collect(),
            Err(m) => return Run::status(Status::Unavailable(m.clone())),
        },
        Tool::Cgal | Tool::OpenMesh => {
            let b = if tool == Tool::Cgal {
                &progs.cgal
            } else {
                &progs.openmesh
            };
            match b {
                Some(b) => vec![b.into(), input.into(), out.into(), e.into()],
                None => {
                    return Run::status(Status::Unavailable(
                        "benches/peers/build.sh did not build it".into(),
                    ));
                }
            }
        }
        Tool::Meshopt => vec![
            progs.me.clone().into(),
            "--meshopt-child".into(),
            input.into(),
            out.into(),
            e.into(),
        ],
    };
    let _ = fs::remove_file(out);
    let m = run_measured(&cmd, timeout, dir, tag);
    let mut r = Run::status(m.status.clone());
    r.wall = Some(m.wall);
    r.peak_mib = m.peak_mib;
    if m.status != Status::Ok {
        return r;
    }
    let reported = match tool {
        Tool::Envelope | Tool::EnvelopeCollapse | Tool::EnvelopeHybrid => report_seconds(&report)
            .map(|(s, cert)| {
                r.cert_seconds = cert;
                s
            }),
        _ => field(&m.stdout, "seconds"),
    };
    (r.seconds, r.seconds_source) = match reported {
        Some(s) => (Some(s), "tool"),
        None => (Some(m.wall), "wall"),
    };
    r
}

/// Measures an output: faces, CGAL's two-sided distance, our certificate, self-intersections.
fn measure(r: &mut Run, oracle: &Oracle, input: &Path, orig: &TriangleSoup, out: &Path, eps: f64) {
    let approx = match read_path(out) {
        Ok((s, _)) => s,
        Err(e) => {
            r.status = Status::Failed(format!("output unreadable: {e}"));
            return;
        }
    };
    r.faces = Some(approx.faces.len());
    let bound = HAUSDORFF_BOUND * eps;
    match (
        oracle.try_hausdorff(out, input, bound),
        oracle.try_hausdorff(input, out, bound),
    ) {
        (Ok(ao), Ok(oa)) => r.dist = Some((ao.max(oa) / eps, ao / eps, oa / eps)),
        (Err(e), _) | (_, Err(e)) => {
            r.dist_limited = matches!(e, OracleError::Limit(_));
            r.dist_error = Some(e.to_string());
        }
    }
    let options = Options {
        resolution: 1e-3 * eps,
        ..Options::distance_only(eps)
    };
    let c = certify(orig, &approx, &options);
    let lower = c.approx_to_orig.lower.max(c.orig_to_approx.lower) / eps;
    let upper = c.approx_to_orig.upper.max(c.orig_to_approx.upper) / eps;
    r.cert = Some((c.verdict, lower, upper));
    match oracle.try_topology_batch(&[input, out]) {
        Ok(t) => r.topo = Some(compare_topology(&t[0], &t[1])),
        Err(e) => r.topo_error = Some(e.to_string()),
    }
    match oracle.try_self_intersections(out, false) {
        Ok(s) => r.self_int = Some((s.pairs.len(), kind_name(&format!("{:?}", s.kind)))),
        Err(_) => match oracle.try_self_intersections(out, true) {
            Ok(s) => r.self_int = Some((s.pairs.len(), "soup")),
            Err(e) => r.self_int_error = Some(e.to_string()),
        },
    }
}

/// `same` when genus, border loops and components agree (CGAL's counts; OpenMesh's when CGAL
/// reads only a polygon soup), else what changed.
fn compare_topology(a: &OracleTopology, b: &OracleTopology) -> String {
    let counts = |t: &OracleTopology| t.cgal.clone().or_else(|_| t.openmesh.clone());
    match (counts(a), counts(b)) {
        (Ok(x), Ok(y)) => {
            let key = |c: &TopoCounts| (c.genus, c.borders, c.components);
            if key(&x) == key(&y) {
                "same".into()
            } else {
                format!(
                    "genus {:?}->{:?}, loops {}->{}, components {}->{}",
                    x.genus, y.genus, x.borders, y.borders, x.components, y.components
                )
            }
        }
        (Err(e), _) | (_, Err(e)) => format!("n/a ({e})"),
    }
}

fn kind_name(debug: &str) -> &'static str {
    if debug.to_ascii_lowercase().contains("soup") {
        "soup"
    } else {
        "mesh"
    }
}

/// `--plot`: faces against epsilon, one series per mesh and tool (runs that did not end
/// well are left out), written beside `path` and renamed into place.
fn write_plot(path: &Path, rows: &[Row]) -> Result<(), String> {
    use envelope_render::plot::{Series, faces_vs_epsilon_svg};
    let mut series: Vec<Series> = Vec::new();
    for row in rows {
        let percent = parse_epsilon(&row.eps_label).map_or(f64::NAN, |(_, f)| 100.0 * f);
        for (tool, run) in &row.runs {
            let Some(faces) = run.faces.filter(|_| run.status == Status::Ok) else {
                continue;
            };
            let name = format!("{} {}", row.mesh, tool.name());
            let point = (percent, faces as f64);
            match series.iter_mut().find(|s| s.name == name) {
                Some(s) => s.points.push(point),
                None => series.push(Series {
                    name,
                    points: vec![point],
                }),
            }
        }
    }
    let size = envelope_render::Size::new(960, 640).map_err(|e| e.to_string())?;
    let svg =
        faces_vs_epsilon_svg("faces against epsilon", &series, size).map_err(|e| e.to_string())?;
    let tmp = path.with_extension("svg.tmp");
    fs::write(&tmp, svg)
        .and_then(|()| fs::rename(&tmp, path))
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// All tools' runs for one (mesh, epsilon).
struct Row {
    mesh: String,
    eps_label: String,
    eps: f64,
    input_faces: usize,
    runs: Vec<(Tool, Run)>,
}

fn run(args: &Args) -> Result<(), String> {
    let corpus = corpus_dir().ok_or("corpus missing: run scripts/corpus.sh")?;
    let oracle = Oracle::locate()
        .map_err(|e| e.to_string())?
        .with_limits(Limits {
            cpu_seconds: Some(args.oracle_cpu),
            address_space_bytes: Some(args.oracle_gib << 30),
        });
    let progs = locate_programs(args);
    if let Err(m) = &progs.envelope {
        if args.tools.iter().any(|t| t.ours()) {
            eprintln!("warning: {m}; its rows are marked n/a");
        }
    }
    let stamp = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let dir = match &args.keep {
        Some(d) => d.clone(),
        None => std::env::temp_dir().join(format!("envelope-peers-{}", std::process::id())),
    };
    fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut rows = Vec::new();
    let started = Instant::now();
    let meshes = if args.meshes == ["all"] {
        let mut all = every_acceptable_mesh(&corpus, args.max_faces);
        all.retain(|m| args.from.as_ref().is_none_or(|f| m >= f));
        all.retain(|m| args.until.as_ref().is_none_or(|u| m < u));
        all
    } else {
        args.meshes.clone()
    };
    for mesh in &meshes {
        let input = corpus.join(format!("{mesh}.off"));
        let (orig, report) = read_path(&input).map_err(|e| format!("{}: {e}", input.display()))?;
        // CGAL's Hausdorff distance wants triangles: polygon input goes to the oracle as the
        // fan triangulation every tool reads.
        let measured_input = if report.polygons_triangulated > 0 {
            let tri = dir.join(format!("{mesh}-triangulated.off"));
            envelope_io::write_path(&tri, &orig, envelope_io::Format::Off)
                .map_err(|e| format!("{}: {e}", tri.display()))?;
            tri
        } else {
            input.clone()
        };
        let diag = orig.diagonal();
        for (label, frac) in &args.epsilons {
            let eps = frac * diag;
            let mut row = Row {
                mesh: mesh.clone(),
                eps_label: label.clone(),
                eps,
                input_faces: orig.faces.len(),
                runs: Vec::new(),
            };
            // Each tool `--repeat` times, in turn (so a slow spell of the machine falls on
            // all of them); a tool that did not finish a run is not run again.
            let tag = |tool: Tool| format!("{mesh}-{}-{}", label.replace('/', "_"), tool.name());
            let mut last: Vec<Option<Run>> = vec![None; args.tools.len()];
            let mut samples: Vec<Vec<f64>> = vec![Vec::new(); args.tools.len()];
            for k in 0..args.repeat {
                for (i, &tool) in args.tools.iter().enumerate() {
                    if last[i].as_ref().is_some_and(|r| r.status != Status::Ok) {
                        continue;
                    }
                    let out = dir.join(format!("{}.off", tag(tool)));
                    eprint!(
                        "[{:>6.0} s] {mesh} {label} {}{} ...",
                        started.elapsed().as_secs_f64(),
                        tool.name(),
                        if args.repeat > 1 {
                            format!(" (run {} of {})", k + 1, args.repeat)
                        } else {
                            String::new()
                        }
                    );
                    let r = run_tool(
                        tool,
                        &progs,
                        &input,
                        &out,
                        eps,
                        args.timeout,
                        &dir,
                        &tag(tool),
                    );
                    match r.seconds {
                        Some(x) if r.status == Status::Ok => {
                            samples[i].push(x);
                            eprintln!(" {}", secs(x));
                        }
                        _ => eprintln!(" {}", summary(&r)),
                    }
                    last[i] = Some(r);
                }
            }
            for (i, &tool) in args.tools.iter().enumerate() {
                let Some(mut r) = last[i].take() else {
                    continue;
                };
                if r.status == Status::Ok {
                    r.seconds = median(&samples[i]).or(r.seconds);
                    r.samples = std::mem::take(&mut samples[i]);
                    let out = dir.join(format!("{}.off", tag(tool)));
                    measure(&mut r, &oracle, &measured_input, &orig, &out, eps);
                }
                eprintln!("           {mesh} {label} {}: {}", tool.name(), summary(&r));
                row.runs.push((tool, r));
            }
            rows.push(row);
        }
    }
    let table = table(&rows, &args.tools);
    println!("{table}");
    let json_path = args
        .json
        .clone()
        .unwrap_or_else(|| repo_root().join(format!("benches/results/peers-{stamp}.json")));
    if let Some(p) = json_path.parent() {
        let _ = fs::create_dir_all(p);
    }
    let mut w = BufWriter::new(File::create(&json_path).map_err(|e| e.to_string())?);
    serde_json::to_writer_pretty(&mut w, &to_json(&rows, args, &progs, stamp))
        .map_err(|e| e.to_string())?;
    w.flush().map_err(|e| e.to_string())?;
    eprintln!("raw results: {}", json_path.display());
    if let Some(path) = &args.plot {
        write_plot(path, &rows)?;
        eprintln!("plot: {}", path.display());
    }
    if args.keep.is_none() {
        let _ = fs::remove_dir_all(&dir);
    }
    Ok(())
}

/// `--meshes all`: every `.off` of the corpus that reads and is acceptable input for
/// `envelope simplify` (no degeneracy of an error class), by name; the others are listed on
/// stderr with the reason, never dropped silently.
fn every_acceptable_mesh(corpus: &Path, max_faces: Option<usize>) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(corpus)
        .map(|d| {
            d.filter_map(|e| {
                let p = e.ok()?.path();
                (p.extension()? == "off").then(|| p.file_stem()?.to_str().map(str::to_string))?
            })
            .collect()
        })
        .unwrap_or_default();
    names.sort();
    names.retain(|n| {
        let path = corpus.join(format!("{n}.off"));
        match read_path(&path) {
            Err(e) => {
                eprintln!("skipped {n}: unreadable ({e})");
                false
            }
            Ok((soup, _)) if max_faces.is_some_and(|m| soup.num_faces() > m) => {
                eprintln!("skipped {n}: {} faces > --max-faces", soup.num_faces());
                false
            }
            Ok((soup, _)) => {
                let problems = envelope_simplify::input_problems(&soup);
                if !problems.is_empty() {
                    eprintln!("skipped {n}: not acceptable input ({problems:?})");
                }
                problems.is_empty()
            }
        }
    });
    names
}

fn summary(r: &Run) -> String {
    match &r.status {
        Status::Ok => format!(
            "{} faces, {:.3} s, {:.0} MiB, d/eps {}, cert {}, self-int {}, topology {}",
            r.faces.map_or("?".into(), |f| f.to_string()),
            r.seconds.unwrap_or(f64::NAN),
            r.peak_mib.unwrap_or(f64::NAN),
            dist_cell(r),
            cert_cell(r),
            si_cell(r),
            topo_cell(r)
        ),
        s => format!("{s:?}"),
    }
}

fn dist_cell(r: &Run) -> String {
    match (&r.dist, &r.dist_error) {
        (Some((d, _, _)), _) => format!("{d:.2}"),
        (None, Some(_)) if r.dist_limited => "limit".into(),
        (None, Some(_)) => "err".into(),
        _ => String::new(),
    }
}

/// `ok` when certified within epsilon both ways, `>=x` when violated (x = proved lower bound
/// over epsilon), `?` when undecided.
fn cert_cell(r: &Run) -> String {
    match r.cert {
        Some((Verdict::Holds, _, _)) => "ok".into(),
        Some((Verdict::Violated, lo, _)) => format!(">={lo:.2}"),
        Some((Verdict::Undecided, _, _)) => "?".into(),
        None => String::new(),
    }
}

fn topo_cell(r: &Run) -> String {
    match (&r.topo, &r.topo_error) {
        (Some(t), _) => t.clone(),
        (None, Some(_)) => "err".into(),
        _ => String::new(),
    }
}

fn si_cell(r: &Run) -> String {
    match (&r.self_int, &r.self_int_error) {
        (Some((0, _)), _) => "no".into(),
        (Some((n, "soup")), _) => format!("yes {n} (soup)"),
        (Some((n, _)), _) => format!("yes {n}"),
        (None, Some(_)) => "err".into(),
        _ => String::new(),
    }
}

fn table(rows: &[Row], tools: &[Tool]) -> String {
    let mut s = String::new();
    let mut head = vec!["mesh".to_string(), "eps".into()];
    for t in tools {
        for c in ["faces", "s", "MiB", "d/eps", "cert", "self-int", "topology"] {
            head.push(format!("{} {c}", t.name()));
        }
    }
    let (ours, peers): (Vec<Tool>, Vec<Tool>) = tools.iter().partition(|t| t.ours());
    for o in &ours {
        for p in &peers {
            head.push(format!("faces {}/{}", o.name(), p.name()));
            head.push(format!("speed {}/{}", p.name(), o.name()));
        }
    }
    let best_columns = tools.contains(&Tool::Envelope) && !peers.is_empty();
    if best_columns {
        head.push("best valid peer".into());
        head.push("ours <= best".into());
    }
    let _ = writeln!(s, "| {} |", head.join(" | "));
    let _ = writeln!(s, "|{}", "---|".repeat(head.len()));
    for row in rows {
        let mut cells = vec![
            format!("{} ({} f)", row.mesh, row.input_faces),
            format!("{} ({:.3e})", row.eps_label, row.eps),
        ];
        for (_, r) in &row.runs {
            match &r.status {
                Status::Ok => {
                    cells.push(r.faces.map_or("?".into(), |f| f.to_string()));
                    let src = if r.seconds_source == "wall" { "*" } else { "" };
                    let cert = r
                        .cert_seconds
                        .map_or(String::new(), |c| format!(" (+{} cert)", secs(c)));
                    cells.push(
                        r.seconds
                            .map_or(String::new(), |x| format!("{}{src}{cert}", secs(x))),
                    );
                    cells.push(r.peak_mib.map_or("-".into(), |m| format!("{m:.0}")));
                    cells.push(dist_cell(r));
                    cells.push(cert_cell(r));
                    cells.push(si_cell(r));
                    cells.push(topo_cell(r));
                }
                other => {
                    let tag = match other {
                        Status::Unavailable(_) => "n/a".to_string(),
                        Status::Timeout => "timeout".into(),
                        _ => "failed".into(),
                    };
                    let wall = if *other == Status::Timeout {
                        r.wall.map_or(String::new(), |w| format!(">{}", secs(w)))
                    } else {
                        String::new()
                    };
                    let mib = r.peak_mib.map_or(String::new(), |m| format!("{m:.0}"));
                    cells.extend([tag, wall, mib]);
                    cells.extend(std::iter::repeat_n(String::new(), 4));
                }
            }
        }
        for &ours_tool in &ours {
            let get = |t: Tool| {
                row.runs
                    .iter()
                    .find(|(x, _)| *x == t)
                    .map(|(_, r)| r)
                    .filter(|r| r.status == Status::Ok)
            };
            let o = get(ours_tool);
            for p in &peers {
                let (fr, sr) = match (o, get(*p)) {
                    (Some(o), Some(q)) => (
                        ratio(o.faces.map(|f| f as f64), q.faces.map(|f| f as f64)),
                        ratio(q.seconds, o.seconds),
                    ),
                    _ => (String::new(), String::new()),
                };
                cells.push(fr);
                cells.push(sr);
            }
        }
        if best_columns {
            let best = best_valid_peer(rows, &row.mesh, row.eps);
            cells.push(best.as_ref().map_or("-".into(), |b| {
                format!("{} ({} @{})", b.faces, b.tool.name(), b.eps_label)
            }));
            cells.push(match ours_le_best(row, best.as_ref()) {
                Some(true) => "yes".into(),
                Some(false) => "no".into(),
                None => "-".into(),
            });
        }
        let _ = writeln!(s, "| {} |", cells.join(" | "));
    }
    s.push_str(
        "\ns: the tool's own simplification time (I/O excluded; `*` = wall time of the process; \
         ours: input check, envelopes and simplification, without the built-in certificate, \
         whose time is the `+x cert`; speed ratios use s; with `--repeat N`, the median of N \
         runs taken in turn). \
         MiB: peak RSS of the process. d/eps: two-sided Hausdorff distance over epsilon \
         (CGAL bounded_error_Hausdorff_distance, bound 1% eps; `limit`: the oracle process hit \
         its CPU or memory limit, `err`: another oracle failure). cert: envelope-verify's \
         certified two-sided check (ok = proved <= eps, >=x = proved violated by x eps). \
         self-int: CGAL self-intersecting face pairs of the output. topology: genus, border \
         loops and components of input and output by CGAL (OpenMesh for a soup). \
         best valid peer (rows of `envelope` at eps E): the fewest faces of any peer output of \
         the same mesh in this run, at any eps (its own after the @), proved within E both \
         ways (our certificate's proved bounds, else CGAL's distance + its error bound <= E), \
         with self-int no and topology same; `-`: none. ours <= best: `envelope`'s faces at \
         most the best valid peer's (`-`: no valid peer, or ours did not finish).\n",
    );
    s
}

/// A peer output proved valid at some epsilon (see [`valid_within`]).
struct BestPeer {
    tool: Tool,
    /// The epsilon the peer ran at (label and absolute).
    eps_label: String,
    eps: f64,
    faces: usize,
}

/// Whether the output of `r`, a run at absolute epsilon `own`, is proved within absolute
/// distance `e` of the input both ways, has no self-intersecting pair and the input's
/// topology; anything unmeasured or undecided counts against it.
///
/// The stored distances are over `own`. Our certificate decides when it can: a violation
/// proved beyond `e` rejects, a verdict `Holds` at `own <= e` or a proved upper bound within
/// `e` accepts (the verdict itself was decided at `own` only). Otherwise CGAL's two-sided
/// distance must be within `e` with its error bound (`HAUSDORFF_BOUND * own`) added.
fn valid_within(r: &Run, own: f64, e: f64) -> bool {
    if r.status != Status::Ok
        || r.faces.is_none()
        || !matches!(r.self_int, Some((0, _)))
        || r.topo.as_deref() != Some("same")
    {
        return false;
    }
    if let Some((verdict, lower, upper)) = r.cert {
        if verdict == Verdict::Violated && lower * own > e {
            return false;
        }
        if (verdict == Verdict::Holds && own <= e) || upper * own <= e {
            return true;
        }
    }
    r.dist
        .is_some_and(|(_, ao, oa)| ao.max(oa) * own + HAUSDORFF_BOUND * own <= e)
}

/// The peer output of `mesh` (any row, any epsilon) with the fewest faces that is valid
/// within absolute `e`; the first in run order among equals.
fn best_valid_peer(rows: &[Row], mesh: &str, e: f64) -> Option<BestPeer> {
    rows.iter()
        .filter(|row| row.mesh == mesh)
        .flat_map(|row| {
            row.runs
                .iter()
                .filter(move |(t, r)| !t.ours() && valid_within(r, row.eps, e))
                .map(move |(t, r)| BestPeer {
                    tool: *t,
                    eps_label: row.eps_label.clone(),
                    eps: row.eps,
                    faces: r.faces.unwrap_or(usize::MAX),
                })
        })
        .min_by_key(|b| b.faces)
}

/// `envelope`'s faces at most `best`'s; `None` without a finished `envelope` run or a best.
fn ours_le_best(row: &Row, best: Option<&BestPeer>) -> Option<bool> {
    let ours = row
        .runs
        .iter()
        .find(|(t, r)| *t == Tool::Envelope && r.status == Status::Ok)?
        .1
        .faces?;
    Some(ours <= best?.faces)
}

/// The median (the mean of the middle two for an even count); `None` for no sample.
fn median(samples: &[f64]) -> Option<f64> {
    let mut v = samples.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    match n {
        0 => None,
        _ if n % 2 == 1 => Some(v[n / 2]),
        _ => Some((v[n / 2 - 1] + v[n / 2]) / 2.0),
    }
}

fn secs(x: f64) -> String {
    if x < 1.0 {
        format!("{x:.3}")
    } else if x < 100.0 {
        format!("{x:.2}")
    } else {
        format!("{x:.0}")
    }
}

fn ratio(a: Option<f64>, b: Option<f64>) -> String {
    match (a, b) {
        (Some(a), Some(b)) if b > 0.0 => format!("{:.2}", a / b),
        _ => String::new(),
    }
}

fn to_json(rows: &[Row], args: &Args, progs: &Programs, stamp: u64) -> Value {
    let runs = |row: &Row| -> Vec<Value> {
        row.runs
            .iter()
            .map(|(t, r)| {
                json!({
                    "tool": t.name(),
                    "status": match &r.status {
                        Status::Ok => "ok".to_string(),
                        Status::Unavailable(m) => format!("unavailable: {m}"),
                        Status::Timeout => "timeout".into(),
                        Status::Failed(m) => format!("failed: {m}"),
                    },
                    "faces": r.faces,
                    "seconds": r.seconds,
                    "seconds_samples": r.samples,
                    "seconds_source": r.seconds_source,
                    "certificate_seconds": r.cert_seconds,
                    "wall_seconds": r.wall,
                    "peak_rss_mib": r.peak_mib,
                    "hausdorff_over_eps": r.dist.map(|d| d.0),
                    "hausdorff_out_to_in_over_eps": r.dist.map(|d| d.1),
                    "hausdorff_in_to_out_over_eps": r.dist.map(|d| d.2),
                    "hausdorff_error": r.dist_error,
                    "certified_verdict": r.cert.map(|c| c.0.as_str()),
                    "certified_lower_over_eps": r.cert.map(|c| c.1),
                    "certified_upper_over_eps": r.cert.map(|c| c.2),
                    "self_intersecting_pairs": r.self_int.map(|s| s.0),
                    "self_intersection_semantics": r.self_int.map(|s| s.1),
                    "self_intersection_error": r.self_int_error,
                    "topology": r.topo,
                    "topology_error": r.topo_error,
                })
            })
            .collect()
    };
    json!({
        "unix_time": stamp,
        "timeout_seconds": args.timeout,
        "repeat": args.repeat,
        "oracle_cpu_seconds": args.oracle_cpu,
        "oracle_address_space_gib": args.oracle_gib,
        "hausdorff_bound_over_eps": HAUSDORFF_BOUND,
        "envelope_binary": progs.envelope.as_ref().map(|p| p.display().to_string()).ok(),
        "rows": rows.iter().map(|row| {
            let best = best_valid_peer(rows, &row.mesh, row.eps);
            json!({
                "mesh": row.mesh,
                "epsilon_label": row.eps_label,
                "epsilon": row.eps,
                "input_faces": row.input_faces,
                "runs": runs(row),
                "best_valid_peer": best.as_ref().map(|b| json!({
                    "tool": b.tool.name(),
                    "epsilon_label": b.eps_label,
                    "epsilon": b.eps,
                    "faces": b.faces,
                })),
                "envelope_faces_le_best_valid_peer": ours_le_best(row, best.as_ref()),
            })
        }).collect::<Vec<_>>(),
    })
}

/// `--meshopt-child IN OUT EPS`: meshoptimizer's `simplify` to 0 triangles under absolute
/// error EPS (positions in f32, as meshoptimizer takes them). Prints `faces=N seconds=S
/// result_error=E` (S: the simplify call alone).
fn meshopt_child(input: &Path, output: &Path, eps: f64) -> ExitCode {
    let soup = match read_path(input) {
        Ok((s, _)) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let run = match meshopt_simplify(&soup, eps) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let (pos, out, secs, err) = (run.positions, run.indices, run.seconds, run.error);
    // Compact the used vertices; f32 -> f64 is exact, `{}` prints the shortest round trip.
    let mut map = vec![u32::MAX; pos.len()];
    let mut used = Vec::new();
    for &i in &out {
        if map[i as usize] == u32::MAX {
            map[i as usize] = u32::try_from(used.len()).expect("fits");
            used.push(i);
        }
    }
    let write = || -> std::io::Result<()> {
        let mut w = BufWriter::new(File::create(output)?);
        writeln!(w, "OFF\n{} {} 0", used.len(), out.len() / 3)?;
        for &i in &used {
            let p = pos[i as usize];
            writeln!(
                w,
                "{} {} {}",
                f64::from(p[0]),
                f64::from(p[1]),
                f64::from(p[2])
            )?;
        }
        for t in out.chunks_exact(3) {
            writeln!(
                w,
                "3 {} {} {}",
                map[t[0] as usize], map[t[1] as usize], map[t[2] as usize]
            )?;
        }
        w.flush()
    };
    if let Err(e) = write() {
        eprintln!("error: {}: {e}", output.display());
        return ExitCode::FAILURE;
    }
    println!("faces={} seconds={secs} result_error={err}", out.len() / 3);
    ExitCode::SUCCESS
}

#[cfg(test)]
mod tests {
    use super::*;

    fn topo(genus: u64, borders: u64, cgal: bool) -> OracleTopology {
        let c = TopoCounts {
            v: 8,
            f: 12,
            e: 18,
            isolated: 0,
            borders,
            components: 1,
            chi: 2 - 2 * genus as i64 - borders as i64,
            genus: Some(genus),
        };
        OracleTopology {
            openmesh: Ok(c.clone()),
            cgal: if cgal { Ok(c) } else { Err("soup".into()) },
            file_polygons: Some(12),
            soup_counts: None,
        }
    }

    #[test]
    fn topology_comparison_names_what_changed() {
        assert_eq!(
            compare_topology(&topo(1, 0, true), &topo(1, 0, true)),
            "same"
        );
        let d = compare_topology(&topo(1, 0, true), &topo(0, 0, true));
        assert!(d.contains("genus Some(1)->Some(0)"), "{d}");
        let d = compare_topology(&topo(0, 2, true), &topo(0, 1, false));
        assert!(d.contains("loops 2->1"), "{d}");
    }
}

#[cfg(test)]
mod best_peer_tests {
    use super::*;

    /// A finished peer run with `faces`, CGAL's two sides over its epsilon and a certificate.
    fn peer(faces: usize, d: (f64, f64), cert: Option<(Verdict, f64, f64)>) -> Run {
        Run {
            faces: Some(faces),
            dist: Some((d.0.max(d.1), d.0, d.1)),
            cert,
            self_int: Some((0, "mesh")),
            topo: Some("same".into()),
            ..Run::status(Status::Ok)
        }
    }

    #[test]
    fn validity_converts_to_absolute_and_is_conservative() {
        // CGAL only: 0.5 of 2.0 = 1.0 absolute, + bound 0.02: valid at 1.02, not at 1.01.
        let r = peer(10, (0.5, 0.3), None);
        assert!(valid_within(&r, 2.0, 1.02));
        assert!(!valid_within(&r, 2.0, 1.01));
        // Holds at its own 1.0 carries to a larger E, not to a smaller one (CGAL decides).
        let r = peer(10, (0.9, 0.9), Some((Verdict::Holds, 0.8, 0.95)));
        assert!(valid_within(&r, 1.0, 1.0));
        assert!(valid_within(&r, 1.0, 2.0));
        assert!(valid_within(&r, 1.0, 0.95));
        assert!(!valid_within(&r, 1.0, 0.9));
        // A proved violation beyond E rejects whatever CGAL says.
        let r = peer(
            10,
            (0.1, 0.1),
            Some((Verdict::Violated, 1.5, f64::INFINITY)),
        );
        assert!(!valid_within(&r, 1.0, 1.4));
        assert!(valid_within(&r, 1.0, 2.0));
        // Self-intersections, changed or unmeasured topology, no measurement: never valid.
        let mut r = peer(10, (0.1, 0.1), None);
        r.self_int = Some((3, "mesh"));
        assert!(!valid_within(&r, 1.0, 1.0));
        let mut r = peer(10, (0.1, 0.1), None);
        r.topo = Some("genus Some(1)->Some(0), loops 0->0, components 1->1".into());
        assert!(!valid_within(&r, 1.0, 1.0));
        let mut r = peer(10, (0.1, 0.1), None);
        r.topo = None;
        assert!(!valid_within(&r, 1.0, 1.0));
        let mut r = peer(10, (0.1, 0.1), None);
        r.dist = None;
        assert!(!valid_within(&r, 1.0, 1.0));
    }

    #[test]
    fn best_peer_looks_across_epsilons_of_the_mesh() {
        let row = |mesh: &str, label: &str, eps: f64, runs: Vec<(Tool, Run)>| Row {
            mesh: mesh.into(),
            eps_label: label.into(),
            eps,
            input_faces: 100,
            runs,
        };
        let ours = |f| Run {
            faces: Some(f),
            ..Run::status(Status::Ok)
        };
        let rows = vec![
            row(
                "m",
                "1%",
                1.0,
                vec![
                    (Tool::Envelope, ours(30)),
                    (Tool::Cgal, peer(40, (0.9, 0.5), None)),
                    (Tool::Meshopt, peer(5, (3.0, 3.0), None)),
                ],
            ),
            row(
                "m",
                "2%",
                2.0,
                vec![
                    (Tool::Envelope, ours(20)),
                    (Tool::Cgal, peer(25, (0.45, 0.2), None)),
                ],
            ),
            row(
                "other",
                "1%",
                1.0,
                vec![(Tool::Cgal, peer(1, (0.0, 0.0), None))],
            ),
        ];
        // At 1.0: cgal@2% is 0.9 + 0.02 absolute, valid and smaller than cgal@1%.
        let b = best_valid_peer(&rows, "m", 1.0).expect("a valid peer");
        assert_eq!(
            (b.tool, b.eps_label.as_str(), b.faces),
            (Tool::Cgal, "2%", 25)
        );
        assert_eq!(ours_le_best(&rows[0], Some(&b)), Some(false));
        // At 0.5 nothing is proved within.
        assert!(best_valid_peer(&rows, "m", 0.5).is_none());
        assert_eq!(ours_le_best(&rows[0], None), None);
        // At 2.0: still cgal@2% (meshopt's 3 eps = 3.0 absolute is too far).
        let b = best_valid_peer(&rows, "m", 2.0).expect("a valid peer");
        assert_eq!(b.faces, 25);
        assert_eq!(ours_le_best(&rows[1], Some(&b)), Some(true));
    }
}

#[cfg(test)]
mod median_tests {
    use super::median;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(&[]), None);
        assert_eq!(median(&[3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&[4.0, 1.0, 3.0, 2.0]), Some(2.5));
    }
}
