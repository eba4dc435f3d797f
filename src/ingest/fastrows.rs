//! Numeric fields and rows parsed without allocating: the hot loop of
//! reading a large export. Each function gives what
//! [`super::dialect::parse_number`] and [`super::dialect::parse_line`] give,
//! or says [`Parsed::Slow`] / [`Row::Slow`] when the text is unusual
//! (quotes, thousands separators, `NaN`, non-ASCII), and the caller asks
//! them instead. A property test checks the two agree.

/// One field, parsed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Parsed {
    /// An empty (or all-whitespace) field: a missing value.
    Empty,
    /// A number.
    Value(f64),
    /// Not decided here: ask [`super::dialect::parse_number`].
    Slow,
}

/// Powers of ten exactly representable as f64.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// The ASCII characters `char::is_whitespace` accepts (what `str::trim`
/// and `split_whitespace` strip).
fn is_ws(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | 0x0B | 0x0C | b'\r')
}

fn trim(mut s: &[u8]) -> &[u8] {
    while let [b, rest @ ..] = s {
        if !is_ws(*b) {
            break;
        }
        s = rest;
    }
    while let [rest @ .., b] = s {
        if !is_ws(*b) {
            break;
        }
        s = rest;
    }
    s
}

/// Parses `[+-]digits[<decimal>digits][(e|E)[+-]digits]`. Up to 19
/// significant digits and a power of ten within ±22 take Clinger's fast
/// path (an exact integer times or over an exact power of ten: one
/// correctly rounded operation, so the same bits as `str::parse`); other
/// numbers of that form go to `str::parse` from a stack buffer.
pub fn number(field: &[u8], decimal: u8) -> Parsed {
    let s = trim(field);
    if s.is_empty() {
        return Parsed::Empty;
    }
    let (neg, body) = match s[0] {
        b'-' => (true, &s[1..]),
        b'+' => (false, &s[1..]),
        _ => (false, s),
    };
    // The common form first, as a row's fields take it ([`plain`]); the
    // sign is already off, so the body must start with a digit.
    let fast = body.first().is_some_and(u8::is_ascii_digit) && !decimal.is_ascii_digit();
    if let Some((v, _)) = fast.then(|| plain(body, |_| false, decimal)).flatten() {
        return Parsed::Value(if neg { -v } else { v });
    }
    let (mut m, mut sig, mut i) = (0u64, 0u32, 0usize);
    let digits = |i: &mut usize, m: &mut u64, sig: &mut u32| -> Option<usize> {
        let start = *i;
        while let Some(&b) = body.get(*i).filter(|b| b.is_ascii_digit()) {
            if *m != 0 || b != b'0' {
                *sig += 1;
                if *sig > 19 {
                    return None;
                }
                *m = *m * 10 + u64::from(b - b'0');
            }
            *i += 1;
        }
        Some(*i - start)
    };
    let Some(int_digits) = digits(&mut i, &mut m, &mut sig) else {
        return slow_parse(s, decimal);
    };
    if int_digits == 0 {
        return Parsed::Slow;
    }
    let mut frac = 0i64;
    if body.get(i) == Some(&decimal) {
        i += 1;
        match digits(&mut i, &mut m, &mut sig) {
            None => return slow_parse(s, decimal),
            Some(0) => return Parsed::Slow,
            Some(n) => frac = n as i64,
        }
    }
    let mut exp = 0i64;
    if body.get(i).is_some_and(|b| b | 0x20 == b'e') {
        match exponent(&body[i + 1..]) {
            Some((e, used)) => {
                exp = e;
                i += 1 + used;
            }
            None => return Parsed::Slow,
        }
    }
    if i != body.len() {
        return Parsed::Slow;
    }
    let e10 = exp - frac;
    let v = if m == 0 {
        0.0
    } else if m <= 1 << 53 && (-22..=22).contains(&e10) {
        if e10 >= 0 {
            m as f64 * POW10[e10 as usize]
        } else {
            m as f64 / POW10[(-e10) as usize]
        }
    } else {
        return slow_parse(s, decimal);
    };
    Parsed::Value(if neg { -v } else { v })
}

