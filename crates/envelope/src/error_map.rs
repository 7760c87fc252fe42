//! Error maps: `approx` coloured by the certified bounds of its distance to `orig`
//! ([`envelope_verify::ErrorMap`]), for a viewer.

use std::path::Path;

use envelope_io::{Format, PlyEncoding, write_path_with_comments};
use envelope_render::ramp::{normalize, viridis};
use envelope_verify::{Certificate, Options, certify};

use crate::{Attributes, Epsilon, Error, Mesh, Wedges};

/// [`verify`](crate::verify) that also keeps the certified bounds of every face, both ways,
/// and of every vertex of `approx` ([`Certificate::map`]; see
/// [`envelope_verify`'s error maps](envelope_verify#error-maps) for what they guarantee). The
/// verdict is the same; the map costs a few times the plain verification.
///
/// ```
/// use envelope::{Epsilon, Verdict};
/// let cup = envelope::Mesh::demo();
/// let certificate = envelope::verify_with_map(&cup, &cup, Epsilon::percent(0.1))?;
/// assert_eq!(certificate.verdict, Verdict::Holds);
/// let map = certificate.map.as_ref().unwrap();
/// assert_eq!(map.approx_vertices.len(), cup.num_vertices());
/// assert_eq!(map.max_vertex_value(), 0.0); // the same mesh: every face is shared
/// # Ok::<(), envelope::Error>(())
/// ```
///
/// # Errors
/// As [`verify`](crate::verify).
pub fn verify_with_map(orig: &Mesh, approx: &Mesh, epsilon: Epsilon) -> Result<Certificate, Error> {
    let eps = crate::oracle::resolve(orig, epsilon)?;
    let options = Options {
        allow_input_intersections: true,
        map: true,
        ..Options::new(eps)
    };
    Ok(certify(orig.soup(), approx.soup(), &options))
}

/// The smallest `f32` value at least `x` (for `x >= 0`), as f64: a bound stays a bound when
/// written as a PLY `float`. Beyond the `f32` range (an unbounded face), the largest `f32`.
fn up_to_f32(x: f64) -> f64 {
    let y = x as f32;
    if !y.is_finite() {
        return f64::from(f32::MAX);
    }
    if f64::from(y) >= x {
        f64::from(y)
    } else {
        // Rounded down, and x >= 0: the next float up is the smallest one above x.
        f64::from(f32::from_bits(y.to_bits() + 1))
    }
}

/// `approx` with its error map as attributes: the vertex [`quality`](Attributes::quality) is
/// the certified bound of [`ErrorMap::approx_vertices`](envelope_verify::ErrorMap), rounded up
/// to the next `f32` (so that a PLY `float` still bounds the distance; an infinite bound,
/// which only a face no bound could be certified for has, becomes the largest `f32`), and the
/// colours are the [viridis](envelope_render::ramp::viridis) ramp over `0 ..= epsilon`, so
/// maps of different meshes at one epsilon compare, and anything at or above epsilon (only
/// where the certificate fails) has the top colour. `approx`'s own attributes are not kept.
///
/// ```
/// use envelope::{Epsilon, Mesh};
/// let cup = Mesh::demo();
/// let certificate = envelope::verify_with_map(&cup, &cup, Epsilon::percent(0.1))?;
/// let map = envelope::error_map(&cup, &certificate)?;
/// let quality = map.attributes().quality.as_ref().unwrap();
/// assert_eq!(quality.value(0, 0), [0.0]);
/// assert!(map.attributes().colors.is_some());
/// # Ok::<(), envelope::Error>(())
/// ```
///
/// # Errors
/// [`Error::InvalidArgument`] when the certificate has no map (see [`verify_with_map`]) or its
/// map is not of a mesh with `approx`'s vertex count.
pub fn error_map(approx: &Mesh, certificate: &Certificate) -> Result<Mesh, Error> {
    let Some(map) = &certificate.map else {
        return Err(Error::InvalidArgument(
            "the certificate has no error map (certify with the map option)".into(),
        ));
    };
    if map.approx_vertices.len() != approx.num_vertices() {
        return Err(Error::InvalidArgument(format!(
            "the error map has {} vertices, the mesh {}",
            map.approx_vertices.len(),
            approx.num_vertices()
        )));
    }
    let eps = certificate.epsilon;
    let quality: Vec<[f64; 1]> = map
        .approx_vertices
        .iter()
        .map(|&x| [up_to_f32(x)])
        .collect();
    let colors: Vec<[f64; 4]> = map
        .approx_vertices
        .iter()
        .map(|&x| {
            let [r, g, b] = viridis(normalize(x, 0.0, eps));
            [
                f64::from(r) / 255.0,
                f64::from(g) / 255.0,
                f64::from(b) / 255.0,
                1.0,
            ]
        })
        .collect();
    // One value per vertex: a corner's value index is its vertex.
    let corners: Vec<[u32; 3]> = approx.soup().faces.iter().map(|f| f.map(|v| v.0)).collect();
    let attributes = Attributes {
        quality: Some(Wedges {
            values: quality,
            corners: corners.clone(),
        }),
        colors: Some(Wedges {
            values: colors,
            corners,
        }),
        ..Attributes::default()
    };
    Ok(approx.clone().with_attributes(attributes)?)
}

