//! `--out DIR`: the directory a command writes its result set to
//! (`gapsim run`, `gapsim study`, `gapsim safety-map`). `DIR` holds either
//! the whole new result set or the old one, never a mix of the two and
//! never a temporary file.
//!
//! 1. Before any work, [`OutDir::check`] makes sure `DIR` can be written:
//!    it is a directory or does not exist yet, no ancestor of it is a
//!    file, and the nearest existing one lets a directory be created in it
//!    (a probe directory, removed at once). Nothing else is created.
//! 2. After the work, [`OutDir::stage`] creates `DIR` (if it did not exist)
//!    and in it the hidden staging directory `.gapsim-staging-PID`; the
//!    command writes its whole result set there ([`Staging::path`]).
//! 3. [`Staging::commit`] moves the files into `DIR` by renames (within
//!    one file system: each replaces its target in one step), then removes
//!    the files of the command's earlier result sets that the new set does
//!    not have (the names [`OutDir`] was given as its own, such as
//!    `step-0007.vtu` of a run with more steps; and the hidden
//!    `.NAME.PID.N.tmp.EXT` temporaries that earlier gapsim versions could
//!    leave next to such a file), then the empty staging directory.
//!    Files of other names in `DIR` are left alone.
//!
//! A [`Staging`] that is dropped without being committed (an error while
//! writing, or an [`Interrupt`] seen by [`Staging::commit`]) removes its
//! staging directory and the directories [`OutDir::stage`] created: `DIR`
//! is then exactly as before. Between the check and the commit a signal
//! only sets the interrupt flag ([`super::interrupt`]), so the renames of
//! step 3 (a few system calls) always run to their end; only a `kill -9`
//! or a power loss within them could leave a mix.

use std::io::ErrorKind;
use std::path::{Path, PathBuf};

use super::interrupt::Interrupt;