/// The exponent after `e`: `[+-]digits`, its value and the bytes used;
/// `None` without digits or beyond ±100 000 (left to `str::parse`).
fn exponent(s: &[u8]) -> Option<(i64, usize)> {
    let (neg, start) = match s.first() {
        Some(b'-') => (true, 1),
        Some(b'+') => (false, 1),
        _ => (false, 0),
    };
    let mut i = start;
    let mut exp = 0i64;
    while let Some(&b) = s.get(i).filter(|b| b.is_ascii_digit()) {
        if exp > 100_000 {
            return None;
        }
        exp = exp * 10 + i64::from(b - b'0');
        i += 1;
    }
    if i == start {
        return None;
    }
    Some((if neg { -exp } else { exp }, i))
}

/// `str::parse` of a field already checked to be of the plain form, with
/// the decimal mark made a dot in a stack buffer.
fn slow_parse(s: &[u8], decimal: u8) -> Parsed {
    let mut buf = [0u8; 64];
    if s.len() > buf.len() || !s.is_ascii() {
        return Parsed::Slow;
    }
    for (o, &b) in buf.iter_mut().zip(s) {
        *o = if b == decimal { b'.' } else { b };
    }
    let text = std::str::from_utf8(&buf[..s.len()]).expect("ASCII");
    // Digits, one mark and an exponent only, else the caller decides.
    let plain = s
        .iter()
        .all(|&b| b.is_ascii_digit() || matches!(b, b'-' | b'+' | b'e' | b'E') || b == decimal);
    match text.parse::<f64>() {
        Ok(v) if plain => Parsed::Value(v),
        _ => Parsed::Slow,
    }
}

/// One line, parsed into `out`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Row {
    /// `out` holds the row (trailing empty fields dropped); `fields` is the
    /// number of fields on the line.
    Numbers {
        /// Fields on the line.
        fields: usize,
    },
    /// Every field empty: not a numeric row.
    NotNumeric {
        /// Fields on the line.
        fields: usize,
    },
    /// Not decided here: ask [`super::dialect::parse_line`].
    Slow,
}

/// Parses a line of numbers into `out` (cleared first), as
/// [`super::dialect::parse_line`] would.
pub fn row(line: &str, delimiter: char, decimal: char, out: &mut Vec<f64>) -> Row {
    out.clear();
    // No search for quotes: a field holding one is never a number here
    // (`number` says Slow), so a quoted line goes to the slow path anyway,
    // unless the quote is the delimiter or the decimal mark.
    let quote = delimiter == '"' || decimal == '"';
    if !delimiter.is_ascii() || !decimal.is_ascii() || quote {
        return Row::Slow;
    }
    let mut fields = Fields::default();
    let done = if delimiter == ' ' {
        whitespace_fields(line, decimal as u8, &mut fields, out)
    } else {
        delimited_fields(
            line.as_bytes(),
            delimiter as u8,
            decimal as u8,
            &mut fields,
            out,
        )
    };
    match (done, fields.kept) {
        (false, _) => Row::Slow,
        (true, 0) => Row::NotNumeric {
            fields: fields.count,
        },
        (true, kept) => {
            out.truncate(kept);
            Row::Numbers {
                fields: fields.count,
            }
        }
    }
}

/// The fields of a line seen so far, and how many of `out`'s values end
/// with a number (the rest are trailing empty fields).
#[derive(Default)]
struct Fields {
    count: usize,
    kept: usize,
}