/// The PLY header comments of an error map: what `quality` is and the ramp's range.
#[must_use]
pub(crate) fn error_map_comments(certificate: &Certificate) -> Vec<String> {
    let eps = certificate.epsilon;
    vec![
        "quality: certified upper bound of the distance to ORIG of the surface around each \
         vertex (the largest bound of its faces), rounded up to float"
            .into(),
        format!("epsilon {eps:?}"),
        format!(
            "verdict {} (approx_to_orig {})",
            certificate.verdict.as_str(),
            certificate.approx_to_orig.verdict.as_str()
        ),
        format!("ramp viridis 0 {eps:?}"),
        "ramp range: 0 to epsilon; epsilon and above have the top colour".into(),
    ]
}

/// Writes [`error_map`] as a binary PLY file (vertex `quality` and colours, the ramp's range
/// in header comments such as `comment ramp viridis 0 <epsilon>`), through a temporary file
/// renamed into place only when complete.
///
/// ```
/// use envelope::{Epsilon, Mesh};
/// let cup = Mesh::demo();
/// let certificate = envelope::verify_with_map(&cup, &cup, Epsilon::percent(0.1))?;
/// let path = std::env::temp_dir().join("envelope-doc-map.ply");
/// envelope::save_error_map(&cup, &certificate, &path)?;
/// let back = envelope::load(&path)?;
/// assert!(back.attributes().quality.is_some());
/// # std::fs::remove_file(&path).ok();
/// # Ok::<(), envelope::Error>(())
/// ```
///
/// # Errors
/// As [`error_map`]; [`Error::InvalidArgument`] when `path` is not a `.ply` file;
/// [`Error::Write`] when writing fails.
pub fn save_error_map(
    approx: &Mesh,
    certificate: &Certificate,
    path: impl AsRef<Path>,
) -> Result<(), Error> {
    let path = path.as_ref();
    if !matches!(Format::from_path(path), Some(Format::Ply(_))) {
        return Err(Error::InvalidArgument(format!(
            "{}: an error map is a PLY file (.ply)",
            path.display()
        )));
    }
    let map = error_map(approx, certificate)?;
    write_path_with_comments(
        path,
        map.soup(),
        map.attributes(),
        Format::Ply(PlyEncoding::BinaryLittleEndian),
        &error_map_comments(certificate),
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_up_to_f32_never_lowers() {
        for x in [
            0.0,
            1e-300,
            0.1,
            1.0 / 3.0,
            1.0,
            2.5e10,
            1e300,
            f64::INFINITY,
        ] {
            let y = up_to_f32(x);
            assert_eq!(f64::from(y as f32), y, "{x}: not a float");
            assert!(y >= x || x > f64::from(f32::MAX), "{x} -> {y}");
            if x <= f64::from(f32::MAX) {
                // The smallest such float: the one below is below x.
                let below = f32::from_bits((y as f32).to_bits().saturating_sub(1));
                assert!(y == 0.0 || f64::from(below) < x, "{x} -> {y}");
            }
        }
    }
}
