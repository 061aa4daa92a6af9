//! The node tags of the `$Nodes` section, block by block.
//!
//! `mshio` keeps a block's node tags only when the file's tags are sparse
//! (`maxNodeTag - minNodeTag + 1 > numNodes`); when they are dense it reads
//! and drops them, and the order of tags in the file is lost. Rather than
//! assume that dense tags run in file order (true of what Gmsh writes, not
//! of every file), this module reads them again from the bytes, after
//! `mshio` accepted the file:
//!
//! ```text
//! $Nodes
//! numEntityBlocks(size_t) numNodes(size_t) minNodeTag(size_t) maxNodeTag(size_t)
//! entityDim(int) entityTag(int) parametric(int; 0) numNodesInBlock(size_t)
//!   nodeTag(size_t) ...
//!   x(double) y(double) z(double) ...
//! ...
//! $EndNodes
//! ```
//!
//! The caller checks the result against `mshio`'s blocks (their number and
//! lengths), so a `$Nodes`-like byte sequence elsewhere cannot go unnoticed.

use super::error::MshErrorKind;
use super::guard::{Encoding, line_break, line_of, unsigned};

/// The node tags of each block of the first `$Nodes` section, in file
/// order.
pub(super) fn node_tags(bytes: &[u8], encoding: Encoding) -> Result<Vec<Vec<u64>>, MshErrorKind> {
    let start = first_section(bytes).ok_or_else(|| malformed(bytes, 0, "no `$Nodes` section"))?;
    let mut cursor = Cursor {
        bytes,
        at: start,
        encoding,
    };
    let blocks = cursor.size_t()?;
    for _ in 0..3 {
        cursor.size_t()?; // numNodes, minNodeTag, maxNodeTag
    }
    let mut tags = Vec::new();
    for _ in 0..blocks {
        for _ in 0..3 {
            cursor.int()?; // entityDim, entityTag, parametric
        }
        let n = cursor.size_t()?;
        let mut block = Vec::new();
        for _ in 0..n {
            block.push(cursor.size_t()?);
        }
        cursor.skip_doubles(n.saturating_mul(3))?;
        tags.push(block);
    }
    Ok(tags)
}

/// The offset just after the first `$Nodes` line.
fn first_section(bytes: &[u8]) -> Option<usize> {
    const TAG: &[u8] = b"$Nodes";
    bytes
        .windows(TAG.len())
        .enumerate()
        .filter(|&(_, w)| w == TAG)
        .find_map(|(at, _)| {
            let after = at + TAG.len();
            line_break(&bytes[after..]).map(|br| after + br)
        })
}

fn malformed(bytes: &[u8], at: usize, what: &str) -> MshErrorKind {
    MshErrorKind::Malformed {
        offset: at,
        line: line_of(bytes, at),
        what: what.to_owned(),
        context: ", reading the node tags".to_owned(),
    }
}

/// Reads numbers of the section, ASCII or binary.
struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
    encoding: Encoding,
}

impl Cursor<'_> {
    /// An unsigned integer (`size_t`).
    fn size_t(&mut self) -> Result<u64, MshErrorKind> {
        match self.encoding.binary {
            Some(little_endian) => {
                let value = self.binary(self.encoding.size_t, little_endian)?;
                u64::try_from(value).map_err(|_| self.error("a size_t beyond 64 bits"))
            }
            None => {
                let token = self.token()?;
                std::str::from_utf8(token)
                    .ok()
                    .and_then(|t| t.parse().ok())
                    .ok_or_else(|| self.error("an unsigned integer expected"))
            }
        }
    }

    /// A signed integer (`int`, 4 bytes in binary files); its value is not
    /// needed.
    fn int(&mut self) -> Result<(), MshErrorKind> {
        match self.encoding.binary {
            Some(little_endian) => self.binary(4, little_endian).map(|_| ()),
            None => self.token().map(|_| ()),
        }
    }

    /// Skips `n` doubles (8 bytes each in binary files).
    fn skip_doubles(&mut self, n: u64) -> Result<(), MshErrorKind> {
        match self.encoding.binary {
            Some(_) => {
                let len = usize::try_from(n)
                    .ok()
                    .and_then(|n| n.checked_mul(8))
                    .filter(|len| self.at + len <= self.bytes.len())
                    .ok_or_else(|| self.error("the file ends in the node coordinates"))?;
                self.at += len;
            }
            None => {
                for _ in 0..n {
                    self.token()?;
                }
            }
        }
        Ok(())
    }

    /// The next `len` bytes as an unsigned integer.
    fn binary(&mut self, len: usize, little_endian: bool) -> Result<u128, MshErrorKind> {
        let bytes = self
            .bytes
            .get(self.at..self.at + len)
            .ok_or_else(|| self.error("the file ends in the node section"))?;
        let value = unsigned(bytes, little_endian);
        self.at += len;
        Ok(value)
    }

    /// The next whitespace-separated token (ASCII files).
    fn token(&mut self) -> Result<&[u8], MshErrorKind> {
        let is_space = |b: &u8| b" \t\r\n".contains(b);
        let rest = &self.bytes[self.at..];
        let start = rest.iter().position(|b| !is_space(b)).unwrap_or(rest.len());
        let len = rest[start..]
            .iter()
            .position(is_space)
            .unwrap_or(rest.len() - start);
        if len == 0 {
            return Err(self.error("the file ends in the node section"));
        }
        self.at += start + len;
        Ok(&self.bytes[self.at - len..self.at])
    }

    fn error(&self, what: &str) -> MshErrorKind {
        malformed(self.bytes, self.at, what)
    }
}
