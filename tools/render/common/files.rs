//! The output files of a run: checked before anything is rendered ([`target`]), written under
//! temporary names ([`Transaction::create`]) and renamed into place together, or not at all
//! ([`Transaction::commit`]).
//!
//! The rules, for every output of a run:
//!
//! - Its name ends in the extension of its kind (`.png`, `.pfm`, `.gif`).
//! - An existing output is replaced only when it is a regular file with write permission and
//!   one hard link (like `cp` without `-f`, a read-only file is refused, also for root), and
//!   the new file gets the old one's permissions. A symbolic link is followed: the file it names
//!   is replaced and the link stays; a link to a missing file is refused (like `cp`).
//! - No two outputs are one file, whatever the spelling (`a.png`, `./a.png`, `d/../a.png`,
//!   symbolic links): targets compare by their resolved path.
//! - No output is an input of the run (a scene file, a texture): they compare by device and
//!   inode, and by resolved path.
//! - A missing directory is created only when the run commits; a run that fails creates
//!   nothing. Until then the temporary files live in the nearest existing directory.
//! - Commit renames every temporary into place, first moving each existing output aside; if a
//!   rename fails, every output is put back as it was, and the run reports the error.

use std::fs::{File, Permissions};
use std::io::{BufWriter, Write};
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// The kinds of output file, by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// An 8-bit sRGB picture.
    Png,
    /// The linear image in 32-bit floats.
    Pfm,
    /// An animation.
    Gif,
}

impl Kind {
    /// The file name's extension.
    pub fn extension(self) -> &'static str {
        match self {
            Kind::Png => "png",
            Kind::Pfm => "pfm",
            Kind::Gif => "gif",
        }
    }
}

/// A file identity: device and inode (on other systems, none: paths compare instead).
pub type FileId = Option<(u64, u64)>;

fn file_id(meta: &std::fs::Metadata) -> FileId {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        Some((meta.dev(), meta.ino()))
    }
    #[cfg(not(unix))]
    {
        let _ = meta;
        None
    }
}

fn hard_links(meta: &std::fs::Metadata) -> u64 {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        meta.nlink()
    }
    #[cfg(not(unix))]
    {
        let _ = meta;
        1
    }
}

/// Whether the mode gives anyone write permission.
fn writable(meta: &std::fs::Metadata) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        meta.permissions().mode() & 0o222 != 0
    }
    #[cfg(not(unix))]
    {
        !meta.permissions().readonly()
    }
}

/// An input of a run (a scene file, a texture), as the user named it and resolved.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Input {
    /// What it is, for messages ("the scene file", "a texture of fig6").
    pub what: String,
    /// The name the user gave.
    pub shown: PathBuf,
    /// Its resolved path and identity.
    pub path: PathBuf,
    /// Its device and inode.
    pub id: FileId,
}

impl Input {
    /// The input at `path` (which exists: it was read).
    pub fn new(what: impl Into<String>, path: &Path) -> Input {
        let resolved = path.canonicalize().unwrap_or_else(|_| path.to_path_buf());
        Input {
            what: what.into(),
            shown: path.to_path_buf(),
            id: std::fs::metadata(&resolved).ok().as_ref().and_then(file_id),
            path: resolved,
        }
    }
}

/// An output file checked before rendering (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Target {
    /// The name the user gave (or the default), for messages.
    pub shown: PathBuf,
    /// The option that named it (`--out`, `--pfm`), or "" for a default name.
    pub flag: &'static str,
    /// What it holds.
    pub kind: Kind,
    /// Where it goes: the resolved directory (which may not exist yet) and the file name.
    pub path: PathBuf,
    /// The directory the temporary file is written in: the target's, or its nearest existing
    /// ancestor when the target's does not exist yet.
    stage: PathBuf,
    /// The file it replaces: its identity and permissions.
    existing: Option<(FileId, Permissions)>,
}

impl Target {
    /// The message prefix naming the target: `--out x.png` or `out/x.png`.
    fn named(&self) -> String {
        named(self.flag, &self.shown)
    }
}

fn named(flag: &str, shown: &Path) -> String {
    if flag.is_empty() {
        shown.display().to_string()
    } else {
        format!("{flag} {}", shown.display())
    }
}

/// `path` with `.` and `..` removed lexically (for components that do not exist yet).
fn lexical(path: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            c => out.push(c),
        }
    }
    out
}

