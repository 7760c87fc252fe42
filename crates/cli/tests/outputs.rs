//! End-to-end tests of the output and argument rules shared by every subcommand
//! (`crates/cli/src/outputs.rs`, `ranges.rs`): outputs checked before any work, nothing
//! replaced unless the command completes, numeric arguments in their documented ranges,
//! messages that name the argument and what is allowed.

use std::path::{Path, PathBuf};
use std::process::Output;

use envelope_io::{Format, write_path};
use envelope_mesh::{TriangleSoup, generate};

mod common;
use common::{assert_ok, envelope};

const KEEP: &str = "KEEP";

/// A list of arguments as owned strings (cases mix literals and paths).
macro_rules! a {
    ($($x:expr),* $(,)?) => { vec![$($x.to_string()),*] };
}

fn run<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Output {
    envelope().args(args).output().unwrap()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Asserts exit 2 and a message mentioning each of `mentions`.
fn assert_refused(out: &Output, mentions: &[&str], context: &str) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "{context}: {err}");
    for m in mentions {
        assert!(
            err.contains(m),
            "{context}: message should mention {m:?}: {err}"
        );
    }
    assert!(!err.contains("panicked"), "{context}: {err}");
}

/// Two overlapping spheres: readable, refused by the genus reduction (self-intersecting).
fn crossing_spheres() -> TriangleSoup {
    let mut two = generate::icosphere(1, 1.0);
    let other = generate::icosphere(1, 1.0);
    let n = two.positions.len() as u32;
    let shift = glam::DVec3::new(0.5, 0.1, 0.05);
    two.positions
        .extend(other.positions.iter().map(|p| *p + shift));
    two.faces.extend(
        other
            .faces
            .iter()
            .map(|t| t.map(|v| envelope_mesh::VertexId(v.0 + n))),
    );
    two
}

/// A scratch directory holding a small sphere, a non-manifold mesh (readable, refused by
/// the simplifiers and the envelopes), two crossing spheres, an unreadable file and `out.off` with the bytes `KEEP`.
struct Scratch {
    dir: tempfile::TempDir,
}

impl Scratch {
    fn new() -> Scratch {
        let dir = tempfile::tempdir().unwrap();
        let s = Scratch { dir };
        s.mesh("sphere.off", &generate::icosphere(2, 1.0));
        s.mesh("bowtie.off", &generate::bow_tie());
        s.mesh("crossing.off", &crossing_spheres());
        std::fs::write(s.path("garbage.off"), "not a mesh").unwrap();
        std::fs::write(s.path("out.off"), KEEP).unwrap();
        s
    }

