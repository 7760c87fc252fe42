//! glTF scenes (`.glb`, `.gltf`) in `simplify`, `lod` and `verify`: chosen by IN's
//! extension, a thin layer over `envelope::SceneSimplifier` and `envelope::SceneLod`.
//!
//! * `envelope simplify IN.glb OUT.glb --epsilon 1% [--epsilon-scope primitive|scene]`:
//!   every triangle primitive simplified, certified after rounding to f32 (the subset run
//!   when rounding breaks the certificate), node transforms and the rest of the document
//!   kept; one line per primitive.
//! * `envelope lod IN.glb OUT.glb --epsilons ... [--per-level-files]`: one file with the
//!   levels as `MSFT_lod` nodes; with `--per-level-files` also `OUT-level-K.EXT` for each
//!   level K beside OUT.
//! * `envelope verify ORIG.glb APPROX.glb --epsilon E`: the triangle primitives paired in
//!   order, each certified at E (relative to the ORIG primitive's diagonal).
//!
//! Exit codes as the other commands: 0 certified, 1 a certificate is violated (or envelopes
//! not proved; nothing is written), 2 bad input or arguments (the message names the file's
//! element), 3 undecided.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use envelope::advanced::gltf::is_gltf_path;
use envelope::advanced::simplify::DriverError;
use envelope::{
    EnvelopeMethod, Epsilon, EpsilonScope, Error, HoleFilling, LodRule, Mesh, Method, Placement,
    SceneLod, SceneSimplifier, Screen, Verdict, defaults,
};

use crate::outputs::{Plan, Staging};
use crate::ranges::Length;

/// What a scene's epsilon is relative to.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub(crate) enum ScopeArg {
    /// Each primitive's own bounding-box diagonal and units (default).
    Primitive,
    /// The whole scene's world-space diagonal and units; each primitive's epsilon is divided
    /// by the largest scale of the nodes that show it.
    Scene,
}

impl ScopeArg {
    fn scope(self) -> EpsilonScope {
        match self {
            ScopeArg::Primitive => EpsilonScope::Primitive,
            ScopeArg::Scene => EpsilonScope::Scene,
        }
    }

    /// The flag for the library's default.
    pub(crate) fn default_() -> Self {
        match defaults::EPSILON_SCOPE {
            EpsilonScope::Primitive => ScopeArg::Primitive,
            EpsilonScope::Scene => ScopeArg::Scene,
        }
    }
}

/// Whether a command's input is a glTF scene.
pub(crate) fn is_scene(input: &Path) -> bool {
    is_gltf_path(input)
}

/// Refuses flags a scene does not take, and an output that is not glTF.
pub(crate) fn check_flags(output: &Path, refused: &[(&str, bool)]) -> Result<(), String> {
    if !is_gltf_path(output) {
        return Err(format!(
            "OUT {}: a glTF input is written as glTF: use .glb or .gltf",
            output.display()
        ));
    }
    for (flag, given) in refused {
        if *given {
            return Err(format!("{flag} is not available for glTF scenes"));
        }
    }
    Ok(())
}

/// `simplify` on a scene.
pub(crate) struct SimplifyJob<'a> {
    pub(crate) input: &'a Path,
    pub(crate) output: &'a Path,
    pub(crate) epsilon: &'a Length,
    pub(crate) scope: ScopeArg,
    pub(crate) method: Method,
    pub(crate) envelope: EnvelopeMethod,
    pub(crate) hole_filling: HoleFilling,
    pub(crate) placement: Placement,
    pub(crate) report: Option<&'a Path>,
    pub(crate) quiet: bool,
}

/// Exit 1 for what is not bad input (a certificate, the envelopes' proof), else the message.
fn failure(input: &Path, e: Error) -> Result<ExitCode, String> {
    let inner = match &e {
        Error::Primitive { source, .. } => source.as_ref(),
        e => e,
    };
    match inner {
        Error::CertificateViolated(_) | Error::Simplify(DriverError::UnprovedEnvelopes { .. }) => {
            eprintln!("envelope: error: {}: {e}", input.display());
            Ok(ExitCode::from(1))
        }
        _ => Err(format!("{}: {e}", input.display())),
    }
}

