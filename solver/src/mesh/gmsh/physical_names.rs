//! The `$PhysicalNames` section, which `mshio` skips.
//!
//! ```text
//! $PhysicalNames
//! numPhysicalNames
//! dimension physicalTag "name"
//! ...
//! $EndPhysicalNames
//! ```
//!
//! The section is text in binary files too. It is found as the first line
//! that is exactly `$PhysicalNames` (Gmsh writes it right after
//! `$MeshFormat`); a file without it has no named groups.

use super::error::MshErrorKind;
use super::guard::{line_break, line_of};

/// One entry of `$PhysicalNames`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct PhysicalName {
    /// The group's dimension (0 to 3).
    pub(super) dim: u8,
    /// The group's physical tag.
    pub(super) tag: i32,
    /// Its name, without the quotes.
    pub(super) name: String,
}

/// The entries of the file's `$PhysicalNames` section, in file order; empty
/// if it has none.
pub(super) fn parse(bytes: &[u8]) -> Result<Vec<PhysicalName>, MshErrorKind> {
    let Some(at) = section_start(bytes) else {
        return Ok(Vec::new());
    };
    let mut lines = Lines {
        bytes,
        at,
        line: line_of(bytes, at),
    };
    let (line, count) = lines.next("the number of names")?;
    let count: usize = count.parse().map_err(|_| {
        bad(
            line,
            format!("expected the number of names, found `{count}`"),
        )
    })?;
    let mut names = Vec::new();
    for k in 0..count {
        let (line, text) = lines.next(&format!("name {} of {count}", k + 1))?;
        names.push(entry(text).map_err(|what| bad(line, what))?);
    }
    let (line, end) = lines.next("`$EndPhysicalNames`")?;
    if end != "$EndPhysicalNames" {
        return Err(bad(
            line,
            format!("expected `$EndPhysicalNames` after {count} names, found `{end}`"),
        ));
    }
    Ok(names)
}

/// A cursor over the lines of the section.
struct Lines<'a> {
    bytes: &'a [u8],
    /// Offset of the next line.
    at: usize,
    /// Its 1-based line number.
    line: usize,
}

impl<'a> Lines<'a> {
    /// The next line (its number and trimmed text); `what` names what it
    /// should hold, for the error if the file ends.
    fn next(&mut self, what: &str) -> Result<(usize, &'a str), MshErrorKind> {
        let line = self.line;
        let rest = &self.bytes[self.at..];
        let Some(len) = rest.iter().position(|&b| b == b'\n') else {
            return Err(bad(line, format!("the file ends before {what}")));
        };
        self.at += len + 1;
        self.line += 1;
        let text = std::str::from_utf8(&rest[..len])
            .map_err(|_| bad(line, "the line is not UTF-8 text".to_owned()))?;
        Ok((line, text.trim()))
    }
}

/// The offset just after the first line `$PhysicalNames`.
fn section_start(bytes: &[u8]) -> Option<usize> {
    const TAG: &[u8] = b"$PhysicalNames";
    let mut line_start = 0;
    while line_start < bytes.len() {
        let rest = &bytes[line_start..];
        if let Some(after) = rest.strip_prefix(TAG)
            && let Some(br) = line_break(after)
        {
            return Some(line_start + TAG.len() + br);
        }
        let len = rest.iter().position(|&b| b == b'\n')?;
        line_start += len + 1;
    }
    None
}

/// `dim tag "name"`.
fn entry(text: &str) -> Result<PhysicalName, String> {
    let malformed = || format!("expected `dimension tag \"name\"`, found `{text}`");
    let (dim, rest) = text.split_once(char::is_whitespace).ok_or_else(malformed)?;
    let (tag, name) = rest
        .trim_start()
        .split_once(char::is_whitespace)
        .ok_or_else(malformed)?;
    let dim: u8 = dim
        .parse()
        .ok()
        .filter(|d| *d <= 3)
        .ok_or_else(|| format!("dimension `{dim}` is not 0, 1, 2 or 3"))?;
    let tag: i32 = tag
        .parse()
        .map_err(|_| format!("physical tag `{tag}` is not an integer"))?;
    let name = name
        .trim()
        .strip_prefix('"')
        .and_then(|n| n.strip_suffix('"'))
        .filter(|n| !n.contains('"'))
        .ok_or_else(malformed)?;
    Ok(PhysicalName {
        dim,
        tag,
        name: name.to_owned(),
    })
}

fn bad(line: usize, what: String) -> MshErrorKind {
    MshErrorKind::BadPhysicalNames { line, what }
}