    fn mesh(&self, name: &str, soup: &TriangleSoup) -> String {
        write_path(self.path(name), soup, Format::Off).unwrap();
        self.p(name)
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    /// The path as a string argument.
    fn p(&self, name: &str) -> String {
        self.path(name).to_str().unwrap().to_string()
    }

    /// Fails if `name` no longer holds `KEEP`.
    fn assert_kept(&self, name: &str, context: &str) {
        assert_eq!(
            std::fs::read_to_string(self.path(name)).unwrap(),
            KEEP,
            "{context}: {name} was replaced"
        );
    }

    /// Fails if a temporary file or directory was left anywhere in the scratch directory.
    fn assert_no_temporaries(&self, context: &str) {
        let mut stack = vec![self.dir.path().to_path_buf()];
        while let Some(d) = stack.pop() {
            for e in std::fs::read_dir(&d).unwrap() {
                let e = e.unwrap();
                let name = e.file_name().to_string_lossy().into_owned();
                assert!(
                    !name.starts_with('.'),
                    "{context}: left {}",
                    e.path().display()
                );
                if e.path().is_dir() {
                    stack.push(e.path());
                }
            }
        }
    }
}

/// Each subcommand that writes, with its outputs under a missing directory: refused with
/// exit 2 naming it, before the input is read (the unreadable input is not what the message
/// is about), and OUT keeps its bytes.
#[test]
fn missing_output_directories_are_refused_before_work() {
    let s = Scratch::new();
    let missing = s.p("nodir");
    let nested = s.p("nodir/sub");
    let report = s.p("nodir/r.json");
    let out = s.p("out.off");
    let for_input = |input: &str| -> Vec<Vec<String>> {
        let v = |a: &[&str]| a.iter().map(|x| (*x).to_string()).collect::<Vec<_>>();
        vec![
            v(&[
                "simplify",
                input,
                &out,
                "--epsilon",
                "1%",
                "--report",
                &report,
            ]),
            v(&["simplify", input, &s.p("nodir/o.off"), "--epsilon", "1%"]),
            v(&["genus", input, &out, "--alpha", "1%", "--report", &report]),
            v(&["genus", input, &s.p("nodir/o.off"), "--alpha", "1%"]),
            v(&["lod", input, &nested, "--epsilons", "1%", "--no-verify"]),
            v(&["pipeline", input, &nested, "--steps", "e1%"]),
            v(&["envelopes", input, "--epsilon", "1%", "--out-dir", &nested]),
            v(&["demo", "--out-dir", &nested]),
        ]
    };
    for input in [s.p("garbage.off"), s.p("sphere.off")] {
        for args in for_input(&input) {
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            let o = run(&args);
            let context = format!("{args:?}");
            assert_refused(&o, &[&missing], &context);
            assert!(
                !stderr(&o).contains("garbage.off"),
                "{context}: input read first"
            );
            s.assert_kept("out.off", &context);
        }
    }
    assert!(!s.path("nodir").exists());
    s.assert_no_temporaries("missing directories");
}

/// Other unusable outputs: a directory as OUT, an unknown extension, a report that is OUT,
/// an out-dir that is a file.
#[test]
fn unusable_outputs_are_refused() {
    let s = Scratch::new();
    let sphere = s.p("sphere.off");
    let out = s.p("out.off");
    std::fs::create_dir(s.path("adir")).unwrap();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            a![
                "simplify",
                &sphere,
                s.dir.path().to_str().unwrap(),
                "--epsilon",
                "1%",
            ],
            "is a directory",
        ),
        (
            a!["genus", &sphere, &s.p("adir"), "--alpha", "1%"],
            "is a directory",
        ),
        (
            a!["simplify", &sphere, &s.p("o.xyz"), "--epsilon", "1%"],
            "unknown output format",
        ),
        (
            a!["genus", &sphere, &s.p("o.xyz"), "--alpha", "1%"],
            "unknown output format",
        ),
        (
            a![
                "simplify",
                &sphere,
                &out,
                "--epsilon",
                "1%",
                "--report",
                &out,
            ],
            "--report",
        ),
        (
            a!["lod", &sphere, &out, "--epsilons", "1%"],
            "not a directory",
        ),
        (
            a!["envelopes", &sphere, "--epsilon", "1%", "--out-dir", &out],
            "not a directory",
        ),
    ];
    for (args, mention) in cases {
        let o = run(&args);
        assert_refused(&o, &[mention], &format!("{args:?}"));
        s.assert_kept("out.off", &format!("{args:?}"));
    }
    s.assert_no_temporaries("unusable outputs");
}

