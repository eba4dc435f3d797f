//! The fast block reader against the old one ([`super::blocks_oracle`]):
//! the same sections, columns (bit for bit), metadata and errors on
//! generated exports — decimal comma, thousands separators, quotes, blank
//! lines, CRLF, preambles, several blocks, junk lines — and on one long
//! enough to be parsed in parallel chunks.

use std::path::Path;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::blocks::read_blocks;
use super::blocks_oracle::read_blocks_oracle;
use super::text::Text;

/// A number as an instrument might print it.
fn number(rng: &mut ChaCha8Rng, decimal: char, thousands: bool) -> String {
    let v: f64 = rng.random_range(-2.0e4..2.0e4);
    let s = match rng.random_range(0..8) {
        0 => format!("{}", v.round() as i64),
        1 => format!("{v:.3}"),
        2 => format!("{v:e}"),
        3 => format!("{:.17}", v / 1e3),
        4 => format!("{}", v * 1e-9),
        5 => String::new(),
        6 if thousands && v.abs() >= 1000.0 => {
            let int = v.abs().trunc() as i64;
            let sign = if v < 0.0 { "-" } else { "" };
            let sep = if decimal == ',' { '.' } else { ',' };
            return format!("{sign}{}{sep}{:03}{decimal}25", int / 1000, int % 1000);
        }
        _ => format!("{v}"),
    };
    if decimal == ',' {
        s.replace('.', ",")
    } else {
        s
    }
}

struct Dialect {
    delimiter: char,
    decimal: char,
    quoted: bool,
    thousands: bool,
}

fn row(rng: &mut ChaCha8Rng, d: &Dialect, width: usize) -> String {
    let cells: Vec<String> = (0..width)
        .map(|_| {
            let n = number(rng, d.decimal, d.thousands);
            if d.quoted {
                format!("\"{n}\"")
            } else {
                n
            }
        })
        .collect();
    let mut line = cells.join(&d.delimiter.to_string());
    if rng.random_range(0..20) == 0 {
        line.push(d.delimiter); // a trailing delimiter
    }
    line
}

/// A generated export: preamble, then blocks with headers, odd lines
/// sprinkled in.
fn export(seed: u64, rows_per_block: usize) -> (String, char, char) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let delimiter = [',', ';', '\t', ' '][rng.random_range(0..4)];
    let decimal = if delimiter != ',' && rng.random_bool(0.5) {
        ','
    } else {
        '.'
    };
    let d = Dialect {
        delimiter,
        decimal,
        quoted: delimiter != ' ' && rng.random_bool(0.2),
        thousands: rng.random_bool(0.3),
    };
    let mut lines = Vec::new();
    for k in 0..rng.random_range(0..3) {
        lines.push(format!("Operator{delimiter}A{k}"));
        lines.push(format!("Rate = {k}0 mm/s"));
    }
    for _ in 0..rng.random_range(1..4) {
        let width = rng.random_range(1..5);
        if rng.random_bool(0.8) {
            let names: Vec<String> = (0..width).map(|k| format!("c{k} [mN]")).collect();
            lines.push(names.join(&delimiter.to_string()));
        }
        for _ in 0..rng.random_range(0..=rows_per_block) {
            let odd = rng.random_range(0..400);
            lines.push(match odd {
                0 => String::new(),
                1 => "junk line".into(),
                2 => row(&mut rng, &d, width + 1),
                3 => format!("x{delimiter}y"),
                _ => row(&mut rng, &d, width),
            });
        }
        if rng.random_bool(0.5) {
            lines.push(String::new());
        }
    }
    let ending = if rng.random_bool(0.5) { "\r\n" } else { "\n" };
    let mut text = lines.join(ending);
    if rng.random_bool(0.5) {
        text.push_str(ending);
    }
    (text, delimiter, decimal)
}

fn assert_same(text: &str, delimiter: char, decimal: char) {
    let t = Text::decode(Path::new("gen.csv"), text.as_bytes()).unwrap();
    let fast = read_blocks(&t, delimiter, decimal);
    let old = read_blocks_oracle(&t, delimiter, decimal);
    // Debug prints floats so that equal text means equal bits (NaN too).
    match (fast, old) {
        (Ok(a), Ok(b)) => assert_eq!(format!("{a:?}"), format!("{b:?}"), "{text}"),
        (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
        (a, b) => panic!("fast {:?} but old {:?} on\n{text}", a.is_ok(), b.is_ok()),
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(300))]
    /// New and old readers agree on generated dialects.
    #[test]
    fn fast_blocks_are_the_old_blocks(seed in proptest::num::u64::ANY) {
        let (text, delimiter, decimal) = export(seed, 40);
        assert_same(&text, delimiter, decimal);
        // Under the other decimal mark too: different errors, same ones.
        assert_same(&text, delimiter, if decimal == '.' { ',' } else { '.' });
    }
}

#[test]
fn long_blocks_parsed_in_chunks_are_the_old_blocks() {
    for seed in 0..4 {
        let (text, delimiter, decimal) = export(seed, 150_000);
        assert_same(&text, delimiter, decimal);
    }
}

#[test]
fn a_bad_row_deep_in_a_long_block_is_named_by_line_and_column() {
    let mut text = String::from("t [s],F [N]\n");
    for i in 0..100_000 {
        text.push_str(&format!("{i}.5,{}\n", i % 7));
    }
    text.push_str("3.5,oops\n");
    let t = Text::decode(Path::new("long.csv"), text.as_bytes()).unwrap();
    let e = read_blocks(&t, ',', '.').unwrap_err().to_string();
    assert!(
        e.contains("long.csv") && e.contains("100002") && e.contains("F"),
        "{e}"
    );
    assert_eq!(e, read_blocks_oracle(&t, ',', '.').unwrap_err().to_string());
}
