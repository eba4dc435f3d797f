//! No function in `src/` is longer than [`MAX_FN_LINES`] lines, from its
//! `fn` line to its closing brace, unit tests included: a long function
//! hides its steps, and naming them is how a reader finds them. The only
//! exceptions are table-driven functions (one arm or line per model or
//! header field or table column), listed in [`TABLE_DRIVEN`] with the
//! reason.

use super::layering::rust_files;

/// The longest a function may be, in lines.
const MAX_FN_LINES: usize = 80;

/// Table-driven functions allowed to be longer: (file under `src/`,
/// function, why). Keep it short; a new entry needs a reason of this kind.
const TABLE_DRIVEN: &[(&str, &str, &str)] = &[
    (
        "fit/nist/models.rs",
        "eval",
        "one match arm per NIST StRD model: value and gradient side by side",
    ),
    (
        "ingest/formats/metropro.rs",
        "header",
        "one line per field of the fixed MetroPro header, at its byte offset",
    ),
    (
        "ingest/formats/opdx.rs",
        "item",
        "one match arm per OPDx item type code",
    ),
    (
        "extract/tensile/facts.rs",
        "testxpert",
        "one entry per printed result, with its German and English keys",
    ),
    (
        "stages/friction/tables.rs",
        "steps_table",
        "one builder line per column of friction_steps (its schema file)",
    ),
];

/// One function: where it starts and how many lines it spans.
#[derive(Debug, PartialEq)]
struct FnSpan {
    name: String,
    line: usize,
    lines: usize,
}

/// The text with comments, string and char literals blanked (newlines
/// kept), so braces and `fn` inside them are not seen.
fn blank_literals(text: &str) -> Vec<u8> {
    let s = text.as_bytes();
    let mut out = s.to_vec();
    let blank = |out: &mut Vec<u8>, from: usize, to: usize| {
        for b in &mut out[from..to.min(s.len())] {
            if *b != b'\n' {
                *b = b' ';
            }
        }
    };
    let ident = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    let mut i = 0;
    while i < s.len() {
        let rest = &s[i..];
        let after_ident = i > 0 && ident(s[i - 1]);
        if rest.starts_with(b"//") {
            let end = rest
                .iter()
                .position(|&b| b == b'\n')
                .map_or(s.len(), |p| i + p);
            blank(&mut out, i, end);
            i = end;
        } else if rest.starts_with(b"/*") {
            let (mut depth, mut j) = (1, i + 2);
            while j < s.len() && depth > 0 {
                if s[j..].starts_with(b"/*") {
                    depth += 1;
                    j += 2;
                } else if s[j..].starts_with(b"*/") {
                    depth -= 1;
                    j += 2;
                } else {
                    j += 1;
                }
            }
            blank(&mut out, i, j);
            i = j;
        } else if let Some(j) = (!after_ident).then(|| raw_string_end(s, i)).flatten() {
            blank(&mut out, i, j);
            i = j;
        } else if s[i] == b'"' {
            let mut j = i + 1;
            while j < s.len() && s[j] != b'"' {
                j += if s[j] == b'\\' { 2 } else { 1 };
            }
            blank(&mut out, i, j + 1);
            i = j + 1;
        } else if s[i] == b'\'' {
            // A char literal ('x', '\n', '\u{1F600}', 'é'); else a lifetime.
            let close = if rest.get(1) == Some(&b'\\') {
                rest.iter().skip(3).position(|&b| b == b'\'').map(|p| p + 3)
            } else {
                let next = text.get(i + 1..).and_then(|t| t.chars().next());
                let len = next.map_or(1, char::len_utf8);
                (rest.get(1 + len) == Some(&b'\'')).then_some(1 + len)
            };
            match close {
                Some(c) if c < 12 => {
                    blank(&mut out, i, i + c + 1);
                    i += c + 1;
                }
                _ => i += 1,
            }
        } else {
            i += 1;
        }
    }
    out
}

/// The end of a raw string (`r"…"`, `r#"…"#`, `br"…"`) starting at `i`.
fn raw_string_end(s: &[u8], i: usize) -> Option<usize> {
    let mut j = i;
    if s.get(j) == Some(&b'b') {
        j += 1;
    }
    if s.get(j) != Some(&b'r') {
        return None;
    }
    j += 1;
    let hashes = s[j..].iter().take_while(|&&b| b == b'#').count();
    j += hashes;
    if s.get(j) != Some(&b'"') {
        return None;
    }
    let mut close = vec![b'"'];
    close.extend(std::iter::repeat_n(b'#', hashes));
    let body = j + 1;
    s[body..]
        .windows(close.len())
        .position(|w| w == close.as_slice())
        .map(|p| body + p + close.len())
}

