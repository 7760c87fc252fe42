//! `envelope simplify IN OUT`: the local algorithm between simplification envelopes (Cohen et
//! al. 5.1, 5.2, 6.1-6.3), or the global / hybrid one (5.3, 5.4, `envelope-global`) with
//! `--method`, then a certificate of the output (`envelope-verify`).
//!
//! Exit codes: 0 written and certified (or certification skipped), 1 the certificate found a
//! violation (OUT is left as it was; the output goes to `OUT.failed.EXT` for inspection), 2 bad
//! input or arguments (OUT is left as it was), 3 the certificate is undecided (OUT written).
//! Every output is checked before any work and written through `crate::outputs` (temporary
//! files renamed at the end), so a failing step leaves OUT and the report as they were.

use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Mutex;

use envelope::advanced::mesh::TriangleSoup;
use envelope::advanced::offset::{EpsilonField, read_epsilon_file};
use envelope::advanced::simplify::{DriverError, SimplifyReport};
use envelope::{
    EnvelopeMethod, Epsilon, Error, Event, HoleFilling, Method, Placement, Simplifier, Stage,
    Verdict, defaults,
};
use glam::DVec3;
use indicatif::{ProgressBar, ProgressStyle};

use crate::outputs::{Plan, Staging};
use crate::ranges::{self, Length};
use crate::scene::{ScopeArg, SimplifyJob};

/// Which epsilon method.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub(crate) enum MethodArg {
    /// Prism clipping (4.1), exact proof and repair (fastest; falls short of large epsilons).
    Analytical,
    /// Iterative growth with exact checks (4.2).
    Numerical,
    /// Analytical; where it falls short of epsilon, numerical growth from it (default).
    Auto,
}

impl MethodArg {
    pub(crate) fn method(self) -> EnvelopeMethod {
        match self {
            MethodArg::Analytical => EnvelopeMethod::Analytical,
            MethodArg::Numerical => EnvelopeMethod::Numerical,
            MethodArg::Auto => EnvelopeMethod::Auto,
        }
    }

    /// The flag for the library's default.
    pub(crate) fn default_() -> Self {
        match defaults::ENVELOPE_METHOD {
            EnvelopeMethod::Analytical => MethodArg::Analytical,
            EnvelopeMethod::Numerical => MethodArg::Numerical,
            EnvelopeMethod::Auto => MethodArg::Auto,
        }
    }
}

/// Which simplification algorithm.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub(crate) enum AlgorithmArg {
    /// One vertex at a time (5.2; default).
    Local,
    /// Greedy set cover by candidate triangles (5.3); border vertices are kept.
    Global,
    /// Local, then global within bounded regions where local is stuck, then local around the
    /// changes and an exhaustive-filling polish (5.4).
    Hybrid,
}

impl AlgorithmArg {
    fn method(self) -> Method {
        match self {
            AlgorithmArg::Local => Method::Local,
            AlgorithmArg::Global => Method::Global,
            AlgorithmArg::Hybrid => Method::Hybrid,
        }
    }

    /// The flag for the library's default.
    fn default_() -> Self {
        match defaults::METHOD {
            Method::Local => AlgorithmArg::Local,
            Method::Global => AlgorithmArg::Global,
            Method::Hybrid => AlgorithmArg::Hybrid,
        }
    }
}

/// Which hole filler.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub(crate) enum FillArg {
    /// The paper's single greedy pass (with a forced-triangle look-ahead).
    Greedy,
    /// Every triangulation of holes up to 10 vertices, greedy above.
    Exhaustive,
}

impl FillArg {
    pub(crate) fn hole_filling(self) -> HoleFilling {
        match self {
            FillArg::Greedy => HoleFilling::default(),
            FillArg::Exhaustive => HoleFilling::Exhaustive { max_vertices: 10 },
        }
    }

    /// The flag for the library's default.
    pub(crate) fn default_() -> Self {
        match defaults::hole_filling() {
            HoleFilling::Greedy { .. } => FillArg::Greedy,
            HoleFilling::Exhaustive { .. } => FillArg::Exhaustive,
        }
    }
}

