//! Load benchmark for binary PLY: writes an N-face binary little-endian PLY (float xyz,
//! `uchar int` face lists) to a temporary directory, streaming it straight to disk, then loads
//! it with `envelope_io::read_path` in a child process (this program re-run with `--child`)
//! and reports the load time and the child's peak RSS (`VmHWM`) against the final array bytes
//! (24 B per vertex + 12 B per face).
//!
//! `cargo run --release -p envelope-benches --bin load_ply [-- --faces N]` (default 10 million).

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::time::Instant;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.as_slice() {
        [flag, path] if flag == "--child" => child(Path::new(path)),
        [] => parent(10_000_000),
        [flag, n] if flag == "--faces" => match n.parse() {
            Ok(n) if n >= 2 => parent(n),
            _ => usage(),
        },
        _ => usage(),
    }
}

fn usage() -> ExitCode {
    eprintln!("usage: load_ply [--faces N]   (N >= 2, default 10000000)");
    ExitCode::FAILURE
}

/// Streams a grid of `faces` triangles (two per quad, row by row) as binary PLY; returns the
/// number of vertices.
fn write_grid(path: &Path, faces: u64) -> std::io::Result<u64> {
    let quads = faces.div_ceil(2);
    let w = (quads as f64).sqrt().ceil() as u64;
    let h = quads.div_ceil(w);
    let vertices = (w + 1) * (h + 1);
    let mut out = BufWriter::with_capacity(1 << 20, File::create(path)?);
    write!(
        out,
        "ply\nformat binary_little_endian 1.0\ncomment envelope load_ply benchmark grid\n\
         element vertex {vertices}\nproperty float x\nproperty float y\nproperty float z\n\
         element face {faces}\nproperty list uchar int vertex_indices\nend_header\n"
    )?;
    for j in 0..=h {
        for i in 0..=w {
            let z = ((i * 7 + j * 13) % 17) as f32 * 0.01;
            for c in [i as f32, j as f32, z] {
                out.write_all(&c.to_le_bytes())?;
            }
        }
    }
    let mut written = 0;
    'rows: for j in 0..h {
        for i in 0..w {
            let v = |di: u64, dj: u64| ((j + dj) * (w + 1) + i + di) as i32;
            for tri in [[v(0, 0), v(1, 0), v(1, 1)], [v(0, 0), v(1, 1), v(0, 1)]] {
                if written == faces {
                    break 'rows;
                }
                out.write_all(&[3])?;
                for idx in tri {
                    out.write_all(&idx.to_le_bytes())?;
                }
                written += 1;
            }
        }
    }
    out.flush()?;
    Ok(vertices)
}

fn parent(faces: u64) -> ExitCode {
    let dir = std::env::temp_dir().join(format!("envelope-load-ply-{}", std::process::id()));
    let result = run(&dir, faces);
    let _ = std::fs::remove_dir_all(&dir);
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("load_ply: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(dir: &PathBuf, faces: u64) -> Result<(), Box<dyn std::error::Error>> {
    std::fs::create_dir_all(dir)?;
    let path = dir.join("grid.ply");
    let t = Instant::now();
    let vertices = write_grid(&path, faces)?;
    let write_secs = t.elapsed().as_secs_f64();
    let size = std::fs::metadata(&path)?.len();
    let out = Command::new(std::env::current_exe()?)
        .arg("--child")
        .arg(&path)
        .output()?;
    if !out.status.success() {
        return Err(format!("child failed: {}", String::from_utf8_lossy(&out.stderr)).into());
    }
    let stdout = String::from_utf8(out.stdout)?;
    let fields: Vec<f64> = stdout
        .split_whitespace()
        .skip_while(|w| *w != "RESULT")
        .skip(1)
        .map(str::parse)
        .collect::<Result<_, _>>()?;
    let [secs, nv, nf, hwm_kib] = fields[..] else {
        return Err(format!("unexpected child output: {stdout}").into());
    };
    assert_eq!(
        (nv as u64, nf as u64),
        (vertices, faces),
        "child read a different mesh"
    );
    let arrays = 24.0 * nv + 12.0 * nf;
    let hwm = hwm_kib * 1024.0;
    let mib = |b: f64| b / (1024.0 * 1024.0);
    println!("binary little-endian PLY load (envelope_io::read_path, child process)");
    println!("{:<28}{:>14}", "faces", nf as u64);
    println!("{:<28}{:>14}", "vertices", nv as u64);
    println!("{:<28}{:>14.1}", "file size (MiB)", mib(size as f64));
    println!("{:<28}{:>14.2}", "generate (s, parent)", write_secs);
    println!("{:<28}{:>14.3}", "load (s)", secs);
    println!(
        "{:<28}{:>14.1}",
        "load rate (MiB/s)",
        mib(size as f64) / secs
    );
    println!("{:<28}{:>14.1}", "peak RSS, VmHWM (MiB)", mib(hwm));
    println!("{:<28}{:>14.1}", "final arrays (MiB)", mib(arrays));
    println!("{:<28}{:>14.3}", "peak RSS / arrays", hwm / arrays);
    Ok(())
}

fn child(path: &Path) -> ExitCode {
    let t = Instant::now();
    let result = envelope_io::read_path(path);
    let secs = t.elapsed().as_secs_f64();
    let (soup, _report) = match result {
        Ok(r) => r,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let hwm_kib: u64 = status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .unwrap_or(0);
    println!(
        "RESULT {secs} {} {} {hwm_kib}",
        soup.num_vertices(),
        soup.num_faces()
    );
    ExitCode::SUCCESS
}
