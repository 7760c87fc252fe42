//! Every file a subcommand writes: checked before any work, written only when the command
//! completes.
//!
//! Checks ([`Plan`], run before the input is read):
//! * a file output (OUT, `--report`, `OUT.failed.EXT`): its directory exists, is a directory
//!   and is writable (a probe file is created and removed there); the path is not a
//!   directory; it is not the same file as an input or as another output; a mesh output's
//!   extension names a format (.obj, .off, .ply, .stl);
//! * an output directory (`lod`, `pipeline`, `demo` OUTDIR, `envelopes --out-dir`): an
//!   existing writable directory, or a missing one whose parent exists and is a writable
//!   directory (it is then created; its parents are not); the files it will hold are checked
//!   as file outputs.
//!
//! Writes ([`Staging`]): each file goes to a hidden temporary file in its final directory, or,
//! when that directory is a missing output directory, into a hidden sibling directory that
//! becomes it. [`Staging::commit`] renames them into place when the command has completed;
//! a `Staging` dropped without a commit (an error, exit 2) removes them, so nothing the user
//! already has is replaced.

use std::ffi::OsString;
use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use envelope::advanced::io::Format;
use envelope::advanced::mesh::TriangleSoup;

/// The directory holding `path` ("." for a bare file name).
fn parent_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// A path comparable with others: canonical when it exists, else its canonical directory
/// joined with its name (`None` when neither resolves).
fn identity(path: &Path) -> Option<PathBuf> {
    if let Ok(p) = fs::canonicalize(path) {
        return Some(p);
    }
    Some(
        fs::canonicalize(parent_of(path))
            .ok()?
            .join(path.file_name()?),
    )
}

/// Whether `a` and `b` name the same file (through symbolic links and, on Unix, hard links).
fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt as _;
        if let (Ok(x), Ok(y)) = (fs::metadata(a), fs::metadata(b))
            && (x.dev(), x.ino()) == (y.dev(), y.ino())
        {
            return true;
        }
    }
    matches!((identity(a), identity(b)), (Some(x), Some(y)) if x == y)
}

static TEMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// A fresh hidden name next to `path`: `.NAME.envelope-PID-N.tmp`.
fn temp_beside(path: &Path) -> PathBuf {
    let n = TEMP_COUNTER.fetch_add(1, Ordering::Relaxed);
    let mut name = OsString::from(".");
    name.push(path.file_name().unwrap_or_else(|| "out".as_ref()));
    name.push(format!(".envelope-{}-{n}.tmp", std::process::id()));
    parent_of(path).join(name)
}

