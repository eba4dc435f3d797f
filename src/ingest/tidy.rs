//! What every reader's sections go through once read: the quirks real
//! exports share whatever their instrument, handled in one place and each
//! said in the preamble (a `tribo.*` entry naming the column), never
//! silently.
//!
//! - **Sentinels.** A value of magnitude ≥ [`HUGE`] (catman's `1E+308`,
//!   a logger's "no value") is missing. So is `−1000000` (catman's unused
//!   channel, [`UNUSED`]) in a column where it is every value, or where it
//!   stands at least ten times beyond every other value: a column that reads
//!   real numbers near −10⁶ keeps them.
//! - **Duplicate column names.** A later column with the name of an earlier
//!   one (a PCS MTM table repeats `Step Time` and `Traction Coeff` after
//!   its summary) is dropped when it holds the same values, else renamed
//!   `name #2`, so that a name finds one column.
//! - **Empty unnamed columns.** A column with no header name (`column_N`)
//!   below a header, and no value at all, is a spacer between column groups
//!   or a trailing delimiter: dropped.
//! - **Row numbers.** A first column named `index` (or `idx`, `#`, `row`,
//!   `no`, `nr`) without a unit that counts 0, 1, 2, … or 1, 2, 3, … is the
//!   rows' numbering, not a measurement (SurfaceTopography's `index,x,y`
//!   CSV): dropped, so that the columns after it read as what they are.

use super::{Channel, MetaEntry, Section};

/// Values of at least this magnitude are a logger's "no value" marker: no
/// measured quantity reads 10³⁰⁰ in any unit.
pub const HUGE: f64 = 1e300;

/// The value HBM catman (and other loggers) write in a channel that
/// records nothing.
pub const UNUSED: f64 = -1_000_000.0;

/// A sentinel −10⁶ must stand this many times beyond every other value of
/// its column to be taken as missing.
const SENTINEL_MARGIN: f64 = 10.0;

/// Applies every rule of the module to `sections`; what was done is
/// appended to `preamble`.
pub fn tidy(sections: &mut [Section], preamble: &mut Vec<MetaEntry>) {
    for s in sections.iter_mut() {
        let line = s.header_line.unwrap_or(s.first_data_line);
        let note = |key: &str, value: String| MetaEntry {
            key: key.into(),
            value: format!("{}: {value}", s.name),
            line,
        };
        let mut notes = Vec::new();
        for c in &mut s.channels {
            if let Some(what) = mask_sentinels(&mut c.values) {
                notes.push(note("tribo.missing_values", format!("'{}' {what}", c.name)));
            }
        }
        if s.channels.len() > 2 && is_row_numbering(&s.channels[0]) {
            let c = s.channels.remove(0);
            let what = format!("'{}' dropped: it numbers the rows", c.name);
            notes.push(note("tribo.dropped_channel", what));
        }
        if s.header_line.is_some() {
            let before = s.channels.len();
            s.channels
                .retain(|c| !(generated_name(&c.name) && c.values.iter().all(|v| v.is_nan())));
            let dropped = before - s.channels.len();
            if dropped > 0 {
                let what = format!("{dropped} empty column(s) without a name dropped");
                notes.push(note("tribo.dropped_channel", what));
            }
        }
        for what in dedupe(&mut s.channels) {
            notes.push(note("tribo.duplicate_column", what));
        }
        preamble.extend(notes);
    }
}

/// A column named as a row number, without a unit, counting by one from 0
/// or 1.
fn is_row_numbering(c: &Channel) -> bool {
    let name = c.name.trim().trim_end_matches('.').to_lowercase();
    let first = c.values.first().copied().unwrap_or(f64::NAN);
    matches!(name.as_str(), "index" | "idx" | "#" | "row" | "no" | "nr")
        && c.raw_unit.is_empty()
        // Row numbers are whole numbers, compared exactly.
        && (first.to_bits() == 0f64.to_bits() || first.to_bits() == 1f64.to_bits())
        && c.values
            .iter()
            .enumerate()
            .all(|(i, v)| v.to_bits() == (first + i as f64).to_bits())
}

/// The name the block reader gives a column whose header cell is empty.
fn generated_name(name: &str) -> bool {
    name.strip_prefix("column_")
        .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
}

/// Turns sentinel values into NaN; what was masked, when anything was.
fn mask_sentinels(v: &mut [f64]) -> Option<String> {
    use rayon::prelude::*;
    // One read-only pass, the largest magnitude, tells whether there can
    // be anything to do (the common case: every value below 10⁶ in
    // magnitude, nothing); on all threads for a long column.
    let most = v
        .par_chunks(1 << 16)
        .map(|c| c.iter().fold(0.0f64, |m, x| m.max(x.abs())))
        .reduce(|| 0.0, f64::max);
    if most < UNUSED.abs() {
        return None;
    }
    let (huge, unused, largest) = v.iter().fold((0usize, 0usize, 0.0f64), |(h, u, m), &x| {
        if x.abs() >= HUGE {
            (h + 1, u, m)
        } else if x == UNUSED {
            (h, u + 1, m)
        } else {
            (h, u, m.max(x.abs()))
        }
    });
    let unused = unused > 0 && largest * SENTINEL_MARGIN <= UNUSED.abs();
    if huge == 0 && !unused {
        return None;
    }
    let mut n = 0usize;
    for x in v.iter_mut() {
        if x.abs() >= HUGE || (unused && *x == UNUSED) {
            *x = f64::NAN;
            n += 1;
        }
    }
    let all = v.iter().all(|x| x.is_nan());
    let what = match (huge > 0, unused) {
        (true, true) => "values of magnitude ≥ 1e300 and -1000000",
        (true, false) => "values of magnitude ≥ 1e300",
        _ => "-1000000 values",
    };
    Some(match all {
        true => format!("{n} {what}: every value missing (an unused channel)"),
        false => format!("{n} {what}: missing values (a logger's no-value marker)"),
    })
}

