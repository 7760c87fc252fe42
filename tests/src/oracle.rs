//! Client for the CGAL/OpenMesh cross-check oracle (`tests/oracle/envelope_oracle.cpp`).
//!
//! The oracle is a separate C++ program speaking a line protocol on stdin/stdout (documented in
//! `tests/oracle/README.md` and at the top of the C++ file). Each typed method here makes **one**
//! process call for a whole batch, so pass thousands of queries at once rather than looping.
//! Doubles travel as C99 hex floats, so inputs reach CGAL bit-exactly.
//!
//! Conventions: `orient3d(a,b,c,d)` is CGAL's, `sign(((b-a)×(c-a))·(d-a))` (the unit
//! tetrahedron `0,e1,e2,e3` gives `+1`), the opposite of Shewchuk's/`robust`'s sign.
//!
//! Use [`oracle_or_skip`] in tests: it returns `None` (with a loud message) when the oracle
//! cannot be built, except under `CI=true`, where it panics. [`corpus_dir`] follows the same rule
//! for the libcgal-demo mesh corpus.

use std::collections::BTreeMap;
use std::fmt;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;

use glam::{DVec2, DVec3};

/// The repository root (the parent of the `tests` package).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tests package has a parent directory")
        .to_path_buf()
}

/// True when running under CI (`CI=true`), where a missing oracle or corpus is a failure.
pub fn is_ci() -> bool {
    std::env::var("CI").is_ok_and(|v| v == "true")
}

/// Why the oracle binary is not available.
#[derive(Debug, Clone)]
pub struct OracleMissing {
    /// Human-readable reason, including what to install.
    pub reason: String,
}

impl fmt::Display for OracleMissing {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "envelope oracle unavailable: {}", self.reason)
    }
}

impl std::error::Error for OracleMissing {}

/// A failed oracle call.
#[derive(Debug)]
pub enum OracleError {
    /// Spawning or talking to the process failed.
    Io(std::io::Error),
    /// The oracle answered `err CMD message`.
    Remote {
        /// The command that failed.
        cmd: String,
        /// The oracle's message.
        message: String,
    },
    /// The answer did not follow the protocol.
    Protocol(String),
    /// The oracle process ran into a limit of [`Oracle::with_limits`] (CPU time or address
    /// space) and was stopped; the message says which.
    Limit(String),
}

impl fmt::Display for OracleError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OracleError::Io(e) => write!(f, "oracle i/o error: {e}"),
            OracleError::Remote { cmd, message } => write!(f, "oracle `{cmd}` failed: {message}"),
            OracleError::Protocol(m) => write!(f, "oracle protocol error: {m}"),
            OracleError::Limit(m) => write!(f, "oracle stopped: {m}"),
        }
    }
}

impl std::error::Error for OracleError {}

impl From<std::io::Error> for OracleError {
    fn from(e: std::io::Error) -> Self {
        OracleError::Io(e)
    }
}

/// One parsed response: `ok CMD n key=value...` plus its `n` payload lines, or an `err`.
#[derive(Debug, Clone)]
pub struct Response {
    /// The command echoed by the oracle.
    pub cmd: String,
    /// `Err(message)` for an `err` line.
    pub status: Result<(), String>,
    /// `key=value` pairs of the header.
    pub fields: BTreeMap<String, String>,
    /// Payload lines.
    pub lines: Vec<String>,
}

impl Response {
    fn into_ok(self) -> Result<Response, OracleError> {
        match self.status {
            Ok(()) => Ok(self),
            Err(message) => Err(OracleError::Remote {
                cmd: self.cmd,
                message,
            }),
        }
    }

    fn field(&self, key: &str) -> Result<&str, OracleError> {
        self.fields
            .get(key)
            .map(String::as_str)
            .ok_or_else(|| OracleError::Protocol(format!("`{}` answer lacks `{key}=`", self.cmd)))
    }
}

/// How a mesh file was interpreted by `self_intersections`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshKind {
    /// A valid polygon mesh: `PMP::self_intersections` on a `Surface_mesh` was used.
    Mesh,
    /// Not a valid polygon mesh: the oracle's soup re-implementation of PMP's rule was used.
    Soup,
}