/// Every function with a body in a source text, nested ones included.
fn functions(text: &str) -> Vec<FnSpan> {
    let s = blank_literals(text);
    let line_of = |i: usize| s[..i].iter().filter(|&&b| b == b'\n').count() + 1;
    let ident = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(p) = s[i..].windows(3).position(|w| w == b"fn ") {
        let at = i + p;
        i = at + 3;
        if at > 0 && ident(s[at - 1]) {
            continue;
        }
        let mut j = i;
        while j < s.len() && s[j].is_ascii_whitespace() {
            j += 1;
        }
        let start = j;
        while j < s.len() && ident(s[j]) {
            j += 1;
        }
        if j == start {
            continue; // `fn (` of a function pointer type
        }
        let name = String::from_utf8_lossy(&s[start..j]).into_owned();
        // The body opens at the first `{` outside parentheses and
        // brackets; a `;` first means a declaration without a body.
        let mut depth = 0i32;
        while j < s.len() {
            match s[j] {
                b'(' | b'[' => depth += 1,
                b')' | b']' => depth -= 1,
                b'{' | b';' if depth == 0 => break,
                _ => {}
            }
            j += 1;
        }
        if j >= s.len() || s[j] == b';' {
            continue;
        }
        let mut braces = 0;
        let mut k = j;
        while k < s.len() {
            match s[k] {
                b'{' => braces += 1,
                b'}' => {
                    braces -= 1;
                    if braces == 0 {
                        break;
                    }
                }
                _ => {}
            }
            k += 1;
        }
        let line = line_of(at);
        out.push(FnSpan {
            name,
            line,
            lines: line_of(k.min(s.len().saturating_sub(1))) - line + 1,
        });
    }
    out
}

#[test]
fn no_function_is_too_long() {
    let src = crate::common::root().join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut long = Vec::new();
    let mut allowed_seen = Vec::new();
    for f in &files {
        let rel = f
            .strip_prefix(&src)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        for span in functions(&std::fs::read_to_string(f).unwrap()) {
            if span.lines <= MAX_FN_LINES {
                continue;
            }
            let listed = TABLE_DRIVEN
                .iter()
                .any(|(p, n, _)| *p == rel && *n == span.name);
            if listed {
                allowed_seen.push((rel.clone(), span.name.clone()));
                continue;
            }
            long.push(format!(
                "src/{rel}:{}: fn {} is {} lines; split it into named steps of at most \
                 {MAX_FN_LINES} lines (or, if it is one table entry per line, add it to \
                 TABLE_DRIVEN in tests/function_length.rs with the reason)",
                span.line, span.name, span.lines
            ));
        }
    }
    assert!(long.is_empty(), "functions too long:\n{}", long.join("\n"));
    // An entry whose function is gone or now short is stale: remove it.
    for (p, n, _) in TABLE_DRIVEN {
        assert!(
            allowed_seen.iter().any(|(rp, rn)| rp == p && rn == n),
            "tests/function_length.rs lists src/{p} fn {n}, which is no longer over \
             {MAX_FN_LINES} lines (or no longer exists): remove the entry"
        );
    }
}

#[test]
fn the_counter_sees_functions_and_skips_literals() {
    let text = r##"
fn short() { let s = "fn fake() {"; }
/* fn commented() { */
fn pointer(f: fn(f64) -> f64) -> f64 { f(1.0) }
trait T { fn declared(&self); }
fn long<'a>(x: &'a str) -> char {
    let c = '{';
    let q = ['\'', 'é', '"', '}'];
    let r = r#"}"#;
    // }
    fn inner() {}
    c
}
"##;
    let spans = functions(text);
    let got: Vec<(&str, usize, usize)> = spans
        .iter()
        .map(|s| (s.name.as_str(), s.line, s.lines))
        .collect();
    assert_eq!(
        got,
        vec![
            ("short", 2, 1),
            ("pointer", 4, 1),
            ("long", 6, 8),
            ("inner", 11, 1)
        ]
    );
}
