//! Field paths to source positions: a lenient skim of RON text.
//!
//! ron 0.12 reports positions only for its own (syntax and shape) errors; it has no spanned
//! values. To give semantic errors a line and column, [`SourceMap::build`] walks the RON text
//! once and records, for every struct field and list element, its path (`kinds[1].quota`,
//! `tasks.hard.search_area.min_m`) and byte range. The walk never fails: on text it does not
//! understand it stops and keeps what it found.
//!
//! Path rules: named fields add `.name` (no leading dot at the top level), list (`[...]`)
//! elements add `[i]`; struct and enum-variant names (`Scenario(`, `Rect(`, `Some(`) and
//! unnamed tuple elements are transparent (a point `(1.0, 2.0)` has its field's path).

use std::collections::HashMap;

/// One recorded field or element.
#[derive(Debug, Clone)]
struct Entry {
    path: String,
    /// Byte offset of the key (named field) or of the element's first character.
    start: usize,
    /// Byte offset just after the value.
    end: usize,
}

/// Field paths of a RON source and where they are: the one source map of the workspace,
/// used by the scenario loader and by every other RON file the tools read (targets, axes,
/// claims), so that an error found after parsing names `file:line:col` and the field.
#[derive(Debug, Clone, Default)]
pub struct SourceMap {
    /// Byte offset of the start of every line.
    line_starts: Vec<usize>,
    src: String,
    entries: Vec<Entry>,
    by_path: HashMap<String, usize>,
    /// Byte offset of the top-level value (`Scenario(`), if the source has one.
    root: Option<usize>,
    /// The brackets the source leaves open where it ends, innermost first: the path of the
    /// field or element each opens the value of, and its byte offset.
    unclosed: Vec<(String, usize)>,
}

impl SourceMap {
    /// Skims `src` and records every field/element path it finds.
    pub fn build(src: &str) -> SourceMap {
        let mut line_starts = vec![0];
        line_starts.extend(src.match_indices('\n').map(|(i, _)| i + 1));
        let mut sc = Scanner {
            s: src.as_bytes(),
            pos: 0,
            entries: Vec::new(),
            depth: 0,
            unclosed: Vec::new(),
        };
        sc.skip_ws_and_attributes();
        let root = (sc.pos < src.len()).then_some(sc.pos);
        sc.value("");
        let mut by_path = HashMap::new();
        for (i, e) in sc.entries.iter().enumerate() {
            by_path.entry(e.path.clone()).or_insert(i);
        }
        SourceMap {
            line_starts,
            src: src.to_owned(),
            entries: sc.entries,
            by_path,
            root,
            unclosed: sc.unclosed,
        }
    }

    /// The innermost bracket the source leaves open where it ends (a file cut short): the
    /// path of the field or element whose value it opens (empty for the top-level value) and
    /// its byte offset; `None` when the skim closed every bracket it met.
    pub(crate) fn innermost_unclosed(&self) -> Option<(&str, usize)> {
        self.unclosed.first().map(|(p, at)| (p.as_str(), *at))
    }