/// Full answer of `self_intersections`.
#[derive(Debug, Clone)]
pub struct SelfIntersections {
    /// Mesh or soup path.
    pub kind: MeshKind,
    /// Vertex count of the file.
    pub vertices: u64,
    /// Face count of the file.
    pub faces: u64,
    /// Intersecting face pairs `(i, j)`, `i <= j`, sorted, in the file's face order;
    /// `(i, i)` marks a degenerate (collinear) face.
    pub pairs: Vec<(u32, u32)>,
}

/// Answer of `self_intersections --time`.
#[derive(Debug, Clone)]
pub struct SelfIntersectTiming {
    /// Mesh or soup path.
    pub kind: MeshKind,
    /// Whether any self-intersection (or degenerate face) exists.
    pub intersects: bool,
    /// Seconds spent in `does_self_intersect` only.
    pub seconds: f64,
    /// Seconds spent loading the file.
    pub load_seconds: f64,
}

/// Topological counts from one library.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TopoCounts {
    /// Vertices (including isolated ones).
    pub v: u64,
    /// Faces (OpenMesh: after triangulating polygons).
    pub f: u64,
    /// Edges.
    pub e: u64,
    /// Vertices without incident faces.
    pub isolated: u64,
    /// Boundary loops.
    pub borders: u64,
    /// Face-connected components (isolated vertices not counted).
    pub components: u64,
    /// Euler characteristic `V - E + F` over non-isolated vertices.
    pub chi: i64,
    /// Sum of per-component genera, `None` when some component gives no nonnegative integer.
    pub genus: Option<u64>,
}

/// Answer of `topology`: OpenMesh's and CGAL's counts.
#[derive(Debug, Clone)]
pub struct OracleTopology {
    /// OpenMesh TriMesh counts, or the load error.
    pub openmesh: Result<TopoCounts, String>,
    /// CGAL Surface_mesh counts, or why not (`"soup"` when not a valid polygon mesh, else error).
    pub cgal: Result<TopoCounts, String>,
    /// Polygons in the file according to CGAL's reader (`None` if it could not read it).
    pub file_polygons: Option<u64>,
    /// CGAL's vertex/face counts when the file is only a polygon soup.
    pub soup_counts: Option<(u64, u64)>,
}

/// Resource limits for each oracle process ([`Oracle::with_limits`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Limits {
    /// CPU seconds per process (`RLIMIT_CPU`: the kernel stops it with `SIGXCPU`, then
    /// `SIGKILL`). Also bounds an orphan: if the caller is killed, its oracle child still ends.
    pub cpu_seconds: Option<u64>,
    /// Address space per process in bytes (`RLIMIT_AS`: allocations beyond it fail).
    pub address_space_bytes: Option<u64>,
}

/// Handle on the oracle binary.
#[derive(Debug, Clone)]
pub struct Oracle {
    bin: PathBuf,
    limits: Limits,
}

static LOCATED: OnceLock<Result<Oracle, OracleMissing>> = OnceLock::new();

impl Oracle {
    /// Finds the oracle: `$ENVELOPE_ORACLE`, else `<repo>/tests/oracle/build/envelope-oracle`,
    /// (re)built by `tests/oracle/build.sh` (idempotent; fails when packages are missing).
    /// The result is cached for the process.
    pub fn locate() -> Result<Oracle, OracleMissing> {
        LOCATED.get_or_init(Self::locate_uncached).clone()
    }

    fn locate_uncached() -> Result<Oracle, OracleMissing> {
        if let Some(p) = std::env::var_os("ENVELOPE_ORACLE") {
            let bin = PathBuf::from(p);
            return if bin.is_file() {
                Ok(Oracle {
                    bin,
                    limits: Limits::default(),
                })
            } else {
                Err(OracleMissing {
                    reason: format!("ENVELOPE_ORACLE={} is not a file", bin.display()),
                })
            };
        }
        let script = repo_root().join("tests/oracle/build.sh");
        let bin = repo_root().join("tests/oracle/build/envelope-oracle");
        let out = Command::new("bash")
            .arg(&script)
            .stdin(Stdio::null())
            .output()
            .map_err(|e| OracleMissing {
                reason: format!("cannot run {}: {e}", script.display()),
            })?;
        if !out.status.success() || !bin.is_file() {
            return Err(OracleMissing {
                reason: format!(
                    "{} failed:\n{}",
                    script.display(),
                    String::from_utf8_lossy(&out.stderr).trim_end()
                ),
            });
        }
        Ok(Oracle {
            bin,
            limits: Limits::default(),
        })
    }