/// OUT (or a file an out-dir command writes) that is the input: refused, the input intact.
#[test]
fn output_equal_to_input_is_refused() {
    let s = Scratch::new();
    let sphere = s.p("sphere.off");
    let before = std::fs::read(&sphere).unwrap();
    // The same file spelt differently.
    let dotted = s.dir.path().join(".").join("sphere.off");
    let dotted = dotted.to_str().unwrap();
    std::fs::create_dir(s.path("lod")).unwrap();
    let level0 = s.mesh("lod/level-0.off", &generate::icosphere(1, 1.0));
    std::fs::create_dir(s.path("env")).unwrap();
    let tube = s.mesh("env/tube-0.off", &generate::icosphere(1, 1.0));
    let cases: Vec<Vec<String>> = vec![
        a!["simplify", &sphere, &sphere, "--epsilon", "1%"],
        a!["simplify", &sphere, dotted, "--epsilon", "1%"],
        a!["genus", &sphere, dotted, "--alpha", "1%"],
        a![
            "simplify",
            &sphere,
            &s.p("out.off"),
            "--epsilon",
            "1%",
            "--report",
            &sphere,
        ],
        a!["lod", &level0, &s.p("lod"), "--epsilons", "1%"],
        a![
            "envelopes",
            &tube,
            "--epsilon",
            "1%",
            "--out-dir",
            &s.p("env"),
        ],
    ];
    for args in cases {
        let o = run(&args);
        assert_refused(&o, &["input"], &format!("{args:?}"));
    }
    // `pipeline IN DIR` with IN = DIR/stage-0.off.
    std::fs::rename(s.path("sphere.off"), s.path("stage-0.off")).unwrap();
    let o = run(&[
        "pipeline",
        &s.p("stage-0.off"),
        s.dir.path().to_str().unwrap(),
    ]);
    assert_refused(&o, &["input"], "pipeline stage-0");
    assert_eq!(std::fs::read(s.path("stage-0.off")).unwrap(), before);
    s.assert_kept("out.off", "same file");
    s.assert_no_temporaries("same file");
}

/// A step that fails after the outputs were checked (a non-manifold input refused by the
/// algorithm) leaves every existing output as it was, including the files of an earlier
/// run in an out-dir.
#[test]
fn a_failing_step_leaves_existing_outputs() {
    let s = Scratch::new();
    let bowtie = s.p("bowtie.off");
    let sphere = s.p("sphere.off");
    let out = s.p("out.off");
    std::fs::write(s.path("r.json"), KEEP).unwrap();
    let report = s.p("r.json");
    for d in ["lod", "pipe", "env"] {
        std::fs::create_dir(s.path(d)).unwrap();
    }
    for f in [
        "lod/level-0.off",
        "lod/summary.json",
        "pipe/stage-0.off",
        "env/outer.off",
    ] {
        std::fs::write(s.path(f), KEEP).unwrap();
    }
    let cases: Vec<Vec<String>> = vec![
        a![
            "simplify",
            &bowtie,
            &out,
            "--epsilon",
            "1%",
            "--report",
            &report,
        ],
        a![
            "genus",
            &s.p("crossing.off"),
            &out,
            "--alpha",
            "1%",
            "--report",
            &report
        ],
        // Decreasing epsilons are refused by the chain, after level 0 is known.
        a!["lod", &sphere, &s.p("lod"), "--epsilons", "1%,1/2%"],
        a!["lod", &bowtie, &s.p("lod"), "--epsilons", "1%"],
        a!["pipeline", &bowtie, &s.p("pipe"), "--steps", "e1%"],
        a![
            "envelopes",
            &bowtie,
            "--epsilon",
            "1%",
            "--out-dir",
            &s.p("env"),
        ],
    ];
    for args in cases {
        let context = format!("{args:?}");
        let o = run(&args);
        assert_eq!(o.status.code(), Some(2), "{context}: {}", stderr(&o));
        for f in ["out.off", "r.json", "lod/level-0.off", "lod/summary.json"] {
            s.assert_kept(f, &context);
        }
        s.assert_kept("pipe/stage-0.off", &context);
        s.assert_kept("env/outer.off", &context);
        assert!(!s.path("lod/level-1.off").exists(), "{context}");
    }
    s.assert_no_temporaries("failing step");
}

/// Success replaces the outputs and creates a missing out-dir (not its parents), leaving no
/// temporary files.
#[test]
fn success_replaces_outputs_and_creates_the_last_directory() {
    let s = Scratch::new();
    let sphere = s.p("sphere.off");
    let o = run(&[
        "simplify",
        &sphere,
        &s.p("out.off"),
        "--epsilon",
        "1%",
        "--report",
        &s.p("r.json"),
        "--no-verify",
        "--quiet",
    ]);
    assert_ok(&o);
    assert_ne!(std::fs::read_to_string(s.path("out.off")).unwrap(), KEEP);
    assert!(s.path("r.json").is_file());
    let o = run(&[
        "lod",
        &sphere,
        &s.p("lod"),
        "--epsilons",
        "1%",
        "--no-verify",
        "--quiet",
    ]);
    assert_ok(&o);
    for f in ["level-0.off", "level-1.off", "summary.json"] {
        assert!(s.path("lod").join(f).is_file(), "{f}");
    }
    // Again into the now existing directory.
    let o = run(&[
        "lod",
        &sphere,
        &s.p("lod"),
        "--epsilons",
        "1%",
        "--no-verify",
        "--quiet",
    ]);
    assert_ok(&o);
    let o = run(&[
        "envelopes",
        &sphere,
        "--epsilon",
        "1%",
        "--out-dir",
        &s.p("env"),
    ]);
    assert_ok(&o);
    assert!(s.path("env/outer.off").is_file() && s.path("env/inner.off").is_file());
    s.assert_no_temporaries("success");
}

