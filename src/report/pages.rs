//! A report over many files, split into pages: the first (`report.html`)
//! holds the overview of every input and the models; the files' sections
//! are on pages of [`FILES_PER_PAGE`] each (`report/files-0001.html`, …).
//! One page with every section of a large archive is more than a browser
//! opens (648 MB of HTML for 20 000 friction traces with their figures)
//! and was rendered as one string.

use std::collections::HashMap;

/// File sections on one page; the report of a folder with more has them
/// split over pages of this many (a page of friction traces with their
/// figures is then about 6 MB).
pub const FILES_PER_PAGE: usize = 200;

/// The folder of the pages, beside `report.html`.
pub const PAGES_DIR: &str = "report";

/// Where each file's section is: on the first page (no pages), or on one
/// of the pages, in input order.
pub(super) struct Split {
    /// The files with a section, in input order.
    files: Vec<String>,
    /// Each file's place in `files`.
    at: HashMap<String, usize>,
    /// Files a page; 0: all on the first page.
    per_page: usize,
}

impl Split {
    /// `files` (those with a section, in input order) split when more than
    /// `per_page` (at least 1).
    pub fn of(files: Vec<String>, per_page: usize) -> Split {
        let per_page = per_page.max(1);
        let at = files
            .iter()
            .enumerate()
            .map(|(i, f)| (f.clone(), i))
            .collect();
        let per_page = if files.len() > per_page { per_page } else { 0 };
        Split {
            files,
            at,
            per_page,
        }
    }

    /// The number of pages of sections (0: they are on the first page).
    pub fn count(&self) -> usize {
        match self.per_page {
            0 => 0,
            n => self.files.len().div_ceil(n),
        }
    }

    /// The files on the first page (all, or none when split).
    pub fn on_first(&self) -> &[String] {
        match self.per_page {
            0 => &self.files,
            _ => &[],
        }
    }

    /// The files of the `i`-th page.
    pub fn page(&self, i: usize) -> &[String] {
        let n = self.per_page;
        let start = (i * n).min(self.files.len());
        &self.files[start..(start + n).min(self.files.len())]
    }

    /// The link to a file's section from the first page, if it has one.
    pub fn link(&self, file: &str) -> Option<String> {
        let at = *self.at.get(file)?;
        match self.per_page {
            0 => Some(format!("#{}", anchor(file))),
            n => Some(format!("{PAGES_DIR}/{}#{}", name(at / n), anchor(file))),
        }
    }
}

/// The anchor of a file's section.
pub(super) fn anchor(source: &str) -> String {
    let slug: String = source
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect();
    format!("file-{slug}")
}

/// The name of the `i`-th page of file sections.
pub(super) fn name(i: usize) -> String {
    format!("files-{:04}.html", i + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn files(n: usize) -> Vec<String> {
        (0..n).map(|i| format!("traces/t{i}.csv")).collect()
    }

    #[test]
    fn sections_stay_on_the_first_page_up_to_the_limit() {
        let split = Split::of(files(3), 3);
        assert_eq!(split.count(), 0);
        assert_eq!(split.on_first().len(), 3);
        assert_eq!(
            split.link("traces/t2.csv").as_deref(),
            Some("#file-traces-t2-csv")
        );
        assert_eq!(split.link("traces/t9.csv"), None);
    }

    #[test]
    fn more_sections_are_split_in_input_order() {
        let split = Split::of(files(7), 3);
        assert_eq!(split.count(), 3);
        assert!(split.on_first().is_empty());
        let sizes: Vec<usize> = (0..3).map(|i| split.page(i).len()).collect();
        assert_eq!(sizes, [3, 3, 1]);
        assert_eq!(split.page(1)[0], "traces/t3.csv");
        let link = split.link("traces/t6.csv");
        assert_eq!(
            link.as_deref(),
            Some("report/files-0003.html#file-traces-t6-csv")
        );
        // A limit of 0 is taken as 1, never a division by zero.
        assert_eq!(Split::of(files(7), 0).count(), 7);
    }
}
