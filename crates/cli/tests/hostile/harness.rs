//! Runs hostile-input cases against the `envelope` binary in parallel threads and checks
//! the post-conditions every case shares (see `Case`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Per-case wall-clock limit: a case still running then is killed and fails as a hang.
pub const TIMEOUT: Duration = Duration::from_secs(60);
/// Address-space limit of every run (KiB, `ulimit -v`): a memory bomb aborts instead of
/// taking the machine.
const MEMORY_KIB: u64 = 3 * 1024 * 1024;

/// One run of the program with its expectations. Paths in `args` are relative to the case's
/// own directory (the working directory of the run).
#[derive(Clone, Debug)]
pub struct Case {
    /// Family and variant, e.g. `truncate/ply-le/@57/check`.
    pub name: String,
    /// Files created before the run: (relative path, bytes).
    pub files: Vec<(String, Vec<u8>)>,
    /// Directories created before the run.
    pub dirs: Vec<String>,
    /// Command-line arguments.
    pub args: Vec<String>,
    /// Allowed exit codes.
    pub codes: Vec<i32>,
    /// On exit 2: strings the error line must contain (the file or the flag at fault).
    pub names: Vec<String>,
    /// On exit 2: the error line must contain at least one of these.
    pub one_of: Vec<String>,
    /// On exit 2: a whole word the error line must contain (an index as written).
    pub word: Option<String>,
    /// Files that must keep their bytes unless the exit code is 0 (`KEEP` is written into
    /// those not among `files`).
    pub keep: Vec<String>,
    /// On exit 0 of `simplify`: (IN, OUT, epsilon) to re-certify with `envelope verify`.
    pub recert: Option<(String, String, String)>,
    /// Two files `envelope check --json` must describe identically (after the run).
    pub same_check: Option<(String, String)>,
    /// Text neither stdout nor stderr may contain (ASCII case-insensitive).
    pub lacks: Vec<String>,
}

impl Case {
    /// A case running `args` (whitespace-separated).
    pub fn new(name: impl Into<String>, args: &str) -> Case {
        Case {
            name: name.into(),
            files: Vec::new(),
            dirs: Vec::new(),
            args: args.split_whitespace().map(str::to_owned).collect(),
            codes: Vec::new(),
            names: Vec::new(),
            one_of: Vec::new(),
            word: None,
            keep: Vec::new(),
            recert: None,
            same_check: None,
            lacks: Vec::new(),
        }
    }
    pub fn file(mut self, path: impl Into<String>, bytes: impl Into<Vec<u8>>) -> Case {
        self.files.push((path.into(), bytes.into()));
        self
    }
    pub fn dir(mut self, path: impl Into<String>) -> Case {
        self.dirs.push(path.into());
        self
    }
    pub fn codes(mut self, codes: &[i32]) -> Case {
        self.codes = codes.to_vec();
        self
    }
    pub fn names(mut self, name: impl Into<String>) -> Case {
        self.names.push(name.into());
        self
    }
    pub fn one_of(mut self, names: &[&str]) -> Case {
        self.one_of = names.iter().map(|n| (*n).to_owned()).collect();
        self
    }
    pub fn word(mut self, w: impl Into<String>) -> Case {
        self.word = Some(w.into());
        self
    }
    pub fn keep(mut self, path: impl Into<String>) -> Case {
        self.keep.push(path.into());
        self
    }
    pub fn recert(mut self, input: &str, output: &str, eps: &str) -> Case {
        self.recert = Some((input.into(), output.into(), eps.into()));
        self
    }
    pub fn same_check(mut self, a: &str, b: &str) -> Case {
        self.same_check = Some((a.into(), b.into()));
        self
    }
    pub fn lacks(mut self, text: &str) -> Case {
        self.lacks.push(text.into());
        self
    }
}

/// What one run printed and how it ended.
struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    seconds: f64,
    timed_out: bool,
}

