//! The dialect of a delimited export: delimiter, decimal mark, thousands
//! separator and quoting, sniffed from the data lines and never guessed
//! silently (`tribo inspect` shows what was chosen, and a pipeline file can
//! set it).

use serde::Serialize;

use super::text::{Encoding, LineEnding};

/// How a delimited text export is written.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Dialect {
    /// Character encoding.
    pub encoding: Encoding,
    /// Line ending.
    pub line_ending: LineEnding,
    /// Field delimiter; `' '` means runs of whitespace.
    pub delimiter: char,
    /// Decimal mark, `.` or `,`.
    pub decimal: char,
    /// Whether fields are quoted with `"`.
    pub quoted: bool,
}

impl Dialect {
    /// Whitespace-separated fields with a decimal point and no quotes, in
    /// the text's own encoding and line ending: what a reader that splits
    /// its lines itself (fixed widths, one height per line) reports.
    pub fn whitespace(text: &super::Text) -> Dialect {
        Dialect {
            encoding: text.encoding,
            line_ending: text.line_ending,
            delimiter: ' ',
            decimal: '.',
            quoted: false,
        }
    }
}

/// Splits a line into fields. Quotes (`"`) group a field, and `""` inside
/// quotes is a literal quote. With `' '` the delimiter is any run of
/// whitespace.
pub fn split_fields(line: &str, delimiter: char) -> Vec<String> {
    if delimiter == ' ' {
        return line.split_whitespace().map(str::to_string).collect();
    }
    let mut fields = Vec::new();
    let mut field = String::new();
    let mut in_quotes = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if in_quotes && chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            '"' => in_quotes = !in_quotes,
            c if c == delimiter && !in_quotes => fields.push(std::mem::take(&mut field)),
            c => field.push(c),
        }
    }
    fields.push(field);
    fields
}

/// Parses one numeric field. Empty fields and `NaN` give `Some(NaN)` (a
/// missing value); text that is not a number gives `None`. With decimal
/// mark `.`, commas between digit groups of three are thousands separators
/// (`180,901.05419`); with decimal mark `,`, dots are.
pub fn parse_number(field: &str, decimal: char) -> Option<f64> {
    let s = field.trim();
    if s.is_empty() || s.eq_ignore_ascii_case("nan") {
        return Some(f64::NAN);
    }
    let thousands = if decimal == ',' { '.' } else { ',' };
    let mut cleaned: String;
    let s = if s.contains(thousands) {
        if !is_grouped(s, thousands, decimal) {
            return None;
        }
        cleaned = s.replace(thousands, "");
        cleaned.as_str()
    } else {
        s
    };
    let s = if decimal == ',' {
        cleaned = s.replace(',', ".");
        cleaned.as_str()
    } else {
        s
    };
    // Rust also accepts "inf" and "infinity": a number column never should.
    if !s.bytes().any(|b| b.is_ascii_digit()) {
        return None;
    }
    s.parse::<f64>().ok()
}

/// Whether `s` uses `sep` only as a thousands separator: 1–3 digits, then
/// groups of exactly three digits, before any decimal mark.
fn is_grouped(s: &str, sep: char, decimal: char) -> bool {
    let int_part = s.split(decimal).next().unwrap_or("");
    let int_part = int_part.trim_start_matches(['-', '+']);
    let mut groups = int_part.split(sep);
    let first = groups.next().unwrap_or("");
    (1..=3).contains(&first.len())
        && first.bytes().all(|b| b.is_ascii_digit())
        && groups.all(|g| g.len() == 3 && g.bytes().all(|b| b.is_ascii_digit()))
}

/// Parses all fields of a line; `None` if any non-empty field is not a number.
/// Trailing empty fields (a trailing delimiter) are dropped.
pub fn parse_row(fields: &[String], decimal: char) -> Option<Vec<f64>> {
    let n = fields
        .iter()
        .rposition(|f| !f.trim().is_empty())
        .map_or(0, |i| i + 1);
    if n == 0 {
        return None;
    }
    fields[..n]
        .iter()
        .map(|f| parse_number(f, decimal))
        .collect()
}

/// [`parse_row`] of [`split_fields`] of `line`, and the number of fields,
/// without allocating a string per field when the line has no quotes (the
/// common case, and the hot loop of every reader).
pub fn parse_line(line: &str, delimiter: char, decimal: char) -> (Option<Vec<f64>>, usize) {
    if line.contains('"') {
        let fields = split_fields(line, delimiter);
        return (parse_row(&fields, decimal), fields.len());
    }
    let parse = |fields: &mut dyn Iterator<Item = &str>| {
        let mut row = Vec::new();
        let (mut count, mut kept, mut ok) = (0, 0, true);
        for f in fields {
            count += 1;
            if !ok {
                continue;
            }
            match parse_number(f, decimal) {
                Some(v) => row.push(v),
                None => ok = false,
            }
            if !f.trim().is_empty() {
                kept = row.len();
            }
        }
        // parse_row drops trailing empty fields and rejects a line of them.
        row.truncate(kept);
        let row = (ok && kept > 0).then_some(row);
        (row, count)
    };
    if delimiter == ' ' {
        parse(&mut line.split_whitespace())
    } else {
        parse(&mut line.split(delimiter))
    }
}

