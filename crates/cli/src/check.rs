//! `envelope check`: counts, topology and every degeneracy class of a mesh.

use std::fmt::Write as _;
use std::path::Path;
use std::process::ExitCode;

use envelope::advanced::check::{
    CheckOptions, CheckReport, DegeneracyClass, Element, Severity, check,
};
use envelope::advanced::io::{ReadReport, read_path};

pub(crate) fn run_check(input: &Path, json: bool, examples: usize) -> Result<ExitCode, String> {
    let (soup, read_report) = read_path(input).map_err(|e| e.to_string())?;
    let options = CheckOptions {
        max_examples: examples,
        ..CheckOptions::default()
    };
    let report = check(&soup, &options);
    if json {
        let mut v = report.to_json();
        v["file"] = input.display().to_string().into();
        v["format"] = read_report.format.to_string().into();
        v["polygons_triangulated"] = read_report.polygons_triangulated.into();
        v["read_notes"] = read_report
            .to_string()
            .lines()
            .skip(1)
            .collect::<Vec<_>>()
            .into();
        println!(
            "{}",
            serde_json::to_string_pretty(&v).map_err(|e| e.to_string())?
        );
    } else {
        print!("{}", render_text(input, &read_report, &report));
    }
    Ok(if report.acceptable() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn yes_no(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

fn describe(e: &Element) -> String {
    let p = |p: glam::DVec3| format!("({}, {}, {})", p.x, p.y, p.z);
    match e {
        Element::Vertex { vertex, position } => format!("{vertex} at {}", p(*position)),
        Element::VertexGroup { vertices, position } => {
            let ids: Vec<String> = vertices.iter().map(ToString::to_string).collect();
            format!("{} at {}", ids.join(" "), p(*position))
        }
        Element::Face {
            face,
            vertices: [a, b, c],
            quality,
        } => match quality {
            Some(q) => format!("{face} [{a} {b} {c}] quality {q:.2e}"),
            None => format!("{face} [{a} {b} {c}]"),
        },
        Element::FacePair { faces: [f, g] } => format!("{f} x {g}"),
        Element::Edge {
            edge: [a, b],
            faces,
        } => {
            let fs: Vec<String> = faces.iter().map(ToString::to_string).collect();
            format!("{a}-{b} in {}", fs.join(" "))
        }
        Element::VertexOnEdge {
            vertex,
            position,
            edge: [a, b],
        } => {
            format!("{vertex} at {} inside {a}-{b}", p(*position))
        }
    }
}

fn render_text(input: &Path, read: &ReadReport, r: &CheckReport) -> String {
    let mut s = String::new();
    let genus = r
        .genus
        .map_or_else(|| "undefined".to_owned(), |g| g.to_string());
    let _ = writeln!(s, "file        {}", input.display());
    for line in read.to_string().lines() {
        let _ = writeln!(s, "read        {line}");
    }
    let _ = writeln!(
        s,
        "counts      {} vertices, {} faces, {} edges, {} border loops, {} components",
        r.vertices, r.faces, r.edges, r.border_loops, r.components
    );
    let _ = writeln!(
        s,
        "topology    euler {}, genus {genus}, manifold {}, orientable {}",
        r.euler,
        yes_no(r.manifold),
        yes_no(r.orientable)
    );
    let _ = writeln!(s, "degeneracies");
    for class in DegeneracyClass::ALL {
        let Some(f) = r.degeneracies.get(&class) else {
            continue;
        };
        let severity = match class.severity() {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        if f.undecided {
            let _ = writeln!(
                s,
                "  {:<26} {:>8}  {severity:<7}  undecided: faces stacked too densely to test every pair",
                class.key(),
                "?"
            );
            continue;
        }
        let _ = write!(s, "  {:<26} {:>8}  {severity:<7}", class.key(), f.count);
        if f.count > 0 {
            let ex: Vec<String> = f.examples.iter().map(describe).collect();
            let more = if f.count > ex.len() { ", ..." } else { "" };
            let _ = write!(s, "  {}{more}", ex.join(", "));
        }
        s.push('\n');
    }
    let errors: Vec<String> = r
        .errors()
        .map(|c| match r.finding(c).undecided {
            true => format!("{} (undecided)", c.key()),
            false => c.key().to_owned(),
        })
        .collect();
    if errors.is_empty() {
        let _ = writeln!(s, "verdict     acceptable input");
    } else {
        let _ = writeln!(s, "verdict     not acceptable: {}", errors.join(", "));
        if r.errors()
            .all(|c| envelope::advanced::simplify::CROSSINGS.contains(&c))
            && r.errors().all(|c| !r.finding(c).undecided)
        {
            let _ = writeln!(
                s,
                "            (simplify keeps the faces where the input meets itself as they are and simplifies the rest)"
            );
        }
    }
    s
}
