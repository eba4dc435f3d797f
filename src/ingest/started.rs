//! When a test started, from its file's header: CETR's `Run date 12 May
//! 2022 12:21:50`, PCS MTM's `Test started at 23/03/2018 10:02:57`, an ISO
//! `Date: 2022-05-12T12:21:50+02:00`, German `Datum: 12.05.2022` with
//! `Uhrzeit: 12:21:50`, and the like. The result is an ISO 8601 text:
//! with the UTC offset when the file states one, else the instrument's
//! local time without an offset (a file rarely says which zone its clock
//! was in; an offset is never guessed).
//!
//! Numeric dates with both fields ≤ 12 (`05/12/2022`) are read in the
//! order the format is known to write (`DayOrder`): PCS MTM writes the day
//! first, CETR the month first; a format whose order is unknown gets an
//! error naming the line rather than a guess.

use super::{Dataset, MetaEntry};
use crate::error::{Error, Location, Result};

/// The order of day and month in a numeric date such as `05/12/2022`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DayOrder {
    /// `dd/mm/yyyy` (PCS Instruments, most of Europe).
    DayFirst,
    /// `mm/dd/yyyy` (US instruments: CETR).
    MonthFirst,
    /// Not known: a date with both fields ≤ 12 is refused.
    Unknown,
}

impl DayOrder {
    /// The order a reader's files write numeric dates in.
    pub fn of_format(format: &str) -> DayOrder {
        match format {
            "pcs-mtm" => DayOrder::DayFirst,
            "cetr-umt" => DayOrder::MonthFirst,
            _ => DayOrder::Unknown,
        }
    }
}

/// A date and time of day as a file states it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StartedAt {
    /// Year, month (1–12), day (1–31).
    pub date: (i32, u32, u32),
    /// Hour, minute, and seconds with their fraction; `None` for a date
    /// without a time.
    pub time: Option<(u32, u32, f64)>,
    /// Offset from UTC in minutes when the file states one.
    pub utc_offset_min: Option<i32>,
}

impl std::fmt::Display for StartedAt {
    /// ISO 8601: `2022-05-12T12:21:58.029`, `…+02:00` with an offset.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (y, m, d) = self.date;
        write!(f, "{y:04}-{m:02}-{d:02}")?;
        let Some((h, mi, s)) = self.time else {
            return Ok(());
        };
        let whole = s.trunc() as u32;
        write!(f, "T{h:02}:{mi:02}:{whole:02}")?;
        let ms = ((s - s.trunc()) * 1000.0).round() as u32;
        if ms > 0 {
            let text = format!("{:.3}", ms as f64 / 1000.0);
            f.write_str(text.trim_start_matches('0').trim_end_matches('0'))?;
        }
        match self.utc_offset_min {
            Some(0) => f.write_str("Z"),
            Some(o) => write!(
                f,
                "{}{:02}:{:02}",
                if o < 0 { '-' } else { '+' },
                o.abs() / 60,
                o.abs() % 60
            ),
            None => Ok(()),
        }
    }
}

/// Labels that introduce the test's start, most telling first; matched at
/// the start of a header line, case ignored.
const TEST_LABELS: &[&str] = &[
    "test started at",
    "run date",
    "test start",
    "test date",
    "date of test",
    "start date",
    "started at",
    "start time",
    "date/time",
    "datetime",
    "date and time",
    "measurement date",
    "acquisition date",
    "prüfdatum",
    "messdatum",
    "datum",
    "date",
];

/// Labels of a time of day given apart from the date (`Time: 12:21:50`).
const TIME_LABELS: &[&str] = &["start time", "time of test", "uhrzeit", "time"];

/// The header line as written, from a metadata entry (whose parse split it
/// at its first `=`, delimiter or `:`).
fn line_of(m: &MetaEntry) -> String {
    match m.value.is_empty() {
        true => m.key.clone(),
        false => format!("{}: {}", m.key, m.value),
    }
}

/// The text after `label` at the start of `line` (and a `:`, `=` or tab).
fn after_label<'a>(line: &'a str, label: &str) -> Option<&'a str> {
    let head = line.get(..label.len())?;
    if !head.eq_ignore_ascii_case(label) && head.to_lowercase() != label {
        return None;
    }
    let rest = &line[label.len()..];
    // "Date" must not match "Datenrate": the label ends at a separator.
    if !rest.is_empty() && !rest.starts_with([' ', ':', '=', '\t', ',', ';']) {
        return None;
    }
    Some(
        rest.trim_start_matches([' ', ':', '=', '\t', ',', ';'])
            .trim(),
    )
}

/// The test's start as the file states it: the first header line with a
/// test label ([`TEST_LABELS`], in that order of preference) whose text is
/// a date, with the time from the same line or a separate time line.
/// `Ok(None)` when the header states no date; an error naming the line
/// when it states one that cannot be read without a guess.
pub fn started_at(ds: &Dataset) -> Result<Option<StartedAt>> {
    let entries: Vec<&MetaEntry> = ds
        .preamble
        .iter()
        .chain(ds.sections.first().into_iter().flat_map(|s| &s.metadata))
        .collect();
    started_in(&ds.source, DayOrder::of_format(ds.format), &entries)
}