    /// Path of the binary.
    pub fn path(&self) -> &Path {
        &self.bin
    }

    /// The same oracle, every process of which runs under `limits` (set by `bash`'s
    /// `ulimit` before it execs the oracle). A call that hits a limit fails with
    /// [`OracleError::Limit`]; the next call starts a fresh process. For long measurements
    /// (CGAL's bounded-error Hausdorff distance can take minutes and gigabytes).
    #[must_use]
    pub fn with_limits(&self, limits: Limits) -> Oracle {
        Oracle {
            bin: self.bin.clone(),
            limits,
        }
    }

    /// The command that starts one `serve` process under the limits.
    fn serve_command(&self) -> Command {
        let Limits {
            cpu_seconds,
            address_space_bytes,
        } = self.limits;
        if cpu_seconds.is_none() && address_space_bytes.is_none() {
            let mut c = Command::new(&self.bin);
            c.arg("serve");
            return c;
        }
        let mut script = String::new();
        if let Some(t) = cpu_seconds {
            script.push_str(&format!("ulimit -t {} && ", t.max(1)));
        }
        if let Some(b) = address_space_bytes {
            script.push_str(&format!("ulimit -v {} && ", (b / 1024).max(1)));
        }
        script.push_str("exec \"$0\" serve");
        let mut c = Command::new("bash");
        c.arg("-c").arg(script).arg(&self.bin);
        c
    }

    /// Why a process that failed stopped, when it was one of the limits.
    fn limit_hit(&self, status: std::process::ExitStatus, stderr: &str) -> Option<String> {
        use std::os::unix::process::ExitStatusExt;
        let Limits {
            cpu_seconds,
            address_space_bytes,
        } = self.limits;
        // SIGXCPU (24) at the soft limit; SIGKILL (9) if it ignored that until the hard one.
        if let Some(t) = cpu_seconds
            && matches!(status.signal(), Some(24 | 9))
        {
            return Some(format!("CPU-time limit of {t} s"));
        }
        let out_of_memory = stderr.contains("bad_alloc") || stderr.contains("memory");
        address_space_bytes
            .filter(|_| out_of_memory || status.signal() == Some(6))
            .map(|b| format!("address-space limit of {} MiB", b >> 20))
    }

    /// `e`, or the limit it stands for: the oracle catches `std::bad_alloc` and answers
    /// `err`, which under an address-space limit is that limit.
    fn under_limits(&self, e: OracleError) -> OracleError {
        match (e, self.limits.address_space_bytes) {
            (OracleError::Remote { message, .. }, Some(b)) if message.contains("bad_alloc") => {
                OracleError::Limit(format!(
                    "address-space limit of {} MiB ({message})",
                    b >> 20
                ))
            }
            (e, _) => e,
        }
    }

    /// Sends a raw request text (one or more requests) and parses every response.
    pub fn raw(&self, request: &str) -> Result<Vec<Response>, OracleError> {
        let mut child = self
            .serve_command()
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()?;
        let mut stdin = child.stdin.take().expect("piped stdin");
        let input = request.as_bytes().to_vec();
        // Write from a thread: the oracle answers while reading, so both pipes must drain.
        let writer = std::thread::spawn(move || -> std::io::Result<()> {
            stdin.write_all(&input)?;
            drop(stdin);
            Ok(())
        });
        let mut stdout = String::new();
        child
            .stdout
            .take()
            .expect("piped stdout")
            .read_to_string(&mut stdout)?;
        let mut stderr = String::new();
        child
            .stderr
            .take()
            .expect("piped stderr")
            .read_to_string(&mut stderr)?;
        let status = child.wait()?;
        let wrote = writer.join().expect("oracle writer thread panicked");
        if !status.success() {
            if let Some(limit) = self.limit_hit(status, &stderr) {
                return Err(OracleError::Limit(limit));
            }
            return Err(OracleError::Protocol(format!(
                "oracle exited with {status}; stderr: {}",
                stderr.trim_end()
            )));
        }
        wrote?;
        parse_responses(&stdout)
    }

