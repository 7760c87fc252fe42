//! `envelope lod IN OUTDIR`: a chain of levels of detail with nested vertex sets (Cohen et al.
//! 7.2), each certified against the original at its cumulative bound.
//!
//! Writes `OUTDIR/level-0.off` (the input), `level-1.off` ... and `summary.json`. The rule
//! for the cumulative bound and the switching-distance formula
//! `d = eps * W / (2 * P * tan(fov / 2))` are documented in `envelope::advanced::simplify::lod`.
//!
//! Exit codes: 0 every level certified (or certification skipped), 1 a level violates its
//! bound, 2 bad input or arguments, 3 a certificate is undecided. Every file is checked
//! before any work and all are put in place together at the end (`crate::outputs`): on exit 2
//! OUTDIR is left as it was; on exit 1 and 3 every file is written (summary.json says which
//! level failed); a missing OUTDIR is created (not its parents).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use envelope::advanced::io::Format;
use envelope::advanced::mesh::TriangleSoup;
use envelope::advanced::simplify::DriverError;
use envelope::{
    EnvelopeMethod, Epsilon, Error, HoleFilling, Level, Lod, LodRule, Mesh, Screen, Verdict,
    defaults,
};
use serde_json::json;

use crate::outputs::{Plan, Staging};
use crate::ranges::{self, Length, Lengths};
use crate::scene::{LodJob, ScopeArg};
use crate::simplify::{Bar, FillArg, MethodArg};

/// The paper's bunny epsilons (Table 1, Figure 11): 1/64 % ... 1 % of the diagonal.
pub(crate) const DEFAULT_EPSILONS: &str = defaults::LOD_EPSILONS;

/// How the requested epsilons become bounds.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub(crate) enum RuleArg {
    /// Each epsilon is the level's bound to the original; steps are the differences.
    Cumulative,
    /// Each epsilon is a step; the bound is the running sum (the paper's 7.2).
    Sum,
}

/// Arguments of `envelope lod`.
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Input mesh (OBJ, OFF, PLY, STL); must pass `envelope check`.
    input: PathBuf,
    /// Output directory: created if missing (its parent must exist); files in it are
    /// replaced only when the command completes. For a glTF IN (.glb, .gltf): the output
    /// file OUT.glb or OUT.gltf, the levels as MSFT_lod nodes.
    out_dir: PathBuf,
    /// Comma-separated epsilons, each > 0 (`1/64%`, `0.5%`, or absolute lengths), increasing.
    #[arg(long, default_value = DEFAULT_EPSILONS, value_parser = ranges::lengths, allow_hyphen_values = true)]
    epsilons: Lengths,
    /// How the epsilons become bounds to the original.
    #[arg(long, value_enum, default_value_t = RuleArg::Cumulative)]
    rule: RuleArg,
    /// Tolerated screen error in pixels, for switching distances: (0, 1e6].
    #[arg(long, default_value_t = 1.0, value_parser = ranges::pixels, allow_hyphen_values = true)]
    pixels: f64,
    /// Screen width in pixels, for switching distances: (0, 1e6].
    #[arg(long, default_value_t = 1920.0, value_parser = ranges::pixels, allow_hyphen_values = true)]
    resolution: f64,
    /// Horizontal field of view in degrees, for switching distances: (0, 180).
    #[arg(long, default_value_t = 60.0, value_parser = ranges::fov, allow_hyphen_values = true)]
    fov: f64,
    /// Envelope method.
    #[arg(long, value_enum, default_value_t = MethodArg::default_())]
    envelope: MethodArg,
    /// Hole filling.
    #[arg(long, value_enum, default_value_t = FillArg::default_())]
    hole_filling: FillArg,
    /// Repair IN in memory first, without moving its surface (`envelope repair`); level 0 is
    /// the repaired IN (the same point set) and summary.json's `repair` lists the changes.
    #[arg(long)]
    repair: bool,
    /// Skip the certificates against the original.
    #[arg(long)]
    no_verify: bool,
    /// glTF input: what a relative epsilon is a part of (each primitive's diagonal, or the
    /// scene's in world space).
    #[arg(long, value_enum, default_value_t = ScopeArg::default_())]
    epsilon_scope: ScopeArg,
    /// glTF input: also write each level as its own file, OUT-level-K.EXT beside OUT.
    #[arg(long)]
    per_level_files: bool,
    /// Also write OUTDIR/correspondence-K.json for each level K: for each face of level K,
    /// the faces of level K-1 it covers (Cohen et al. 8.1, decided exactly on the step's
    /// envelope prisms), and a bound of its distance to level K-1.
    #[arg(long)]
    correspondences: bool,
    /// With --correspondences: also the faces of level 0 each face covers (`to_original`,
    /// composed through the levels between).
    #[arg(long, requires = "correspondences")]
    to_original: bool,
    /// No progress bar and no table.
    #[arg(long)]
    quiet: bool,
    /// Also write OUTDIR/lod.png (level 0 and each level, one camera, +Y up) and the chain's
    /// faces against epsilon as OUTDIR/faces-vs-epsilon.svg and .png.
    #[arg(long)]
    picture: bool,
}