/// Sniffs delimiter and decimal mark from the last lines of a file, where
/// the data usually is. The winner is the pair under which the most lines
/// parse as numeric rows with the same number of fields (≥ 2); ties prefer
/// tab, semicolon, comma, pipe, whitespace, and `.` over `,`.
pub fn sniff<'a>(lines: impl DoubleEndedIterator<Item = &'a str>) -> (char, char, bool) {
    let sample: Vec<&str> = lines
        .rev()
        .filter(|l| !l.trim().is_empty())
        .take(200)
        .collect();
    let mut best = (0usize, '\t', '.');
    for delimiter in ['\t', ';', ',', '|', ' '] {
        for decimal in ['.', ','] {
            if decimal == delimiter {
                // A comma may still be the decimal mark inside quoted fields.
                if !sample.iter().any(|l| l.contains('"')) {
                    continue;
                }
            }
            let mut counts = std::collections::HashMap::new();
            for line in &sample {
                if let (Some(row), _) = parse_line(line, delimiter, decimal) {
                    if row.len() >= 2 {
                        *counts.entry(row.len()).or_insert(0usize) += 1;
                    }
                }
            }
            let score = counts.values().copied().max().unwrap_or(0);
            if score > best.0 {
                best = (score, delimiter, decimal);
            }
        }
    }
    let quoted = sample.iter().any(|l| l.trim_start().starts_with('"'));
    (best.1, best.2, quoted)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(s: &str) -> Vec<String> {
        s.lines().map(str::to_string).collect()
    }

    #[test]
    fn numbers_with_marks_and_groups() {
        assert_eq!(parse_number("0,18478", ','), Some(0.18478));
        assert_eq!(parse_number(" 180,901.05419 ", '.'), Some(180901.05419));
        assert_eq!(parse_number("1.234,5", ','), Some(1234.5));
        assert_eq!(parse_number("-1.5e-3", '.'), Some(-1.5e-3));
        assert!(parse_number("", '.').unwrap().is_nan());
        assert_eq!(parse_number("12,34", '.'), None, "not a thousands group");
        assert_eq!(parse_number("inf", '.'), None);
        assert_eq!(parse_number("Fx", '.'), None);
    }

    #[test]
    fn quoted_fields_keep_their_delimiters() {
        assert_eq!(split_fields(r#""0,5","1,25""#, ','), vec!["0,5", "1,25"]);
        assert_eq!(
            split_fields(r#"a,"b ""q""",c"#, ','),
            vec!["a", "b \"q\"", "c"]
        );
    }

    #[test]
    fn sniffs_tab_decimal_comma_and_quoted_comma_comma() {
        let tsv = lines("Time \tmu\n0,100\t0,18\n0,200\t0,16\n0,300\t0,17");
        assert_eq!(sniff(tsv.iter().map(String::as_str)), ('\t', ',', false));
        let q = lines("\"Distance\",\"Profile\"\n\"0,00050\",\"0,03\"\n\"0,00100\",\"0,03\"");
        assert_eq!(sniff(q.iter().map(String::as_str)), (',', ',', true));
        let csv = lines("a,b,c\n1.5,2,3\n2.5,3,4");
        assert_eq!(sniff(csv.iter().map(String::as_str)), (',', '.', false));
        let semi = lines("a;b\n1,5;2\n2,5;3");
        assert_eq!(sniff(semi.iter().map(String::as_str)), (';', ',', false));
    }

    proptest::proptest! {
        /// The allocation-free path gives what splitting then parsing gives,
        /// on lines of digits, signs, marks, delimiters, spaces and quotes.
        #[test]
        fn parse_line_is_split_then_parse(
            line in "[0-9.,;\t +eE\"a-]{0,24}",
            d in 0usize..4,
            comma_decimal in proptest::bool::ANY,
        ) {
            let delimiter = [',', ';', '\t', ' '][d];
            let decimal = if comma_decimal { ',' } else { '.' };
            let fields = split_fields(&line, delimiter);
            let want = (parse_row(&fields, decimal), fields.len());
            let got = parse_line(&line, delimiter, decimal);
            // NaN != NaN: compare the bits.
            let bits = |r: &(Option<Vec<f64>>, usize)| {
                (r.0.as_ref().map(|v| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>()), r.1)
            };
            proptest::prop_assert_eq!(bits(&got), bits(&want));
        }
    }
}