/// Where output vertices may lie.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub(crate) enum PlacementArg {
    /// Output vertices are input vertices, unmoved (the paper's 5.2).
    Subset,
    /// After the subset run, stuck vertices are tried again with their neighbours slid
    /// along their normals between the envelopes (the paper's section 8).
    Slide,
    /// `slide`, then a vertex that still cannot go is removed by collapsing an edge into a
    /// neighbour moved to a quadric-optimal point between the envelopes.
    Collapse,
    /// `subset`, then the moving phase of `collapse` when the subset run left at most a tenth
    /// of the vertices (large epsilons, where it is cheap), else a light one (no slide, each
    /// vertex's cheapest collapse only); the report's placement says which ran (default).
    Auto,
}

impl PlacementArg {
    fn placement(self) -> Placement {
        match self {
            PlacementArg::Subset => Placement::Subset,
            PlacementArg::Slide => Placement::Slide,
            PlacementArg::Collapse => Placement::Collapse,
            PlacementArg::Auto => Placement::Auto,
        }
    }

    /// The flag for the library's default.
    fn default_() -> Self {
        match defaults::PLACEMENT {
            Placement::Subset => PlacementArg::Subset,
            Placement::Slide => PlacementArg::Slide,
            Placement::Collapse => PlacementArg::Collapse,
            Placement::Auto => PlacementArg::Auto,
        }
    }
}

/// Arguments of `envelope simplify`.
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Input mesh (OBJ, OFF, PLY, STL); must pass `envelope check`. A glTF scene (.glb,
    /// .gltf): every triangle primitive is simplified, certified after rounding to f32.
    input: PathBuf,
    /// Output mesh; the format follows the extension (.obj, .off, .ply, .stl; .glb or .gltf
    /// for a glTF input). Its directory must exist; it must not be IN.
    output: PathBuf,
    /// Epsilon, > 0: `0.5%` or `1/64%` of the bounding-box diagonal, or an absolute length.
    /// With --viewpoint: the epsilon at the vertex nearest the viewpoint.
    #[arg(long, required_unless_present = "epsilon_file", value_parser = ranges::length, allow_hyphen_values = true)]
    epsilon: Option<Length>,
    /// Per-vertex epsilon file (6.3): one value per line in vertex order, same syntax as
    /// --epsilon, `#` comments.
    #[arg(long, conflicts_with_all = ["epsilon", "viewpoint"])]
    epsilon_file: Option<PathBuf>,
    /// Adaptive epsilon (6.3) growing with the distance to this point `X,Y,Z` (three finite
    /// numbers): linear from --epsilon at the nearest vertex to --epsilon-far at the farthest.
    #[arg(long, value_parser = parse_point, requires_all = ["epsilon", "epsilon_far"], allow_hyphen_values = true)]
    viewpoint: Option<DVec3>,
    /// With --viewpoint: the epsilon at the farthest vertex, > 0 (same syntax as --epsilon).
    #[arg(long, requires = "viewpoint", value_parser = ranges::length, allow_hyphen_values = true)]
    epsilon_far: Option<Length>,
    /// Envelope method.
    #[arg(long, value_enum, default_value_t = MethodArg::default_())]
    envelope: MethodArg,
    /// Hole filling of the local algorithm and of the hybrid's local stages (the global
    /// method fills the sub-holes around its placed candidates greedily).
    #[arg(long, value_enum, default_value_t = FillArg::default_())]
    hole_filling: FillArg,
    /// Simplification algorithm (the report's `method` and `method_details` say what ran and
    /// the candidate counts).
    #[arg(long, value_enum, default_value_t = AlgorithmArg::default_())]
    method: AlgorithmArg,
    /// Where output vertices may lie (the report's `placement`; `slide` and `collapse` move
    /// vertices, so the output's vertices are no longer a subset of the input's).
    #[arg(long, value_enum, default_value_t = PlacementArg::default_())]
    placement: PlacementArg,
    /// After the simplification, go on where the envelopes stop (thin parts at large
    /// epsilons): removals and edge collapses each proved against the contract itself
    /// (uniform epsilon only).
    #[arg(long, default_value_t = defaults::TOLERANCE_PHASE, action = clap::ArgAction::Set)]
    tolerance_phase: bool,
    /// Write the report as JSON to this file (its directory must exist).
    #[arg(long)]
    report: Option<PathBuf>,
    /// Repair IN in memory first, without moving its surface (`envelope repair`); the
    /// certificate is then against the repaired IN, whose point set is IN's. The report's
    /// `repair` lists the changes.
    #[arg(long, conflicts_with = "epsilon_file")]
    repair: bool,
    /// glTF input: what a relative --epsilon is a part of (and an absolute one a length in):
    /// each primitive's own diagonal, or the whole scene's in world space.
    #[arg(long, value_enum, default_value_t = ScopeArg::default_())]
    epsilon_scope: ScopeArg,
    /// Skip the certificate of the output.
    #[arg(long)]
    no_verify: bool,
    /// No progress bar and no summary (errors are still printed).
    #[arg(long)]
    quiet: bool,
}

