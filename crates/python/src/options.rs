//! Arguments as Python passes them: epsilons (a number or the command line's string syntax),
//! named choices, counts; and the defaults, read from `envelope::defaults` and handed to the
//! Python layer, which shows them in its signatures instead of restating them.

use envelope::advanced::simplify::policy::Exhaustive;
use envelope::{
    EnvelopeMethod, Epsilon, Error, HoleFilling, LodRule, Method, Placement, Screen,
    TessellationSource, defaults,
};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyString};

use crate::errors::from_error;

/// An epsilon (or alpha): a number is an absolute length; a string is parsed as the command
/// line parses it (`"0.01"`, `"1%"`, `"1/64%"`), with its messages.
pub(crate) fn epsilon(value: &Bound<'_, PyAny>) -> PyResult<Epsilon> {
    if let Ok(s) = value.cast::<PyString>() {
        return s.to_str()?.parse::<Epsilon>().map_err(from_error);
    }
    if !value.is_instance_of::<PyBool>()
        && let Ok(x) = value.extract::<f64>()
    {
        return Ok(Epsilon::absolute(x));
    }
    Err(from_error(Error::InvalidEpsilon(format!(
        "expected a number or a string such as \"1%\", got {}",
        value.get_type().name()?
    ))))
}

/// A list of epsilons: a sequence of numbers and strings, or one comma-separated string
/// (the command line's `--epsilons`).
pub(crate) fn epsilons(value: &Bound<'_, PyAny>) -> PyResult<Vec<Epsilon>> {
    if let Ok(s) = value.cast::<PyString>() {
        return s
            .to_str()?
            .split(',')
            .map(|item| item.trim().parse::<Epsilon>().map_err(from_error))
            .collect();
    }
    value
        .try_iter()
        .map_err(|_| {
            from_error(Error::InvalidEpsilon(format!(
                "expected a list of epsilons or a comma-separated string, got {}",
                value
                    .get_type()
                    .name()
                    .map_or_else(|_| "?".into(), |n| n.to_string())
            )))
        })?
        .map(|item| epsilon(&item?))
        .collect()
}

