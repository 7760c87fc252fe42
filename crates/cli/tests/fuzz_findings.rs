//! Inputs the fuzz target `command_path` found slow (libFuzzer's timeout and slow-unit
//! reports), rebuilt in code: an open cylinder of 32 faces with one or two moved vertices,
//! certified at an epsilon where the output lies at epsilon along a curve. The certificate's
//! branch and bound ran past libFuzzer's timeout before its total budget per face; it must
//! now end (undecided is an honest answer) well within the time limit.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use envelope_io::{Format, write_path};
use envelope_mesh::generate;
use glam::DVec3;

fn cylinder(dir: &Path, scale: f64, moved: &[(usize, [f64; 3])]) -> std::path::PathBuf {
    let mut soup = generate::open_cylinder(1.0, 1.0, 8, 2);
    for p in &mut soup.positions {
        *p *= scale;
    }
    for &(v, p) in moved {
        soup.positions[v] = DVec3::from_array(p);
    }
    let path = dir.join("cylinder.off");
    write_path(&path, &soup, Format::Off).unwrap();
    path
}

/// Runs `envelope simplify IN OUT --epsilon E` and returns its exit code, failing the test
/// when it runs longer than `limit`.
fn simplify_within(input: &Path, epsilon: &str, limit: Duration) -> i32 {
    let out = input.with_file_name("out.off");
    let mut child = Command::new(env!("CARGO_BIN_EXE_envelope"))
        .arg("simplify")
        .args([input, &out])
        .args(["--epsilon", epsilon, "--quiet"])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return status.code().expect("exited, not killed");
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("{} still running after {limit:?}", input.display());
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn a_cylinder_at_1e12_ends_its_certificate() {
    let dir = tempfile::tempdir().unwrap();
    let input = cylinder(
        dir.path(),
        1e12,
        &[
            (
                8,
                [1_106_250_000_000.0, -7_000_000.0, 500_059_999_999.999_94],
            ),
            (
                19,
                [
                    -707_106_781_186.547_5,
                    6_707_106_781_186.548,
                    1_000_001_250_000.0,
                ],
            ),
        ],
    );
    let code = simplify_within(&input, "3.0824319822691305e5", Duration::from_secs(120));
    assert!(code == 0 || code == 3, "exit {code}");
}

#[test]
fn a_cylinder_at_100_ends_its_certificate() {
    let dir = tempfile::tempdir().unwrap();
    let input = cylinder(
        dir.path(),
        100.0,
        &[(
            12,
            [
                -100.000_088_749_999_99,
                1.224_646_799_147_353_2e-14,
                50.000_012_500_000_004,
            ],
        )],
    );
    let code = simplify_within(&input, "3.0625e-10", Duration::from_secs(120));
    assert!(code == 0 || code == 3, "exit {code}");
}