/// Runs the program with `args` in `cwd` under the memory limit and `TIMEOUT`.
fn run(cwd: &Path, logs: &Path, args: &[String]) -> Run {
    let (out_path, err_path) = (logs.join("stdout"), logs.join("stderr"));
    let start = Instant::now();
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {MEMORY_KIB} && exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_envelope"))
        .args(args)
        .current_dir(cwd)
        // Few threads and malloc arenas: each arena reserves 64 MiB of address space, which
        // on a many-core machine would hit the address-space cap without any real use.
        .env("RAYON_NUM_THREADS", "2")
        .env("MALLOC_ARENA_MAX", "2")
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).expect("stdout log"))
        .stderr(std::fs::File::create(&err_path).expect("stderr log"))
        .spawn()
        .expect("spawn envelope");
    let mut timed_out = false;
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if start.elapsed() > TIMEOUT {
            let _ = child.kill();
            timed_out = true;
            break child.wait().expect("wait after kill");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let read =
        |p: &Path| String::from_utf8_lossy(&std::fs::read(p).unwrap_or_default()).into_owned();
    Run {
        code: status.code(),
        stdout: read(&out_path),
        stderr: read(&err_path),
        seconds: start.elapsed().as_secs_f64(),
        timed_out,
    }
}

/// Entries under `dir` (recursively) whose names start with a dot.
fn hidden_files(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return found;
    };
    for e in entries.flatten() {
        let p = e.path();
        if e.file_name().to_string_lossy().starts_with('.') {
            found.push(p.clone());
        }
        if p.is_dir() {
            found.extend(hidden_files(&p));
        }
    }
    found
}

/// `check --json` of `file`, without the keys naming the file or listing read notes.
fn check_json(cwd: &Path, logs: &Path, file: &str) -> Result<serde_json::Value, String> {
    let r = run(cwd, logs, &["check".into(), "--json".into(), file.into()]);
    let mut v: serde_json::Value = serde_json::from_str(&r.stdout).map_err(|e| {
        format!(
            "check --json {file}: exit {:?}, no JSON ({e}): {}",
            r.code,
            first_line(&r.stderr)
        )
    })?;
    if let Some(o) = v.as_object_mut() {
        o.remove("file");
        o.remove("read_notes");
    }
    Ok(v)
}

fn first_line(s: &str) -> &str {
    s.lines().find(|l| !l.trim().is_empty()).unwrap_or("")
}

