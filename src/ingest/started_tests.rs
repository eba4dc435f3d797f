//! Tests of [`super`]: dates and times as real headers write them.

use super::*;

fn iso(text: &str, order: DayOrder) -> String {
    parse(text, order).unwrap().unwrap().to_string()
}

/// The forms real headers use, each read to the date and time it
/// states.
#[test]
fn header_dates_read_as_written() {
    let u = DayOrder::Unknown;
    assert_eq!(iso("12 May 2022 12:21:50", u), "2022-05-12T12:21:50");
    assert_eq!(
        iso("12:21:58.029 12 May 2022", u),
        "2022-05-12T12:21:58.029"
    );
    assert_eq!(iso("23/03/2018 10:02:57", u), "2018-03-23T10:02:57");
    assert_eq!(
        iso("2022-05-12T12:21:50+02:00", u),
        "2022-05-12T12:21:50+02:00"
    );
    assert_eq!(iso("2022-05-12T12:21:50Z", u), "2022-05-12T12:21:50Z");
    assert_eq!(
        iso("2022-05-12 07:01 -0500", u),
        "2022-05-12T07:01:00-05:00"
    );
    assert_eq!(iso("12.05.2022", u), "2022-05-12");
    assert_eq!(
        iso("Thursday, May 12, 2022 1:05:09 PM", u),
        "2022-05-12T13:05:09"
    );
    assert_eq!(iso("12-May-22 12:00 AM", u), "2022-05-12T00:00:00");
    assert_eq!(
        iso("3. März 2021 08:15 UTC+1", u),
        "2021-03-03T08:15:00+01:00"
    );
    assert_eq!(
        iso("05/12/22 14:43:46", DayOrder::MonthFirst),
        "2022-05-12T14:43:46"
    );
    assert_eq!(iso("05/12/22", DayOrder::DayFirst), "2022-12-05");
    assert_eq!(iso("2020-02-29", u), "2020-02-29");
}

/// What is not a date, or not one without a guess, says so.
#[test]
fn doubtful_dates_are_refused() {
    let u = DayOrder::Unknown;
    let e = parse("05/12/2022", u).unwrap_err();
    assert!(e.contains("day 5 of month 12 or day 12 of month 5"), "{e}");
    assert!(parse("2021-02-29", u)
        .unwrap_err()
        .contains("not a calendar date"));
    assert!(parse("31/04/2021", u)
        .unwrap_err()
        .contains("not a calendar date"));
    assert_eq!(parse("1 h 20 min", u).unwrap(), None);
    assert_eq!(parse("", u).unwrap(), None);
    assert!(parse("12 May 2022 13:00 PM", u).is_err());
}

fn meta(key: &str, value: &str, line: usize) -> MetaEntry {
    MetaEntry {
        key: key.into(),
        value: value.into(),
        line,
    }
}

fn started(format: &'static str, preamble: Vec<MetaEntry>) -> Result<Option<StartedAt>> {
    let entries: Vec<&MetaEntry> = preamble.iter().collect();
    started_in(
        std::path::Path::new("x.csv"),
        DayOrder::of_format(format),
        &entries,
    )
}

/// The run date is preferred to a step's start; a date line without a
/// time takes the time line's; an ambiguous date names its line.
#[test]
fn the_test_label_is_chosen_and_a_time_line_joined() {
    let cetr = started(
        "cetr-umt",
        vec![
            meta(
                "Created by CETR Data Viewer ver.2.19.106 05/12/22 14:43:46",
                "",
                1,
            ),
            meta("Started at", "12:21:58.029 12 May 2022", 20),
            meta("Run date 12 May 2022 12:21:50", "", 10),
        ],
    );
    assert_eq!(cetr.unwrap().unwrap().to_string(), "2022-05-12T12:21:50");
    let german = started(
        "delimited",
        vec![
            meta("Datum", "12.05.2022", 2),
            meta("Uhrzeit", "08:30:00", 3),
        ],
    );
    assert_eq!(german.unwrap().unwrap().to_string(), "2022-05-12T08:30:00");
    let doubtful = started("delimited", vec![meta("Date", "05/06/2022", 7)]);
    let e = doubtful.unwrap_err().to_string();
    assert!(e.contains("line 7") && e.contains("test_started_at"), "{e}");
    let none = started("delimited", vec![meta("Data rate", "50 Hz", 1)]);
    assert_eq!(none.unwrap(), None);
}