/// [`started_at`] over a file's header lines.
fn started_in(
    source: &std::path::Path,
    order: DayOrder,
    entries: &[&MetaEntry],
) -> Result<Option<StartedAt>> {
    let lines: Vec<(String, usize)> = entries.iter().map(|m| (line_of(m), m.line)).collect();
    for label in TEST_LABELS {
        for (line, number) in &lines {
            let Some(text) = after_label(line, label) else {
                continue;
            };
            let located = |e: String| Error::input(Location::line(source, *number), e);
            let Some(mut at) = parse(text, order).map_err(located)? else {
                continue;
            };
            if at.time.is_none() {
                at.time = separate_time(&lines);
            }
            return Ok(Some(at));
        }
    }
    Ok(None)
}

/// A time of day on its own header line.
fn separate_time(lines: &[(String, usize)]) -> Option<(u32, u32, f64)> {
    TIME_LABELS.iter().find_map(|label| {
        lines.iter().find_map(|(l, _)| {
            let text = after_label(l, label)?;
            text.split_whitespace().find_map(time_of)
        })
    })
}

/// Month names (English, German; three-letter forms) → 1–12.
fn month_of(word: &str) -> Option<u32> {
    const NAMES: [&[&str]; 12] = [
        &["jan", "january", "januar", "jän", "jänner"],
        &["feb", "february", "februar"],
        &["mar", "march", "märz", "maerz", "mär"],
        &["apr", "april"],
        &["may", "mai"],
        &["jun", "june", "juni"],
        &["jul", "july", "juli"],
        &["aug", "august"],
        &["sep", "sept", "september"],
        &["oct", "october", "okt", "oktober"],
        &["nov", "november"],
        &["dec", "december", "dez", "dezember"],
    ];
    let w = word.trim_end_matches('.').to_lowercase();
    NAMES
        .iter()
        .position(|names| names.contains(&w.as_str()))
        .map(|i| i as u32 + 1)
}

/// `hh:mm`, `hh:mm:ss`, `hh:mm:ss.fff`.
fn time_of(token: &str) -> Option<(u32, u32, f64)> {
    let mut parts = token.split(':');
    let h: u32 = parts.next()?.parse().ok()?;
    let m: u32 = parts.next()?.parse().ok()?;
    let s: f64 = match parts.next() {
        Some(s) if !s.is_empty() && s.chars().all(|c| c.is_ascii_digit() || c == '.') => {
            s.parse().ok()?
        }
        Some(_) => return None,
        None => 0.0,
    };
    (parts.next().is_none() && h < 24 && m < 60 && (0.0..61.0).contains(&s)).then_some((h, m, s))
}

/// `Z`, `UTC`, `GMT`, `+02:00`, `+0200`, `UTC+2`, `-05` → minutes.
fn offset_of(token: &str) -> Option<i32> {
    let t = token.trim_start_matches('(').trim_end_matches(')');
    let t = ["UTC", "GMT", "Z"]
        .iter()
        .find_map(|p| t.strip_prefix(p))
        .map_or(t, |rest| if rest.is_empty() { "+00" } else { rest });
    let sign = match t.chars().next()? {
        '+' => 1,
        '-' | '−' => -1,
        _ => return None,
    };
    let digits: String = t.chars().skip(1).filter(|c| *c != ':').collect();
    if digits.is_empty() || !digits.chars().all(|c| c.is_ascii_digit()) {
        return None;
    }
    let (h, m): (i32, i32) = match digits.len() {
        1 | 2 => (digits.parse().ok()?, 0),
        4 => (digits[..2].parse().ok()?, digits[2..].parse().ok()?),
        _ => return None,
    };
    (h <= 14 && m < 60).then_some(sign * (h * 60 + m))
}

fn days_in_month(y: i32, m: u32) -> u32 {
    match m {
        4 | 6 | 9 | 11 => 30,
        2 if (y % 4 == 0 && y % 100 != 0) || y % 400 == 0 => 29,
        2 => 28,
        _ => 31,
    }
}

/// A two-digit year is 19xx from 70, else 20xx (instrument software of
/// the 1990s onwards).
fn full_year(y: i32, digits: usize) -> i32 {
    match digits {
        2 if y >= 70 => 1900 + y,
        2 => 2000 + y,
        _ => y,
    }
}

/// A calendar date, checked.
fn checked(y: i32, m: u32, d: u32) -> std::result::Result<(i32, u32, u32), String> {
    if (1..=12).contains(&m) && d >= 1 && d <= days_in_month(y, m) && (1900..2200).contains(&y) {
        Ok((y, m, d))
    } else {
        Err(format!("{y:04}-{m:02}-{d:02} is not a calendar date"))
    }
}

