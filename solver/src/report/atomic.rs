//! Atomic file output: every file `gapsim run --out` and `gapsim study
//! --out` write goes through [`write_atomic`] (or [`replace_with`] for
//! writers that want a path, such as the plotting backends).
//!
//! The contents are written to a temporary file in the **same directory**
//! (`.NAME.PID.N.tmp.EXT`: hidden, unique per process and call, with the
//! target's extension so that writers that pick a format by extension
//! still work), flushed to disk, and then renamed over the target. A rename
//! within one file system replaces the target in one step, so a reader
//! sees either the old file or the complete new one, never a partial
//! write; a failed write removes its temporary file and leaves the target
//! as it was.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Calls so far in this process (makes temporary names unique across
/// threads).
static CALLS: AtomicUsize = AtomicUsize::new(0);

/// The temporary file [`replace_with`] writes before renaming it to
/// `path`.
fn temporary_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let ext = path
        .extension()
        .map_or_else(String::new, |e| format!(".{}", e.to_string_lossy()));
    let n = CALLS.fetch_add(1, Ordering::Relaxed);
    path.with_file_name(format!(".{name}.{}.{n}.tmp{ext}", std::process::id()))
}

/// Writes `contents` to `path` atomically (see the module docs).
pub fn write_atomic(path: impl AsRef<Path>, contents: impl AsRef<[u8]>) -> std::io::Result<()> {
    replace_with(path.as_ref(), |tmp| {
        let mut file = std::fs::File::create_new(tmp)?;
        file.write_all(contents.as_ref())?;
        file.sync_all()
    })
}

/// Lets `write` create the file at a temporary path next to `path`, then
/// renames it to `path`. On an error from `write` or the rename the
/// temporary file is removed and `path` is untouched.
pub fn replace_with<T, E: From<std::io::Error>>(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<T, E>,
) -> Result<T, E> {
    let tmp = temporary_path(path);
    let result = write(&tmp).and_then(|value| {
        std::fs::rename(&tmp, path)?;
        Ok(value)
    });
    if result.is_err() {
        // the temporary file may not exist (the writer failed before
        // creating it); nothing else to do then
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fresh, empty directory for test `name`.
    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("gapsim-out-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn writes_and_replaces_without_leaving_a_temporary_file() {
        let dir = scratch("replace");
        let path = dir.join("a.csv");
        write_atomic(&path, "first\n").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "first\n");
        write_atomic(&path, "second, longer\n").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "second, longer\n");
        write_atomic(&path, "3\n").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "3\n");
        assert_eq!(entries(&dir), ["a.csv"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failed_write_leaves_the_target_and_no_temporary_file() {
        let dir = scratch("fail");
        let path = dir.join("plot.png");
        write_atomic(&path, "old").unwrap();
        let result: Result<(), std::io::Error> = replace_with(&path, |tmp| {
            assert_eq!(tmp.parent(), Some(dir.as_path()));
            assert_eq!(tmp.extension().unwrap(), "png");
            std::fs::write(tmp, "partial")?;
            Err(std::io::Error::other("the writer failed"))
        });
        assert_eq!(result.unwrap_err().to_string(), "the writer failed");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(entries(&dir), ["plot.png"]);
        // a directory in the way: the rename fails, the temporary goes
        let blocked = dir.join("sub");
        std::fs::create_dir(&blocked).unwrap();
        std::fs::write(blocked.join("x"), "").unwrap();
        assert!(write_atomic(&blocked, "text").is_err());
        assert_eq!(entries(&dir), ["plot.png", "sub"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