impl Fields {
    /// Records one field's parse in `out`; `false` when it is undecided.
    fn take(&mut self, parsed: Parsed, out: &mut Vec<f64>) -> bool {
        self.count += 1;
        match parsed {
            Parsed::Empty => out.push(f64::NAN),
            Parsed::Value(v) => {
                out.push(v);
                self.kept = out.len();
            }
            Parsed::Slow => return false,
        }
        true
    }
}

/// Fields separated by runs of whitespace; `false` if one is undecided.
/// Each field is tried by [`plain`] first, as in [`delimited_fields`].
fn whitespace_fields(line: &str, decimal: u8, fields: &mut Fields, out: &mut Vec<f64>) -> bool {
    if !line.is_ascii() {
        return false;
    }
    let fused = !matches!(decimal, b'-' | b'0'..=b'9') && !is_ws(decimal);
    let mut rest = line.as_bytes();
    loop {
        let start = rest.iter().position(|&b| !is_ws(b)).unwrap_or(rest.len());
        rest = &rest[start..];
        if rest.is_empty() {
            return true;
        }
        let quick = if fused {
            plain(rest, is_ws, decimal)
        } else {
            None
        };
        let (parsed, end) = match quick {
            Some((v, end)) => (Parsed::Value(v), end),
            None => {
                let end = rest.iter().position(|&b| is_ws(b)).unwrap_or(rest.len());
                (number(&rest[..end], decimal), end)
            }
        };
        if !fields.take(parsed, out) {
            return false;
        }
        rest = &rest[end..];
    }
}

/// Fields separated by `d`; `false` if one is undecided. Each field is
/// first tried by [`plain`], which finds its end while reading its digits
/// (one pass over the bytes instead of a delimiter search and then a
/// parse); what it declines goes to [`number`] as a field cut at the
/// delimiter, as before.
fn delimited_fields(b: &[u8], d: u8, decimal: u8, fields: &mut Fields, out: &mut Vec<f64>) -> bool {
    // `plain` reads a leading `-`, digits and a mark before it looks for
    // the delimiter, so none of them may be the delimiter.
    let fused =
        !matches!(d, b'-' | b'0'..=b'9') && !matches!(decimal, b'-' | b'0'..=b'9') && d != decimal;
    let mut rest = b;
    loop {
        let quick = if fused {
            plain(rest, |b| b == d, decimal)
        } else {
            None
        };
        let (parsed, end) = match quick {
            Some((v, end)) => (Parsed::Value(v), end),
            None => {
                let end = rest.iter().position(|&b| b == d).unwrap_or(rest.len());
                (number(&rest[..end], decimal), end)
            }
        };
        if !fields.take(parsed, out) {
            return false;
        }
        if end == rest.len() {
            return true;
        }
        rest = &rest[end + 1..];
    }
}

/// The common field at the start of `b`: `[-]digits[<decimal>digits]`
/// ended by a delimiter (a byte `ends` accepts) or by the end of `b`, with
/// the value [`number`]'s general path gives (the same mantissa and single
/// division) and the field's length; `None` for anything else (more than
/// 19 bytes after the sign, a mantissa beyond 2^53), which that path
/// decides.
fn plain(b: &[u8], ends: impl Fn(u8) -> bool, decimal: u8) -> Option<(f64, usize)> {
    let neg = b.first() == Some(&b'-');
    let start = usize::from(neg);
    let (mut i, mut m) = digit_run(b, start, 0);
    if i == start {
        return None;
    }
    let mut frac = 0;
    if b.get(i) == Some(&decimal) {
        let (j, mf) = digit_run(b, i + 1, m);
        frac = j - i - 1;
        if frac == 0 {
            return None;
        }
        (i, m) = (j, mf);
    }
    if b.get(i).is_some_and(|&c| !ends(c)) || i - start > 19 || m > 1 << 53 {
        return None;
    }
    // Exact: m is at most 2^53, so the signed conversion (one instruction)
    // gives the same f64 as `m as f64`.
    let v = if m == 0 {
        0.0
    } else {
        m as i64 as f64 / POW10[frac]
    };
    Some((if neg { -v } else { v }, i))
}

