//! The PLY writer: `double` positions and `int` (or `uint`) index lists; with attributes,
//! per-vertex `u v`, `nx ny nz` (`double`), `red green blue alpha` and `quality` (`float`,
//! rounded to nearest: a caller that needs a bound rounds it first) columns, and header
//! `comment` lines.
//!
//! PLY holds one value of each attribute per vertex, so a vertex whose corners carry
//! different values (a seam) is written once per distinct combination of texture
//! coordinate, normal and colour, and the faces name those copies: positions are unchanged,
//! but the copies are separate vertices to any reader (`envelope repair` welds them back,
//! carrying the attributes). The copies of a vertex follow each other in the input's vertex
//! order (each copy in order of its first corner), so a mesh without seams keeps its
//! numbering. A vertex no face uses is written with zero values (alpha 1). Colours are written
//! as `uchar` when every component is exactly `k / 255` for an integer `k`, else as `double`.

use std::collections::HashMap;
use std::io::{self, Write};

use envelope_mesh::{Attributes, TriangleSoup, VertexId};
use glam::DVec3;

use crate::PlyEncoding;

/// Per-vertex attribute columns, each absent or one value per written vertex.
#[derive(Default)]
struct Columns {
    texcoords: Option<Vec<[f64; 2]>>,
    normals: Option<Vec<[f64; 3]>>,
    colors: Option<Vec<[f64; 4]>>,
    quality: Option<Vec<[f64; 1]>>,
}

/// How one value after x y z is written.
#[derive(Clone, Copy, PartialEq)]
enum Column {
    Double,
    /// A colour component that is exactly `k / 255`.
    Uchar,
    Float,
}

pub(crate) fn write<W: Write>(
    w: &mut W,
    soup: &TriangleSoup,
    encoding: PlyEncoding,
) -> io::Result<()> {
    write_columns(
        w,
        &soup.positions,
        &soup.faces,
        &Columns::default(),
        encoding,
        &[],
    )
}

/// The colour component as a `uchar`, when it is exactly one.
fn as_uchar(c: f64) -> Option<u8> {
    let k = (c * 255.0).round();
    ((0.0..=255.0).contains(&k) && k / 255.0 == c).then_some(k as u8)
}