/// Everything a chain needs besides the mesh.
pub(crate) struct Chain<'a> {
    pub(crate) input_label: String,
    pub(crate) out_dir: &'a Path,
    pub(crate) epsilons: &'a [Length],
    pub(crate) settings: Settings,
    pub(crate) quiet: bool,
    /// The repair report (`--repair`), for summary.json.
    pub(crate) repair: Option<serde_json::Value>,
    /// Write the pictures (`crate::render::LOD_PICTURES`), with this axis up.
    pub(crate) picture: Option<envelope_render::Up>,
}

/// How a chain is built, besides its epsilons.
pub(crate) struct Settings {
    pub(crate) rule: LodRule,
    pub(crate) envelope: EnvelopeMethod,
    pub(crate) hole_filling: HoleFilling,
    pub(crate) certify: bool,
    pub(crate) screen: Screen,
    /// Write `correspondence-K.json` files (`Some(true)`: with the map to level 0).
    pub(crate) correspondences: Option<bool>,
}

impl Default for Settings {
    /// The library's defaults.
    fn default() -> Self {
        Settings {
            rule: LodRule::default(),
            envelope: defaults::ENVELOPE_METHOD,
            hole_filling: defaults::hole_filling(),
            certify: defaults::CERTIFY,
            screen: Screen::default(),
            correspondences: None,
        }
    }
}

/// Checks OUTDIR and the files a chain of `levels` levels writes there (with
/// `correspondence-K.json` files and the pictures, when asked).
pub(crate) fn plan_chain(
    plan: &mut Plan,
    out_dir: &Path,
    levels: usize,
    correspondences: bool,
    picture: bool,
) -> Result<(), String> {
    let mut names: Vec<String> = (0..=levels).map(|i| format!("level-{i}.off")).collect();
    if correspondences {
        names.extend((1..=levels).map(correspondence_name));
    }
    names.push("summary.json".into());
    if picture {
        names.extend(crate::render::LOD_PICTURES.map(String::from));
    }
    plan.dir("OUTDIR", out_dir, &names)
}

pub(crate) fn run(args: &Args) -> Result<ExitCode, String> {
    if crate::scene::is_scene(&args.input) {
        return lod_scene(args);
    }
    if args.per_level_files {
        return Err("--per-level-files is for glTF scenes (each level is already a file)".into());
    }
    let mut plan = Plan::new(&[("IN", &args.input)]);
    plan_chain(
        &mut plan,
        &args.out_dir,
        args.epsilons.0.len(),
        args.correspondences,
        args.picture,
    )?;
    let mesh = envelope::load(&args.input).map_err(|e| e.to_string())?;
    let label = args.input.display().to_string();
    let (mesh, repair) = crate::repair::maybe(mesh, args.repair, &label, args.quiet)?;
    let settings = Settings {
        rule: rule(args.rule),
        envelope: args.envelope.method(),
        hole_filling: args.hole_filling.hole_filling(),
        certify: !args.no_verify,
        screen: Screen {
            pixels: args.pixels,
            resolution: args.resolution,
            fov_degrees: args.fov,
        },
        correspondences: args.correspondences.then_some(args.to_original),
    };
    run_chain(
        &mesh,
        Chain {
            input_label: args.input.display().to_string(),
            out_dir: &args.out_dir,
            epsilons: &args.epsilons.0,
            settings,
            quiet: args.quiet,
            repair,
            picture: args.picture.then_some(envelope_render::Up::Y),
        },
    )
}

fn rule(r: RuleArg) -> LodRule {
    match r {
        RuleArg::Cumulative => LodRule::Cumulative,
        RuleArg::Sum => LodRule::Sum,
    }
}