/// The ASCII digits from `b[i]` on, appended to `m`: the index after them
/// and the new mantissa (wrapped past 19 digits, which the caller rejects
/// by length).
fn digit_run(b: &[u8], mut i: usize, mut m: u64) -> (usize, u64) {
    while let Some(&c) = b.get(i) {
        let digit = c.wrapping_sub(b'0');
        if digit >= 10 {
            break;
        }
        m = m.wrapping_mul(10).wrapping_add(u64::from(digit));
        i += 1;
    }
    (i, m)
}

#[cfg(test)]
mod tests {
    use super::super::dialect::{parse_line, parse_number};
    use super::*;

    fn same(field: &str, decimal: char) {
        let want = parse_number(field, decimal).map(f64::to_bits);
        match number(field.as_bytes(), decimal as u8) {
            Parsed::Slow => {}
            Parsed::Empty => assert!(want.is_some_and(|b| f64::from_bits(b).is_nan())),
            Parsed::Value(v) => assert_eq!(Some(v.to_bits()), want, "{field:?}"),
        }
    }

    #[test]
    fn fast_numbers_are_the_parsed_ones() {
        for f in [
            "0",
            "-0",
            "1",
            "0.1",
            "-1.5e-3",
            "1E5",
            " 3.25 ",
            "123456789012345678",
            "1234567890123456789012",
            "0.000000000000000000000000001",
            "9007199254740993",
            "4.9e-324",
            "1e400",
            "1.7976931348623157e308",
            "+2.5",
            "1.",
            ".5",
            "1e",
            "0,5",
            "1,234.5",
            "nan",
            "",
            "-0.0",
            "00012.5000",
            "0.00000000000000001",
            "12.3456789012345678",
            "900719925474099.3",
            "1.2.3",
        ] {
            same(f, '.');
            same(f, ',');
        }
        assert_eq!(number(b"0,18478", b','), Parsed::Value(0.18478));
        assert_eq!(number(b"-1.5e-3", b'.'), Parsed::Value(-1.5e-3));
        assert_eq!(
            number(b"1.234,5", b','),
            Parsed::Slow,
            "thousands: the slow path"
        );
    }

    /// [`row`] as it was before fields were read in one pass: the line cut
    /// at each delimiter, each field given to [`number`].
    fn by_fields(line: &str, delimiter: char, decimal: char, out: &mut Vec<f64>) -> Row {
        out.clear();
        let (mut fields, mut kept) = (0, 0);
        let bytes = line.as_bytes();
        if delimiter == ' ' && !line.is_ascii() {
            return Row::Slow;
        }
        let cut: Box<dyn Iterator<Item = &[u8]>> = if delimiter == ' ' {
            Box::new(bytes.split(|&b| is_ws(b)).filter(|f| !f.is_empty()))
        } else {
            Box::new(bytes.split(|&b| b == delimiter as u8))
        };
        for f in cut {
            fields += 1;
            match number(f, decimal as u8) {
                Parsed::Empty => out.push(f64::NAN),
                Parsed::Value(v) => {
                    out.push(v);
                    kept = out.len();
                }
                Parsed::Slow => return Row::Slow,
            }
        }
        if kept == 0 {
            return Row::NotNumeric { fields };
        }
        out.truncate(kept);
        Row::Numbers { fields }
    }

    /// `row` decides `line` as [`by_fields`] does, to the bit, and as
    /// `parse_line` where it decides.
    fn same_row(line: &str, delimiter: char, decimal: char) {
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let (mut out, mut want) = (Vec::new(), Vec::new());
        let got = row(line, delimiter, decimal, &mut out);
        let before = by_fields(line, delimiter, decimal, &mut want);
        assert_eq!(got, before, "{line:?} {delimiter:?} {decimal:?}");
        if let Row::Numbers { fields } = got {
            assert_eq!(bits(&out), bits(&want), "{line:?}");
            let (parsed, count) = parse_line(line, delimiter, decimal);
            assert_eq!(parsed.as_deref().map(bits), Some(bits(&out)), "{line:?}");
            assert_eq!(count, fields);
        }
    }