pub(crate) fn write_with_attributes<W: Write>(
    w: &mut W,
    soup: &TriangleSoup,
    attributes: &Attributes,
    encoding: PlyEncoding,
    comments: &[String],
) -> io::Result<()> {
    if attributes.is_empty() {
        return write_columns(
            w,
            &soup.positions,
            &soup.faces,
            &Columns::default(),
            encoding,
            comments,
        );
    }
    let (tex, normals, colors, quality) = (
        &attributes.texcoords,
        &attributes.normals,
        &attributes.colors,
        &attributes.quality,
    );
    // A written vertex: the input vertex and its corner's value bits.
    type Key = (u32, [u64; 10]);
    let key = |f: usize, k: usize, v: VertexId| -> Key {
        let mut bits = [0u64; 10];
        if let Some(t) = tex {
            for (b, x) in bits[..2].iter_mut().zip(t.value(f, k)) {
                *b = x.to_bits();
            }
        }
        if let Some(n) = normals {
            for (b, x) in bits[2..5].iter_mut().zip(n.value(f, k)) {
                *b = x.to_bits();
            }
        }
        if let Some(c) = colors {
            for (b, x) in bits[5..9].iter_mut().zip(c.value(f, k)) {
                *b = x.to_bits();
            }
        }
        if let Some(q) = quality {
            bits[9] = q.value(f, k)[0].to_bits();
        }
        (v.0, bits)
    };
    let mut first: HashMap<Key, u32> = HashMap::new();
    let mut keys: Vec<Key> = Vec::new();
    let mut corner_key: Vec<[u32; 3]> = Vec::with_capacity(soup.num_faces());
    for (f, face) in soup.faces.iter().enumerate() {
        let mut ids = [0u32; 3];
        for (k, &v) in face.iter().enumerate() {
            let key = key(f, k, v);
            ids[k] = *first.entry(key).or_insert_with(|| {
                keys.push(key);
                (keys.len() - 1) as u32
            });
        }
        corner_key.push(ids);
    }
    // Unused vertices keep their place with zero values.
    let mut used = vec![false; soup.num_vertices()];
    for &(v, _) in &keys {
        used[v as usize] = true;
    }
    let unused = (0..soup.num_vertices() as u32).filter(|&v| !used[v as usize]);
    let mut written: Vec<(u32, Option<u32>)> = keys
        .iter()
        .enumerate()
        .map(|(i, &(v, _))| (v, Some(i as u32)))
        .chain(unused.map(|v| (v, None)))
        .collect();
    // By input vertex, then by first corner (a stable sort keeps the latter).
    written.sort_by_key(|&(v, _)| v);
    let mut new_of_key = vec![0u32; keys.len()];
    for (new, &(_, key)) in written.iter().enumerate() {
        if let Some(k) = key {
            new_of_key[k as usize] = new as u32;
        }
    }
    let positions: Vec<DVec3> = written
        .iter()
        .map(|&(v, _)| soup.positions[v as usize])
        .collect();
    let faces: Vec<[VertexId; 3]> = corner_key
        .iter()
        .map(|ids| ids.map(|i| VertexId(new_of_key[i as usize])))
        .collect();
    // The value of a written vertex: from any corner with its key.
    let mut corner_of_key = vec![(0usize, 0usize); keys.len()];
    for (f, ids) in corner_key.iter().enumerate().rev() {
        for (k, &i) in ids.iter().enumerate() {
            corner_of_key[i as usize] = (f, k);
        }
    }
    let column = |value: &dyn Fn(usize, usize) -> Vec<f64>, zero: Vec<f64>| -> Vec<Vec<f64>> {
        written
            .iter()
            .map(|&(_, key)| match key {
                Some(i) => {
                    let (f, k) = corner_of_key[i as usize];
                    value(f, k)
                }
                None => zero.clone(),
            })
            .collect()
    };
    let columns = Columns {
        texcoords: tex.as_ref().map(|t| {
            column(&|f, k| t.value(f, k).to_vec(), vec![0.0; 2])
                .into_iter()
                .map(|x| [x[0], x[1]])
                .collect()
        }),
        normals: normals.as_ref().map(|n| {
            column(&|f, k| n.value(f, k).to_vec(), vec![0.0; 3])
                .into_iter()
                .map(|x| [x[0], x[1], x[2]])
                .collect()
        }),
        colors: colors.as_ref().map(|c| {
            column(&|f, k| c.value(f, k).to_vec(), vec![0.0, 0.0, 0.0, 1.0])
                .into_iter()
                .map(|x| [x[0], x[1], x[2], x[3]])
                .collect()
        }),
        quality: quality.as_ref().map(|q| {
            column(&|f, k| q.value(f, k).to_vec(), vec![0.0])
                .into_iter()
                .map(|x| [x[0]])
                .collect()
        }),
    };
    write_columns(w, &positions, &faces, &columns, encoding, comments)
}

