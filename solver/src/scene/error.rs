//! Why a scene could not be read, and where in its file.

use serde_path_to_error::Segment;

use super::Scene;

/// Why a scene could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("{origin}: cannot read the scene: {message}")]
    Io {
        /// The file.
        origin: String,
        /// The operating system's message.
        message: String,
    },
    /// TOML syntax error, unknown or missing key, or a value of the wrong
    /// type.
    #[error("{origin}:{line}:{column}: {field}: {message}")]
    Syntax {
        /// The file (or another name of the text's origin).
        origin: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The dotted path of the field (e.g. `body[1].nx`,
        /// `loading.steps[0]`, or the unknown key itself), or `(document)`
        /// for a TOML syntax error, which comes before any field.
        field: String,
        /// What is wrong.
        message: String,
    },
    /// A feature the scene asks for that the solver does not have yet: the
    /// scene is read and checked, but no model is built. (No scene key
    /// gives it now: 3D contact pairs are built and solved.)
    #[error("{origin}: {field}: {message}")]
    Unsupported {
        /// The file.
        origin: String,
        /// The dotted path of the item (`contact[0]`).
        field: String,
        /// What is not supported.
        message: String,
    },
    /// A value that parses but makes no sense (e.g. `nx = 0`, a load point
    /// with no node).
    #[error("{origin}: {field}: {message}")]
    Invalid {
        /// The file.
        origin: String,
        /// The dotted path of the field.
        field: String,
        /// What is wrong.
        message: String,
    },
}

/// Parses `text` as a scene. A TOML error (syntax, unknown or missing key,
/// wrong type) becomes a [`SceneError::Syntax`] that names `origin`, the
/// line and column of the TOML crate's span, and the field's path as
/// `serde_path_to_error` tracked it (`(document)` for a syntax error, which
/// comes before any field).
pub(super) fn parse(text: &str, origin: &str) -> Result<Scene, SceneError> {
    let syntax = |e: &toml::de::Error, field: String| {
        let (line, column) = match e.span() {
            Some(span) => line_column(text, span.start),
            None => (0, 0),
        };
        SceneError::Syntax {
            origin: origin.to_owned(),
            line,
            column,
            field,
            message: e.message().trim().to_owned(),
        }
    };
    let document = toml::Deserializer::parse(text).map_err(|e| syntax(&e, field_path(&[])))?;
    serde_path_to_error::deserialize(document).map_err(|e| {
        let segments: Vec<&Segment> = e.path().iter().collect();
        syntax(e.inner(), field_path(&segments))
    })
}

/// The dotted path of a field (`body[1].nx`), or `(document)` for the
/// whole text.
fn field_path(segments: &[&Segment]) -> String {
    let mut path = String::new();
    for segment in segments {
        match segment {
            Segment::Seq { index } => path.push_str(&format!("[{index}]")),
            Segment::Map { key } | Segment::Enum { variant: key } => {
                if !path.is_empty() {
                    path.push('.');
                }
                path.push_str(key);
            }
            Segment::Unknown => {}
        }
    }
    if path.is_empty() {
        "(document)".to_owned()
    } else {
        path
    }
}

/// The 1-based line and column (in characters) of a byte offset in `text`.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (
        before.matches('\n').count() + 1,
        before[line_start..].chars().count() + 1,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_and_column_count_characters_from_one() {
        let text = "a = 1\nname = \"Müller\" x\n";
        assert_eq!(line_column(text, 0), (1, 1));
        assert_eq!(line_column(text, 6), (2, 1));
        let x = text.find(" x").unwrap() + 1;
        assert_eq!(line_column(text, x), (2, 17));
        // inside a multi-byte character: its start
        let u = text.find('ü').unwrap();
        assert_eq!(line_column(text, u + 1), line_column(text, u));
        assert_eq!(line_column(text, usize::MAX), (3, 1));
    }

    #[test]
    fn paths_name_array_elements_and_unknown_keys() {
        let text = crate::scenes::STACKED_CANTILEVER;
        let e = parse(
            &text.replace("steps = [4, 6", "steps = [4, \"6\""),
            "s.toml",
        )
        .unwrap_err();
        assert!(
            matches!(&e, SceneError::Syntax { field, line: 54, column: 13, .. } if field == "loading.steps[1]"),
            "{e:?}"
        );
        let e = parse(&text.replace("ny = 1", "ny = 1\nnw = 2"), "s.toml").unwrap_err();
        assert!(
            matches!(&e, SceneError::Syntax { field, .. } if field == "body[0].nw"),
            "{e:?}"
        );
        let e = parse(&text.replace("nx = 7", "nx = = 7"), "s.toml").unwrap_err();
        assert!(
            matches!(&e, SceneError::Syntax { field, line: 25, column: 6, .. } if field == "(document)"),
            "{e:?}"
        );
    }
}