/// The nearest existing ancestor of `dir` (resolved) and the components below it (`..`
/// included: they are removed lexically later, as the directories below do not exist).
fn existing_ancestor(dir: &Path) -> std::io::Result<(PathBuf, PathBuf)> {
    let parts: Vec<Component> = dir.components().collect();
    let mut keep = parts.len();
    loop {
        let base: PathBuf = parts[..keep].iter().collect();
        let probe = if base.as_os_str().is_empty() {
            Path::new(".")
        } else {
            base.as_path()
        };
        match probe.canonicalize() {
            Ok(resolved) => return Ok((resolved, parts[keep..].iter().collect())),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound && keep > 0 => keep -= 1,
            Err(e) => return Err(e),
        }
    }
}

/// Checks an output file before anything is rendered: its name, its directory (the nearest
/// existing one takes new files), and the file it would replace (see the [module docs](self)).
/// `flag` is the option that named it ("" for a default name).
pub fn target(path: &Path, kind: Kind, flag: &'static str) -> Result<Target, String> {
    let shown = named(flag, path);
    let ext = kind.extension();
    let name = path.file_name().map(|n| n.to_string_lossy().to_lowercase());
    if name.as_deref() == Some(&format!(".{ext}")) {
        return Err(format!(
            "{shown}: expected a file name before the extension .{ext}"
        ));
    }
    if !path
        .extension()
        .is_some_and(|x| x.eq_ignore_ascii_case(ext))
    {
        return Err(format!("{shown}: expected a file name ending in .{ext}"));
    }
    let name = path
        .file_name()
        .ok_or_else(|| format!("{shown}: expected a file name"))?;
    let dir = path.parent().unwrap_or(Path::new(""));
    let (ancestor, below) = existing_ancestor(dir).map_err(|e| {
        format!(
            "{shown}: cannot resolve the directory {}: {e}",
            dir.display()
        )
    })?;
    if !ancestor.is_dir() {
        return Err(format!(
            "{shown}: cannot create the directory {}: {} is not a directory",
            dir.display(),
            ancestor.display()
        ));
    }
    let mut resolved = lexical(&ancestor.join(below).join(name));
    let mut stage = ancestor;
    let mut existing = None;
    if let Ok(link) = std::fs::symlink_metadata(&resolved) {
        if link.file_type().is_symlink() {
            // The file the link names is replaced, the link stays.
            resolved = resolved.canonicalize().map_err(|_| {
                format!(
                    "{shown}: is a symbolic link to a missing file: not followed (remove the \
                     link, or name another file)"
                )
            })?;
            stage = resolved.parent().unwrap_or(Path::new("/")).to_path_buf();
        }
        let meta = std::fs::metadata(&resolved).map_err(|e| format!("{shown}: {e}"))?;
        if !meta.is_file() {
            return Err(format!(
                "{shown}: exists and is not a regular file, so it is not replaced"
            ));
        }
        if !writable(&meta) {
            return Err(format!(
                "{shown}: exists and is read-only: not replaced (make it writable, or name \
                 another file{})",
                if flag.is_empty() { " with --out" } else { "" }
            ));
        }
        let links = hard_links(&meta);
        if links > 1 {
            return Err(format!(
                "{shown}: has {links} hard links: not replaced, which would leave the other \
                 names with the old content (remove it first, or name another file)"
            ));
        }
        existing = Some((file_id(&meta), meta.permissions()));
    }
    // Writable: a temporary file can be made where it will be staged (and is removed at once).
    let probe = temporary(&stage, name);
    File::options()
        .write(true)
        .create_new(true)
        .open(&probe)
        .map_err(|e| format!("{shown}: cannot create a file in {}: {e}", stage.display()))?;
    let _ = std::fs::remove_file(&probe);
    Ok(Target {
        shown: path.to_path_buf(),
        flag,
        kind,
        path: resolved,
        stage,
        existing,
    })
}

