//! One test exported as several files (MODELS.md §11; docs/friction.md,
//! "Tests as series"), as CETR's linear-wear module writes one file per
//! block of cycles. The files the manifest gives one `test_id` are the
//! members of one test:
//!
//! - **order**: by when each member started (`test_started_at`, from the
//!   manifest or the file's header) when every member states it, else by
//!   the file name in natural order (runs of digits compared as numbers:
//!   `run_2` before `run_10`);
//! - **cycles** numbered on through the members and sliding distances
//!   carried on from each member's last cycle, as the sections of one
//!   file are ([`super::assess::number_cycles`]);
//! - **one running-in and one steady state** over all the members' whole
//!   cycles ([`super::assess`]'s row of a run of cycles), scope `series`.
//!
//! Members whose names end in numbers that skip (exports 001, 002, 010)
//! leave the cycles between them out: the numbering and the distance count
//! only the files present, and the row says `series_gap`.

use super::assess::{row_of, Scope, TestRow};
use super::cycles::{CycleKind, CycleRow};
use super::running_in::SteadyParams;
use crate::status::{Code, Status};

/// One file of a series: its name, start and cycles (numbered within the
/// file, distances from the file's start).
#[derive(Debug, Clone)]
pub struct Member {
    /// The path as given.
    pub source: String,
    /// When the member started (ISO 8601), if stated.
    pub started_at: Option<String>,
    /// Its cycles, in order.
    pub cycles: Vec<CycleRow>,
}

impl CycleRow {
    /// A cycle as the `friction_cycles` table holds what a series needs
    /// of it (the rest left empty).
    #[allow(clippy::too_many_arguments)]
    pub fn summary(
        cycle: usize,
        kind: CycleKind,
        distance_m: Option<(f64, f64)>,
        mu: Option<f64>,
        complete: bool,
        energy_j: Option<f64>,
        normal_force_n: Option<f64>,
        wear_depth_m: Option<f64>,
    ) -> CycleRow {
        CycleRow {
            section: String::new(),
            kind,
            cycle,
            stroke: None,
            lap: None,
            direction_sign: 1.0,
            start_s: 0.0,
            end_s: 0.0,
            distance_m,
            window_s: None,
            n_window: 0,
            mu,
            mu_sd: None,
            mu_peak: None,
            normal_force_n,
            mu_instrument: None,
            energy_j,
            loop_area_j: None,
            wear_depth_m,
            complete,
            extent: 0.0,
            at_edge: false,
            status: Status::ok(),
        }
    }
}

/// A name's sort key: digit runs as numbers, the rest as text.
fn natural_key(name: &str) -> Vec<(u8, u128, String)> {
    let mut key = Vec::new();
    let mut rest = name;
    while let Some(c) = rest.chars().next() {
        let digits = c.is_ascii_digit();
        let end = rest
            .find(|ch: char| ch.is_ascii_digit() != digits)
            .unwrap_or(rest.len());
        let (run, tail) = rest.split_at(end);
        key.push(match digits {
            true => (0, run.parse().unwrap_or(u128::MAX), String::new()),
            false => (1, 0, run.to_string()),
        });
        rest = tail;
    }
    key
}

/// The file name of a path (either separator).
fn file_name(source: &str) -> &str {
    source.rsplit(['/', '\\']).next().unwrap_or(source)
}

/// The number a file name ends with before its extension (`_050.csv`: 50).
fn trailing_number(source: &str) -> Option<u64> {
    let name = file_name(source);
    let stem = name.rsplit_once('.').map_or(name, |(s, _)| s);
    let digits: String = stem
        .chars()
        .rev()
        .take_while(char::is_ascii_digit)
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .collect();
    digits.parse().ok()
}

/// Orders the members (see the module documentation); says which rule.
pub fn order(members: &mut [Member]) -> &'static str {
    if members.iter().all(|m| m.started_at.is_some()) {
        // ISO 8601 of one instrument sorts as text; ties by name.
        members.sort_by(|a, b| {
            (&a.started_at, natural_key(file_name(&a.source)))
                .cmp(&(&b.started_at, natural_key(file_name(&b.source))))
        });
        "test_started_at"
    } else {
        members.sort_by_key(|m| natural_key(file_name(&m.source)));
        "file_name"
    }
}

/// The numbers missing between consecutive members' trailing numbers, as
/// ranges (`4-9`), when every member's name ends in one.
fn gaps(members: &[Member]) -> Vec<String> {
    let numbers: Option<Vec<u64>> = members.iter().map(|m| trailing_number(&m.source)).collect();
    let Some(numbers) = numbers else {
        return Vec::new();
    };
    numbers
        .windows(2)
        .filter(|w| w[1] > w[0] + 1)
        .map(|w| match w[1] - w[0] {
            2 => format!("{}", w[0] + 1),
            _ => format!("{}-{}", w[0] + 1, w[1] - 1),
        })
        .collect()
}

