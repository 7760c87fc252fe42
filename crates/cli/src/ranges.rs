//! Valid ranges of the numeric arguments, checked by clap value parsers before any work (an
//! out-of-range value exits 2 with clap's message, which names the flag), and the
//! resolution of lengths (`--epsilon`, `--alpha`, ...) against the input's diagonal.
//!
//! Each range is stated in the flag's `--help` text; the constants here are the one place it
//! is defined.

use envelope::advanced::mesh::TriangleSoup;
use envelope::advanced::offset::{EPSILON_SYNTAX, EpsilonField, EpsilonSpec, parse_epsilon};

/// `check --examples`: listing more than this per class is a wall of text, not a report.
pub(crate) const MAX_EXAMPLES: usize = 10_000;
/// `envelopes --tube-segments`: the library's range.
pub(crate) const TUBE_SEGMENTS: std::ops::RangeInclusive<u32> =
    envelope::defaults::TUBE_SEGMENTS_RANGE;
/// `--threads`: more workers than this only cost memory on any machine this runs on.
pub(crate) const MAX_THREADS: usize = 1024;
/// `lod --pixels` and `--resolution`: a screen wider than this is not a screen.
pub(crate) const MAX_PIXELS: f64 = 1e6;

/// A number of the given type, or a message naming the allowed syntax.
fn number<T: std::str::FromStr>(s: &str, kind: &str) -> Result<T, String> {
    s.trim().parse::<T>().map_err(|_| format!("not {kind}"))
}

/// `check --examples`: 0..=10000.
pub(crate) fn examples(s: &str) -> Result<usize, String> {
    match number::<usize>(s, "a whole number") {
        Ok(n) if n <= MAX_EXAMPLES => Ok(n),
        _ => Err(format!("must be a whole number in 0..={MAX_EXAMPLES}")),
    }
}

/// `--threads`: 1..=1024.
pub(crate) fn threads(s: &str) -> Result<usize, String> {
    match number::<usize>(s, "a whole number") {
        Ok(n) if (1..=MAX_THREADS).contains(&n) => Ok(n),
        _ => Err(format!("must be a whole number in 1..={MAX_THREADS}")),
    }
}

/// `envelopes --tube-segments`: 0 (no tubes) or 3..=64.
pub(crate) fn tube_segments(s: &str) -> Result<u32, String> {
    match number::<u32>(s, "a whole number") {
        Ok(n) if n == 0 || TUBE_SEGMENTS.contains(&n) => Ok(n),
        _ => Err(format!(
            "must be 0 (no tubes) or a whole number in {}..={}",
            TUBE_SEGMENTS.start(),
            TUBE_SEGMENTS.end()
        )),
    }
}

/// `render --view`: azimuth within one turn either way, elevation from below to above.
pub(crate) const AZIMUTH: f64 = 360.0;
/// `render --view`: looking straight up or down at most.
pub(crate) const ELEVATION: f64 = 90.0;

/// `render --view AZ,EL`: azimuth in [-360, 360], elevation in [-90, 90] degrees.
pub(crate) fn view(s: &str) -> Result<envelope_render::View, String> {
    let syntax = format!(
        "must be AZ,EL in degrees: azimuth in [-{AZIMUTH}, {AZIMUTH}], elevation in [-{ELEVATION}, {ELEVATION}] (e.g. 30,20)"
    );
    let (az, el) = s.split_once(',').ok_or_else(|| syntax.clone())?;
    let az = float_in(az, (-AZIMUTH, true), (AZIMUTH, true), "").map_err(|_| syntax.clone())?;
    let el = float_in(el, (-ELEVATION, true), (ELEVATION, true), "").map_err(|_| syntax.clone())?;
    envelope_render::View::new(az, el).map_err(|_| syntax)
}

/// `render --size WxH`: each side a whole number of pixels in 16..=8192.
pub(crate) fn size(s: &str) -> Result<envelope_render::Size, String> {
    let (lo, hi) = (envelope_render::MIN_SIDE, envelope_render::MAX_SIDE);
    let syntax =
        format!("must be WxH, each a whole number of pixels in {lo}..={hi} (e.g. 640x480)");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(|| syntax.clone())?;
    let side = |t: &str| number::<u32>(t, "a whole number").map_err(|_| syntax.clone());
    envelope_render::Size::new(side(w)?, side(h)?).map_err(|_| syntax.clone())
}