    /// The brackets that close [`SourceMap::innermost_unclosed`] and every bracket open
    /// around it, innermost first: what completes a source cut short.
    pub(crate) fn unclosed_closers(&self) -> impl Iterator<Item = char> + '_ {
        self.unclosed
            .iter()
            .map(|&(_, at)| match self.src.as_bytes()[at] {
                b'[' => ']',
                b'{' => '}',
                _ => ')',
            })
    }

    /// The byte offset just past the source's last character that is not whitespace.
    pub(crate) fn text_end(&self) -> usize {
        self.src.trim_end().len()
    }

    /// Line and column (1-based, column in characters) of `path`, or of its nearest ancestor
    /// that appears in the source (`kinds[1].quota.easy` -> `kinds[1].quota` -> `kinds[1]` ->
    /// `kinds`), or else of the top-level value (`Scenario(`: a field whose whole block is
    /// left to its defaults, such as `sim.dt_s` without `sim`); `None` only for a source
    /// without a value.
    pub fn line_col_of(&self, path: &str) -> Option<(usize, usize)> {
        let mut p = path;
        loop {
            if let Some(&i) = self.by_path.get(p) {
                return Some(self.line_col(self.entries[i].start));
            }
            match parent_path(p) {
                Some(parent) => p = parent,
                None => return self.root.map(|r| self.line_col(r)),
            }
        }
    }

    /// Whether `path` itself appears in the source.
    pub(crate) fn contains(&self, path: &str) -> bool {
        self.by_path.contains_key(path)
    }

    /// The path of the innermost recorded field or element whose range contains `offset`
    /// (key through value, ends inclusive), if any.
    pub fn path_at(&self, offset: usize) -> Option<&str> {
        self.innermost(|e| e.start <= offset && offset <= e.end)
    }

    /// The path of the innermost recorded field or element whose value is still open at
    /// `offset` (key through value, end exclusive): the struct a closing bracket at `offset`
    /// belongs to. ron reports a missing field at the struct's closing bracket, which
    /// [`SourceMap::path_at`] would give to the struct's last field when no comma follows it.
    pub fn path_within(&self, offset: usize) -> Option<&str> {
        self.innermost(|e| e.start <= offset && offset < e.end)
    }

    /// The path of the shortest entry `holds` accepts.
    fn innermost(&self, holds: impl Fn(&Entry) -> bool) -> Option<&str> {
        self.entries
            .iter()
            .filter(|e| holds(e))
            .min_by_key(|e| e.end - e.start)
            .map(|e| e.path.as_str())
    }

    /// Byte offset of a 1-based line and character column (clamped to the source).
    pub fn offset_of(&self, line: usize, col: usize) -> usize {
        let Some(&ls) = self.line_starts.get(line.saturating_sub(1)) else {
            return self.src.len();
        };
        let rest = &self.src[ls..];
        rest.char_indices()
            .nth(col.saturating_sub(1))
            .map_or(self.src.len(), |(i, _)| ls + i)
    }

    /// 1-based line and character column of a byte offset.
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let line_idx = match self.line_starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i - 1,
        };
        let ls = self.line_starts[line_idx];
        let end = offset.min(self.src.len());
        let col = self.src.get(ls..end).map_or(1, |s| s.chars().count() + 1);
        (line_idx + 1, col)
    }
}

/// `a.b[2].c` -> `a.b[2]` -> `a.b` -> `a` -> `None`.
pub(crate) fn parent_path(path: &str) -> Option<&str> {
    if path.is_empty() {
        return None;
    }
    let cut = path.rfind(['.', '[']).unwrap_or(0);
    Some(&path[..cut])
}

/// Joins a parent path and a field name.
pub(crate) fn join(parent: &str, field: &str) -> String {
    if parent.is_empty() {
        field.to_owned()
    } else {
        format!("{parent}.{field}")
    }
}

/// Deepest nesting of brackets the skim follows; deeper text is left to ron (whose own
/// recursion limit, 128, reports it as a positioned error). Keeps the skim's recursion, and so
/// its stack use, bounded whatever the input.
const MAX_NESTING: usize = 128;

struct Scanner<'a> {
    s: &'a [u8],
    pos: usize,
    entries: Vec<Entry>,
    /// Brackets open at the cursor.
    depth: usize,
    /// The brackets open where the text ended, innermost first ([`SourceMap::unclosed`]).
    unclosed: Vec<(String, usize)>,
}

fn is_delim(b: u8) -> bool {
    ron_ws_len(&[b]) == 1 || b"()[]{},:\"'/#".contains(&b)
}

/// Byte length of the whitespace character RON accepts at the start of `s`, 0 if there is
/// none: ron 0.12's `is_whitespace_char` (space, tab, LF, CR, vertical tab, form feed, and
/// U+0085, U+200E, U+200F, U+2028, U+2029 in UTF-8). Scanning with less would lose the
/// position of every field after such a character (found by the scenario fuzz test).
fn ron_ws_len(s: &[u8]) -> usize {
    match s {
        [b' ' | b'\t' | b'\n' | b'\r' | 0x0B | 0x0C, ..] => 1,
        [0xC2, 0x85, ..] => 2,
        [0xE2, 0x80, 0x8E | 0x8F | 0xA8 | 0xA9, ..] => 3,
        _ => 0,
    }
}

