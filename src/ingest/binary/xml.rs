//! A small XML reader for the metadata documents of structured formats
//! (X3P's `main.xml`): elements, their text and attributes, with the
//! predefined and numeric entities, comments, CDATA, processing
//! instructions and a DOCTYPE skipped. Names lose their namespace prefix
//! (`p:ISO5436_2` is `ISO5436_2`). No recursion: any depth parses.
//!
//! Written here rather than taken from `quick-xml` (3 s of build, small):
//! the documents are a few kB and what is needed is a tree to look values
//! up in, with errors at a byte offset.

/// An element.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Element {
    /// Local name (namespace prefix removed).
    pub name: String,
    /// Attributes (local names), in document order.
    pub attributes: Vec<(String, String)>,
    /// Text directly inside, entities resolved, trimmed.
    pub text: String,
    /// Child elements.
    pub children: Vec<Element>,
    /// Byte offset of the start tag.
    pub offset: usize,
}

impl Element {
    /// The first child with this name.
    pub fn child(&self, name: &str) -> Option<&Element> {
        self.children.iter().find(|c| c.name == name)
    }

    /// The element at a `/`-separated path of child names.
    pub fn find(&self, path: &str) -> Option<&Element> {
        path.split('/').try_fold(self, |e, name| e.child(name))
    }

    /// The text of the element at `path`, when it is there and not empty.
    pub fn text_at(&self, path: &str) -> Option<&str> {
        self.find(path)
            .map(|e| e.text.as_str())
            .filter(|t| !t.is_empty())
    }

    /// Every element below this one with its `/`-path, depth first:
    /// metadata to keep as it is.
    pub fn leaves(&self) -> Vec<(String, &str)> {
        let mut out = Vec::new();
        let mut stack: Vec<(String, &Element)> = vec![(String::new(), self)];
        while let Some((prefix, e)) = stack.pop() {
            for c in e.children.iter().rev() {
                let p = match prefix.is_empty() {
                    true => c.name.clone(),
                    false => format!("{prefix}/{}", c.name),
                };
                if c.children.is_empty() {
                    out.push((p.clone(), c.text.as_str()));
                }
                stack.push((p, c));
            }
        }
        out.sort_by_key(|(p, _)| p.clone());
        out
    }
}

/// Deepest nesting accepted: a tree is dropped recursively, and metadata
/// documents are a few levels deep.
const MAX_DEPTH: usize = 256;

/// A parse error: byte offset and what was wrong.
pub type ParseError = (usize, String);

/// Parses a document into its root element.
pub fn parse(doc: &[u8]) -> Result<Element, ParseError> {
    let s = std::str::from_utf8(doc).map_err(|e| {
        (
            e.valid_up_to(),
            "not UTF-8 (XML documents of these formats are)".to_string(),
        )
    })?;
    let b = s.as_bytes();
    let mut stack: Vec<Element> = Vec::new();
    let mut root: Option<Element> = None;
    let mut i = s.strip_prefix('\u{feff}').map_or(0, |_| 3);
    while i < b.len() {
        if b[i] != b'<' {
            let end = s[i..].find('<').map_or(b.len(), |k| i + k);
            let text = unescape(&s[i..end], i)?;
            match stack.last_mut() {
                Some(e) => e.text.push_str(&text),
                None if text.trim().is_empty() => {}
                None => return Err((i, "text outside the root element".into())),
            }
            i = end;
            continue;
        }
        let rest = &s[i..];
        if let Some(r) = rest.strip_prefix("<!--") {
            i += 4
                + r.find("-->")
                    .ok_or((i, "unterminated comment".to_string()))?
                + 3;
        } else if let Some(r) = rest.strip_prefix("<![CDATA[") {
            let k = r.find("]]>").ok_or((i, "unterminated CDATA".to_string()))?;
            if let Some(e) = stack.last_mut() {
                e.text.push_str(&r[..k]);
            }
            i += 9 + k + 3;
        } else if rest.starts_with("<?") {
            i += rest.find("?>").ok_or((i, "unterminated <?".to_string()))? + 2;
        } else if rest.starts_with("<!") {
            i += skip_declaration(rest).ok_or((i, "unterminated <!".to_string()))?;
        } else if let Some(r) = rest.strip_prefix("</") {
            let k = r.find('>').ok_or((i, "unterminated end tag".to_string()))?;
            let name = local(r[..k].trim());
            let mut e = stack
                .pop()
                .ok_or((i, format!("end tag </{name}> without a start")))?;
            if e.name != name {
                return Err((i, format!("end tag </{name}> closes <{}>", e.name)));
            }
            e.text = e.text.trim().to_string();
            close(&mut stack, &mut root, e, i)?;
            i += 2 + k + 1;
        } else {
            let (e, len, empty) = start_tag(s, i)?;
            i += len;
            match empty {
                true => close(&mut stack, &mut root, e, i)?,
                false if stack.len() >= MAX_DEPTH => {
                    return Err((i, format!("elements nested deeper than {MAX_DEPTH}")))
                }
                false => stack.push(e),
            }
        }
    }
    if let Some(e) = stack.last() {
        return Err((b.len(), format!("<{}> is not closed (truncated?)", e.name)));
    }
    root.ok_or((0, "no root element".into()))
}

fn close(
    stack: &mut [Element],
    root: &mut Option<Element>,
    e: Element,
    at: usize,
) -> Result<(), ParseError> {
    match stack.last_mut() {
        Some(parent) => parent.children.push(e),
        None if root.is_none() => *root = Some(e),
        None => return Err((at, "a second root element".into())),
    }
    Ok(())
}

