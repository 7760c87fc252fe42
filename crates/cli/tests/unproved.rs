//! No command makes an output from envelopes whose proof failed: two parallel sheets 2^-50
//! apart leave contacts however far the offsets are halved.

use std::process::Command;

const SHEETS: &str = "OFF\n8 4 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n\
    0 0 8.881784197001252e-16\n1 0 8.881784197001252e-16\n1 1 8.881784197001252e-16\n\
    0 1 8.881784197001252e-16\n3 0 1 2\n3 0 2 3\n3 4 5 6\n3 4 6 7\n";

#[test]
fn unproved_envelopes_give_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("sheets.off");
    std::fs::write(&input, SHEETS).unwrap();
    let check = Command::new(env!("CARGO_BIN_EXE_envelope"))
        .args(["check".as_ref(), input.as_os_str()])
        .output()
        .unwrap();
    assert_eq!(
        check.status.code(),
        Some(0),
        "the sheets are acceptable input"
    );
    for extra in [&[][..], &["--no-verify"][..]] {
        let out = dir.path().join("out.off");
        std::fs::write(&out, "KEEP").unwrap();
        let run = Command::new(env!("CARGO_BIN_EXE_envelope"))
            .arg("simplify")
            .args([&input, &out])
            .args(["--epsilon", "1%", "--quiet"])
            .args(extra)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(1), "{extra:?}: {stderr}");
        assert!(stderr.contains("could not be proved"), "{stderr}");
        assert_eq!(std::fs::read_to_string(&out).unwrap(), "KEEP");
        assert!(!dir.path().join("out.failed.off").exists());
    }
}