    fn one(&self, request: &str) -> Result<Response, OracleError> {
        let mut v = self.raw(request)?;
        if v.len() != 1 {
            return Err(OracleError::Protocol(format!(
                "expected 1 response, got {}",
                v.len()
            )));
        }
        v.pop()
            .expect("one response")
            .into_ok()
            .map_err(|e| self.under_limits(e))
    }

    /// `version` answer fields (`protocol`, `cgal`, `openmesh`).
    pub fn version(&self) -> BTreeMap<String, String> {
        self.one("version\n")
            .unwrap_or_else(|e| panic!("{e}"))
            .fields
    }

    fn batch<const W: usize>(
        &self,
        cmd: &str,
        rows: impl ExactSizeIterator<Item = [f64; W]>,
    ) -> Vec<i8> {
        let n = rows.len();
        let mut req = String::with_capacity(32 + n * W * 24);
        req.push_str(&format!("{cmd} {n}\n"));
        for row in rows {
            for (k, x) in row.iter().enumerate() {
                if k > 0 {
                    req.push(' ');
                }
                push_hex_f64(&mut req, *x);
            }
            req.push('\n');
        }
        let r = self.one(&req).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            r.lines.len(),
            n,
            "oracle `{cmd}` answered {} of {n} rows",
            r.lines.len()
        );
        r.lines
            .iter()
            .map(|l| match l.trim() {
                "-1" => -1,
                "0" => 0,
                "1" => 1,
                other => panic!("oracle `{cmd}`: bad answer line `{other}`"),
            })
            .collect()
    }

    /// Signs of CGAL `orientation(a,b,c,d)` = `sign(((b-a)×(c-a))·(d-a))`, one per query.
    pub fn orient3d_batch(&self, q: &[[DVec3; 4]]) -> Vec<i8> {
        self.batch::<12>("orient3d", q.iter().map(flat::<4, 12>))
    }

    /// Signs of CGAL `orientation(a,b,c)` = `sign((b-a)×(c-a))` (counter-clockwise: `+1`).
    pub fn orient2d_batch(&self, q: &[[DVec2; 3]]) -> Vec<i8> {
        self.batch::<6>(
            "orient2d",
            q.iter()
                .map(|p| [p[0].x, p[0].y, p[1].x, p[1].y, p[2].x, p[2].y]),
        )
    }

    /// Whether closed triangles intersect (CGAL `do_intersect`; degenerate ones handled exactly).
    pub fn tri_tri_batch(&self, q: &[([DVec3; 3], [DVec3; 3])]) -> Vec<bool> {
        let rows = q.iter().map(|(a, b)| {
            let mut r = [0.0; 18];
            r[..9].copy_from_slice(&flat::<3, 9>(a));
            r[9..].copy_from_slice(&flat::<3, 9>(b));
            r
        });
        self.batch::<18>("tri_tri", rows)
            .into_iter()
            .map(|s| s != 0)
            .collect()
    }

    /// Whether a closed segment `[p, q]` intersects a closed triangle.
    pub fn seg_tri_batch(&self, q: &[([DVec3; 2], [DVec3; 3])]) -> Vec<bool> {
        let rows = q.iter().map(|(s, t)| {
            let mut r = [0.0; 15];
            r[..6].copy_from_slice(&flat::<2, 6>(s));
            r[6..].copy_from_slice(&flat::<3, 9>(t));
            r
        });
        self.batch::<15>("seg_tri", rows)
            .into_iter()
            .map(|s| s != 0)
            .collect()
    }

    /// `sign(sqdist(p, T) - eps2)` computed exactly, for queries `(p, T, eps2)`.
    pub fn point_tri_sqdist_cmp_batch(&self, q: &[(DVec3, [DVec3; 3], f64)]) -> Vec<i8> {
        let rows = q.iter().map(|(p, t, e)| {
            let mut r = [0.0; 13];
            r[..3].copy_from_slice(&p.to_array());
            r[3..12].copy_from_slice(&flat::<3, 9>(t));
            r[12] = *e;
            r
        });
        self.batch::<13>("point_tri_sqdist", rows)
    }

    /// Intersecting face pairs of a triangle-mesh file (panics on oracle errors).
    pub fn self_intersections(&self, path: &Path) -> Vec<(u32, u32)> {
        self.try_self_intersections(path, false)
            .unwrap_or_else(|e| panic!("{e}"))
            .pairs
    }

    /// Full `self_intersections` answer; `force_soup` uses the soup path even for valid meshes.
    pub fn try_self_intersections(
        &self,
        path: &Path,
        force_soup: bool,
    ) -> Result<SelfIntersections, OracleError> {
        let opt = if force_soup { " --soup" } else { "" };
        let r = self.one(&format!("self_intersections{opt}\n{}\n", path_line(path)?))?;
        let mut pairs = Vec::with_capacity(r.lines.len());
        for l in &r.lines {
            let mut it = l.split_whitespace().map(str::parse::<u32>);
            match (it.next(), it.next(), it.next()) {
                (Some(Ok(a)), Some(Ok(b)), None) => pairs.push((a, b)),
                _ => return Err(OracleError::Protocol(format!("bad pair line `{l}`"))),
            }
        }
        Ok(SelfIntersections {
            kind: parse_kind(r.field("kind")?)?,
            vertices: parse_field(&r, "vertices")?,
            faces: parse_field(&r, "faces")?,
            pairs,
        })
    }

    /// Times only `does_self_intersect` on a file (after loading it).
    pub fn time_does_self_intersect(
        &self,
        path: &Path,
    ) -> Result<SelfIntersectTiming, OracleError> {
        let r = self.one(&format!(
            "self_intersections --time\n{}\n",
            path_line(path)?
        ))?;
        Ok(SelfIntersectTiming {
            kind: parse_kind(r.field("kind")?)?,
            intersects: r.field("intersects")? == "1",
            seconds: parse_field(&r, "seconds")?,
            load_seconds: parse_field(&r, "load_seconds")?,
        })
    }

    /// One-sided Hausdorff distance A→B, `PMP::bounded_error_Hausdorff_distance` (panics on error).
    pub fn hausdorff(&self, a: &Path, b: &Path, error_bound: f64) -> f64 {
        self.try_hausdorff(a, b, error_bound)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// Fallible [`Oracle::hausdorff`].
    pub fn try_hausdorff(&self, a: &Path, b: &Path, error_bound: f64) -> Result<f64, OracleError> {
        let mut req = String::from("hausdorff ");
        push_hex_f64(&mut req, error_bound);
        req.push_str(&format!("\n{}\n{}\n", path_line(a)?, path_line(b)?));
        let r = self.one(&req)?;
        parse_f64(r.field("distance")?).ok_or_else(|| OracleError::Protocol("bad distance".into()))
    }

    /// `PMP::approximate_Hausdorff_distance` A→B with `points_on_faces` samples (a lower bound).
    pub fn hausdorff_approx(
        &self,
        a: &Path,
        b: &Path,
        points_on_faces: u64,
    ) -> Result<f64, OracleError> {
        let r = self.one(&format!(
            "hausdorff_approx {points_on_faces}\n{}\n{}\n",
            path_line(a)?,
            path_line(b)?
        ))?;
        parse_f64(r.field("distance")?).ok_or_else(|| OracleError::Protocol("bad distance".into()))
    }

    /// OpenMesh's and CGAL's topology of a mesh file (panics only on protocol failures).
    pub fn topology(&self, path: &Path) -> OracleTopology {
        self.topology_batch(&[path]).pop().expect("one answer")
    }

    /// [`Oracle::topology`] for many files in one process call.
    pub fn topology_batch<P: AsRef<Path>>(&self, paths: &[P]) -> Vec<OracleTopology> {
        self.try_topology_batch(paths)
            .unwrap_or_else(|e| panic!("{e}"))
    }

    /// Fallible [`Oracle::topology_batch`].
    pub fn try_topology_batch<P: AsRef<Path>>(
        &self,
        paths: &[P],
    ) -> Result<Vec<OracleTopology>, OracleError> {
        let mut req = String::new();
        for p in paths {
            req.push_str("topology\n");
            req.push_str(&path_line(p.as_ref())?);
            req.push('\n');
        }
        let rs = self.raw(&req)?;
        if rs.len() != paths.len() {
            return Err(OracleError::Protocol(format!(
                "oracle answered {} of {} topology requests",
                rs.len(),
                paths.len()
            )));
        }
        rs.into_iter()
            .map(|r| parse_topology(r.into_ok().map_err(|e| self.under_limits(e))?))
            .collect()
    }
}