fn parse_point(s: &str) -> Result<DVec3, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|t| {
            t.trim()
                .parse::<f64>()
                .map_err(|_| format!("{t:?} is not a number; expected three finite numbers X,Y,Z"))
        })
        .collect::<Result<_, _>>()?;
    match v[..] {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(DVec3::new(x, y, z)),
        _ => Err("expected three finite numbers X,Y,Z".into()),
    }
}

/// The epsilon field the arguments ask for, checked against the mesh before work.
fn field(args: &Args, soup: &TriangleSoup) -> Result<EpsilonField, String> {
    let field = field_unchecked(args, soup)?;
    let flag = match (&args.epsilon_file, args.viewpoint) {
        (Some(f), _) => format!("--epsilon-file {}", f.display()),
        (None, Some(_)) => "--epsilon, --epsilon-far and --viewpoint".into(),
        (None, None) => format!(
            "--epsilon {}",
            args.epsilon.as_ref().map_or("", |e| e.text.as_str())
        ),
    };
    ranges::epsilon_in_range(&flag, &args.input.display().to_string(), &field, soup)?;
    Ok(field)
}

fn field_unchecked(args: &Args, soup: &TriangleSoup) -> Result<EpsilonField, String> {
    let diagonal = soup.diagonal();
    if let Some(f) = &args.epsilon_file {
        let specs = read_epsilon_file(f, soup.num_vertices())
            .map_err(|err| format!("--epsilon-file {}: {err}", f.display()))?;
        return Ok(EpsilonField::from_specs(&specs, diagonal));
    }
    let input = args.input.display().to_string();
    let Some(e) = &args.epsilon else {
        return Err("--epsilon or --epsilon-file is required".into());
    };
    let near = e.resolve("--epsilon", &input, soup)?;
    let Some(viewpoint) = args.viewpoint else {
        return Ok(EpsilonField::Constant(near));
    };
    let Some(far) = &args.epsilon_far else {
        return Err("--viewpoint needs --epsilon-far".into());
    };
    let far = far.resolve("--epsilon-far", &input, soup)?;
    let d: Vec<f64> = soup
        .positions
        .iter()
        .map(|p| p.distance(viewpoint))
        .collect();
    let (lo, hi) = d.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
        (lo.min(x), hi.max(x))
    });
    let span = (hi - lo).max(f64::MIN_POSITIVE);
    Ok(EpsilonField::PerVertex(
        d.iter()
            .map(|&x| near + (far - near) * (x - lo) / span)
            .collect(),
    ))
}

/// A progress bar on stderr (hidden when stderr is not a terminal or when quiet), told
/// through the library's progress callback ([`Bar::tell`]).
pub(crate) struct Bar {
    bar: ProgressBar,
    prefix: Mutex<String>,
}

impl Bar {
    pub(crate) fn new(quiet: bool) -> Bar {
        let bar = if quiet || !std::io::stderr().is_terminal() {
            ProgressBar::hidden()
        } else {
            ProgressBar::new_spinner()
        };
        Bar {
            bar,
            prefix: Mutex::new(String::new()),
        }
    }

    pub(crate) fn finish(&self) {
        self.bar.finish_and_clear();
    }

    /// The progress callback: shows the event, never cancels (Ctrl-C ends the process).
    pub(crate) fn tell(&self, event: Event) -> ControlFlow<()> {
        match event {
            Event::Level { index, count } => {
                if let Ok(mut p) = self.prefix.lock() {
                    *p = format!("level {index}/{count}: ");
                }
            }
            Event::Stage(stage) => self.stage(stage),
            Event::Removed { removed, .. } => self.bar.set_position(removed as u64),
            _ => {}
        }
        ControlFlow::Continue(())
    }

