//! Shared pieces of the fuzz targets: the reader oracle and the byte decoder for geometric
//! inputs. Each target in `fuzz_targets/` is a few lines on top of these.
#![forbid(unsafe_code)]

pub mod input;

use envelope_io::{Format, PlyEncoding, read, write};
use envelope_mesh::{TriangleSoup, check_coordinate};

/// Positions as bit patterns and faces as raw indices: compares soups bit for bit.
fn bits(s: &TriangleSoup) -> (Vec<[u64; 3]>, Vec<[u32; 3]>) {
    let p = s
        .positions
        .iter()
        .map(|p| p.to_array().map(f64::to_bits))
        .collect();
    (p, s.faces.iter().map(|f| f.map(|v| v.0)).collect())
}

/// Feeds `data` to the reader of `format`. Whenever it accepts them, checks the reader's
/// guarantees against independent oracles: every index in range, every coordinate accepted by
/// `check_coordinate`, at least one face, a consistent report, and writing the soup (in the
/// format read and in binary PLY) then reading it back gives the same soup bit for bit.
pub fn check_reader(data: &[u8], format: Format) -> Result<(), String> {
    let Ok((soup, report)) = read(data, format) else {
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

/// Panics with `why` and `data` as a pasteable Rust byte string.
pub fn fail_with_input(why: &str, data: &[u8]) -> ! {
    let escaped: String = data
        .iter()
        .flat_map(|&b| std::ascii::escape_default(b))
        .map(char::from)
        .collect();
    panic!("{why}\nlet data: &[u8] = b\"{escaped}\";");
}