/// The oracle, or `None` after a loud skip message; panics instead under `CI=true`.
pub fn oracle_or_skip() -> Option<Oracle> {
    match Oracle::locate() {
        Ok(o) => Some(o),
        Err(e) if is_ci() => panic!("CI=true and the oracle is required: {e}"),
        Err(e) => {
            eprintln!("\n=== SKIPPING ORACLE TEST ===\n{e}\n============================\n");
            None
        }
    }
}

/// Directory of the libcgal-demo mesh corpus (`<repo>/.corpus/data/meshes`, or `$ENVELOPE_CORPUS`),
/// unpacked by `scripts/corpus.sh` on first use. `None` after a loud message when unavailable;
/// panics under `CI=true`.
pub fn corpus_dir() -> Option<PathBuf> {
    static DIR: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    let r = DIR.get_or_init(|| {
        if let Some(p) = std::env::var_os("ENVELOPE_CORPUS") {
            let p = PathBuf::from(p);
            return if has_off(&p) {
                Ok(p)
            } else {
                Err(format!("ENVELOPE_CORPUS={} has no .off files", p.display()))
            };
        }
        let dir = repo_root().join(".corpus/data/meshes");
        if has_off(&dir) {
            return Ok(dir);
        }
        let archive = Path::new("/usr/share/doc/libcgal-dev/data.tar.gz");
        if !archive.is_file() {
            return Err(format!(
                "{} is missing; run `bash scripts/corpus.sh` (as root it installs libcgal-demo)",
                archive.display()
            ));
        }
        let script = repo_root().join("scripts/corpus.sh");
        match Command::new("bash")
            .arg(&script)
            .stdin(Stdio::null())
            .output()
        {
            Ok(o) if o.status.success() && has_off(&dir) => Ok(dir),
            Ok(o) => Err(format!(
                "{} failed: {}",
                script.display(),
                String::from_utf8_lossy(&o.stderr)
            )),
            Err(e) => Err(format!("cannot run {}: {e}", script.display())),
        }
    });
    match r {
        Ok(p) => Some(p.clone()),
        Err(e) if is_ci() => panic!("CI=true and the mesh corpus is required: {e}"),
        Err(e) => {
            eprintln!(
                "\n=== SKIPPING CORPUS TEST ===\nmesh corpus unavailable: {e}\n============================\n"
            );
            None
        }
    }
}