/// A directory of outputs (several scenes' pictures, or an animation's frames), named by
/// `--out` (`flag`) or by default: it may not exist yet (it is created when the run commits),
/// but an existing path must be a directory, and a missing one must not look like a file name.
pub fn directory(dir: &Path, flag: &'static str, why: &str) -> Result<PathBuf, String> {
    let shown = named(flag, dir);
    if dir.exists() && !dir.is_dir() {
        return Err(format!(
            "{shown}: not a directory (give a directory, or one scene and a file name ending \
             in .png or .pfm)"
        ));
    }
    let looks_like_a_file = dir.file_name().is_some_and(|n| {
        let n = n.to_string_lossy().to_lowercase();
        ["png", "pfm", "gif"]
            .iter()
            .any(|x| n.ends_with(&format!(".{x}")))
    });
    if !dir.exists() && looks_like_a_file {
        return Err(format!(
            "{shown}: names a file, but {why} go into a directory: give a directory"
        ));
    }
    Ok(dir.to_path_buf())
}

/// Refuses two outputs on one file, and an output on an input of the run.
pub fn check(targets: &[Target], inputs: &[Input]) -> Result<(), String> {
    let mut seen: std::collections::HashMap<&Path, &Target> = std::collections::HashMap::new();
    for a in targets {
        if let Some(b) = seen.insert(&a.path, a) {
            return Err(format!(
                "{} and {} are the same file ({}): refusing to write two outputs on it",
                b.shown.display(),
                a.shown.display(),
                a.path.display()
            ));
        }
        let id = a.existing.as_ref().and_then(|(id, _)| *id);
        if let Some(i) = inputs
            .iter()
            .find(|i| i.path == a.path || (id.is_some() && i.id == id))
        {
            return Err(format!(
                "{}: is {} ({}): refusing to write over an input of the run",
                a.named(),
                i.what,
                i.shown.display()
            ));
        }
    }
    Ok(())
}

/// A temporary name in `dir` for a file called `name` (hidden, unique to this process).
fn temporary(dir: &Path, name: &std::ffi::OsStr) -> PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    let name = name.to_string_lossy();
    dir.join(format!(".{name}.{}-{n}.tmp", std::process::id()))
}

#[cfg(test)]
thread_local! {
    /// Tests: the bytes this thread may still write into staged files before a write fails as
    /// on a full disk (`None`: no limit).
    pub static SPACE_LEFT: std::cell::Cell<Option<u64>> = const { std::cell::Cell::new(None) };
}

/// A staged file's handle: writes fail like a full disk when the tests ask for it.
#[derive(Debug)]
pub struct Sink(File);

impl Sink {
    /// A second handle on the same file.
    pub fn try_clone(&self) -> std::io::Result<Sink> {
        self.0.try_clone().map(Sink)
    }
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        #[cfg(test)]
        if let Some(left) = SPACE_LEFT.with(|s| s.get()) {
            if left < buf.len() as u64 {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::StorageFull,
                    "No space left on device (a test's full disk)",
                ));
            }
            SPACE_LEFT.with(|s| s.set(Some(left - buf.len() as u64)));
        }
        self.0.write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.0.flush()
    }
}

/// One staged output: the temporary file being written.
#[derive(Debug)]
pub struct Staged {
    index: usize,
    writer: BufWriter<Sink>,
}

impl Staged {
    /// Where the content goes.
    pub fn writer(&mut self) -> &mut BufWriter<Sink> {
        &mut self.writer
    }
}

#[derive(Debug)]
struct Entry {
    target: Target,
    tmp: PathBuf,
    closed: bool,
}

/// The outputs of one run: each written to a temporary file, all renamed into place by
/// [`commit`](Transaction::commit). Dropped without a commit (an error, a panic), it removes
/// every temporary file and nothing is replaced.
#[derive(Debug, Default)]
pub struct Transaction {
    entries: Vec<Entry>,
}

impl Transaction {
    /// A new temporary file for `target`.
    pub fn create(&mut self, target: &Target) -> Result<Staged, String> {
        let name = target.path.file_name().unwrap_or_default();
        let tmp = temporary(&target.stage, name);
        let file = File::options()
            .write(true)
            .create_new(true)
            .open(&tmp)
            .map_err(|e| {
                format!(
                    "{}: cannot create a file in {}: {e}",
                    target.named(),
                    target.stage.display()
                )
            })?;
        self.entries.push(Entry {
            target: target.clone(),
            tmp,
            closed: false,
        });
        Ok(Staged {
            index: self.entries.len() - 1,
            writer: BufWriter::new(Sink(file)),
        })
    }

