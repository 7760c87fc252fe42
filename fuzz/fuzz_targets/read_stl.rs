//! Feeds arbitrary bytes to the STL reader. Whenever it accepts them, checks the reader's
//! guarantees against independent oracles: every index in range, every coordinate accepted by
//! `check_coordinate`, at least one face, a consistent report, and writing the soup (in the
//! format read and in binary PLY) then reading it back gives the same soup bit for bit.
//! A failure prints the input as a pasteable Rust byte string.
#![no_main]

use envelope_io::{Format, PlyEncoding, StlEncoding, read, write};
use envelope_mesh::{TriangleSoup, check_coordinate};

const FORMAT: Format = Format::Stl(StlEncoding::Binary);

fn bits(s: &TriangleSoup) -> (Vec<[u64; 3]>, Vec<[u32; 3]>) {
    let p = s
        .positions
        .iter()
        .map(|p| p.to_array().map(f64::to_bits))
        .collect();
    (p, s.faces.iter().map(|f| f.map(|v| v.0)).collect())
}

fn check(data: &[u8]) -> Result<(), String> {
    let Ok((soup, report)) = read(data, FORMAT) else {
        return Ok(());
    };
    if !soup.indices_in_range() {
        return Err("index out of range".into());
    }
    if soup.faces.is_empty() {
        return Err("no faces accepted".into());
    }
    if let Some(x) = soup
        .positions
        .iter()
        .flat_map(|p| p.to_array())
        .find(|&x| check_coordinate(x).is_err())
    {
        return Err(format!("coordinate {x:e} accepted"));
    }
    if (report.vertices, report.triangles) != (soup.positions.len() as u64, soup.faces.len() as u64)
    {
        return Err("report counts disagree with the soup".into());
    }
    for format in [report.format, Format::Ply(PlyEncoding::BinaryLittleEndian)] {
        let mut bytes = Vec::new();
        write(&mut bytes, &soup, format).map_err(|e| format!("write {format}: {e}"))?;
        let (back, _) = read(&bytes[..], format).map_err(|e| format!("re-read {format}: {e}"))?;
        if bits(&back) != bits(&soup) {
            return Err(format!("{format} round trip changed the soup"));
        }
    }
    Ok(())
}

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Err(why) = check(data) {
        let escaped: String = data
            .iter()
            .flat_map(|&b| std::ascii::escape_default(b))
            .map(char::from)
            .collect();
        panic!("{why}\nlet data: &[u8] = b\"{escaped}\";");
    }
});