/// A finite float in the interval `lo..hi` (closed or open at each end as given), or a
/// message stating it.
fn float_in(s: &str, lo: (f64, bool), hi: (f64, bool), unit: &str) -> Result<f64, String> {
    let x = number::<f64>(s, "a number").ok().filter(|x| x.is_finite());
    let inside = x.is_some_and(|x| {
        (if lo.1 { x >= lo.0 } else { x > lo.0 }) && (if hi.1 { x <= hi.0 } else { x < hi.0 })
    });
    match x {
        Some(x) if inside => Ok(x),
        _ => Err(format!(
            "must be a number in {}{}, {}{}{unit}",
            if lo.1 { '[' } else { '(' },
            show(lo.0),
            show(hi.0),
            if hi.1 { ']' } else { ')' },
        )),
    }
}

/// `genus --beta`, `pipeline --beta`: an angle between face normals, (0, 180) degrees.
pub(crate) fn beta(s: &str) -> Result<f64, String> {
    float_in(s, (0.0, false), (180.0, false), " degrees")
}

/// `lod --fov`: (0, 180) degrees.
pub(crate) fn fov(s: &str) -> Result<f64, String> {
    float_in(s, (0.0, false), (180.0, false), " degrees")
}

/// `lod --pixels` and `--resolution`: (0, 1e6] pixels.
pub(crate) fn pixels(s: &str) -> Result<f64, String> {
    float_in(s, (0.0, false), (MAX_PIXELS, true), " pixels")
}

/// `verify --resolution`: [0, inf) (a length, or a fraction with `--relative`).
pub(crate) fn resolution(s: &str) -> Result<f64, String> {
    match number::<f64>(s, "a number") {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
        _ => Err("must be a finite number >= 0".into()),
    }
}

/// A length as the user wrote it (`0.01`, `2%`, `1/64%`), already known to be positive.
#[derive(Clone, Debug)]
pub(crate) struct Length {
    pub(crate) text: String,
    pub(crate) spec: EpsilonSpec,
}

/// `--epsilon`, `--epsilon-far`, `--alpha`: the syntax of `envelope::advanced::offset::parse_epsilon`,
/// finite and positive.
pub(crate) fn length(s: &str) -> Result<Length, String> {
    let spec = parse_epsilon(s).map_err(|e| format!("{}; {EPSILON_SYNTAX}", e.reason()))?;
    Ok(Length {
        text: s.trim().to_string(),
        spec,
    })
}

/// A comma-separated list of lengths (a newtype: clap reads a `Vec` field as repeated flags).
#[derive(Clone, Debug)]
pub(crate) struct Lengths(pub(crate) Vec<Length>);

/// `lod --epsilons`: a comma-separated list of lengths.
pub(crate) fn lengths(s: &str) -> Result<Lengths, String> {
    s.split(',')
        .enumerate()
        .map(|(i, t)| length(t).map_err(|e| format!("item {} {:?}: {e}", i + 1, t.trim())))
        .collect::<Result<_, _>>()
        .map(Lengths)
}

impl Length {
    /// The absolute length on `soup` (read from `input`); `flag` names the argument.
    pub(crate) fn resolve(
        &self,
        flag: &str,
        input: &str,
        soup: &TriangleSoup,
    ) -> Result<f64, String> {
        self.resolve_as(flag, input, soup, false)
    }