/// Every numeric argument outside its documented range: exit 2 naming the flag, nothing
/// written.
#[test]
fn numeric_arguments_out_of_range_are_refused() {
    let s = Scratch::new();
    let sphere = s.p("sphere.off");
    let out = s.p("out.off");
    let d = s.p("d");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (a!["check", &sphere, "--examples", "10001"], "--examples"),
        (a!["check", &sphere, "--examples", "-1"], "--examples"),
        (
            a![
                "envelopes",
                &sphere,
                "--epsilon",
                "1%",
                "--out-dir",
                &d,
                "--tube-segments",
                "1",
            ],
            "--tube-segments",
        ),
        (
            a![
                "envelopes",
                &sphere,
                "--epsilon",
                "1%",
                "--out-dir",
                &d,
                "--tube-segments",
                "2",
            ],
            "--tube-segments",
        ),
        (
            a![
                "envelopes",
                &sphere,
                "--epsilon",
                "1%",
                "--out-dir",
                &d,
                "--tube-segments",
                "65",
            ],
            "--tube-segments",
        ),
        (
            a![
                "envelopes",
                &sphere,
                "--epsilon",
                "1%",
                "--out-dir",
                &d,
                "--tube-segments",
                "4294967295",
            ],
            "--tube-segments",
        ),
        (
            a!["envelopes", &sphere, "--epsilon", "0", "--out-dir", &d],
            "--epsilon",
        ),
        (
            a!["envelopes", &sphere, "--epsilon", "-1%", "--out-dir", &d],
            "--epsilon",
        ),
        (a!["simplify", &sphere, &out, "--epsilon", "0"], "--epsilon"),
        (
            a!["simplify", &sphere, &out, "--epsilon", "nan"],
            "--epsilon",
        ),
        (
            a!["simplify", &sphere, &out, "--epsilon", "1/0%"],
            "--epsilon",
        ),
        (
            a![
                "simplify",
                &sphere,
                &out,
                "--epsilon",
                "1%",
                "--viewpoint",
                "0,0,5",
                "--epsilon-far",
                "-2%",
            ],
            "--epsilon-far",
        ),
        (
            a![
                "simplify",
                &sphere,
                &out,
                "--epsilon",
                "1%",
                "--viewpoint",
                "0,0,inf",
                "--epsilon-far",
                "2%",
            ],
            "--viewpoint",
        ),
        (a!["genus", &sphere, &out, "--alpha", "0"], "--alpha"),
        (a!["genus", &sphere, &out, "--alpha", "-1"], "--alpha"),
        (a!["genus", &sphere, &out, "--alpha", "inf"], "--alpha"),
        (
            a!["genus", &sphere, &out, "--alpha", "1%", "--beta", "200"],
            "--beta",
        ),
        (
            a!["genus", &sphere, &out, "--alpha", "1%", "--beta", "0"],
            "--beta",
        ),
        (a!["pipeline", &sphere, &d, "--beta", "180"], "--beta"),
        (a!["pipeline", &sphere, &d, "--steps", "e1%,a0"], "--steps"),
        (a!["pipeline", &sphere, &d, "--steps", "x1"], "--steps"),
        (a!["lod", &sphere, &d, "--epsilons", "1%,0"], "--epsilons"),
        (a!["lod", &sphere, &d, "--pixels", "0"], "--pixels"),
        (
            a!["lod", &sphere, &d, "--resolution", "1e7"],
            "--resolution",
        ),
        (a!["lod", &sphere, &d, "--fov", "180"], "--fov"),
        (a!["lod", &sphere, &d, "--fov", "-5"], "--fov"),
        (
            a!["verify", &sphere, &sphere, "--epsilon", "0"],
            "--epsilon",
        ),
        (
            a![
                "verify",
                &sphere,
                &sphere,
                "--epsilon",
                "1%",
                "--resolution",
                "-1",
            ],
            "--resolution",
        ),
    ];
    for (args, flag) in cases {
        let o = run(&args);
        assert_refused(&o, &[flag], &format!("{args:?}"));
    }
    s.assert_kept("out.off", "ranges");
    assert!(!s.path("d").exists());
}

