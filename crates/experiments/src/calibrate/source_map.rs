//! Where the fields of a targets file are: a lenient skim of RON text that records, for every
//! struct field and list element, its path (`targets[3].statistic`) and byte range, so that an
//! error found after parsing (a band, an unknown metric, a duplicate name) names the line and
//! column of what it is about. ron 0.12 gives positions only for its own errors.
//!
//! Paths: named fields add `.name` (no dot at the top level), list elements `[i]`; struct and
//! variant names (`Targets(`, `Mean(`) and positional items are transparent. The skim never
//! fails: on text it does not understand it stops and keeps what it found.

/// Field paths of a RON text and where they are.
#[derive(Debug, Clone, Default)]
pub(crate) struct SourceMap {
    /// Byte offset of the start of every line.
    line_starts: Vec<usize>,
    src: String,
    /// `(path, start, end)`: start is the field's name or the element's first character.
    entries: Vec<(String, usize, usize)>,
}

impl SourceMap {
    /// Skims `src`.
    pub(crate) fn build(src: &str) -> Self {
        let mut line_starts = vec![0];
        line_starts.extend(src.match_indices('\n').map(|(i, _)| i + 1));
        let mut sc = Scanner {
            s: src.as_bytes(),
            pos: 0,
            entries: Vec::new(),
            depth: 0,
        };
        sc.skip_ws();
        while sc.s[sc.pos..].starts_with(b"#![") {
            sc.pos += 2;
            sc.skip_balanced();
            sc.skip_ws();
        }
        sc.value("");
        Self {
            line_starts,
            src: src.to_owned(),
            entries: sc.entries,
        }
    }

    /// The 1-based line and column (in characters, as ron counts) of the first occurrence of
    /// `path`.
    pub(crate) fn line_col_of(&self, path: &str) -> Option<(usize, usize)> {
        let &(_, start, _) = self.entries.iter().find(|(p, _, _)| p == path)?;
        Some(self.line_col(start))
    }

    /// The 1-based line and column of byte `offset`.
    pub(crate) fn line_col(&self, offset: usize) -> (usize, usize) {
        let offset = offset.min(self.src.len());
        let line = self.line_starts.partition_point(|&s| s <= offset);
        let start = self.line_starts[line - 1];
        let col = self
            .src
            .get(start..offset)
            .map_or(1, |t| t.chars().count() + 1);
        (line, col)
    }

    /// The byte offset of 1-based `line` and `col` (characters), clamped to the text.
    pub(crate) fn offset_of(&self, line: usize, col: usize) -> usize {
        let Some(&start) = self.line_starts.get(line.saturating_sub(1)) else {
            return self.src.len();
        };
        self.src[start..]
            .char_indices()
            .nth(col.saturating_sub(1))
            .map_or(self.src.len(), |(i, _)| start + i)
    }

    /// The innermost recorded field or element whose range holds byte `offset`.
    pub(crate) fn path_at(&self, offset: usize) -> Option<&str> {
        self.entries
            .iter()
            .filter(|(_, s, e)| *s <= offset && offset <= *e)
            .max_by_key(|(p, _, _)| p.len())
            .map(|(p, _, _)| p.as_str())
    }
}

/// Deepest nesting the skim follows (deeper text is left unmapped).
const MAX_DEPTH: usize = 64;

struct Scanner<'a> {
    s: &'a [u8],
    pos: usize,
    entries: Vec<(String, usize, usize)>,
    depth: usize,
}