/// Length of a `<!DOCTYPE ...>` with its internal subset.
fn skip_declaration(rest: &str) -> Option<usize> {
    let mut depth = 0;
    for (k, c) in rest.char_indices() {
        match c {
            '[' => depth += 1,
            ']' => depth -= 1,
            '>' if depth <= 0 => return Some(k + 1),
            _ => {}
        }
    }
    None
}

fn local(name: &str) -> String {
    name.rsplit(':').next().unwrap_or(name).to_string()
}

/// A start tag at `i`: the element, the tag's length, whether it is empty
/// (`<x/>`).
fn start_tag(s: &str, i: usize) -> Result<(Element, usize, bool), ParseError> {
    let b = s.as_bytes();
    let mut k = i + 1;
    let name_end = |k: usize| {
        s[k..]
            .find(|c: char| c.is_whitespace() || c == '>' || c == '/')
            .map(|n| k + n)
    };
    let end = name_end(k).ok_or((i, "unterminated start tag".to_string()))?;
    if end == k {
        return Err((i, "a tag without a name".into()));
    }
    let mut e = Element {
        name: local(&s[k..end]),
        offset: i,
        ..Default::default()
    };
    k = end;
    loop {
        while k < b.len() && b[k].is_ascii_whitespace() {
            k += 1;
        }
        match b.get(k) {
            None => return Err((i, format!("unterminated start tag <{}>", e.name))),
            Some(b'>') => return Ok((e, k + 1 - i, false)),
            Some(b'/') if b.get(k + 1) == Some(&b'>') => return Ok((e, k + 2 - i, true)),
            _ => {}
        }
        let eq = s[k..]
            .find('=')
            .map(|n| k + n)
            .ok_or((k, "attribute without '='".to_string()))?;
        let name = local(s[k..eq].trim());
        let q = eq + 1 + s[eq + 1..].len() - s[eq + 1..].trim_start().len();
        let quote = *b
            .get(q)
            .ok_or((q, "attribute without a value".to_string()))?;
        if quote != b'"' && quote != b'\'' {
            return Err((q, format!("attribute '{name}' value not quoted")));
        }
        let close = s[q + 1..]
            .find(quote as char)
            .map(|n| q + 1 + n)
            .ok_or((q, format!("attribute '{name}' value not terminated")))?;
        e.attributes
            .push((name, unescape(&s[q + 1..close], q + 1)?));
        k = close + 1;
    }
}

/// Resolves `&lt;`, `&gt;`, `&amp;`, `&quot;`, `&apos;`, `&#N;`, `&#xH;`.
fn unescape(t: &str, at: usize) -> Result<String, ParseError> {
    if !t.contains('&') {
        return Ok(t.to_string());
    }
    let mut out = String::with_capacity(t.len());
    let mut rest = t;
    while let Some(a) = rest.find('&') {
        out.push_str(&rest[..a]);
        let semi = rest[a..]
            .find(';')
            .ok_or((at, "'&' without ';'".to_string()))?;
        let name = &rest[a + 1..a + semi];
        let c = match name {
            "lt" => Some('<'),
            "gt" => Some('>'),
            "amp" => Some('&'),
            "quot" => Some('"'),
            "apos" => Some('\''),
            n if n.starts_with("#x") => u32::from_str_radix(&n[2..], 16)
                .ok()
                .and_then(char::from_u32),
            n if n.starts_with('#') => n[1..].parse().ok().and_then(char::from_u32),
            _ => None,
        };
        out.push(c.ok_or((at, format!("unknown entity &{name};")))?);
        rest = &rest[a + semi + 1..];
    }
    out.push_str(rest);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elements_text_attributes_and_entities() {
        let doc = br#"<?xml version="1.0" encoding="UTF-8"?>
<!DOCTYPE x [ <!ENTITY a "b"> ]>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2">
  <!-- a comment -->
  <Record1><Revision>ISO5436 - 2000</Revision>
    <Axes><CX axis='x'><Increment>1.5e-06</Increment></CX><CZ/></Axes>
  </Record1>
  <Note>a &lt; b &amp; &#x3bc;m &#181;<![CDATA[<raw>]]></Note>
</p:ISO5436_2>"#;
        let r = parse(doc).unwrap();
        assert_eq!(r.name, "ISO5436_2");
        assert_eq!(r.text_at("Record1/Revision"), Some("ISO5436 - 2000"));
        assert_eq!(r.text_at("Record1/Axes/CX/Increment"), Some("1.5e-06"));
        let cx = r.find("Record1/Axes/CX").unwrap();
        assert_eq!(cx.attributes, vec![("axis".to_string(), "x".to_string())]);
        assert!(r.find("Record1/Axes/CZ").is_some());
        assert_eq!(r.text_at("Note"), Some("a < b & μm µ<raw>"));
        let leaves = r.leaves();
        assert!(leaves.contains(&("Record1/Revision".to_string(), "ISO5436 - 2000")));
    }

    #[test]
    fn malformed_documents_give_offsets() {
        for (doc, want) in [
            (&b"<a><b></a>"[..], "closes <b>"),
            (b"<a><b>", "not closed"),
            (b"<a x=1/>", "not quoted"),
            (b"<a>&bogus;</a>", "unknown entity"),
            (b"<a/><b/>", "second root"),
            (b"<a>\xff</a>", "not UTF-8"),
            (b"", "no root"),
        ] {
            let (_, m) = parse(doc).unwrap_err();
            assert!(m.contains(want), "{m}");
        }
        let deep = "<a>".repeat(100_000) + &"</a>".repeat(100_000);
        let (_, m) = parse(deep.as_bytes()).unwrap_err();
        assert!(m.contains("nested deeper"), "{m}");
    }
}