pub(crate) fn simplify(job: &SimplifyJob<'_>) -> Result<ExitCode, String> {
    let mut plan = Plan::new(&[("IN", job.input)]);
    plan.file("OUT", job.output)?;
    if let Some(r) = job.report {
        plan.file("--report", r)?;
    }
    let scene = envelope::load_scene(job.input).map_err(|e| e.to_string())?;
    let start = std::time::Instant::now();
    let result = SceneSimplifier::new(Epsilon::from(job.epsilon.spec))
        .scope(job.scope.scope())
        .method(job.method)
        .envelope_method(job.envelope)
        .hole_filling(job.hole_filling)
        .placement(job.placement)
        .run(&scene);
    let done = match result {
        Ok(done) => done,
        Err(e) => return failure(job.input, e),
    };
    let seconds = start.elapsed().as_secs_f64();
    let bytes = scene_bytes(&done.scene, job.output)?;
    let mut staging = Staging::new();
    staging.bytes(job.output, &bytes)?;
    if let Some(path) = job.report {
        let v = serde_json::json!({
            "input": job.input.display().to_string(),
            "output": job.output.display().to_string(),
            "epsilon": job.epsilon.text,
            "epsilon_scope": format!("{:?}", job.scope).to_lowercase(),
            "seconds": seconds,
            "primitives": done.primitives.iter().map(|p| p.to_json()).collect::<Vec<_>>(),
        });
        let text = serde_json::to_string_pretty(&v).map_err(|e| e.to_string())?;
        staging.text(path, &(text + "\n"))?;
    }
    staging.commit()?;
    if !job.quiet {
        println!(
            "{} -> {}: {} primitives in {seconds:.2} s",
            job.input.display(),
            job.output.display(),
            done.primitives.len()
        );
        for p in &done.primitives {
            match (&p.kept, &p.certificate) {
                (Some(why), _) => println!("  {}: kept as it is ({why})", p.label),
                (None, Some(c)) => println!(
                    "  {}: {} -> {} faces, epsilon {:.6e}, certificate {} after rounding to f32 (out->in <= {:.4e}, in->out <= {:.4e}){}",
                    p.label,
                    p.faces_in,
                    p.faces_out,
                    p.epsilon,
                    c.verdict.as_str(),
                    c.approx_to_orig.upper,
                    c.orig_to_approx.upper,
                    if p.subset_fallback {
                        "; rounding broke the first certificate: input vertices only"
                    } else {
                        ""
                    }
                ),
                (None, None) => {}
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn scene_bytes(scene: &envelope::Scene, path: &Path) -> Result<Vec<u8>, String> {
    let gltf = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gltf"));
    let r = if gltf {
        scene.to_gltf()
    } else {
        scene.to_glb()
    };
    r.map_err(|e| format!("{}: {e}", path.display()))
}

/// `lod` on a scene.
pub(crate) struct LodJob<'a> {
    pub(crate) input: &'a Path,
    pub(crate) output: &'a Path,
    pub(crate) epsilons: &'a [Length],
    pub(crate) scope: ScopeArg,
    pub(crate) per_level_files: bool,
    pub(crate) rule: LodRule,
    pub(crate) envelope: EnvelopeMethod,
    pub(crate) hole_filling: HoleFilling,
    pub(crate) screen: Screen,
    pub(crate) quiet: bool,
}

/// `OUT-level-K.EXT` beside OUT.
fn level_path(out: &Path, k: usize) -> PathBuf {
    let stem = out
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let ext = out
        .extension()
        .map_or_else(String::new, |e| e.to_string_lossy().into_owned());
    out.with_file_name(format!("{stem}-level-{k}.{ext}"))
}

pub(crate) fn lod(job: &LodJob<'_>) -> Result<ExitCode, String> {
    let mut plan = Plan::new(&[("IN", job.input)]);
    plan.file("OUT", job.output)?;
    let n = job.epsilons.len();
    if job.per_level_files {
        for k in 1..=n {
            plan.file(&format!("level {k}"), &level_path(job.output, k))?;
        }
    }
    let scene = envelope::load_scene(job.input).map_err(|e| e.to_string())?;
    let start = std::time::Instant::now();
    let result = SceneLod::new(job.epsilons.iter().map(|l| Epsilon::from(l.spec)).collect())
        .scope(job.scope.scope())
        .rule(job.rule)
        .envelope_method(job.envelope)
        .hole_filling(job.hole_filling)
        .screen(job.screen)
        .run(&scene);
    let chains = match result {
        Ok(c) => c,
        Err(e) => return failure(job.input, e),
    };
    let mut staging = Staging::new();
    let lod = chains.lod_scene().map_err(|e| e.to_string())?;
    staging.bytes(job.output, &scene_bytes(&lod, job.output)?)?;
    if job.per_level_files {
        for k in 1..=n {
            let path = level_path(job.output, k);
            let level = chains.level_scene(k).map_err(|e| e.to_string())?;
            staging.bytes(&path, &scene_bytes(&level, &path)?)?;
        }
    }
    staging.commit()?;
    if !job.quiet {
        println!(
            "{} -> {}: {n} levels (MSFT_lod) in {:.2} s",
            job.input.display(),
            job.output.display(),
            start.elapsed().as_secs_f64()
        );
        for p in chains.primitives() {
            if let Some(why) = &p.kept {
                println!("  {}: kept as it is ({why})", p.label);
                continue;
            }
            let faces: Vec<String> = p.levels.iter().map(|l| l.faces.to_string()).collect();
            let verdicts: Vec<&str> = p
                .levels
                .iter()
                .map(|l| l.certificate.verdict.as_str())
                .collect();
            println!(
                "  {}: {} -> {} faces; certificates after rounding to f32: {}",
                p.label,
                p.faces_in,
                faces.join(" -> "),
                verdicts.join(", ")
            );
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// `verify` on two scenes: triangle primitives paired in order.
pub(crate) fn verify(orig: &Path, approx: &Path, epsilon: &Length) -> Result<ExitCode, String> {
    if is_gltf_path(orig) != is_gltf_path(approx) {
        return Err(format!(
            "ORIG {} and APPROX {}: compare two glTF scenes (.glb, .gltf) or two meshes",
            orig.display(),
            approx.display()
        ));
    }
    let a = envelope::load_scene(orig).map_err(|e| e.to_string())?;
    let b = envelope::load_scene(approx).map_err(|e| e.to_string())?;
    let tri = |s: &envelope::Scene| {
        s.primitives()
            .iter()
            .filter(|p| p.is_triangles())
            .cloned()
            .collect::<Vec<_>>()
    };
    let (pa, pb) = (tri(&a), tri(&b));
    if pa.len() != pb.len() {
        return Err(format!(
            "{} has {} triangle primitives, {} has {}: they are paired in order",
            orig.display(),
            pa.len(),
            approx.display(),
            pb.len()
        ));
    }
    let mut worst = Verdict::Holds;
    for (p, q) in pa.iter().zip(&pb) {
        let m = Mesh::from_soup(p.soup().clone());
        let c = envelope::verify(
            &m,
            &Mesh::from_soup(q.soup().clone()),
            Epsilon::from(epsilon.spec),
        )
        .map_err(|e| format!("{}: {e}", p.label()))?;
        println!(
            "{} / {}: {} (epsilon {:.6e}; approx->orig <= {:.4e}, orig->approx <= {:.4e}){}",
            p.label(),
            q.label(),
            c.verdict.as_str(),
            c.epsilon,
            c.approx_to_orig.upper,
            c.orig_to_approx.upper,
            if c.violations().is_empty() {
                String::new()
            } else {
                format!("; violated: {}", c.violations().join(", "))
            }
        );
        worst = worst.max(c.verdict);
    }
    Ok(match worst {
        Verdict::Holds => ExitCode::SUCCESS,
        Verdict::Violated => ExitCode::from(1),
        Verdict::Undecided => ExitCode::from(3),
    })
}