/// Whether `line` holds `word` delimited by characters other than digits, letters, `-`.
fn has_word(line: &str, word: &str) -> bool {
    line.split(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
        .any(|t| t == word)
}

/// Runs one case; returns what went wrong (empty when nothing did).
fn run_case(case: &Case, root: &Path) -> Vec<String> {
    let mut problems = Vec::new();
    let logs = root.join("logs");
    let cwd = root.join("work");
    std::fs::create_dir_all(&logs).unwrap();
    std::fs::create_dir_all(&cwd).unwrap();
    for d in &case.dirs {
        std::fs::create_dir_all(cwd.join(d)).unwrap();
    }
    for (p, bytes) in &case.files {
        std::fs::write(cwd.join(p), bytes).unwrap();
    }
    let mut kept = Vec::new();
    for k in &case.keep {
        let p = cwd.join(k);
        if !p.exists() {
            std::fs::write(&p, b"KEEP").unwrap();
        }
        kept.push((k.clone(), std::fs::read(&p).unwrap()));
    }
    let r = run(&cwd, &logs, &case.args);
    let stderr_head: String = r.stderr.lines().take(3).collect::<Vec<_>>().join(" | ");
    if r.timed_out {
        problems.push(format!("hang: killed after {} s", TIMEOUT.as_secs()));
    }
    if r.stderr.contains("panicked") {
        problems.push(format!("panic: {stderr_head}"));
    }
    match r.code {
        None if !r.timed_out => problems.push(format!("killed by a signal: {stderr_head}")),
        Some(101) => problems.push(format!("exit 101: {stderr_head}")),
        Some(c) if !case.codes.contains(&c) => problems.push(format!(
            "exit {c}, expected {:?}: {}",
            case.codes,
            if stderr_head.is_empty() {
                first_line(&r.stdout).to_string()
            } else {
                stderr_head.clone()
            }
        )),
        _ => {}
    }
    if r.code == Some(2) {
        // One error line: ours (`envelope: error:`) or, for argument syntax, clap's.
        let errors: Vec<&str> = r
            .stderr
            .lines()
            .filter(|l| l.starts_with("envelope: error:") || l.starts_with("error:"))
            .collect();
        match errors[..] {
            [line] => {
                // clap names a missing or conflicting flag on the lines after its error line.
                let scope = if line.starts_with("error:") {
                    r.stderr.as_str()
                } else {
                    line
                };
                for n in &case.names {
                    if !scope.contains(n.as_str()) {
                        problems.push(format!("error line does not name {n:?}: {line}"));
                    }
                }
                if !case.one_of.is_empty()
                    && !case.one_of.iter().any(|n| scope.contains(n.as_str()))
                {
                    problems.push(format!(
                        "error line names none of {:?}: {line}",
                        case.one_of
                    ));
                }
                if let Some(w) = &case.word {
                    if !has_word(line, w) {
                        problems.push(format!("error line does not quote {w:?}: {line}"));
                    }
                }
            }
            _ => problems.push(format!(
                "exit 2 with {} error lines (expected one): {stderr_head}",
                errors.len()
            )),
        }
    }
    for l in &case.lacks {
        let low = l.to_ascii_lowercase();
        for (stream, text) in [("stdout", &r.stdout), ("stderr", &r.stderr)] {
            if let Some(line) = text
                .lines()
                .find(|line| line.to_ascii_lowercase().contains(&low))
            {
                problems.push(format!("{stream} mentions {l:?}: {line}"));
            }
        }
    }
    if r.code != Some(0) {
        for (k, before) in &kept {
            match std::fs::read(cwd.join(k)) {
                Ok(now) if &now == before => {}
                Ok(_) => problems.push(format!("{k} changed although the exit code is not 0")),
                Err(e) => problems.push(format!("{k} lost although the exit code is not 0: {e}")),
            }
        }
    }
    let hidden = hidden_files(&cwd);
    if !hidden.is_empty() {
        problems.push(format!("temporary files left: {hidden:?}"));
    }
    if let (Some(0), Some((input, output, eps))) = (r.code, &case.recert) {
        let v = run(
            &cwd,
            &logs,
            &[
                "verify".into(),
                input.clone(),
                output.clone(),
                "--epsilon".into(),
                eps.clone(),
            ],
        );
        if v.code != Some(0) {
            problems.push(format!(
                "simplify exited 0 but `verify {input} {output} --epsilon {eps}` exits {:?}: {}",
                v.code,
                v.stdout
                    .lines()
                    .chain(v.stderr.lines())
                    .filter(|l| l.contains("verdict") || l.contains("error"))
                    .collect::<Vec<_>>()
                    .join(" | ")
            ));
        }
    }
    if let Some((a, b)) = &case.same_check {
        match (check_json(&cwd, &logs, a), check_json(&cwd, &logs, b)) {
            (Ok(x), Ok(y)) if x == y => {}
            (Ok(x), Ok(y)) => problems.push(format!(
                "check --json differs: {a}: {} faces, {} vertices; {b}: {} faces, {} vertices",
                x["faces"], x["vertices"], y["faces"], y["vertices"]
            )),
            (Err(e), _) | (_, Err(e)) => problems.push(e),
        }
    }
    if r.seconds > 20.0 && !r.timed_out {
        eprintln!("slow case {}: {:.1} s", case.name, r.seconds);
    }
    problems
}

/// Runs every case on `threads` threads; returns the failures as (case, problems), in case
/// order.
pub fn run_all(cases: &[Case], threads: usize) -> Vec<(String, Vec<String>)> {
    let tmp = tempfile::tempdir().expect("temporary directory");
    let next = AtomicUsize::new(0);
    let failures = Mutex::new(Vec::new());
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(case) = cases.get(i) else { break };
                    let problems = run_case(case, &tmp.path().join(format!("case-{i}")));
                    if !problems.is_empty() {
                        failures
                            .lock()
                            .unwrap()
                            .push((i, case.name.clone(), problems));
                    }
                }
            });
        }
    });
    let mut f = failures.into_inner().unwrap();
    f.sort_by_key(|x| x.0);
    f.into_iter().map(|(_, n, p)| (n, p)).collect()
}

/// A table of failures: one line per problem.
pub fn table(failures: &[(String, Vec<String>)], total: usize) -> String {
    let mut s = format!("{} of {total} hostile cases failed:\n", failures.len());
    let width = failures.iter().map(|f| f.0.len()).max().unwrap_or(0);
    for (name, problems) in failures {
        for p in problems {
            let mut p = p.replace('\n', " ");
            if p.len() > 400 {
                let mut cut = 400;
                while !p.is_char_boundary(cut) {
                    cut -= 1;
                }
                p.truncate(cut);
                p.push_str("...");
            }
            let _ = writeln!(s, "  {name:<width$}  {p}");
        }
    }
    s
}