/// The corpus's `.off` files, sorted (empty when the corpus is unavailable outside CI).
pub fn corpus_meshes() -> Vec<PathBuf> {
    let Some(dir) = corpus_dir() else {
        return Vec::new();
    };
    let mut v: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x.eq_ignore_ascii_case("off")))
        .collect();
    v.sort();
    v
}

fn has_off(dir: &Path) -> bool {
    std::fs::read_dir(dir).is_ok_and(|mut it| {
        it.any(|e| e.is_ok_and(|e| e.path().extension().is_some_and(|x| x == "off")))
    })
}

// ---------------------------------------------------------------------------- number format

/// Formats a finite `f64` as a C99 hex float (`%a`-like, exact). Panics on NaN/infinity.
pub fn hex_f64(x: f64) -> String {
    let mut s = String::new();
    push_hex_f64(&mut s, x);
    s
}

fn push_hex_f64(s: &mut String, x: f64) {
    assert!(x.is_finite(), "oracle inputs must be finite, got {x}");
    let bits = x.to_bits();
    if bits >> 63 == 1 {
        s.push('-');
    }
    let exp = ((bits >> 52) & 0x7ff) as i64;
    let mant = bits & ((1u64 << 52) - 1);
    use std::fmt::Write as _;
    if exp == 0 && mant == 0 {
        s.push_str("0x0p+0");
    } else if exp == 0 {
        write!(s, "0x0.{mant:013x}p-1022").expect("write to String");
    } else {
        write!(s, "0x1.{mant:013x}p{:+}", exp - 1023).expect("write to String");
    }
}