    fn stage(&self, stage: Stage) {
        let p = self.prefix.lock().map(|p| p.clone()).unwrap_or_default();
        match stage {
            Stage::Check => self.spin(format!("{p}checking the input")),
            Stage::Envelopes => self.spin(format!("{p}building envelopes")),
            Stage::Simplify { vertices } => {
                self.bar.set_length(vertices as u64);
                self.bar.set_position(0);
                self.bar.set_style(
                    ProgressStyle::with_template(
                        "{msg} [{bar:30}] {pos}/{len} vertices removed ({elapsed})",
                    )
                    .unwrap_or_else(|_| ProgressStyle::default_bar())
                    .progress_chars("=> "),
                );
                self.bar.set_message(format!("{p}simplifying"));
            }
            Stage::Verify => self.spin(format!("{p}certifying the output")),
        }
    }

    fn spin(&self, msg: String) {
        self.bar.set_style(
            ProgressStyle::with_template("{spinner} {msg} ({elapsed})")
                .unwrap_or_else(|_| ProgressStyle::default_spinner()),
        );
        self.bar.set_message(msg);
        self.bar
            .enable_steady_tick(std::time::Duration::from_millis(120));
    }
}

/// A simplifier for an epsilon field of absolute lengths (constant or per vertex).
pub(crate) fn simplifier<'a>(field: EpsilonField) -> Result<Simplifier<'a>, String> {
    match field {
        EpsilonField::Constant(e) => Ok(Simplifier::new(Epsilon::absolute(e))),
        EpsilonField::PerVertex(v) => Ok(Simplifier::per_vertex(
            v.into_iter().map(Epsilon::absolute).collect(),
        )),
        EpsilonField::Function(_) => Err("an epsilon function is not a command-line field".into()),
    }
}

/// `OUT.failed.EXT` next to OUT.
fn failed_path(out: &Path) -> PathBuf {
    let ext = out
        .extension()
        .map(|e| e.to_string_lossy().into_owned())
        .unwrap_or_else(|| "off".into());
    out.with_extension(format!("failed.{ext}"))
}

fn print_summary(args: &Args, r: &SimplifyReport) {
    println!(
        "{} -> {}: {} -> {} faces ({} -> {} vertices) in {:.2} s ({})",
        args.input.display(),
        args.output.display(),
        r.input_faces,
        r.output_faces,
        r.input_vertices,
        r.output_vertices,
        r.seconds,
        r.method
    );
    let g = |x: Option<u32>| x.map_or("undefined".to_string(), |g| g.to_string());
    println!(
        "epsilon {:.6e} ({:.4}% of the diagonal); genus {} -> {}; border loops {} -> {}",
        r.epsilon_abs,
        100.0 * r.epsilon_fraction,
        g(r.genus_in),
        g(r.genus_out),
        r.border_loops_in,
        r.border_loops_out
    );
    let e = &r.envelope;
    println!(
        "envelopes {}: achieved median {:.1}%, p5 {:.1}% of requested, proof {}, {} tubes, {:.2} s",
        e.method,
        100.0 * e.achieved_median,
        100.0 * e.achieved_p5,
        if e.proved { "holds" } else { "FAILED" },
        e.tubes,
        e.seconds
    );
    if let Some(mb) = r.peak_memory_bytes {
        println!("peak memory {:.1} MiB", mb as f64 / (1024.0 * 1024.0));
    }
    if let Some(k) = &r.kept {
        let why = match k.intersecting_pairs {
            0 => "envelopes not provable everywhere".to_owned(),
            n => format!("self-intersecting input ({n} intersecting pairs)"),
        };
        println!(
            "{why}: {} faces kept as they are ({} rounds of envelopes after the first), {} vertices they share kept",
            k.kept_faces, k.rounds, k.shared_vertices
        );
    }
    match &r.verify {
        Some(v) => println!(
            "certificate {}: output->input <= {:.4e}, input->output <= {:.4e}, {} self-intersections{}, topology {}",
            v.verdict.as_str(),
            v.approx_to_orig_upper,
            v.orig_to_approx_upper,
            v.self_intersections,
            match v.certificate.kept_intersections.len() {
                0 => String::new(),
                k => format!(" ({k} kept from the input)"),
            },
            if v.topology_matches {
                "unchanged"
            } else {
                "CHANGED"
            }
        ),
        None => println!("certificate skipped (--no-verify)"),
    }
}