    /// As [`Length::resolve`], but a plain number is a fraction of the diagonal when
    /// `fraction` (`verify --relative`).
    pub(crate) fn resolve_as(
        &self,
        flag: &str,
        input: &str,
        soup: &TriangleSoup,
        fraction: bool,
    ) -> Result<f64, String> {
        let diagonal = soup.diagonal();
        let (v, relative) = match self.spec {
            EpsilonSpec::Absolute(x) if fraction => (x * diagonal, true),
            EpsilonSpec::Absolute(x) => (x, false),
            spec @ EpsilonSpec::PercentOfDiagonal(_) => (spec.resolve(diagonal), true),
        };
        let text = &self.text;
        if relative && diagonal == 0.0 {
            // The input is at fault, not the length: it has no extent to be a percentage of.
            return Err(format!(
                "{input}: all {} vertices are at one point (the bounding-box diagonal is zero): not acceptable input, `envelope check` lists its degeneracies",
                soup.num_vertices()
            ));
        }
        if !v.is_finite() {
            return Err(format!(
                "{flag} {text}: is not a finite length on {input} (diagonal {}); {EPSILON_SYNTAX}",
                show(diagonal)
            ));
        }
        if v <= 0.0 {
            return Err(format!(
                "{flag} {text}: is zero on {input} (diagonal {}); {EPSILON_SYNTAX}",
                show(diagonal)
            ));
        }
        Ok(v)
    }
}

/// The library's range rule for epsilons against the mesh's coordinates
/// ([`EpsilonField::evaluate`]: non-finite values refused, above the diagonal taken as the
/// diagonal, offsets lost in rounding refused), checked before work with the error naming
/// `flag` as the user wrote it.
pub(crate) fn epsilon_in_range(
    flag: &str,
    input: &str,
    field: &EpsilonField,
    soup: &TriangleSoup,
) -> Result<(), String> {
    field
        .evaluate(&soup.positions)
        .map(|_| ())
        .map_err(|e| format!("{flag}: {e} (on {input})"))
}

/// A number in its shortest round-trip form, with an exponent when very large or small
/// (so that 1e300 does not print 301 digits).
pub(crate) fn show(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 || !a.is_finite() || (1e-4..1e6).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A genus, or "undefined" (a non-orientable or non-manifold mesh).
pub(crate) fn show_genus(g: Option<u32>) -> String {
    g.map_or_else(|| "undefined".to_string(), |g| g.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_accept_their_ends_and_refuse_beyond() {
        assert_eq!(examples("10000"), Ok(10_000));
        assert!(examples("10001").is_err() && examples("-1").is_err());
        for ok in ["0", "3", "64"] {
            assert!(tube_segments(ok).is_ok(), "{ok}");
        }
        for bad in ["1", "2", "65", "4294967295", "x"] {
            assert!(tube_segments(bad).is_err(), "{bad}");
        }
        assert!(beta("0").is_err() && beta("179.5").is_ok() && beta("180").is_err());
        assert!(fov("0").is_err() && fov("179.9").is_ok() && fov("nan").is_err());
        assert!(pixels("0").is_err() && pixels("1e6").is_ok() && pixels("inf").is_err());
        assert!(resolution("0").is_ok() && resolution("-1e-9").is_err());
        for bad in ["0", "-1", "0%", "inf", "1/0", "", "abc"] {
            let e = length(bad).unwrap_err();
            assert!(!e.contains("epsilon"), "{bad}: {e}");
        }
        assert!(lengths("1%, 2").is_ok() && lengths("1%,,2").is_err());
        assert!(view("30,20").is_ok() && view("-360,-90").is_ok() && view("0,90").is_ok());
        for bad in ["30", "30,91", "361,0", "nan,0", "1,2,3", ""] {
            assert!(view(bad).is_err(), "{bad}");
        }
        assert!(size("16x8192").is_ok() && size("640X480").is_ok());
        for bad in ["15x100", "100x8193", "100", "x", "-5x10", "1e3x100"] {
            assert!(size(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn lengths_resolve_against_the_diagonal() {
        let point = TriangleSoup::from_raw(&[[1.0, 1.0, 1.0]; 3], &[[0, 1, 2]]);
        let e = length("1%").unwrap().resolve("--alpha", "p.off", &point);
        assert!(e.unwrap_err().contains("all 3 vertices are at one point"));
        let tri = TriangleSoup::from_raw(
            &[[0.0, 0.0, 0.0], [3.0, 0.0, 0.0], [0.0, 4.0, 0.0]],
            &[[0, 1, 2]],
        );
        assert_eq!(length("10%").unwrap().resolve("-", "t", &tri), Ok(0.5));
        assert!(length("1e-323%").unwrap().resolve("-", "t", &tri).is_err());
        assert_eq!(show(1e300), "1e300");
        assert_eq!(show(0.25), "0.25");
    }
}