/// Creates a new file at `path`, retrying with fresh names if one exists already.
fn create_temp_file(beside: &Path) -> std::io::Result<(PathBuf, fs::File)> {
    loop {
        let tmp = temp_beside(beside);
        match fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
        {
            Ok(f) => return Ok((tmp, f)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
            Err(e) => return Err(e),
        }
    }
}

/// Fails unless a file can be created in `dir` (the only reliable test of write access).
fn probe_writable(what: &str, dir: &Path) -> Result<(), String> {
    let (tmp, file) = create_temp_file(&dir.join("probe"))
        .map_err(|e| format!("{what}: cannot write in directory {}: {e}", dir.display()))?;
    drop(file);
    let _ = fs::remove_file(tmp);
    Ok(())
}

/// The output checks of one command, accumulated so that outputs are also compared with
/// each other.
pub(crate) struct Plan {
    inputs: Vec<(String, PathBuf)>,
    outputs: Vec<(String, PathBuf)>,
    /// Directories already checked (existing and writable, or missing with a writable
    /// parent): their files skip the directory checks and the probe.
    checked_dirs: Vec<PathBuf>,
}

impl Plan {
    /// A plan for a command reading `inputs` (label, path), e.g. `("IN", path)`.
    pub(crate) fn new(inputs: &[(&str, &Path)]) -> Plan {
        Plan {
            inputs: inputs
                .iter()
                .map(|(l, p)| ((*l).to_string(), p.to_path_buf()))
                .collect(),
            outputs: Vec::new(),
            checked_dirs: Vec::new(),
        }
    }

    /// Checks a file output; `what` names it in messages (`OUT`, `--report`).
    pub(crate) fn file(&mut self, what: &str, path: &Path) -> Result<(), String> {
        let shown = path.display();
        if path.file_name().is_none() {
            return Err(format!("{what} {shown}: not a file name"));
        }
        let dir = parent_of(path);
        if !self.checked_dirs.iter().any(|d| d == dir) {
            match fs::metadata(dir) {
                Ok(m) if m.is_dir() => {}
                Ok(_) => {
                    return Err(format!(
                        "{what} {shown}: {} is not a directory",
                        dir.display()
                    ));
                }
                Err(_) => {
                    return Err(format!(
                        "{what} {shown}: directory {} does not exist (output directories are not created; create it first)",
                        dir.display()
                    ));
                }
            }
            probe_writable(&format!("{what} {shown}"), dir)?;
            self.checked_dirs.push(dir.to_path_buf());
        }
        if fs::metadata(path).is_ok_and(|m| m.is_dir()) {
            return Err(format!("{what} {shown}: is a directory; give a file name"));
        }
        for (label, input) in &self.inputs {
            if same_file(path, input) {
                return Err(format!(
                    "{what} {shown}: is the input {label} ({}); write to another file",
                    input.display()
                ));
            }
        }
        for (label, other) in &self.outputs {
            if same_file(path, other) {
                return Err(format!(
                    "{what} {shown}: is also the output {label}; give each output its own file"
                ));
            }
        }
        self.outputs.push((what.to_string(), path.to_path_buf()));
        Ok(())
    }

    /// Checks a mesh file output and returns the format its extension names.
    pub(crate) fn mesh(&mut self, what: &str, path: &Path) -> Result<Format, String> {
        if path.is_dir() {
            // Said first: "unknown format" would hide that a directory was given.
            return Err(format!(
                "{what} {}: is a directory; give a file name",
                path.display()
            ));
        }
        let format = Format::from_path(path).ok_or_else(|| {
            let ext = path
                .extension()
                .map_or("none".to_string(), |e| format!("{:?}", e.to_string_lossy()));
            format!(
                "{what} {}: unknown output format (extension {ext}; use .obj, .off, .ply or .stl)",
                path.display()
            )
        })?;
        self.file(what, path)?;
        Ok(format)
    }

    /// Checks an output directory and the files `names` it will hold (more may be added by
    /// [`Plan::file`] on `dir.join(name)`).
    pub(crate) fn dir(&mut self, what: &str, dir: &Path, names: &[String]) -> Result<(), String> {
        let shown = dir.display();
        match fs::metadata(dir) {
            Ok(m) if m.is_dir() => {
                probe_writable(&format!("{what} {shown}"), dir)?;
                self.checked_dirs.push(dir.to_path_buf());
            }
            Ok(_) => return Err(format!("{what} {shown}: exists and is not a directory")),
            Err(_) => {
                if dir.file_name().is_none() {
                    return Err(format!("{what} {shown}: not a directory name"));
                }
                let parent = parent_of(dir);
                if !fs::metadata(parent).is_ok_and(|m| m.is_dir()) {
                    return Err(format!(
                        "{what} {shown}: parent directory {} does not exist (only the last directory of the path is created)",
                        parent.display()
                    ));
                }
                probe_writable(&format!("{what} {shown}"), parent)?;
                self.checked_dirs.push(dir.to_path_buf());
            }
        }
        for name in names {
            self.file(&format!("{what} file {name}"), &dir.join(name))?;
        }
        Ok(())
    }
}

impl Plan {
    /// Refuses an input that lies in `dir` under a name `writes` says the command may write
    /// there (for files whose number is known only after the work, e.g. border tubes).
    pub(crate) fn inputs_not_in(
        &self,
        what: &str,
        dir: &Path,
        writes: impl Fn(&str) -> bool,
    ) -> Result<(), String> {
        let Ok(dir) = fs::canonicalize(dir) else {
            return Ok(()); // A missing directory holds no input.
        };
        for (label, input) in &self.inputs {
            let Some(path) = identity(input) else {
                continue;
            };
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
            if path.parent() == Some(dir.as_path()) && name.is_some_and(|n| writes(&n)) {
                return Err(format!(
                    "{what} {}: would replace the input {label} ({}); choose another directory",
                    dir.display(),
                    input.display()
                ));
            }
        }
        Ok(())
    }
}

/// One line on stderr (unless `quiet`) naming the input's attributes `format` cannot hold.
pub(crate) fn note_dropped(
    path: &Path,
    format: Format,
    attributes: &envelope::Attributes,
    quiet: bool,
) {
    let dropped = format.dropped_attributes(attributes);
    if !quiet && !dropped.is_empty() {
        eprintln!(
            "envelope: note: {} is {format}, which holds no {}; not written",
            path.display(),
            dropped.join(" or ")
        );
    }
}

/// Outputs written to temporary places until [`Staging::commit`].
pub(crate) struct Staging {
    /// (temporary file, final path), renamed in this order.
    files: Vec<(PathBuf, PathBuf)>,
    /// (temporary directory, final directory) for missing output directories.
    dirs: Vec<(PathBuf, PathBuf)>,
}

impl Staging {
    pub(crate) fn new() -> Staging {
        Staging {
            files: Vec::new(),
            dirs: Vec::new(),
        }
    }

    /// Prepares the output directory `dir`: when it is missing, a hidden sibling directory
    /// takes its files and becomes it at the commit.
    pub(crate) fn dir(&mut self, dir: &Path) -> Result<(), String> {
        if dir.is_dir() || self.dirs.iter().any(|(_, d)| d == dir) {
            return Ok(());
        }
        let tmp = temp_beside(dir);
        fs::create_dir(&tmp).map_err(|e| format!("{}: cannot create: {e}", tmp.display()))?;
        self.dirs.push((tmp, dir.to_path_buf()));
        Ok(())
    }

    /// Creates the temporary file that will become `path`.
    fn create(&mut self, path: &Path) -> Result<(PathBuf, fs::File), String> {
        let fail = |e: std::io::Error| format!("{}: {e}", path.display());
        let dir = parent_of(path);
        if let Some((tmp_dir, _)) = self.dirs.iter().find(|(_, d)| d == dir) {
            // The whole directory is renamed at the commit: files keep their final names.
            let name = path.file_name().unwrap_or_else(|| "out".as_ref());
            let p = tmp_dir.join(name);
            let f = fs::File::create(&p).map_err(fail)?;
            return Ok((p, f));
        }
        let (tmp, f) = create_temp_file(path).map_err(fail)?;
        self.files.push((tmp.clone(), path.to_path_buf()));
        Ok((tmp, f))
    }

    /// Writes `soup` in `format` to what becomes `path` at the commit.
    pub(crate) fn mesh(
        &mut self,
        path: &Path,
        soup: &TriangleSoup,
        format: Format,
    ) -> Result<(), String> {
        let (_, file) = self.create(path)?;
        envelope::advanced::io::write(&file, soup, format)
            .map_err(|e| format!("{}: {}", path.display(), e.kind))?;
        file.sync_all()
            .map_err(|e| format!("{}: {e}", path.display()))
    }

    /// Writes `mesh` with the attributes `format` holds to what becomes `path` at the commit;
    /// says on stderr (unless `quiet`) which attributes the format cannot hold.
    pub(crate) fn mesh_with_attributes(
        &mut self,
        path: &Path,
        mesh: &envelope::Mesh,
        format: Format,
        quiet: bool,
    ) -> Result<(), String> {
        let (_, file) = self.create(path)?;
        envelope::advanced::io::write_with_attributes(
            &file,
            mesh.soup(),
            mesh.attributes(),
            format,
        )
        .map_err(|e| format!("{}: {}", path.display(), e.kind))?;
        note_dropped(path, format, mesh.attributes(), quiet);
        file.sync_all()
            .map_err(|e| format!("{}: {e}", path.display()))
    }

    /// Writes `text` to what becomes `path` at the commit.
    pub(crate) fn text(&mut self, path: &Path, text: &str) -> Result<(), String> {
        self.bytes(path, text.as_bytes())
    }

    /// Writes `bytes` to what becomes `path` at the commit.
    pub(crate) fn bytes(&mut self, path: &Path, bytes: &[u8]) -> Result<(), String> {
        let (_, mut file) = self.create(path)?;
        file.write_all(bytes)
            .and_then(|()| file.sync_all())
            .map_err(|e| format!("{}: {e}", path.display()))
    }

    /// Moves every staged file and directory into place.
    pub(crate) fn commit(mut self) -> Result<(), String> {
        while !self.files.is_empty() {
            let (tmp, path) = self.files.remove(0);
            if let Err(e) = fs::rename(&tmp, &path) {
                let _ = fs::remove_file(&tmp);
                return Err(format!("{}: cannot replace: {e}", path.display()));
            }
        }
        while !self.dirs.is_empty() {
            let (tmp, dir) = self.dirs.remove(0);
            if let Err(e) = fs::rename(&tmp, &dir) {
                let _ = fs::remove_dir_all(&tmp);
                return Err(format!("{}: cannot create: {e}", dir.display()));
            }
        }
        Ok(())
    }
}

impl Drop for Staging {
    /// Without a commit, whatever was staged is removed.
    fn drop(&mut self) {
        for (tmp, _) in &self.files {
            let _ = fs::remove_file(tmp);
        }
        for (tmp, _) in &self.dirs {
            let _ = fs::remove_dir_all(tmp);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn staged_files_appear_only_at_the_commit() {
        let dir = tempfile::tempdir().unwrap();
        let kept = dir.path().join("kept.txt");
        fs::write(&kept, "KEEP").unwrap();
        let new_dir = dir.path().join("new");
        let mut s = Staging::new();
        s.text(&kept, "replaced").unwrap();
        s.dir(&new_dir).unwrap();
        s.text(&new_dir.join("a.txt"), "a").unwrap();
        assert_eq!(fs::read_to_string(&kept).unwrap(), "KEEP");
        assert!(!new_dir.exists());
        drop(s);
        assert_eq!(
            fs::read_dir(dir.path()).unwrap().count(),
            1,
            "temporaries left"
        );

        let mut s = Staging::new();
        s.text(&kept, "replaced").unwrap();
        s.dir(&new_dir).unwrap();
        s.text(&new_dir.join("a.txt"), "a").unwrap();
        s.commit().unwrap();
        assert_eq!(fs::read_to_string(&kept).unwrap(), "replaced");
        assert_eq!(fs::read_to_string(new_dir.join("a.txt")).unwrap(), "a");
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 2);
    }

    #[test]
    fn plans_refuse_bad_paths() {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("in.off");
        fs::write(&input, "x").unwrap();
        let mut plan = Plan::new(&[("IN", &input)]);
        assert!(plan.file("OUT", &dir.path().join("no/out.off")).is_err());
        assert!(plan.file("OUT", dir.path()).is_err());
        assert!(plan.file("OUT", &input).is_err());
        assert!(plan.mesh("OUT", &dir.path().join("out.xyz")).is_err());
        assert!(plan.mesh("OUT", &dir.path().join("out.off")).is_ok());
        assert!(plan.file("--report", &dir.path().join("out.off")).is_err());
        assert!(plan.dir("OUTDIR", &dir.path().join("a/b"), &[]).is_err());
        assert!(
            plan.dir("OUTDIR", &dir.path().join("a"), &["x.off".into()])
                .is_ok()
        );
    }
}