pub(crate) fn run(args: &Args) -> Result<ExitCode, String> {
    if matches!(args.method, AlgorithmArg::Global)
        && matches!(args.placement, PlacementArg::Slide | PlacementArg::Collapse)
    {
        return Err(
            "--placement slide and collapse move vertices in the local algorithm's \
                    phase, which --method global does not run (use --method local or hybrid)"
                .into(),
        );
    }
    if crate::scene::is_scene(&args.input) {
        return simplify_scene(args);
    }
    let mut inputs = vec![("IN", args.input.as_path())];
    if let Some(path) = &args.epsilon_file {
        inputs.push(("--epsilon-file", path));
    }
    let mut plan = Plan::new(&inputs);
    let format = plan.mesh("OUT", &args.output)?;
    let failed = failed_path(&args.output);
    plan.file("OUT.failed", &failed)?;
    if let Some(path) = &args.report {
        plan.file("--report", path)?;
    }
    let mesh = envelope::load(&args.input).map_err(|e| e.to_string())?;
    let label = args.input.display().to_string();
    let (mesh, repair) = crate::repair::maybe(mesh, args.repair, &label, args.quiet)?;
    let bar = Bar::new(args.quiet);
    let result = simplifier(field(args, mesh.soup())?)?
        .method(args.method.method())
        .envelope_method(args.envelope.method())
        .hole_filling(args.hole_filling.hole_filling())
        .placement(args.placement.placement())
        .tolerance_phase(args.tolerance_phase)
        .certify(!args.no_verify)
        .progress(|e| bar.tell(e))
        .run(&mesh);
    bar.finish();
    let done = match result {
        Ok(done) => done,
        Err(Error::CertificateViolated(done)) => *done,
        // Not bad input: a property (the envelopes' proof) does not hold, exit 1.
        Err(e @ Error::Simplify(DriverError::UnprovedEnvelopes { .. })) => {
            eprintln!("envelope: error: {}: {e}", args.input.display());
            return Ok(ExitCode::from(1));
        }
        Err(e) => return Err(format!("{}: {e}", args.input.display())),
    };
    let report = done.report();
    let verdict = report.verify.as_ref().map(|v| v.verdict);
    let target = if verdict == Some(Verdict::Violated) {
        failed
    } else {
        args.output.clone()
    };
    let mut staging = Staging::new();
    staging.mesh_with_attributes(&target, done.mesh(), format, args.quiet)?;
    if let Some(path) = &args.report {
        let mut v = report.to_json();
        v["input"] = args.input.display().to_string().into();
        v["output"] = target.display().to_string().into();
        if let Some(r) = repair {
            v["repair"] = r;
        }
        let text = serde_json::to_string_pretty(&v).map_err(|e| e.to_string())?;
        staging.text(path, &(text + "\n"))?;
    }
    staging.commit()?;
    if !args.quiet {
        print_summary(args, report);
    }
    Ok(match verdict {
        Some(Verdict::Violated) => {
            eprintln!(
                "envelope: the output FAILED its certificate ({}); written to {}, {} left as it was",
                done.violations().join(", "),
                target.display(),
                args.output.display()
            );
            ExitCode::from(1)
        }
        Some(Verdict::Undecided) => ExitCode::from(3),
        _ => ExitCode::SUCCESS,
    })
}

/// A glTF scene (`crate::scene`).
fn simplify_scene(args: &Args) -> Result<ExitCode, String> {
    crate::scene::check_flags(
        &args.output,
        &[
            ("--epsilon-file", args.epsilon_file.is_some()),
            ("--viewpoint", args.viewpoint.is_some()),
            ("--repair", args.repair),
            (
                "--no-verify (f32 outputs need the certificate)",
                args.no_verify,
            ),
        ],
    )?;
    let Some(epsilon) = &args.epsilon else {
        return Err("--epsilon is required for a glTF scene".into());
    };
    crate::scene::simplify(&SimplifyJob {
        input: &args.input,
        output: &args.output,
        epsilon,
        scope: args.epsilon_scope,
        method: args.method.method(),
        envelope: args.envelope.method(),
        hole_filling: args.hole_filling.hole_filling(),
        placement: args.placement.placement(),
        report: args.report.as_deref(),
        quiet: args.quiet,
    })
}