/// Why `--out DIR` cannot be written, or was left as it was.
#[derive(Debug, thiserror::Error)]
pub enum OutDirError {
    /// `DIR`, or one of its ancestors, is a file.
    #[error("--out {path}: {blocker} is a file, not a directory")]
    NotADirectory {
        /// The `--out` directory.
        path: PathBuf,
        /// The file in the way.
        blocker: PathBuf,
    },
    /// A directory cannot be created where `DIR` is (or would be).
    #[error("--out {path}: cannot create a directory in {dir}: {source}")]
    Unwritable {
        /// The `--out` directory.
        path: PathBuf,
        /// The nearest existing directory.
        dir: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A file operation of staging or committing failed.
    #[error("--out {path}: cannot {action} {file}: {source}")]
    Io {
        /// The `--out` directory.
        path: PathBuf,
        /// What was being done.
        action: &'static str,
        /// The file or directory.
        file: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The new result set would replace a directory of the same name.
    #[error("--out {path}: {file} is a directory; the result file of that name cannot replace it")]
    DirectoryInTheWay {
        /// The `--out` directory.
        path: PathBuf,
        /// The directory in the way.
        file: PathBuf,
    },
    /// A signal arrived before the result set was moved into place.
    #[error("interrupted: nothing written, {path} left as it was")]
    Interrupted {
        /// The `--out` directory.
        path: PathBuf,
    },
}

/// A checked `--out` directory (module docs).
#[derive(Debug, Clone)]
pub struct OutDir {
    path: PathBuf,
    /// Whether a file name belongs to this command's result sets.
    owns: fn(&str) -> bool,
}

impl OutDir {
    /// Checks that `path` can become the output directory (module docs,
    /// step 1); `owns` names the files of the command's result sets.
    pub fn check(path: &Path, owns: fn(&str) -> bool) -> Result<OutDir, OutDirError> {
        let out = OutDir {
            path: path.to_owned(),
            owns,
        };
        let existing = out.nearest_existing()?;
        let probe = existing.join(format!(".gapsim-probe-{}", std::process::id()));
        std::fs::create_dir(&probe).map_err(|source| OutDirError::Unwritable {
            path: out.path.clone(),
            dir: existing.clone(),
            source,
        })?;
        std::fs::remove_dir(&probe).map_err(|source| out.io("remove", &probe, source))?;
        Ok(out)
    }

    /// The output directory.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// `path` itself or its nearest existing ancestor (a directory), or
    /// the file that is in the way.
    fn nearest_existing(&self) -> Result<PathBuf, OutDirError> {
        let mut at: &Path = &self.path;
        loop {
            let probe = if at.as_os_str().is_empty() {
                Path::new(".")
            } else {
                at
            };
            match std::fs::metadata(probe) {
                Ok(m) if m.is_dir() => return Ok(probe.to_owned()),
                Ok(_) => {
                    return Err(OutDirError::NotADirectory {
                        path: self.path.clone(),
                        blocker: probe.to_owned(),
                    });
                }
                // missing, or below a file: look further up
                Err(e) if matches!(e.kind(), ErrorKind::NotFound | ErrorKind::NotADirectory) => {}
                Err(e) => return Err(self.io("inspect", probe, e)),
            }
            match at.parent() {
                Some(parent) => at = parent,
                None => return Err(self.io("inspect", &self.path, ErrorKind::NotFound.into())),
            }
        }
    }

    fn io(&self, action: &'static str, file: &Path, source: std::io::Error) -> OutDirError {
        OutDirError::Io {
            path: self.path.clone(),
            action,
            file: file.to_owned(),
            source,
        }
    }

    /// Creates the staging directory (module docs, step 2).
    pub fn stage(&self) -> Result<Staging<'_>, OutDirError> {
        let mut staging = Staging {
            out: self,
            dir: self
                .path
                .join(format!(".gapsim-staging-{}", std::process::id())),
            created: Vec::new(),
            committed: false,
        };
        // the missing ancestors, outermost first
        let mut missing = Vec::new();
        let mut at = Some(self.path.as_path());
        while let Some(a) = at.filter(|a| !a.as_os_str().is_empty() && !a.exists()) {
            missing.push(a.to_owned());
            at = a.parent();
        }
        for dir in missing.into_iter().rev() {
            std::fs::create_dir(&dir).map_err(|e| self.io("create", &dir, e))?;
            staging.created.push(dir);
        }
        if staging.dir.exists() {
            // left by a killed process that had this process id
            std::fs::remove_dir_all(&staging.dir)
                .map_err(|e| self.io("remove", &staging.dir, e))?;
        }
        std::fs::create_dir(&staging.dir).map_err(|e| self.io("create", &staging.dir, e))?;
        Ok(staging)
    }

    /// Whether `name` is a temporary file that an earlier version's atomic
    /// writer could leave: `.NAME.PID.N.tmp[.EXT]` with an owned `NAME`.
    fn is_old_temporary(&self, name: &str) -> bool {
        let Some(rest) = name.strip_prefix('.') else {
            return false;
        };
        let Some(head) = rest.rfind(".tmp").map(|i| &rest[..i]) else {
            return false;
        };
        let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
        let mut parts = head.rsplitn(3, '.');
        match (parts.next(), parts.next(), parts.next()) {
            (Some(n), Some(pid), Some(base)) => digits(n) && digits(pid) && (self.owns)(base),
            _ => false,
        }
    }
}

/// A result set being written (module docs, steps 2 and 3).
#[derive(Debug)]
pub struct Staging<'a> {
    out: &'a OutDir,
    dir: PathBuf,
    /// Directories [`OutDir::stage`] created, outermost first.
    created: Vec<PathBuf>,
    committed: bool,
}

impl Staging<'_> {
    /// The staging directory: write the result set here.
    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// Moves the result set into the output directory (module docs, step
    /// 3), unless `interrupt` has been requested: then nothing is moved,
    /// the staging directory is removed and the error says so.
    pub fn commit(mut self, interrupt: Option<&Interrupt>) -> Result<(), OutDirError> {
        let out = self.out;
        if interrupt.is_some_and(Interrupt::requested) {
            return Err(OutDirError::Interrupted {
                path: out.path.clone(),
            });
        }
        let names = file_names(&self.dir).map_err(|e| out.io("list", &self.dir, e))?;
        // nothing is moved when one of them cannot be
        for name in &names {
            let target = out.path.join(name);
            if target.is_dir() {
                return Err(OutDirError::DirectoryInTheWay {
                    path: out.path.clone(),
                    file: target,
                });
            }
        }
        for name in &names {
            let (from, to) = (self.dir.join(name), out.path.join(name));
            std::fs::rename(&from, &to).map_err(|e| out.io("move into place", &to, e))?;
        }
        let old = file_names(&out.path).map_err(|e| out.io("list", &out.path, e))?;
        for name in old {
            let stale = !names.contains(&name) && (out.owns)(&name);
            if stale || out.is_old_temporary(&name) {
                let path = out.path.join(&name);
                std::fs::remove_file(&path).map_err(|e| out.io("remove", &path, e))?;
            }
        }
        std::fs::remove_dir(&self.dir).map_err(|e| out.io("remove", &self.dir, e))?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for Staging<'_> {
    fn drop(&mut self) {
        if self.committed {
            return;
        }
        // best effort: an error here has nothing left to report to
        let _ = std::fs::remove_dir_all(&self.dir);
        for dir in self.created.iter().rev() {
            let _ = std::fs::remove_dir(dir);
        }
    }
}