/// Parses a C99 hex float (`[-]0xH[.H]p[+-]D`) or a decimal number. Exact for any value `%a`
/// prints for a double.
pub fn parse_f64(t: &str) -> Option<f64> {
    let t = t.trim();
    let (neg, body) = match t.strip_prefix('-') {
        Some(r) => (true, r),
        None => (false, t.strip_prefix('+').unwrap_or(t)),
    };
    let Some(hex) = body.strip_prefix("0x").or_else(|| body.strip_prefix("0X")) else {
        return t.parse::<f64>().ok();
    };
    let (mant_str, exp_str) = match hex.find(['p', 'P']) {
        Some(i) => (&hex[..i], &hex[i + 1..]),
        None => (hex, "0"),
    };
    let mut exp: i64 = exp_str.parse().ok()?;
    let (int_part, frac_part) = mant_str.split_once('.').unwrap_or((mant_str, ""));
    if int_part.is_empty() && frac_part.is_empty() {
        return None;
    }
    let mut m: u64 = 0;
    for c in int_part.chars().chain(frac_part.chars()) {
        let d = c.to_digit(16)? as u64;
        if m >> 60 != 0 {
            return None; // more than 15 significant hex digits: not produced by %a for doubles
        }
        m = (m << 4) | d;
    }
    exp -= 4 * frac_part.len() as i64;
    if m == 0 {
        return Some(if neg { -0.0 } else { 0.0 });
    }
    if m >> 53 != 0 {
        return None; // would need rounding; %a output for doubles never does
    }
    // m < 2^53 is exact; scaling by powers of two in steps is exact when the result is a double.
    let mut v = m as f64;
    while exp > 0 {
        let k = exp.min(1000);
        v *= 2f64.powi(k as i32);
        exp -= k;
    }
    while exp < 0 {
        let k = (-exp).min(1000);
        v *= 2f64.powi(-(k as i32));
        exp += k;
    }
    Some(if neg { -v } else { v })
}

// ---------------------------------------------------------------------------- parsing helpers

fn flat<const N: usize, const W: usize>(p: &[DVec3; N]) -> [f64; W] {
    let mut r = [0.0; W];
    for (i, v) in p.iter().enumerate() {
        r[3 * i..3 * i + 3].copy_from_slice(&v.to_array());
    }
    r
}

fn path_line(p: &Path) -> Result<String, OracleError> {
    let s = p
        .to_str()
        .ok_or_else(|| OracleError::Protocol(format!("path is not UTF-8: {}", p.display())))?;
    if s.contains(['\n', '\r']) || s.is_empty() {
        return Err(OracleError::Protocol(format!(
            "path unusable in the protocol: {s:?}"
        )));
    }
    Ok(s.to_string())
}

fn parse_kind(s: &str) -> Result<MeshKind, OracleError> {
    match s {
        "mesh" => Ok(MeshKind::Mesh),
        "soup" => Ok(MeshKind::Soup),
        _ => Err(OracleError::Protocol(format!("bad kind `{s}`"))),
    }
}

fn parse_field<T: std::str::FromStr>(r: &Response, key: &str) -> Result<T, OracleError> {
    r.field(key)?
        .parse()
        .map_err(|_| OracleError::Protocol(format!("bad `{key}` in `{}` answer", r.cmd)))
}

fn kv_pairs<'a>(words: impl Iterator<Item = &'a str>) -> BTreeMap<String, String> {
    words
        .filter_map(|w| {
            w.split_once('=')
                .map(|(k, v)| (k.to_string(), v.to_string()))
        })
        .collect()
}