impl Scanner<'_> {
    fn peek(&self) -> Option<u8> {
        self.s.get(self.pos).copied()
    }

    /// Skips white space and comments (`//` to the line's end, nested `/* */`).
    fn skip_ws(&mut self) {
        loop {
            match (self.peek(), self.s.get(self.pos + 1)) {
                (Some(b), _) if b.is_ascii_whitespace() => self.pos += 1,
                (Some(b'/'), Some(b'/')) => {
                    while self.peek().is_some_and(|b| b != b'\n') {
                        self.pos += 1;
                    }
                }
                (Some(b'/'), Some(b'*')) => {
                    let mut nest = 0;
                    while self.pos < self.s.len() {
                        if self.s[self.pos..].starts_with(b"/*") {
                            nest += 1;
                            self.pos += 2;
                        } else if self.s[self.pos..].starts_with(b"*/") {
                            nest -= 1;
                            self.pos += 2;
                            if nest == 0 {
                                break;
                            }
                        } else {
                            self.pos += 1;
                        }
                    }
                }
                _ => return,
            }
        }
    }

    fn ident(&mut self) -> Option<(usize, usize)> {
        let start = self.pos;
        while self
            .peek()
            .is_some_and(|b| b.is_ascii_alphanumeric() || b == b'_')
        {
            self.pos += 1;
        }
        (self.pos > start).then_some((start, self.pos))
    }

    /// Skips a quoted string (`"..."` with escapes, `r#"..."#`) or character literal.
    fn skip_quoted(&mut self) {
        if self.peek() == Some(b'r') {
            self.pos += 1;
            let hashes = self.s[self.pos..]
                .iter()
                .take_while(|&&b| b == b'#')
                .count();
            self.pos += hashes + 1;
            let close: Vec<u8> = std::iter::once(b'"')
                .chain(std::iter::repeat_n(b'#', hashes))
                .collect();
            while self.pos < self.s.len() && !self.s[self.pos..].starts_with(&close) {
                self.pos += 1;
            }
            self.pos = (self.pos + close.len()).min(self.s.len());
            return;
        }
        let quote = self.s[self.pos];
        self.pos += 1;
        while let Some(b) = self.peek() {
            self.pos += 1;
            if b == b'\\' {
                self.pos += 1;
            } else if b == quote {
                return;
            }
        }
    }

    /// Skips a bracketed group from its opening bracket, strings and comments included.
    fn skip_balanced(&mut self) {
        let mut depth = 0usize;
        while let Some(b) = self.peek() {
            match b {
                b'"' | b'\'' => {
                    self.skip_quoted();
                    continue;
                }
                b'(' | b'[' | b'{' => depth += 1,
                b')' | b']' | b'}' => {
                    depth = depth.saturating_sub(1);
                    if depth == 0 {
                        self.pos += 1;
                        return;
                    }
                }
                b'/' => {
                    let before = self.pos;
                    self.skip_ws();
                    if self.pos != before {
                        continue;
                    }
                }
                _ => {}
            }
            self.pos += 1;
        }
    }

    /// Reads one value at `path`; false when the text is not understood.
    fn value(&mut self, path: &str) -> bool {
        self.skip_ws();
        match self.peek() {
            None => false,
            Some(b'(') if self.depth < MAX_DEPTH => self.paren(path),
            Some(b'[') if self.depth < MAX_DEPTH => self.list(path),
            Some(b'(' | b'[' | b'{') => {
                self.skip_balanced();
                true
            }
            Some(b'"' | b'\'') => {
                self.skip_quoted();
                true
            }
            Some(b'r') if matches!(self.s.get(self.pos + 1), Some(b'"' | b'#')) => {
                self.skip_quoted();
                true
            }
            Some(b) if b.is_ascii_alphabetic() || b == b'_' => {
                self.ident();
                self.skip_ws();
                self.peek() != Some(b'(') || self.value(path)
            }
            Some(_) => {
                while self
                    .peek()
                    .is_some_and(|b| !b.is_ascii_whitespace() && !b",)]}".contains(&b))
                {
                    self.pos += 1;
                }
                true
            }
        }
    }

    /// `( ... )`: named fields (recorded) or positional items (transparent).
    fn paren(&mut self, path: &str) -> bool {
        self.pos += 1;
        self.depth += 1;
        let ok = self.items(b')', |sc| {
            let start = sc.pos;
            if let Some((a, b)) = sc.ident() {
                sc.skip_ws();
                if sc.peek() == Some(b':') {
                    sc.pos += 1;
                    let name = String::from_utf8_lossy(&sc.s[a..b]).into_owned();
                    let child = if path.is_empty() {
                        name
                    } else {
                        format!("{path}.{name}")
                    };
                    let ok = sc.value(&child);
                    sc.entries.push((child, start, sc.pos));
                    return ok;
                }
                sc.pos = start;
            }
            sc.value(path)
        });
        self.depth -= 1;
        ok
    }

    /// `[ ... ]`: elements recorded as `path[i]`.
    fn list(&mut self, path: &str) -> bool {
        self.pos += 1;
        self.depth += 1;
        let mut i = 0;
        let ok = self.items(b']', |sc| {
            let start = sc.pos;
            let child = format!("{path}[{i}]");
            let ok = sc.value(&child);
            sc.entries.push((child, start, sc.pos));
            i += 1;
            ok
        });
        self.depth -= 1;
        ok
    }

    /// Comma-separated items up to `close`, each read by `item`.
    fn items(&mut self, close: u8, mut item: impl FnMut(&mut Self) -> bool) -> bool {
        loop {
            self.skip_ws();
            if self.peek() == Some(close) {
                self.pos += 1;
                return true;
            }
            if !item(self) {
                return false;
            }
            self.skip_ws();
            match self.peek() {
                Some(b',') => self.pos += 1,
                Some(b) if b == close => {
                    self.pos += 1;
                    return true;
                }
                _ => return false,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TEXT: &str = "// a comment (with a bracket\nTargets(\n    targets: [\n        \
        /* one */ (name: \"a, b)\", statistic: Mean(\"rounds\"), value: 1.0, band: \
        PlusMinus(0.5)),\n        (name: \"é\", value: 2.0),\n    ],\n)\n";

    #[test]
    fn fields_and_elements_are_placed() {
        let map = SourceMap::build(TEXT);
        assert_eq!(map.line_col_of("targets"), Some((3, 5)));
        assert_eq!(map.line_col_of("targets[0]"), Some((4, 19)));
        assert_eq!(map.line_col_of("targets[0].statistic"), Some((4, 35)));
        assert_eq!(map.line_col_of("targets[0].band"), Some((4, 74)));
        // Columns count characters: "é" is two bytes.
        assert_eq!(map.line_col_of("targets[1].value"), Some((5, 21)));
        assert_eq!(map.line_col_of("targets[2]"), None);
        let at = map.offset_of(5, 21);
        assert_eq!(map.path_at(at), Some("targets[1].value"));
        assert_eq!(map.line_col(at), (5, 21));
    }

    #[test]
    fn text_it_does_not_understand_keeps_what_came_before() {
        let map = SourceMap::build("Targets(targets: [(name: \"x\", value: ???");
        assert_eq!(map.line_col_of("targets[0].name"), Some((1, 20)));
        let map = SourceMap::build("");
        assert_eq!(map.line_col_of("targets"), None);
        assert_eq!(map.line_col(0), (1, 1));
    }
}