/// Messages of class C: genus numbers, huge lengths, the flag named, a zero diagonal.
#[test]
fn messages_name_the_argument_and_print_numbers_readably() {
    let s = Scratch::new();
    let sphere = s.p("sphere.off");
    let torus = s.mesh("torus.off", &generate::torus(1.0, 0.35, 24, 12));
    // pipeline: genus as a number, never `Some(1)`.
    let o = run(&["pipeline", &torus, &s.p("p"), "--steps", "e1%"]);
    assert_ok(&o);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("genus 1") && !text.contains("Some("),
        "{text}"
    );
    // genus --alpha 1e300: a short number.
    let o = run(&["genus", &sphere, &s.p("g.off"), "--alpha", "1e300"]);
    assert_ok(&o);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("1e300") && !text.contains("0000000000"),
        "{text}"
    );
    // genus --alpha 0: about --alpha, not epsilon.
    let o = run(&["genus", &sphere, &s.p("g.off"), "--alpha", "0"]);
    assert_refused(&o, &["--alpha", "positive"], "alpha 0");
    assert!(
        !stderr(&o).to_lowercase().contains("epsilon"),
        "{}",
        stderr(&o)
    );
    // All vertices at one point: the diagonal is named, not the epsilon's sign.
    let point = s.mesh(
        "point.off",
        &TriangleSoup::from_raw(&[[1.0, 2.0, 3.0]; 3], &[[0, 1, 2]]),
    );
    let runs: Vec<Vec<String>> = vec![
        a!["simplify", &point, &s.p("o.off"), "--epsilon", "1%"],
        a!["genus", &point, &s.p("o.off"), "--alpha", "1%"],
        a!["lod", &point, &s.p("l"), "--epsilons", "1%"],
        a!["verify", &point, &point, "--epsilon", "1%"],
    ];
    for args in runs {
        let o = run(&args);
        let context = format!("{args:?}");
        assert_refused(
            &o,
            &["diagonal", "zero", "all 3 vertices are at one point"],
            &context,
        );
        assert!(
            !stderr(&o).contains("must be positive"),
            "{context}: {}",
            stderr(&o)
        );
    }
    // Errors after the work started name the argument and the input.
    let o = run(&["lod", &sphere, &s.p("l"), "--epsilons", "1%,1/2%"]);
    assert_refused(
        &o,
        &["--epsilons", "increasing", "\"1/2%\"", "sphere.off"],
        "lod order",
    );
    let o = run(&["pipeline", &s.p("bowtie.off"), &s.p("p2"), "--steps", "e1%"]);
    assert_refused(&o, &["bowtie.off", "--steps step 1 e1%"], "pipeline step");
    s.assert_no_temporaries("messages");
}

/// `simplify`'s rule for a violated certificate is kept: `OUT.failed.EXT` is checked up front
/// like OUT (here: it would be the input).
#[test]
fn the_failed_output_path_is_checked_too() {
    let s = Scratch::new();
    std::fs::copy(s.path("sphere.off"), s.path("x.failed.off")).unwrap();
    let o = run(&[
        "simplify",
        &s.p("x.failed.off"),
        &s.p("x.off"),
        "--epsilon",
        "1%",
    ]);
    assert_refused(&o, &["OUT.failed", "input"], "failed path");
    assert!(!Path::new(&s.p("x.off")).exists());
}