/// A glTF scene: one file with MSFT_lod levels (`crate::scene`).
fn lod_scene(args: &Args) -> Result<ExitCode, String> {
    crate::scene::check_flags(
        &args.out_dir,
        &[
            ("--repair", args.repair),
            ("--correspondences", args.correspondences),
            ("--picture", args.picture),
            (
                "--no-verify (f32 outputs need the certificate)",
                args.no_verify,
            ),
        ],
    )?;
    crate::scene::lod(&LodJob {
        input: &args.input,
        output: &args.out_dir,
        epsilons: &args.epsilons.0,
        scope: args.epsilon_scope,
        per_level_files: args.per_level_files,
        rule: rule(args.rule),
        envelope: args.envelope.method(),
        hole_filling: args.hole_filling.hole_filling(),
        screen: Screen {
            pixels: args.pixels,
            resolution: args.resolution,
            fov_degrees: args.fov,
        },
        quiet: args.quiet,
    })
}

/// Runs a chain on `original` and writes its files, table and summary.
pub(crate) fn run_chain(mesh: &Mesh, chain: Chain<'_>) -> Result<ExitCode, String> {
    let original = mesh.soup();
    let diagonal = original.diagonal();
    let epsilons: Vec<f64> = chain
        .epsilons
        .iter()
        .map(|l| {
            let e = l.resolve("--epsilons", &chain.input_label, original)?;
            let flag = format!("--epsilons item {}", l.text);
            let field = envelope::advanced::offset::EpsilonField::Constant(e);
            ranges::epsilon_in_range(&flag, &chain.input_label, &field, original)?;
            Ok(e)
        })
        .collect::<Result<_, String>>()?;
    if chain.settings.rule == LodRule::Cumulative {
        let e = &epsilons;
        if let Some(i) = (1..e.len()).find(|&i| e[i] <= e[i - 1]) {
            return Err(format!(
                "--epsilons: cumulative bounds must be strictly increasing, but item {} {:?} ({}) is not larger than item {} {:?} ({}) on {}; give them in increasing order, or use --rule sum for steps",
                i + 1,
                chain.epsilons[i].text,
                ranges::show(e[i]),
                i,
                chain.epsilons[i - 1].text,
                ranges::show(e[i - 1]),
                chain.input_label
            ));
        }
    }
    let dir = chain.out_dir;
    let mut staging = Staging::new();
    staging.dir(dir)?;
    let level_path = |i: usize| dir.join(format!("level-{i}.off"));
    staging.mesh(&level_path(0), original, Format::Off)?;
    // The levels are OFF files: attributes are carried by the library (`Lod::level_mesh`)
    // but not written here.
    crate::outputs::note_dropped(&level_path(0), Format::Off, mesh.attributes(), chain.quiet);

    let start = std::time::Instant::now();
    let bar = Bar::new(chain.quiet);
    let mut write_error = None;
    let mut on_level = |l: &Level| {
        if let Err(e) = staging.mesh(&level_path(l.index), &l.mesh, Format::Off) {
            write_error.get_or_insert(e);
        }
    };
    let s = &chain.settings;
    let result = Lod::new(epsilons.iter().map(|&e| Epsilon::absolute(e)).collect())
        .rule(s.rule)
        .envelope_method(s.envelope)
        .hole_filling(s.hole_filling)
        .certify(s.certify)
        .correspondences(s.correspondences.is_some())
        .screen(s.screen)
        .progress(|e| bar.tell(e))
        .run_with(mesh, &mut on_level);
    bar.finish();
    let levels = match result {
        Ok(levels) => levels,
        // Not bad input: a property (the envelopes' proof) does not hold, exit 1.
        Err(e @ Error::Simplify(DriverError::UnprovedEnvelopes { .. })) => {
            eprintln!("envelope: error: {}: {e}", chain.input_label);
            return Ok(ExitCode::from(1));
        }
        Err(e) => return Err(format!("{}: {e}", chain.input_label)),
    };
    if let Some(e) = write_error {
        return Err(e);
    }
    let seconds = start.elapsed().as_secs_f64();

    let rule = match chain.settings.rule {
        LodRule::Cumulative => "cumulative",
        LodRule::Sum => "sum",
    };
    let s = chain.settings.screen;
    let summary = json!({
        "input": chain.input_label,
        "diagonal": diagonal,
        "rule": rule,
        "rule_doc": match chain.settings.rule {
            LodRule::Cumulative => "level i is simplified from level i-1 with step eps_i - eps_(i-1); its bound to the original is eps_i (triangle inequality, both directions)",
            LodRule::Sum => "level i is simplified from level i-1 with step eps_i; its bound to the original is eps_1 + ... + eps_i (triangle inequality, both directions)",
        },
        "screen": { "pixels": s.pixels, "resolution": s.resolution, "fov_degrees": s.fov_degrees },
        "switching_distance_formula": "d = cumulative_bound * resolution / (2 * pixels * tan(fov / 2))",
        "seconds": seconds,
        "level_0": { "file": "level-0.off", "faces": original.num_faces(), "vertices": original.num_vertices() },
        "levels": levels.iter().map(|l| {
            let mut v = l.to_json(diagonal);
            v["file"] = format!("level-{}.off", l.index).into();
            v
        }).collect::<Vec<_>>(),
    });
    let mut summary = summary;
    if let Some(r) = chain.repair {
        summary["repair"] = r;
    }
    if let Some(to_original) = chain.settings.correspondences {
        write_correspondences(&mut staging, dir, &levels, to_original)?;
    }
    let summary_path = dir.join("summary.json");
    let text = serde_json::to_string_pretty(&summary).map_err(|e| e.to_string())?;
    staging.text(&summary_path, &(text + "\n"))?;
    if let Some(up) = chain.picture {
        let label = &chain.input_label;
        crate::render::stage_lod_pictures(&mut staging, dir, label, original, &levels, up)?;
    }
    staging.commit()?;

    if !chain.quiet {
        print_table(original, &levels, diagonal);
        println!(
            "{} levels in {seconds:.1} s; files and summary.json in {}",
            levels.len(),
            dir.display()
        );
        if chain.picture.is_some() {
            let [strip, svg, png] = crate::render::LOD_PICTURES.map(|n| dir.join(n));
            println!(
                "picture: {}; plot: {}, {}",
                strip.display(),
                svg.display(),
                png.display()
            );
        }
    }
    let worst = levels
        .iter()
        .filter_map(|l| l.certified.as_ref().map(|c| c.verdict))
        .max();
    Ok(match worst {
        Some(Verdict::Violated) => {
            eprintln!(
                "envelope: a level FAILED its certificate against the original (see summary.json)"
            );
            ExitCode::from(1)
        }
        Some(Verdict::Undecided) => ExitCode::from(3),
        _ => ExitCode::SUCCESS,
    })
}