/// A numeric date `a/b/c`, `a-b-c` or `a.b.c` (year first when it has four
/// digits, else last).
fn numeric_date(
    token: &str,
    order: DayOrder,
) -> std::result::Result<Option<(i32, u32, u32)>, String> {
    let sep = match token.chars().find(|c| matches!(c, '/' | '-' | '.')) {
        Some(s) => s,
        None => return Ok(None),
    };
    let parts: Vec<&str> = token.split(sep).collect();
    if parts.len() != 3
        || parts
            .iter()
            .any(|p| p.is_empty() || !p.chars().all(|c| c.is_ascii_digit()))
    {
        return Ok(None);
    }
    let n = |i: usize| parts[i].parse::<u32>().unwrap_or(0);
    if parts[0].len() == 4 {
        return checked(n(0) as i32, n(1), n(2)).map(Some);
    }
    let year = full_year(n(2) as i32, parts[2].len());
    let (a, b) = (n(0), n(1));
    // Dots are the day-first (German, European) form.
    let day_first = match (sep, order) {
        _ if a > 12 => true,
        _ if b > 12 => false,
        ('.', _) | (_, DayOrder::DayFirst) => true,
        (_, DayOrder::MonthFirst) => false,
        (_, DayOrder::Unknown) if a == b => true,
        (_, DayOrder::Unknown) => {
            return Err(format!(
                "the date '{token}' reads as day {a} of month {b} or day {b} of month {a}, and this format's order is not known; give test_started_at in the manifest (ISO 8601, for example 2022-05-12T12:21:50)"
            ))
        }
    };
    let (d, m) = if day_first { (a, b) } else { (b, a) };
    checked(year, m, d).map(Some)
}

/// Parses the text after a date label. `Ok(None)` when it holds no date.
pub fn parse(text: &str, order: DayOrder) -> std::result::Result<Option<StartedAt>, String> {
    let mut date = None;
    let mut time = None;
    let mut offset = None;
    let mut pm = None;
    let mut words: Vec<String> = Vec::new();
    let cleaned = text.replace(',', " ");
    for raw in cleaned.split_whitespace() {
        // ISO 8601 date and time in one token.
        let (d, rest) = match raw.split_once('T') {
            Some((d, r)) if d.len() == 10 && d.as_bytes()[4] == b'-' => (d, Some(r)),
            _ => (raw, None),
        };
        if let Some(r) = rest {
            let cut = r.find(['+', '-', 'Z']).unwrap_or(r.len());
            time = time_of(&r[..cut]);
            offset = offset.or_else(|| offset_of(&r[cut..]));
        }
        if let Some(dt) = numeric_date(d, order)? {
            date = Some(dt);
        } else if let Some(t) = time_of(d) {
            time = Some(t);
        } else if let Some(o) = offset_of(d).filter(|_| time.is_some()) {
            offset = Some(o);
        } else if d.eq_ignore_ascii_case("pm") || d.eq_ignore_ascii_case("am") {
            pm = Some(d.eq_ignore_ascii_case("pm"));
        } else if rest.is_none() {
            words.push(d.to_string());
        }
    }
    if date.is_none() {
        date = word_date(&words)?;
    }
    let Some(date) = date else {
        return Ok(None);
    };
    if let (Some((h, m, s)), Some(pm)) = (time, pm) {
        if !(1..=12).contains(&h) {
            return Err(format!("'{text}': hour {h} with AM/PM"));
        }
        time = Some(((h % 12) + if pm { 12 } else { 0 }, m, s));
    }
    Ok(Some(StartedAt {
        date,
        time,
        utc_offset_min: offset,
    }))
}

/// A date with a month name: `12 May 2022`, `12-May-2022`, `May 12 2022`
/// (a weekday name before it is ignored).
fn word_date(words: &[String]) -> std::result::Result<Option<(i32, u32, u32)>, String> {
    let tokens: Vec<String> = words
        .iter()
        .flat_map(|w| w.split('-').map(str::to_string).collect::<Vec<_>>())
        .filter(|w| !w.is_empty())
        .collect();
    let Some(mi) = tokens.iter().position(|w| month_of(w).is_some()) else {
        return Ok(None);
    };
    let month = month_of(&tokens[mi]).unwrap_or(0);
    let number = |i: usize| -> Option<(u32, usize)> {
        let t = tokens.get(i)?.trim_end_matches('.');
        t.chars()
            .all(|c| c.is_ascii_digit())
            .then(|| (t.parse().ok(), t.len()))
            .and_then(|(v, l)| Some((v?, l)))
    };
    let (day, year) = match (
        mi.checked_sub(1).and_then(number),
        number(mi + 1),
        number(mi + 2),
    ) {
        // 12 May 2022
        (Some((d, _)), Some((y, l)), _) => (d, full_year(y as i32, l)),
        // May 12 2022
        (_, Some((d, _)), Some((y, l))) => (d, full_year(y as i32, l)),
        _ => return Ok(None),
    };
    checked(year, month, day).map(Some)
}

#[cfg(test)]
#[path = "started_tests.rs"]
mod tests;