/// The names of the files (not directories) in `dir`, sorted.
fn file_names(dir: &Path) -> std::io::Result<Vec<String>> {
    let mut names = Vec::new();
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        if !entry.file_type()?.is_dir() {
            names.push(entry.file_name().to_string_lossy().into_owned());
        }
    }
    names.sort();
    Ok(names)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn owns(name: &str) -> bool {
        matches!(name, "a.csv" | "b.csv")
    }

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("gapsim-outdir-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    fn entries(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn a_file_in_the_way_is_named_before_any_work() {
        let dir = scratch("file");
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("f");
        std::fs::write(&file, "").unwrap();
        for path in [file.clone(), file.join("sub"), file.join("sub/deeper")] {
            let msg = OutDir::check(&path, owns).unwrap_err().to_string();
            assert_eq!(
                msg,
                format!(
                    "--out {}: {} is a file, not a directory",
                    path.display(),
                    file.display()
                )
            );
        }
        // a new directory below a directory is fine, and is not created
        let new = dir.join("x/y");
        OutDir::check(&new, owns).unwrap();
        assert_eq!(entries(&dir), ["f"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_commit_replaces_the_whole_set_and_keeps_other_files() {
        let dir = scratch("commit");
        std::fs::create_dir_all(&dir).unwrap();
        for (name, text) in [
            ("a.csv", "old a"),
            ("b.csv", "old b"),
            ("notes.txt", "mine"),
            (".a.csv.123.0.tmp.csv", "old temporary"),
            (".notes.txt.123.0.tmp.txt", "not ours"),
        ] {
            std::fs::write(dir.join(name), text).unwrap();
        }
        let out = OutDir::check(&dir, owns).unwrap();
        let staging = out.stage().unwrap();
        std::fs::write(staging.path().join("a.csv"), "new a").unwrap();
        staging.commit(None).unwrap();
        assert_eq!(
            entries(&dir),
            [".notes.txt.123.0.tmp.txt", "a.csv", "notes.txt"]
        );
        assert_eq!(std::fs::read_to_string(dir.join("a.csv")).unwrap(), "new a");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_abandoned_staging_leaves_everything_as_it_was() {
        let dir = scratch("abandon");
        let out = OutDir::check(&dir.join("new/deeper"), owns).unwrap();
        assert!(!dir.exists());
        {
            let staging = out.stage().unwrap();
            std::fs::write(staging.path().join("a.csv"), "new a").unwrap();
            assert!(dir.join("new/deeper").is_dir());
        }
        assert!(!dir.exists());
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("a.csv"), "old a").unwrap();
        let out = OutDir::check(&dir, owns).unwrap();
        let staging = out.stage().unwrap();
        std::fs::write(staging.path().join("a.csv"), "new a").unwrap();
        drop(staging);
        assert_eq!(entries(&dir), ["a.csv"]);
        assert_eq!(std::fs::read_to_string(dir.join("a.csv")).unwrap(), "old a");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_directory_in_the_way_stops_the_commit_before_anything_moves() {
        let dir = scratch("dir");
        std::fs::create_dir_all(dir.join("b.csv")).unwrap();
        std::fs::write(dir.join("a.csv"), "old a").unwrap();
        let out = OutDir::check(&dir, owns).unwrap();
        let staging = out.stage().unwrap();
        std::fs::write(staging.path().join("a.csv"), "new a").unwrap();
        std::fs::write(staging.path().join("b.csv"), "new b").unwrap();
        let msg = staging.commit(None).unwrap_err().to_string();
        assert!(msg.contains("is a directory"), "{msg}");
        assert_eq!(entries(&dir), ["a.csv", "b.csv"]);
        assert_eq!(std::fs::read_to_string(dir.join("a.csv")).unwrap(), "old a");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
