//! Why a scene could not be read, and where in its file.

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
        /// The dotted path of the field (e.g. `body[1].nx`), as far as it
        /// can be located.
        field: String,
        /// What is wrong.
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

/// A TOML error (syntax, unknown or missing key, wrong type) as a
/// [`SceneError::Syntax`] that names `origin`, the line and column, and the
/// field.
pub(super) fn syntax(text: &str, origin: &str, e: &toml::de::Error) -> SceneError {
    let (line, column, field) = match e.span() {
        Some(span) => locate(text, span.start),
        None => (0, 0, String::from("(document)")),
    };
    SceneError::Syntax {
        origin: origin.to_owned(),
        line,
        column,
        field,
        message: e.message().trim().to_owned(),
    }
}

/// Line, column and dotted field path of a byte offset in a TOML text:
/// the last table header at or before it (`[[body]]` counted into
/// `body[i]`) and the keys on its line before the offset (inline tables
/// nest).
fn locate(text: &str, offset: usize) -> (usize, usize, String) {
    let offset = offset.min(text.len());
    let mut header = String::new();
    let mut counts: std::collections::HashMap<String, usize> = std::collections::HashMap::new();
    let mut line_no = 0;
    let mut line_start = 0;
    let mut current = "";
    for (i, line) in text.split_inclusive('\n').enumerate() {
        line_no = i;
        current = line;
        let t = line.trim();
        if let Some(name) = t.strip_prefix("[[").and_then(|r| r.split("]]").next()) {
            let name = name.trim().to_owned();
            let k = counts.entry(name.clone()).or_insert(0);
            header = format!("{name}[{k}]");
            *k += 1;
        } else if let Some(name) = t.strip_prefix('[').and_then(|r| r.split(']').next()) {
            header = name.trim().to_owned();
        }
        if offset < line_start + line.len() {
            break;
        }
        line_start += line.len();
    }
    let line = current.trim_end_matches(['\n', '\r']);
    let mut col = offset.saturating_sub(line_start).min(line.len());
    while !line.is_char_boundary(col) {
        col -= 1;
    }
    let mut path: Vec<String> = Vec::new();
    if !header.is_empty() {
        path.push(header);
    }
    if !line.trim_start().starts_with('[') {
        // keys before the offset on this line
        let mut stack: Vec<String> = Vec::new();
        let mut pending: Option<String> = None;
        let mut word = String::new();
        let mut in_str: Option<char> = None;
        for ch in line[..col].chars() {
            if let Some(q) = in_str {
                if ch == q {
                    in_str = None;
                }
                continue;
            }
            match ch {
                '"' | '\'' => in_str = Some(ch),
                '=' => {
                    pending = Some(word.trim().to_owned());
                    word.clear();
                }
                '{' => {
                    if let Some(p) = pending.take() {
                        stack.push(p);
                    }
                    word.clear();
                }
                '}' => {
                    stack.pop();
                    word.clear();
                }
                ',' => {
                    pending = None;
                    word.clear();
                }
                '#' => break,
                c => word.push(c),
            }
        }
        path.extend(stack);
        if let Some(p) = pending.filter(|p| !p.is_empty()) {
            path.push(p);
        }
    }
    let field = if path.is_empty() {
        "(document)".to_owned()
    } else {
        path.join(".")
    };
    (line_no + 1, line[..col].chars().count() + 1, field)
}