/// Numbers the ordered members' cycles on through the series (in place)
/// and returns the series' `friction_tests` row.
pub fn join(members: &mut [Member], p: &SteadyParams) -> TestRow {
    let (mut next, mut carried) = (1, 0.0);
    for m in members.iter_mut() {
        let mut end = carried;
        for c in m.cycles.iter_mut() {
            c.cycle = next;
            next += 1;
            if let Some((a, b)) = c.distance_m {
                c.distance_m = Some((a + carried, b + carried));
                end = b + carried;
            }
        }
        carried = end;
    }
    let all: Vec<&CycleRow> = members.iter().flat_map(|m| &m.cycles).collect();
    let mut row = row_of(&all, p);
    row.scope = Scope::Series;
    let missing = gaps(members);
    if !missing.is_empty() {
        let mut s = Status::of(
            Code::SeriesGap,
            format!(
                "the members' numbers skip {}: those files are absent, so the series' cycles and \
                 sliding distance count only the {} files present",
                missing.join(", "),
                members.len()
            ),
        );
        s.extend(std::mem::take(&mut row.status));
        row.status = s;
    }
    row
}

#[cfg(test)]
mod tests {
    use super::*;

    fn member(source: &str, started: Option<&str>, mu: &[f64]) -> Member {
        let cycles = mu
            .iter()
            .enumerate()
            .map(|(i, &m)| {
                let d = Some((i as f64 * 0.01, (i + 1) as f64 * 0.01));
                CycleRow::summary(i + 1, CycleKind::Stroke, d, Some(m), true, None, None, None)
            })
            .collect();
        Member {
            source: source.into(),
            started_at: started.map(str::to_string),
            cycles,
        }
    }

    #[test]
    fn members_sort_by_start_else_by_natural_name() {
        let mut m = vec![
            member("d/t_10.csv", None, &[0.1]),
            member("d/t_2.csv", None, &[0.1]),
            member("d/t_1.csv", None, &[0.1]),
        ];
        assert_eq!(order(&mut m), "file_name");
        let names: Vec<&str> = m.iter().map(|m| m.source.as_str()).collect();
        assert_eq!(names, ["d/t_1.csv", "d/t_2.csv", "d/t_10.csv"]);
        let mut m = vec![
            member("a_1.csv", Some("2022-05-12T12:22:02"), &[0.1]),
            member("a_2.csv", Some("2022-05-12T12:21:50"), &[0.1]),
        ];
        assert_eq!(order(&mut m), "test_started_at");
        assert_eq!(m[0].source, "a_2.csv");
    }

    /// Three files of 10 strokes of 10 mm: cycles 1..30, the distance
    /// carried on to 0.3 m; μ decaying over the first file then flat: one
    /// running-in for the series, and its steady μ the plateau's.
    #[test]
    fn a_series_is_numbered_on_and_settles_once() {
        let decay: Vec<f64> = (0..10)
            .map(|k| 0.2 + 0.3 * (-(k as f64) / 2.0).exp())
            .collect();
        let mut m = vec![
            member("x/run_3.csv", None, &[0.2; 10]),
            member("x/run_1.csv", None, &decay),
            member("x/run_2.csv", None, &[0.2; 10]),
        ];
        order(&mut m);
        let p = SteadyParams::default();
        let row = join(&mut m, &p);
        assert_eq!(row.scope, Scope::Series);
        assert_eq!((row.n_cycles, row.cycles), (30, Some((1, 30))));
        let last = m[2].cycles.last().unwrap();
        assert_eq!(last.cycle, 30);
        let (a, b) = last.distance_m.unwrap();
        assert!((a - 0.29).abs() < 1e-12 && (b - 0.3).abs() < 1e-12);
        assert!((row.distance_m.unwrap() - 0.3).abs() < 1e-12);
        assert!((row.steady.mu.unwrap() - 0.2).abs() < 1e-3, "{row:?}");
        let onset = row.steady_from_cycle.unwrap();
        assert!((2..=12).contains(&onset), "onset {onset}");
        assert!(!row.status.to_string().contains("series_gap"));
    }

    #[test]
    fn skipped_exports_are_said() {
        let mut m = vec![
            member("HT_001.csv", None, &[0.2; 4]),
            member("HT_002.csv", None, &[0.2; 4]),
            member("HT_010.csv", None, &[0.2; 4]),
            member("HT_050.csv", None, &[0.2; 4]),
        ];
        order(&mut m);
        let row = join(&mut m, &SteadyParams::default());
        let s = row.status.to_string();
        assert!(
            s.starts_with("series_gap") && s.contains("3-9, 11-49"),
            "{s}"
        );
        assert_eq!(trailing_number("a/b_007.csv"), Some(7));
        assert_eq!(trailing_number("a/b.csv"), None);
    }
}