fn correspondence_name(level: usize) -> String {
    format!("correspondence-{level}.json")
}

/// Stages `correspondence-K.json` for every level: `level`, `coarse_faces`, `fine_faces`,
/// `covers`, `by_nearest`, `error` (`envelope::Correspondence`), and with `to_original` the
/// same against level 0 under `to_original`.
fn write_correspondences(
    staging: &mut Staging,
    dir: &Path,
    levels: &[Level],
    to_original: bool,
) -> Result<(), String> {
    let mut composed: Option<envelope::Correspondence> = None;
    for l in levels {
        let Some(c) = &l.correspondence else {
            return Err(format!("level {} has no correspondence", l.index));
        };
        let mut v = c.to_json();
        v["level"] = l.index.into();
        if to_original {
            let down = match &composed {
                Some(finer) => c.then(finer),
                None => c.clone(),
            };
            v["to_original"] = down.to_json();
            composed = Some(down);
        }
        let text = serde_json::to_string(&v).map_err(|e| e.to_string())?;
        staging.text(&dir.join(correspondence_name(l.index)), &(text + "\n"))?;
    }
    Ok(())
}

fn print_table(original: &TriangleSoup, levels: &[Level], diagonal: f64) {
    println!(
        "{:>5} {:>8} {:>8} {:>10} {:>10} {:>12} {:>9}  certified (out->orig, orig->out)",
        "level", "faces", "verts", "eps %", "bound %", "switch at", "seconds"
    );
    println!(
        "{:>5} {:>8} {:>8} {:>10} {:>10} {:>12} {:>9}  input",
        0,
        original.num_faces(),
        original.num_vertices(),
        "-",
        "0",
        "0",
        "-"
    );
    for l in levels {
        let cert = l.certified.as_ref().map_or("skipped".to_string(), |c| {
            format!(
                "{} ({:.4}%, {:.4}%)",
                c.verdict.as_str(),
                100.0 * c.approx_to_orig_upper / diagonal,
                100.0 * c.orig_to_approx_upper / diagonal
            )
        });
        println!(
            "{:>5} {:>8} {:>8} {:>10.4} {:>10.4} {:>12.4} {:>9.2}  {cert}",
            l.index,
            l.mesh.num_faces(),
            l.mesh.num_vertices(),
            100.0 * l.requested / diagonal,
            100.0 * l.cumulative / diagonal,
            l.switching_distance,
            l.report.seconds
        );
    }
}