    #[test]
    fn one_pass_fields_are_the_cut_ones() {
        for (line, d, m) in [
            ("0.1234,1000.123,2000.010", ',', '.'),
            ("-0,-0.0,0,00012.5000", ',', '.'),
            (
                "9007199254740992,9007199254740993,900719925474099.3",
                ',',
                '.',
            ),
            (
                "1234567890123456789,12345678901234567890,1.234567890123456789",
                ',',
                '.',
            ),
            ("0.000000000000000001,0.0000000000000000001", ',', '.'),
            ("1,5;-2,25;;", ';', ','),
            ("1.5\t-2\t\t", '\t', '.'),
            ("1.5, 2.5 ,3.", ',', '.'),
            ("1e3,1.,.5,-,--1,+1", ',', '.'),
            ("1,5,2", ',', ','),
            ("1-5-2", '-', '.'),
            ("1.5", ',', '-'),
            ("  1.5 \t-2.25\r\n3 ", ' ', '.'),
            ("1,5  -2,25 x", ' ', ','),
            ("1.5 2é", ' ', '.'),
            (" \t ", ' ', '.'),
            ("", ',', '.'),
            (",,", ',', '.'),
        ] {
            same_row(line, d, m);
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(2000))]

        /// Lines of several fields, mostly numbers of 0 to 20 digits on
        /// each side of a mark, some with signs, spaces, exponents or a
        /// foreign mark, read as [`by_fields`] and `parse_line` read them.
        #[test]
        fn fields_agree(
            fields in proptest::collection::vec(
                "[ ]?[+-]?[0-9]{0,20}([.,][0-9]{0,20})?(e-?[0-9])?[ ]?|[0-9]{1,4}[.,][0-9]{1,4}",
                1..7,
            ),
            dialect in 0usize..7,
            trailing in 0usize..3,
        ) {
            let (delimiter, decimal) = [
                (',', '.'),
                (';', ','),
                ('\t', '.'),
                ('\t', ','),
                (',', ','),
                (' ', '.'),
                (' ', ','),
            ][dialect];
            let mut line = fields.join(&delimiter.to_string());
            for _ in 0..trailing {
                line.push(delimiter);
            }
            same_row(&line, delimiter, decimal);
        }
    }

    proptest::proptest! {
        /// Any field the fast parser decides, it decides as `parse_number`.
        #[test]
        fn number_agrees(field in "[ ]?[+-]?[0-9]{0,22}([.,][0-9]{0,22})?([eE][+-]?[0-9]{0,4})?[ ]?",
                         comma in proptest::bool::ANY) {
            same(&field, if comma { ',' } else { '.' });
        }

        /// Any line the fast parser decides, it decides as `parse_line`.
        #[test]
        fn row_agrees(line in "[0-9.,;\t +eE\"a-]{0,24}", d in 0usize..4, comma in proptest::bool::ANY) {
            let delimiter = [',', ';', '\t', ' '][d];
            let decimal = if comma { ',' } else { '.' };
            let (want, want_fields) = parse_line(&line, delimiter, decimal);
            let mut out = Vec::new();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            match row(&line, delimiter, decimal, &mut out) {
                Row::Slow => {}
                Row::NotNumeric { fields } => {
                    proptest::prop_assert!(want.is_none());
                    proptest::prop_assert_eq!(fields, want_fields);
                }
                Row::Numbers { fields } => {
                    proptest::prop_assert_eq!(Some(bits(&out)), want.as_deref().map(bits));
                    proptest::prop_assert_eq!(fields, want_fields);
                }
            }
        }
    }
}
