//! Checks made before `mshio` sees the bytes, so that it never panics.
//!
//! `mshio` 0.4.2 returns errors for most malformed input, but panics on
//! three kinds of it (read from its source and confirmed by the tests in
//! `tests.rs`):
//!
//! * a binary file whose `$MeshFormat` data size is not 1, 2, 4, 8 or 16
//!   bytes (`unimplemented!` in its integer parsers);
//! * a data size whose digits overflow `usize` (`unwrap` in the header
//!   parser);
//! * a `$Nodes` or `$Elements` section that declares zero items but a valid
//!   tag range (`num - 1` underflows; a panic wherever overflow checks are
//!   on, as in the dev and test profiles).
//!
//! [`check`] rejects all three with a [`MshErrorKind`] before parsing: it
//! reads the header itself (which also gives the clear message for MSH 2
//! files), and looks at the item count after every `$Nodes` and
//! `$Elements` tag in the file. The second check may look at a tag-like
//! byte sequence inside binary data too; it then rejects a file only if
//! that sequence is followed by a zero count, which a real file never
//! has. Everything `mshio` reads without panicking is left to it (and to
//! the tests that truncate and corrupt files).

use super::error::MshErrorKind;

/// The integer sizes `mshio` has binary parsers for.
const SUPPORTED_SIZES: [usize; 5] = [1, 2, 4, 8, 16];

/// What the header says about the encoding of the data.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Encoding {
    /// `Some(little_endian)` for a binary file, `None` for ASCII.
    pub(super) binary: Option<bool>,
    /// Bytes of a `size_t` value (in binary files).
    pub(super) size_t: usize,
}

/// Rejects what would make `mshio` panic (see the module docs); returns the
/// file's encoding.
pub(super) fn check(bytes: &[u8]) -> Result<Encoding, MshErrorKind> {
    let encoding = header(bytes)?;
    for section in [&b"$Nodes"[..], b"$Elements"] {
        for start in section_starts(bytes, section) {
            if second_count_is_zero(&bytes[start..], encoding) {
                return Err(MshErrorKind::Malformed {
                    offset: start,
                    line: line_of(bytes, start),
                    what: format!(
                        "the `{}` section declares no items",
                        String::from_utf8_lossy(section)
                    ),
                    context: String::new(),
                });
            }
        }
    }
    Ok(encoding)
}

/// The 1-based line of byte `offset`.
pub(super) fn line_of(bytes: &[u8], offset: usize) -> usize {
    1 + bytes[..offset.min(bytes.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
}

/// The length of the line break at the start of `rest` (`\n` or `\r\n`),
/// if there is one.
pub(super) fn line_break(rest: &[u8]) -> Option<usize> {
    if rest.starts_with(b"\n") {
        Some(1)
    } else if rest.starts_with(b"\r\n") {
        Some(2)
    } else {
        None
    }
}

/// Reads `$MeshFormat` / `4.1 <0|1> <size>` and the binary endianness
/// marker.
fn header(bytes: &[u8]) -> Result<Encoding, MshErrorKind> {
    const TAG: &[u8] = b"$MeshFormat";
    let after_tag = bytes.strip_prefix(TAG).ok_or(MshErrorKind::NotMsh)?;
    let br = line_break(after_tag).ok_or(MshErrorKind::NotMsh)?;
    let rest = &after_tag[br..];
    let end = rest
        .iter()
        .position(|&b| b == b'\n')
        .ok_or_else(|| MshErrorKind::BadHeader("the file ends in the header".to_owned()))?;
    let line = std::str::from_utf8(&rest[..end])
        .map_err(|_| MshErrorKind::BadHeader("the version line is not text".to_owned()))?;
    let tokens: Vec<&str> = line.split_ascii_whitespace().collect();
    let [version, file_type, data_size] = tokens[..] else {
        return Err(MshErrorKind::BadHeader(format!(
            "expected `version file-type data-size`, found `{}`",
            line.trim()
        )));
    };
    match version.parse::<f64>() {
        Ok(4.1) => {}
        Ok(_) => return Err(MshErrorKind::UnsupportedVersion(version.to_owned())),
        Err(_) => {
            return Err(MshErrorKind::BadHeader(format!(
                "version `{version}` is not a number"
            )));
        }
    }
    let binary = match file_type {
        "0" => false,
        "1" => true,
        _ => {
            return Err(MshErrorKind::BadHeader(format!(
                "file type `{file_type}` is neither 0 (ASCII) nor 1 (binary)"
            )));
        }
    };
    let size_t = data_size
        .parse::<usize>()
        .ok()
        .filter(|s| SUPPORTED_SIZES.contains(s))
        .ok_or_else(|| {
            MshErrorKind::BadHeader(format!(
                "data size `{data_size}` is not one of 1, 2, 4, 8, 16"
            ))
        })?;
    if !binary {
        return Ok(Encoding {
            binary: None,
            size_t,
        });
    }
    let marker = rest
        .get(end + 1..end + 5)
        .ok_or_else(|| MshErrorKind::BadHeader("the file ends in the header".to_owned()))?;
    let marker: [u8; 4] = [marker[0], marker[1], marker[2], marker[3]];
    let little_endian = if i32::from_le_bytes(marker) == 1 {
        true
    } else if i32::from_be_bytes(marker) == 1 {
        false
    } else {
        return Err(MshErrorKind::BadHeader(
            "the binary endianness marker is not the integer 1".to_owned(),
        ));
    };
    Ok(Encoding {
        binary: Some(little_endian),
        size_t,
    })
}

/// The offsets just after every `tag` that is followed by a line break
/// (where `mshio` starts parsing a section's content).
fn section_starts<'a>(bytes: &'a [u8], tag: &'a [u8]) -> impl Iterator<Item = usize> + 'a {
    bytes
        .windows(tag.len())
        .enumerate()
        .filter(move |&(_, w)| w == tag)
        .filter_map(move |(at, _)| {
            let after = at + tag.len();
            line_break(&bytes[after..]).map(|br| after + br)
        })
}

/// Whether the second `size_t` of `content` (the number of nodes or
/// elements of a section) reads as zero. `false` when it cannot be read:
/// `mshio` then reports the error itself.
fn second_count_is_zero(content: &[u8], encoding: Encoding) -> bool {
    match encoding.binary {
        Some(little_endian) => {
            let n = encoding.size_t;
            content
                .get(n..2 * n)
                .is_some_and(|bytes| unsigned(bytes, little_endian) == 0)
        }
        None => {
            // As mshio's `ws(digit1)`: spaces, digits, spaces; twice.
            let is_space = |b: &u8| b" \t\r\n".contains(b);
            let mut rest = content;
            let mut digits: &[u8] = &[];
            for _ in 0..2 {
                let start = rest.iter().position(|b| !is_space(b)).unwrap_or(rest.len());
                rest = &rest[start..];
                let len = rest
                    .iter()
                    .position(|b| !b.is_ascii_digit())
                    .unwrap_or(rest.len());
                if len == 0 {
                    return false;
                }
                digits = &rest[..len];
                rest = &rest[len..];
            }
            digits.iter().all(|&b| b == b'0')
        }
    }
}

/// `bytes` (at most 16) as an unsigned integer.
pub(super) fn unsigned(bytes: &[u8], little_endian: bool) -> u128 {
    let mut value: u128 = 0;
    for k in 0..bytes.len() {
        let byte = if little_endian {
            bytes[bytes.len() - 1 - k]
        } else {
            bytes[k]
        };
        value = (value << 8) | u128::from(byte);
    }
    value
}