/// A choice's values by name, as the command line spells them (`_` for its `-`).
type Table<T> = [(&'static str, T)];

const ENVELOPES: &Table<EnvelopeMethod> = &[
    ("analytical", EnvelopeMethod::Analytical),
    ("numerical", EnvelopeMethod::Numerical),
    ("auto", EnvelopeMethod::Auto),
];

/// The library's names ([`Placement::as_str`]).
const PLACEMENTS: &Table<Placement> = &{
    let mut t = [("", Placement::Subset); 4];
    let mut i = 0;
    while i < t.len() {
        t[i] = (Placement::ALL[i].as_str(), Placement::ALL[i]);
        i += 1;
    }
    t
};

const RULES: &Table<LodRule> = &[("cumulative", LodRule::Cumulative), ("sum", LodRule::Sum)];

const SOURCES: &Table<TessellationSource> = &[
    ("sharp_edges", TessellationSource::SharpEdges),
    ("prism_union", TessellationSource::PrismUnion),
    ("closing", TessellationSource::Closing),
];

/// The library's names ([`Method::as_str`]).
const METHODS: &Table<Method> = &{
    let mut t = [("", Method::Local); 3];
    let mut i = 0;
    while i < t.len() {
        t[i] = (Method::ALL[i].as_str(), Method::ALL[i]);
        i += 1;
    }
    t
};

/// The hole fillers: the paper's greedy pass, or every triangulation up to the engine's
/// hole size, greedy above (as the command line's `--hole-filling exhaustive`).
fn hole_fillings() -> [(&'static str, HoleFilling); 2] {
    [
        ("greedy", defaults::hole_filling()),
        (
            "exhaustive",
            HoleFilling::Exhaustive {
                max_vertices: Exhaustive::default().max_vertices,
            },
        ),
    ]
}

/// The value named `given` (`None`: `default`); `what` names the argument in the message.
fn choose<T: Copy>(what: &str, table: &Table<T>, given: Option<&str>, default: T) -> PyResult<T> {
    let Some(given) = given else {
        return Ok(default);
    };
    table
        .iter()
        .find(|(name, _)| *name == given)
        .map(|&(_, value)| value)
        .ok_or_else(|| {
            let names: Vec<&str> = table.iter().map(|(name, _)| *name).collect();
            from_error(Error::InvalidArgument(format!(
                "{what} must be one of {}; got {given:?}",
                names.join(", ")
            )))
        })
}

/// The name of `value` in `table`.
fn name_of<T: PartialEq>(table: &Table<T>, value: &T) -> &'static str {
    table
        .iter()
        .find(|(_, v)| v == value)
        .map_or("?", |(name, _)| name)
}

pub(crate) fn method(given: Option<&str>) -> PyResult<Method> {
    choose("method", METHODS, given, defaults::METHOD)
}

pub(crate) fn envelope_method(given: Option<&str>) -> PyResult<EnvelopeMethod> {
    choose("envelope", ENVELOPES, given, defaults::ENVELOPE_METHOD)
}

pub(crate) fn placement(given: Option<&str>) -> PyResult<Placement> {
    choose("placement", PLACEMENTS, given, defaults::PLACEMENT)
}

pub(crate) fn hole_filling(given: Option<&str>) -> PyResult<HoleFilling> {
    choose(
        "hole_filling",
        &hole_fillings(),
        given,
        defaults::hole_filling(),
    )
}

pub(crate) fn lod_rule(given: Option<&str>) -> PyResult<LodRule> {
    choose("rule", RULES, given, LodRule::default())
}

pub(crate) fn tessellation_source(given: Option<&str>) -> PyResult<TessellationSource> {
    choose("source", SOURCES, given, TessellationSource::default())
}

/// Worker threads: `None` is the library's default; below 1 is passed on as 0 for the
/// library to refuse with its message.
pub(crate) fn threads(given: Option<i64>) -> Option<usize> {
    given.map(|n| usize::try_from(n).unwrap_or(0))
}

/// A count that must not be negative; `what` names it.
pub(crate) fn count(what: &str, given: i64) -> PyResult<usize> {
    usize::try_from(given).map_err(|_| {
        from_error(Error::InvalidArgument(format!(
            "{what} must not be negative, got {given}"
        )))
    })
}

/// Border-tube segments: `None` keeps every border vertex; out of `u32` is out of the
/// library's range, refused with its wording.
pub(crate) fn tube_segments(given: Option<i64>) -> PyResult<Option<u32>> {
    given
        .map(|n| {
            u32::try_from(n).map_err(|_| {
                let range = defaults::TUBE_SEGMENTS_RANGE;
                from_error(Error::InvalidArgument(format!(
                    "tube segments must be in {}..={}, got {n}",
                    range.start(),
                    range.end()
                )))
            })
        })
        .transpose()
}

/// The display switching distances are computed for; each `None` is the library's.
pub(crate) fn screen(
    pixels: Option<f64>,
    resolution: Option<f64>,
    fov_degrees: Option<f64>,
) -> PyResult<Screen> {
    let d = Screen::default();
    let screen = Screen {
        pixels: pixels.unwrap_or(d.pixels),
        resolution: resolution.unwrap_or(d.resolution),
        fov_degrees: fov_degrees.unwrap_or(d.fov_degrees),
    };
    let positive = |x: f64| x.is_finite() && x > 0.0;
    for (what, ok, x) in [
        ("pixels", positive(screen.pixels), screen.pixels),
        ("resolution", positive(screen.resolution), screen.resolution),
        (
            "fov_degrees",
            positive(screen.fov_degrees) && screen.fov_degrees < 180.0,
            screen.fov_degrees,
        ),
    ] {
        if !ok {
            let range = if what == "fov_degrees" {
                "in (0, 180)"
            } else {
                "positive and finite"
            };
            return Err(from_error(Error::InvalidArgument(format!(
                "{what} must be {range}, got {x}"
            ))));
        }
    }
    Ok(screen)
}

/// Every default, by the Python argument it is the default of.
pub(crate) fn defaults_dict(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    let hole_filling = match defaults::hole_filling() {
        HoleFilling::Greedy { .. } => "greedy",
        HoleFilling::Exhaustive { .. } => "exhaustive",
    };
    let range = defaults::TUBE_SEGMENTS_RANGE;
    let screen = Screen::default();
    d.set_item("method", defaults::METHOD.as_str())?;
    d.set_item("envelope", name_of(ENVELOPES, &defaults::ENVELOPE_METHOD))?;
    d.set_item("placement", name_of(PLACEMENTS, &defaults::PLACEMENT))?;
    d.set_item("hole_filling", hole_filling)?;
    d.set_item("tube_segments", defaults::TUBE_SEGMENTS)?;
    d.set_item("tube_segments_range", (*range.start(), *range.end()))?;
    d.set_item("certify", defaults::CERTIFY)?;
    d.set_item("tolerance_phase", defaults::TOLERANCE_PHASE)?;
    d.set_item("lod_epsilons", defaults::LOD_EPSILONS)?;
    d.set_item("lod_rule", name_of(RULES, &LodRule::default()))?;
    d.set_item("pixels", screen.pixels)?;
    d.set_item("resolution", screen.resolution)?;
    d.set_item("fov_degrees", screen.fov_degrees)?;
    d.set_item("genus_beta_degrees", defaults::GENUS_BETA_DEGREES)?;
    d.set_item(
        "genus_source",
        name_of(SOURCES, &TessellationSource::default()),
    )?;
    Ok(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_default_has_a_name() {
        assert_ne!(name_of(ENVELOPES, &defaults::ENVELOPE_METHOD), "?");
        assert_ne!(name_of(PLACEMENTS, &defaults::PLACEMENT), "?");
        assert_ne!(name_of(RULES, &LodRule::default()), "?");
        assert_ne!(name_of(SOURCES, &TessellationSource::default()), "?");
        assert_eq!(
            name_of(METHODS, &defaults::METHOD),
            defaults::METHOD.as_str()
        );
    }

    #[test]
    fn method_names_are_the_library_names() {
        for (name, method) in METHODS {
            assert_eq!(Method::parse(name), Some(*method));
        }
    }

    #[test]
    fn threads_below_one_reach_the_library_as_zero() {
        assert_eq!(threads(Some(-3)), Some(0));
        assert_eq!(threads(Some(2)), Some(2));
        assert_eq!(threads(None), None);
    }
}