impl Scanner<'_> {
    fn peek(&self) -> Option<u8> {
        self.s.get(self.pos).copied()
    }

    fn peek_at(&self, k: usize) -> Option<u8> {
        self.s.get(self.pos + k).copied()
    }

    /// Skips whitespace, `//` line comments and (nested) `/* */` block comments.
    fn skip_ws(&mut self) {
        loop {
            match (self.peek(), self.peek_at(1)) {
                (Some(_), _) if ron_ws_len(&self.s[self.pos..]) > 0 => {
                    self.pos += ron_ws_len(&self.s[self.pos..]);
                }
                (Some(b'/'), Some(b'/')) => {
                    while let Some(b) = self.peek() {
                        self.pos += 1;
                        if b == b'\n' {
                            break;
                        }
                    }
                }
                (Some(b'/'), Some(b'*')) => {
                    self.pos += 2;
                    let mut depth = 1;
                    while depth > 0 && self.pos < self.s.len() {
                        match (self.peek(), self.peek_at(1)) {
                            (Some(b'/'), Some(b'*')) => {
                                depth += 1;
                                self.pos += 2;
                            }
                            (Some(b'*'), Some(b'/')) => {
                                depth -= 1;
                                self.pos += 2;
                            }
                            _ => self.pos += 1,
                        }
                    }
                }
                _ => return,
            }
        }
    }

    /// Skips whitespace, comments and leading `#![enable(...)]` attributes.
    fn skip_ws_and_attributes(&mut self) {
        loop {
            self.skip_ws();
            if self.peek() != Some(b'#') {
                return;
            }
            let mut depth = 0usize;
            while let Some(b) = self.peek() {
                self.pos += 1;
                match b {
                    b'[' => depth += 1,
                    b']' => {
                        depth = depth.saturating_sub(1);
                        if depth == 0 {
                            break;
                        }
                    }
                    _ => {}
                }
            }
        }
    }

    /// An identifier at the cursor (ASCII letters, digits, `_`, optional `r#`), consumed.
    fn ident(&mut self) -> Option<&str> {
        let start = self.pos;
        let mut p = self.pos;
        if self.s.get(p) == Some(&b'r') && self.s.get(p + 1) == Some(&b'#') {
            p += 2;
        }
        match self.s.get(p) {
            Some(b) if b.is_ascii_alphabetic() || *b == b'_' => {}
            _ => return None,
        }
        while matches!(self.s.get(p), Some(b) if b.is_ascii_alphanumeric() || *b == b'_') {
            p += 1;
        }
        self.pos = p;
        let raw = std::str::from_utf8(&self.s[start..p]).ok()?;
        Some(raw.strip_prefix("r#").unwrap_or(raw))
    }

    /// Skips a quoted string or char starting at the cursor (the quote byte given).
    fn quoted(&mut self, quote: u8) {
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

    /// Skips a raw string `r#"..."#` at the cursor.
    fn raw_string(&mut self) {
        self.pos += 1; // r
        let mut hashes = 0;
        while self.peek() == Some(b'#') {
            hashes += 1;
            self.pos += 1;
        }
        if self.peek() != Some(b'"') {
            return;
        }
        self.pos += 1;
        while self.pos < self.s.len() {
            if self.s[self.pos] == b'"'
                && self.s[self.pos + 1..]
                    .iter()
                    .take(hashes)
                    .filter(|&&b| b == b'#')
                    .count()
                    == hashes
            {
                self.pos += 1 + hashes;
                return;
            }
            self.pos += 1;
        }
    }

    /// Skims one value; returns `false` if it met something it cannot read.
    fn value(&mut self, path: &str) -> bool {
        self.skip_ws();
        let Some(b) = self.peek() else {
            return false;
        };
        match b {
            b'(' => self.container(path, b')'),
            b'[' => self.container(path, b']'),
            b'{' => self.container(path, b'}'),
            b'"' | b'\'' => {
                self.quoted(b);
                true
            }
            b'r' if matches!(self.peek_at(1), Some(b'"')) => {
                self.raw_string();
                true
            }
            b'r' if matches!(self.peek_at(1), Some(b'#'))
                && matches!(self.peek_at(2), Some(b'"' | b'#')) =>
            {
                self.raw_string();
                true
            }
            b'b' if matches!(self.peek_at(1), Some(b'"' | b'\'')) => {
                self.pos += 1;
                let q = self.s[self.pos];
                self.quoted(q);
                true
            }
            _ if is_delim(b) => false,
            _ => {
                // A word: number, identifier, unit variant, or a struct/variant name.
                while matches!(self.peek(), Some(c) if !is_delim(c))
                    && ron_ws_len(&self.s[self.pos..]) == 0
                {
                    self.pos += 1;
                }
                let after_word = self.pos;
                self.skip_ws();
                if self.peek() == Some(b'(') {
                    self.container(path, b')')
                } else {
                    self.pos = after_word;
                    true
                }
            }
        }
    }

    /// Skims `(...)`, `[...]` or `{...}` at the cursor; gives up (`false`) beyond
    /// [`MAX_NESTING`] open brackets.
    fn container(&mut self, path: &str, close: u8) -> bool {
        if self.depth >= MAX_NESTING {
            return false;
        }
        self.depth += 1;
        let open = self.pos;
        let ok = self.container_items(path, close);
        self.depth -= 1;
        if !ok && self.pos >= self.s.len() {
            self.unclosed.push((path.to_owned(), open));
        }
        ok
    }

    /// The items of the container whose opening bracket is at the cursor.
    fn container_items(&mut self, path: &str, close: u8) -> bool {
        self.pos += 1;
        let mut index = 0usize;
        loop {
            self.skip_ws();
            match self.peek() {
                None => return false,
                Some(b) if b == close => {
                    self.pos += 1;
                    return true;
                }
                _ => {}
            }
            let start = self.pos;
            let ok = match close {
                b']' => {
                    let p = format!("{path}[{index}]");
                    let ok = self.value(&p);
                    self.record(p, start);
                    ok
                }
                b'}' => {
                    // Map: key, colon, value; the value gets `path[index]`.
                    if !self.value(path) {
                        return false;
                    }
                    self.skip_ws();
                    if self.peek() != Some(b':') {
                        return false;
                    }
                    self.pos += 1;
                    let p = format!("{path}[{index}]");
                    let ok = self.value(&p);
                    self.record(p, start);
                    ok
                }
                _ => {
                    let named = self.ident().map(str::to_owned).and_then(|name| {
                        self.skip_ws();
                        (self.peek() == Some(b':')).then_some(name)
                    });
                    match named {
                        Some(name) => {
                            self.pos += 1; // ':'
                            let p = join(path, &name);
                            let ok = self.value(&p);
                            self.record(p, start);
                            ok
                        }
                        None => {
                            self.pos = start;
                            self.value(path)
                        }
                    }
                }
            };
            if !ok {
                return false;
            }
            index += 1;
            self.skip_ws();
            match self.peek() {
                Some(b',') => self.pos += 1,
                Some(b) if b == close => {}
                _ => return false,
            }
        }
    }

    fn record(&mut self, path: String, start: usize) {
        let end = self.pos;
        self.entries.push(Entry { path, start, end });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SRC: &str = r#"#![enable(implicit_some)]
// comment with ( and [ and "quotes
Scenario(
    name: "a(b)", /* block /* nested */ ) */
    kinds: [
        (name: "c", quota: (easy: 1, hard: 2), starts: Row(first_m: (1.0, 2.0), step_m: (1, 0))),
        (
            name: "d",
            starts: List([(1.0, 2.0), (3.0, 4.0)]),
        ),
    ],
    seed: Some(3),
)
"#;

    #[test]
    fn records_nested_paths_with_positions() {
        let m = SourceMap::build(SRC);
        assert!(m.contains("name"));
        assert!(m.contains("kinds"));
        assert!(m.contains("kinds[0].quota.hard"));
        assert!(m.contains("kinds[0].starts.first_m"));
        assert!(m.contains("kinds[1].starts[1]"));
        assert!(m.contains("seed"));
        assert_eq!(m.line_col_of("name"), Some((4, 5)));
        assert_eq!(m.line_col_of("kinds[1]"), Some((7, 9)));
        assert_eq!(m.line_col_of("kinds[1].name"), Some((8, 13)));
        // Fallback to the nearest ancestor.
        assert_eq!(m.line_col_of("kinds[1].quota.easy"), Some((7, 9)));
        // No ancestor in the source: the top-level value's position.
        assert_eq!(m.line_col_of("mission.duration_s"), Some((3, 1)));
        assert_eq!(SourceMap::build("  // nothing\n").line_col_of("name"), None);
    }

    #[test]
    fn innermost_path_at_offset() {
        let m = SourceMap::build(SRC);
        let off = m.offset_of(6, 30);
        assert_eq!(m.path_at(off), Some("kinds[0].quota.easy"));
        assert_eq!(m.line_col(off), (6, 30));
    }

    #[test]
    fn brackets_left_open_at_the_end_are_found_innermost_first() {
        let m = SourceMap::build("Scenario(name: \"x\", kinds: [(count: 1");
        assert_eq!(m.innermost_unclosed(), Some(("kinds[0]", 28)));
        assert_eq!(m.unclosed.len(), 3);
        assert_eq!(m.unclosed[2], (String::new(), 8));
        assert_eq!(m.text_end(), 37);
        assert_eq!(SourceMap::build(SRC).innermost_unclosed(), None);
        assert_eq!(SourceMap::build("(a: [1, 2)").innermost_unclosed(), None);
    }

    #[test]
    fn parent_paths() {
        assert_eq!(parent_path("a.b[2].c"), Some("a.b[2]"));
        assert_eq!(parent_path("a.b[2]"), Some("a.b"));
        assert_eq!(parent_path("a"), Some(""));
        assert_eq!(parent_path(""), None);
    }

    #[test]
    fn survives_garbage() {
        let m = SourceMap::build("(a: 1, b: ) ) ]]] \"unterminated");
        assert!(m.contains("a"));
    }
}