/// Drops or renames the columns whose name an earlier column has; what
/// was done, one line per column.
fn dedupe(channels: &mut Vec<Channel>) -> Vec<String> {
    let mut notes = Vec::new();
    let mut kept: Vec<Channel> = Vec::with_capacity(channels.len());
    for c in channels.drain(..) {
        let Some(first) = kept.iter().find(|k| k.name == c.name) else {
            kept.push(c);
            continue;
        };
        let same = first.raw_unit == c.raw_unit
            && first.values.len() == c.values.len()
            && first
                .values
                .iter()
                .zip(&c.values)
                .all(|(a, b)| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()));
        if same {
            notes.push(format!(
                "'{}' repeated with the same values: dropped",
                c.name
            ));
            continue;
        }
        let name = (2..)
            .map(|k| format!("{} #{k}", c.name))
            .find(|n| kept.iter().all(|k| &k.name != n))
            .expect("a free name");
        notes.push(format!(
            "'{}' repeated with other values: renamed '{name}'",
            c.name
        ));
        kept.push(Channel { name, ..c });
    }
    *channels = kept;
    notes
}

#[cfg(test)]
mod tests {
    use super::*;

    fn channel(name: &str, values: &[f64]) -> Channel {
        Channel {
            name: name.into(),
            raw_unit: "N".into(),
            values: values.to_vec(),
        }
    }

    fn section(channels: Vec<Channel>) -> Section {
        Section {
            name: "1".into(),
            metadata: vec![],
            header_line: Some(3),
            first_data_line: 4,
            channels,
        }
    }

    /// catman's unused channel (every value −10⁶) and its 1E+308 markers
    /// become missing values; a column of real numbers near −10⁶ and a
    /// −10⁶ that does not stand out keep their values.
    #[test]
    fn sentinels_are_missing_and_real_values_stay() {
        let nan = f64::NAN;
        let mut s = vec![section(vec![
            channel("unused", &[UNUSED, UNUSED, UNUSED]),
            channel("force", &[1.0, 1e308, 2.0]),
            channel("gap", &[1.5, UNUSED, -2.0]),
            channel("big", &[-999_000.0, UNUSED, -1_001_000.0]),
            channel("edge", &[1e5, UNUSED, 3.0]),
        ])];
        let mut pre = vec![];
        tidy(&mut s, &mut pre);
        let v = |k: usize| format!("{:?}", s[0].channels[k].values);
        assert_eq!(v(0), format!("{:?}", [nan, nan, nan]));
        assert_eq!(v(1), format!("{:?}", [1.0, nan, 2.0]));
        assert_eq!(v(2), format!("{:?}", [1.5, nan, -2.0]));
        assert_eq!(v(3), format!("{:?}", [-999_000.0, UNUSED, -1_001_000.0]));
        assert_eq!(v(4), format!("{:?}", [1e5, nan, 3.0]));
        assert_eq!(pre.len(), 4);
        assert!(pre[0].value.contains("'unused'") && pre[0].value.contains("unused channel"));
        assert!(pre
            .iter()
            .all(|m| m.key == "tribo.missing_values" && m.line == 3));
    }

    /// An `index` column counting the rows is dropped; one that does not
    /// count by one, or has a unit, stays.
    #[test]
    fn row_numbers_are_dropped() {
        let mut s = vec![section(vec![
            channel("index", &[0.0, 1.0, 2.0]),
            channel("x", &[0.5, 1.0, 1.5]),
            channel("y", &[3.0, 2.0, 1.0]),
        ])];
        s[0].channels[0].raw_unit.clear();
        let mut pre = vec![];
        tidy(&mut s, &mut pre);
        let names: Vec<&str> = s[0].channels.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["x", "y"]);
        assert!(pre[0].value.contains("'index' dropped"), "{pre:?}");
        let mut s = vec![section(vec![
            channel("index", &[0.0, 2.0, 4.0]),
            channel("x", &[0.5, 1.0, 1.5]),
            channel("y", &[3.0, 2.0, 1.0]),
        ])];
        s[0].channels[0].raw_unit.clear();
        tidy(&mut s, &mut pre);
        assert_eq!(s[0].channels.len(), 3);
    }

    /// A repeated column with the same values is dropped, one with other
    /// values renamed; empty unnamed columns are dropped, named ones kept.
    #[test]
    fn duplicates_and_empty_spacers() {
        let nan = f64::NAN;
        let mut s = vec![section(vec![
            channel("Step Time", &[1.0, 2.0]),
            channel("Traction Coeff", &[0.1, nan]),
            channel("column_3", &[nan, nan]),
            channel("Step Time", &[1.0, 2.0]),
            channel("Pin Load", &[nan, nan]),
            channel("Traction Coeff", &[0.1, nan]),
            channel("Step Time", &[5.0, 6.0]),
        ])];
        let mut pre = vec![];
        tidy(&mut s, &mut pre);
        let names: Vec<&str> = s[0].channels.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(
            names,
            ["Step Time", "Traction Coeff", "Pin Load", "Step Time #2"]
        );
        let keys: Vec<&str> = pre.iter().map(|m| m.key.as_str()).collect();
        assert_eq!(
            keys,
            [
                "tribo.dropped_channel",
                "tribo.duplicate_column",
                "tribo.duplicate_column",
                "tribo.duplicate_column"
            ]
        );
        assert!(pre[3].value.contains("renamed 'Step Time #2'"), "{pre:?}");
    }
}