    /// Flushes and syncs a staged file: it is complete.
    pub fn close(&mut self, staged: Staged) -> Result<(), String> {
        let entry = &mut self.entries[staged.index];
        let fail =
            |e: std::io::Error| format!("cannot write {}: {e}", entry.target.shown.display());
        let file = staged
            .writer
            .into_inner()
            .map_err(|e| fail(e.into_error()))?;
        file.0.sync_all().map_err(fail)?;
        entry.closed = true;
        Ok(())
    }

    /// Writes a whole file with `write` and closes it.
    pub fn write(
        &mut self,
        target: &Target,
        write: impl FnOnce(&mut dyn Write) -> Result<(), String>,
    ) -> Result<(), String> {
        let mut staged = self.create(target)?;
        write(staged.writer())
            .map_err(|e| format!("cannot write {}: {e}", target.shown.display()))?;
        self.close(staged)
    }

    /// Renames every staged file into place (creating missing directories), each existing
    /// output moved aside first; on any failure everything is put back and nothing is
    /// replaced. Every staged file must be closed.
    pub fn commit(mut self) -> Result<(), String> {
        let entries = std::mem::take(&mut self.entries);
        let mut created: Vec<PathBuf> = Vec::new();
        // (target, its old content moved aside)
        let mut done: Vec<(PathBuf, Option<PathBuf>)> = Vec::new();
        let mut result = Ok(());
        for e in &entries {
            if let Err(msg) = Self::place(e, &mut created, &mut done) {
                result = Err(msg);
                break;
            }
        }
        if result.is_err() {
            for (target, old) in done.iter().rev() {
                match old {
                    Some(old) => {
                        let _ = std::fs::rename(old, target);
                    }
                    None => {
                        let _ = std::fs::remove_file(target);
                    }
                }
            }
        }
        for e in &entries {
            let _ = std::fs::remove_file(&e.tmp);
        }
        if result.is_err() {
            for dir in created.iter().rev() {
                let _ = std::fs::remove_dir(dir);
            }
        } else {
            for old in done.iter().filter_map(|(_, old)| old.as_ref()) {
                let _ = std::fs::remove_file(old);
            }
        }
        result
    }

    fn place(
        e: &Entry,
        created: &mut Vec<PathBuf>,
        done: &mut Vec<(PathBuf, Option<PathBuf>)>,
    ) -> Result<(), String> {
        let shown = e.target.shown.display();
        if !e.closed {
            return Err(format!("{shown}: not written"));
        }
        let target = &e.target.path;
        let dir = target.parent().unwrap_or(Path::new("/"));
        // The missing directories, outermost first.
        let missing: Vec<&Path> = dir.ancestors().take_while(|d| !d.exists()).collect();
        for d in missing.into_iter().rev() {
            std::fs::create_dir(d).map_err(|err| {
                format!(
                    "{shown}: cannot create the directory {}: {err}",
                    d.display()
                )
            })?;
            created.push(d.to_path_buf());
        }
        let mut old = None;
        if let Some((_, permissions)) = &e.target.existing {
            std::fs::set_permissions(&e.tmp, permissions.clone())
                .map_err(|err| format!("cannot write {shown}: {err}"))?;
            let aside =
                temporary(dir, target.file_name().unwrap_or_default()).with_extension("old");
            std::fs::rename(target, &aside)
                .map_err(|err| format!("cannot replace {shown}: {err}"))?;
            old = Some(aside);
        }
        match std::fs::rename(&e.tmp, target) {
            Ok(()) => {
                done.push((target.clone(), old));
                Ok(())
            }
            Err(err) => {
                if let Some(old) = old {
                    let _ = std::fs::rename(old, target);
                }
                Err(format!("cannot write {shown}: {err}"))
            }
        }
    }
}

/// Writes one file with `write` through its own checked target and transaction (`flag` the
/// option that named it).
pub fn write_one(
    path: &Path,
    kind: Kind,
    flag: &'static str,
    write: impl FnOnce(&mut dyn Write) -> Result<(), String>,
) -> Result<(), String> {
    let t = target(path, kind, flag)?;
    let mut files = Transaction::default();
    files.write(&t, write)?;
    files.commit()
}

impl Drop for Transaction {
    fn drop(&mut self) {
        for e in &self.entries {
            let _ = std::fs::remove_file(&e.tmp);
        }
    }
}