fn write_columns<W: Write>(
    w: &mut W,
    positions: &[DVec3],
    faces: &[[VertexId; 3]],
    columns: &Columns,
    encoding: PlyEncoding,
    comments: &[String],
) -> io::Result<()> {
    let enc = match encoding {
        PlyEncoding::Ascii => "ascii",
        PlyEncoding::BinaryLittleEndian => "binary_little_endian",
        PlyEncoding::BinaryBigEndian => "binary_big_endian",
    };
    let index_type = if positions.len() <= i32::MAX as usize {
        "int"
    } else {
        "uint"
    };
    let uchar_colors = columns
        .colors
        .as_ref()
        .is_some_and(|c| c.iter().flatten().all(|&x| as_uchar(x).is_some()));
    write!(w, "ply\nformat {enc} 1.0\ncomment written by envelope-io\n")?;
    for c in comments {
        // A line break would end the comment and start a header line of its own.
        let line: String = c
            .chars()
            .map(|ch| if ch == '\n' || ch == '\r' { ' ' } else { ch })
            .collect();
        writeln!(w, "comment {line}")?;
    }
    write!(
        w,
        "element vertex {}\nproperty double x\nproperty double y\nproperty double z\n",
        positions.len(),
    )?;
    if columns.texcoords.is_some() {
        write!(w, "property double u\nproperty double v\n")?;
    }
    if columns.normals.is_some() {
        write!(
            w,
            "property double nx\nproperty double ny\nproperty double nz\n"
        )?;
    }
    if columns.colors.is_some() {
        let t = if uchar_colors { "uchar" } else { "double" };
        for c in ["red", "green", "blue", "alpha"] {
            writeln!(w, "property {t} {c}")?;
        }
    }
    if columns.quality.is_some() {
        writeln!(w, "property float quality")?;
    }
    write!(
        w,
        "element face {}\nproperty list uchar {index_type} vertex_indices\nend_header\n",
        faces.len()
    )?;
    // The values after x y z of vertex `v`, and how each is written.
    let color = if uchar_colors {
        Column::Uchar
    } else {
        Column::Double
    };
    let extra = |v: usize, out: &mut Vec<(f64, Column)>| {
        out.clear();
        if let Some(t) = &columns.texcoords {
            out.extend(t[v].iter().map(|&x| (x, Column::Double)));
        }
        if let Some(n) = &columns.normals {
            out.extend(n[v].iter().map(|&x| (x, Column::Double)));
        }
        if let Some(c) = &columns.colors {
            out.extend(c[v].iter().map(|&x| (x, color)));
        }
        if let Some(q) = &columns.quality {
            out.push((q[v][0], Column::Float));
        }
    };
    let mut values = Vec::new();
    match encoding {
        PlyEncoding::Ascii => {
            for (v, p) in positions.iter().enumerate() {
                write!(w, "{:?} {:?} {:?}", p.x, p.y, p.z)?;
                extra(v, &mut values);
                for &(x, column) in &values {
                    match (column, as_uchar(x)) {
                        (Column::Uchar, Some(k)) => write!(w, " {k}")?,
                        (Column::Float, _) => write!(w, " {:?}", x as f32)?,
                        _ => write!(w, " {x:?}")?,
                    }
                }
                writeln!(w)?;
            }
            for f in faces {
                writeln!(w, "3 {} {} {}", f[0].0, f[1].0, f[2].0)?;
            }
        }
        PlyEncoding::BinaryLittleEndian | PlyEncoding::BinaryBigEndian => {
            let be = encoding == PlyEncoding::BinaryBigEndian;
            let mut rec = Vec::with_capacity(24 + 9 * 8);
            for (v, p) in positions.iter().enumerate() {
                rec.clear();
                extra(v, &mut values);
                let all = p.to_array().map(|x| (x, Column::Double));
                for &(x, column) in all.iter().chain(&values) {
                    match (column, as_uchar(x)) {
                        (Column::Uchar, Some(k)) => rec.push(k),
                        (Column::Float, _) if be => {
                            rec.extend_from_slice(&(x as f32).to_be_bytes());
                        }
                        (Column::Float, _) => rec.extend_from_slice(&(x as f32).to_le_bytes()),
                        _ if be => rec.extend_from_slice(&x.to_be_bytes()),
                        _ => rec.extend_from_slice(&x.to_le_bytes()),
                    }
                }
                w.write_all(&rec)?;
            }
            let mut rec = [0u8; 13];
            rec[0] = 3;
            for f in faces {
                for (k, v) in f.iter().enumerate() {
                    let b = if be {
                        v.0.to_be_bytes()
                    } else {
                        v.0.to_le_bytes()
                    };
                    rec[1 + 4 * k..5 + 4 * k].copy_from_slice(&b);
                }
                w.write_all(&rec)?;
            }
        }
    }
    Ok(())
}