fn parse_responses(out: &str) -> Result<Vec<Response>, OracleError> {
    let mut lines = out.lines();
    let mut rs = Vec::new();
    while let Some(h) = lines.next() {
        let mut w = h.split_whitespace();
        match w.next() {
            Some("ok") => {
                let cmd = w
                    .next()
                    .ok_or_else(|| OracleError::Protocol(format!("bad header `{h}`")))?;
                let n: usize = w
                    .next()
                    .and_then(|n| n.parse().ok())
                    .ok_or_else(|| OracleError::Protocol(format!("bad header `{h}`")))?;
                let fields = kv_pairs(w);
                let body: Vec<String> = lines.by_ref().take(n).map(str::to_string).collect();
                if body.len() != n {
                    return Err(OracleError::Protocol(format!(
                        "`{cmd}`: output ended after {} of {n} lines",
                        body.len()
                    )));
                }
                rs.push(Response {
                    cmd: cmd.to_string(),
                    status: Ok(()),
                    fields,
                    lines: body,
                });
            }
            Some("err") => {
                let cmd = w.next().unwrap_or("?").to_string();
                let message = w.collect::<Vec<_>>().join(" ");
                rs.push(Response {
                    cmd,
                    status: Err(message),
                    fields: BTreeMap::new(),
                    lines: Vec::new(),
                });
            }
            _ => return Err(OracleError::Protocol(format!("unexpected line `{h}`"))),
        }
    }
    Ok(rs)
}

fn parse_counts(f: &BTreeMap<String, String>) -> Result<TopoCounts, String> {
    let get = |k: &str| -> Result<i64, String> {
        f.get(k)
            .and_then(|v| v.parse().ok())
            .ok_or_else(|| format!("missing/bad `{k}`"))
    };
    let u = |k: &str| get(k).map(|x| x.max(0) as u64);
    let genus = get("genus")?;
    Ok(TopoCounts {
        v: u("V")?,
        f: u("F")?,
        e: u("E")?,
        isolated: u("isolated")?,
        borders: u("borders")?,
        components: u("components")?,
        chi: get("chi")?,
        genus: (genus >= 0).then_some(genus as u64),
    })
}

fn parse_topology(r: Response) -> Result<OracleTopology, OracleError> {
    let mut om = None;
    let mut cg = None;
    for l in &r.lines {
        let mut w = l.split_whitespace();
        let who = w.next();
        let f = kv_pairs(w);
        match who {
            Some("openmesh") => om = Some(f),
            Some("cgal") => cg = Some(f),
            _ => return Err(OracleError::Protocol(format!("bad topology line `{l}`"))),
        }
    }
    let (Some(om), Some(cg)) = (om, cg) else {
        return Err(OracleError::Protocol(
            "topology answer lacks a library line".into(),
        ));
    };
    let loaded = |f: &BTreeMap<String, String>| f.get("loaded").map(String::as_str) == Some("1");
    let openmesh = if loaded(&om) {
        Ok(parse_counts(&om).map_err(OracleError::Protocol)?)
    } else {
        Err(om
            .get("error")
            .cloned()
            .unwrap_or_else(|| "not loaded".into()))
    };
    let file_polygons = om
        .get("file_polygons")
        .and_then(|v| v.parse::<i64>().ok())
        .filter(|&x| x >= 0)
        .map(|x| x as u64);
    let mut soup_counts = None;
    let cgal = if loaded(&cg) {
        Ok(parse_counts(&cg).map_err(OracleError::Protocol)?)
    } else if cg.get("kind").map(String::as_str) == Some("soup") {
        let v = cg.get("V").and_then(|x| x.parse().ok());
        let f = cg.get("F").and_then(|x| x.parse().ok());
        soup_counts = v.zip(f);
        Err("soup".to_string())
    } else {
        Err(cg
            .get("error")
            .cloned()
            .unwrap_or_else(|| "not loaded".into()))
    };
    Ok(OracleTopology {
        openmesh,
        cgal,
        file_polygons,
        soup_counts,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hex_roundtrip() {
        for x in [
            0.0,
            -0.0,
            1.0,
            -1.5,
            0.1,
            1e300,
            -1e-300,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            3.0e-310,
        ] {
            let h = hex_f64(x);
            let y = parse_f64(&h).unwrap_or_else(|| panic!("cannot parse {h}"));
            assert_eq!(x.to_bits(), y.to_bits(), "{x} -> {h} -> {y}");
        }
        assert_eq!(hex_f64(1.0), "0x1.0000000000000p+0");
        assert_eq!(parse_f64("0x1.8p+1"), Some(3.0));
        assert_eq!(parse_f64("0x0p+0"), Some(0.0));
        assert_eq!(parse_f64("2.5"), Some(2.5));
        assert_eq!(parse_f64("0x1p-1074"), Some(5e-324));
        assert_eq!(parse_f64("0xzz"), None);
    }
}
