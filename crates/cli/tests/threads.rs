//! `--threads N` on every command: refused out of range before any work, and the same
//! output files for any N.

mod common;

use common::{assert_ok, envelope};
use envelope_io::{Format, write_path};
use envelope_mesh::generate;

#[test]
fn threads_is_accepted_by_every_command_and_checked() {
    for command in [
        "check",
        "envelopes",
        "verify",
        "simplify",
        "lod",
        "genus",
        "pipeline",
        "batch",
        "demo",
    ] {
        let out = envelope().args([command, "--help"]).output().unwrap();
        let help = String::from_utf8_lossy(&out.stdout);
        assert!(help.contains("--threads"), "{command} --help: {help}");
    }
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("torus.off");
    write_path(&input, &generate::torus(2.0, 0.5, 24, 12), Format::Off).unwrap();
    for bad in ["0", "1025", "-1", "two"] {
        let out = envelope()
            .args(["--threads", bad, "check"])
            .arg(&input)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "--threads {bad}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("--threads") && err.contains("1..=1024"),
            "{err}"
        );
    }
}

#[test]
fn outputs_are_the_same_for_one_and_four_threads() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("torus.off");
    write_path(&input, &generate::torus(2.0, 0.5, 48, 24), Format::Off).unwrap();
    let run = |n: &str| {
        let out_mesh = dir.path().join(format!("out-{n}.off"));
        let levels = dir.path().join(format!("levels-{n}"));
        let filled = dir.path().join(format!("genus-{n}.off"));
        assert_ok(
            &envelope()
                .args(["simplify", "--quiet", "--epsilon", "2%", "--threads", n])
                .arg(&input)
                .arg(&out_mesh)
                .output()
                .unwrap(),
        );
        assert_ok(
            &envelope()
                .args(["--threads", n, "lod", "--quiet", "--epsilons", "0.5%,2%"])
                .arg(&input)
                .arg(&levels)
                .output()
                .unwrap(),
        );
        assert_ok(
            &envelope()
                .args(["genus", "--alpha", "30%", "--threads", n])
                .arg(&input)
                .arg(&filled)
                .output()
                .unwrap(),
        );
        [
            std::fs::read(out_mesh).unwrap(),
            std::fs::read(levels.join("level-1.off")).unwrap(),
            std::fs::read(levels.join("level-2.off")).unwrap(),
            std::fs::read(filled).unwrap(),
        ]
    };
    let one = run("1");
    assert!(one[0].len() > 100 && one[0] != std::fs::read(&input).unwrap());
    assert_eq!(one, run("4"), "outputs differ between 1 and 4 threads");
}
