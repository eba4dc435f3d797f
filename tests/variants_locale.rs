//! Generated variants of the generic delimited friction trace, the family
//! a lab's own logger or spreadsheet writes: column names in English,
//! German, Spanish or Portuguese; decimal comma with semicolons (or tabs)
//! where the locale writes one; a trailing delimiter on every line; a
//! column repeated under its own name; an unused channel filled with the
//! logger's −1000000; a "no value" of 1E+300 in one cell; UTF-8, UTF-8 with
//! BOM, UTF-16 LE/BE with BOM or ISO-8859-1; LF, CRLF or CR-only lines.
//! Each reads as the same roles with the same SI values, the sentinels
//! missing and each quirk said in the preamble.

use std::collections::BTreeMap;

use crate::common::variants::{read_written, render, signature, ENCODINGS, ENDINGS};

use tribo::ingest::Dataset;

/// Column headings per language: time, friction force, normal force,
/// coefficient of friction, an unused channel.
const HEADINGS: [(&str, [&str; 5]); 4] = [
    (
        "en",
        [
            "Time [s]",
            "Friction force [N]",
            "Normal force [N]",
            "COF",
            "Channel 7 [V]",
        ],
    ),
    (
        "de",
        [
            "Zeit [s]",
            "Reibkraft [N]",
            "Normalkraft [N]",
            "Reibwert",
            "Kanal 7 [V]",
        ],
    ),
    (
        "es",
        [
            "Tiempo (s)",
            "Fuerza de fricción (N)",
            "Carga normal (N)",
            "Coeficiente de fricción",
            "Canal 7 (V)",
        ],
    ),
    (
        "pt",
        [
            "Tempo (s)",
            "Força de atrito (N)",
            "Força normal (N)",
            "Coeficiente de atrito",
            "Canal 7 (V)",
        ],
    ),
];

/// A trace of 60 rows in `language`: `comma` writes decimal commas (with
/// `;` between cells, or tabs when `tabs`), else points and commas. Every
/// line ends in a delimiter; the time column is repeated at the end; the
/// unused channel reads −1000000 throughout; row 7's friction force is
/// 1E+300.
fn trace(language: &str, comma: bool, tabs: bool) -> String {
    let (_, h) = HEADINGS.iter().find(|(l, _)| *l == language).unwrap();
    let d = match (comma, tabs) {
        (_, true) => "\t",
        (true, false) => ";",
        (false, false) => ",",
    };
    let mark = |s: String| if comma { s.replace('.', ",") } else { s };
    let mut lines = vec![format!(
        "{}{d}{}{d}{}{d}{}{d}{}{d}{}{d}",
        h[0], h[1], h[2], h[3], h[4], h[0]
    )];
    for i in 0..60 {
        let t = format!("{:.2}", i as f64 * 0.05);
        let n = 2.0 + 0.001 * i as f64;
        let mu = 0.15 + 0.0005 * (i % 7) as f64;
        let f = if i == 7 {
            "1E+300".to_string()
        } else {
            format!("{:.5}", mu * n)
        };
        let cells = [
            t.clone(),
            f,
            format!("{n:.4}"),
            format!("{mu:.4}"),
            "-1000000".into(),
            t,
        ];
        let cells: Vec<String> = cells.into_iter().map(mark).collect();
        lines.push(format!("{}{d}", cells.join(d)));
    }
    lines.join("\n")
}

/// Each role's SI unit and values (bits) in the trace's one section.
fn by_role(ds: &Dataset) -> BTreeMap<&'static str, (String, Vec<u64>)> {
    let sig = signature(ds);
    assert_eq!(sig.len(), 1, "{}: one section", ds.source.display());
    sig[0]
        .1
        .iter()
        .filter_map(|(_, unit, role, bits)| Some(((*role)?, (unit.clone(), bits.clone()))))
        .collect()
}

#[test]
fn generic_trace_in_every_locale_reads_alike() {
    let dir = tempfile::tempdir().unwrap();
    let base = read_written(dir.path(), "t.csv", trace("en", false, false).as_bytes());
    assert_eq!(base.format, "delimited");
    let want = by_role(&base);
    let roles: Vec<&str> = want.keys().copied().collect();
    assert_eq!(
        roles,
        ["friction_force", "instrument_cof", "normal_force", "time"],
        "{want:?}"
    );
    // The independent values: row 7's friction force is missing, row 8's
    // is μ·N as written.
    let f: Vec<f64> = want["friction_force"]
        .1
        .iter()
        .map(|b| f64::from_bits(*b))
        .collect();
    assert!(f[7].is_nan() && f.iter().filter(|v| v.is_nan()).count() == 1);
    assert_eq!(
        f[8],
        format!("{:.5}", 0.1505 * 2.008).parse::<f64>().unwrap()
    );
    // The unused channel is all missing and said so; the repeated time
    // column is dropped and said so; the trailing delimiter makes no
    // column.
    let s = &base.sections[0];
    let names: Vec<&str> = s.channels.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(
        names,
        ["Time", "Friction force", "Normal force", "COF", "Channel 7"]
    );
    assert!(s.channels[4].values.iter().all(|v| v.is_nan()));
    for key in ["tribo.missing_values", "tribo.duplicate_column"] {
        assert!(base.preamble.iter().any(|m| m.key == key), "{key} not said");
    }
    for (language, _) in HEADINGS {
        for (comma, tabs) in [(false, false), (true, false), (true, true), (false, true)] {
            for ending in ENDINGS {
                for enc in ENCODINGS {
                    let what = format!("{language} comma={comma} tabs={tabs} {ending:?} {enc:?}");
                    let bytes = render(&trace(language, comma, tabs), ending, enc);
                    let ds = read_written(dir.path(), "t.csv", &bytes);
                    assert_eq!(ds.format, "delimited", "{what}");
                    assert_eq!(by_role(&ds), want, "{what}");
                    let said = |k: &str| ds.preamble.iter().any(|m| m.key == k);
                    assert!(
                        said("tribo.missing_values") && said("tribo.duplicate_column"),
                        "{what}"
                    );
                }
            }
        }
    }
}
