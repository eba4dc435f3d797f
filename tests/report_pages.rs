//! A report over more files than one page holds: the first page keeps the
//! overview and the models, the files' sections go to `report/` pages,
//! every link from the overview reaches its section, a rerun keeps the
//! pages, `tribo report` redoes them, and a folder small again has one page.

use std::path::Path;

use crate::common::tribo;

/// More files than a page holds (`tribo::report::FILES_PER_PAGE`).
const FILES: usize = tribo::report::FILES_PER_PAGE + 5;

/// A short stepped-free friction trace: a static peak, then a plateau.
fn trace(i: usize) -> String {
    let mut s = String::from("t (s),Fx [mN],Fz [mN]\n");
    for k in 0..300 {
        let t = k as f64 * 1e-2;
        let f = if t < 1.0 {
            1200.0 * t
        } else {
            1000.0 + (i % 7) as f64
        };
        s.push_str(&format!("{t:.3},{f:.3},2000\n"));
    }
    s
}

fn lab() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let traces = dir.path().join("traces");
    std::fs::create_dir(&traces).unwrap();
    for i in 0..FILES {
        std::fs::write(traces.join(format!("t{i:04}.csv")), trace(i)).unwrap();
    }
    let p =
        "stages = [\"friction\"]\n[input]\nfiles = [\"traces/*.csv\"]\n[output]\ndir = \"out\"\n";
    std::fs::write(dir.path().join("p.toml"), p).unwrap();
    dir
}

/// [`lab`] after a first run, with its output folder.
fn ran() -> (tempfile::TempDir, std::path::PathBuf) {
    let lab = lab();
    run(lab.path(), &["run", "p.toml"]);
    let out = lab.path().join("out");
    (lab, out)
}

fn run(dir: &Path, args: &[&str]) {
    let o = tribo(dir, args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
}

/// The pages' names and HTML, in name order.
fn pages(out: &Path) -> Vec<(String, String)> {
    let mut v: Vec<(String, String)> = match std::fs::read_dir(out.join("report")) {
        Ok(d) => d
            .flatten()
            .map(|e| {
                let html = std::fs::read_to_string(e.path()).unwrap();
                (e.file_name().to_string_lossy().to_string(), html)
            })
            .collect(),
        Err(_) => Vec::new(),
    };
    v.sort();
    v
}

/// Every file link of the first page: (page, anchor).
fn links(index: &str) -> Vec<(String, String)> {
    index
        .split("<a href=\"")
        .skip(1)
        .filter_map(|s| s.split('"').next())
        .filter(|h| h.contains("#file-"))
        .map(|h| {
            let (page, anchor) = h.split_once('#').unwrap();
            (page.to_string(), anchor.to_string())
        })
        .collect()
}

#[test]
fn a_report_over_many_files_is_split_into_pages_whose_links_hold() {
    let (lab, out) = ran();
    let index = std::fs::read_to_string(out.join("report.html")).unwrap();
    let split = pages(&out);
    let names: Vec<&str> = split.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["files-0001.html", "files-0002.html"]);
    assert!(
        !index.contains("<section id=\"file-"),
        "sections left on the first page"
    );
    // Each file is linked once, to the one page that has its section.
    let links = links(&index);
    assert_eq!(links.len(), FILES);
    for (page, anchor) in &links {
        let name = page.strip_prefix("report/").expect(page);
        let holding: Vec<&str> = split
            .iter()
            .filter(|(_, html)| html.contains(&format!("<section id=\"{anchor}\">")))
            .map(|(n, _)| n.as_str())
            .collect();
        assert_eq!(holding, [name], "{anchor}");
    }
    let sections: usize = split
        .iter()
        .map(|(_, h)| h.matches("<section id=\"file-").count())
        .sum();
    assert_eq!(sections, FILES);
    // Each page leads back, and to its neighbours; each has its figures.
    let (first, second) = (&split[0].1, &split[1].1);
    assert!(
        first.contains("href=\"../report.html#files\"")
            && first.contains("href=\"files-0002.html\"")
    );
    assert!(second.contains("href=\"files-0001.html\"") && !second.contains("next page"));
    assert!(first.contains("<svg") && second.contains("<svg"));
    assert!(second.contains("<p>Page 2: "));

    // An unchanged rerun keeps the pages as they are; `tribo report` makes
    // the same pages again.
    run(lab.path(), &["run", "p.toml"]);
    assert_eq!(pages(&out), split);
    run(lab.path(), &["report", "out"]);
    assert_eq!(pages(&out), split);
    assert_eq!(
        std::fs::read_to_string(out.join("report.html")).unwrap(),
        index
    );
    // A page removed by hand: the next run renders the report again, never
    // keeping a first page that links to nothing (the run before it
    // records the report `tribo report` rewrote).
    run(lab.path(), &["run", "p.toml"]);
    std::fs::remove_file(out.join("report/files-0002.html")).unwrap();
    run(lab.path(), &["run", "p.toml"]);
    assert_eq!(pages(&out), split);

    // Fewer files than a page holds: one page again, and no pages left.
    for i in 0..10 {
        std::fs::remove_file(lab.path().join(format!("traces/t{i:04}.csv"))).unwrap();
    }
    run(lab.path(), &["run", "p.toml"]);
    assert!(pages(&out).is_empty());
    assert!(!out.join("report").exists());
    let index = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert_eq!(index.matches("<section id=\"file-").count(), FILES - 10);
}

/// A report rendered again when one file is added writes only the pages
/// that change: the others are the last set's files (the same inode), and
/// every page is the one a fresh run renders.
#[test]
fn pages_that_come_out_the_same_are_linked_not_written_again() {
    use std::os::unix::fs::MetadataExt;
    let (lab, out) = ran();
    let ino = |name: &str| {
        let page = out.join("report").join(name);
        std::fs::metadata(page).unwrap().ino()
    };
    let (first, second) = (ino("files-0001.html"), ino("files-0002.html"));
    // The added file sorts last: its section goes on the second page.
    let added = format!("traces/t{FILES:04}.csv");
    std::fs::write(lab.path().join(&added), trace(FILES)).unwrap();
    run(lab.path(), &["run", "p.toml"]);
    assert_eq!(ino("files-0001.html"), first);
    assert_ne!(ino("files-0002.html"), second);
    assert!(pages(&out)[1].1.contains(&added));

    let fresh = lab_with_one_more();
    run(fresh.path(), &["run", "p.toml"]);
    assert_eq!(pages(&out), pages(&fresh.path().join("out")));
}

/// The figures of a page whose outline is unchanged are not read: with
/// the figure file of a file on the first page overwritten with zeros
/// (in place: the cache still takes it for its part), a run that adds a
/// file to the second page succeeds and keeps the first page. A page
/// edited by hand is rendered again.
#[test]
fn a_page_that_did_not_change_is_neither_rendered_nor_read() {
    use std::io::Write as _;
    let (lab, out) = ran();
    let before = pages(&out);
    // t0000's figures: the dataset's `t0000-<key>.parquet`, the cache's
    // part under another name.
    let names = crate::common::files_with_ext(&out.join("friction_figures"), "parquet");
    let mine = names
        .into_iter()
        .find(|p| {
            p.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with("t0000-")
        })
        .expect("t0000's figure file");
    let bytes = std::fs::read(&mine).unwrap();
    let overwrite = |with: &[u8]| {
        let mut f = std::fs::OpenOptions::new().write(true).open(&mine).unwrap();
        f.write_all(with).unwrap();
    };
    overwrite(&vec![0; bytes.len()]);

    let added = format!("traces/t{FILES:04}.csv");
    std::fs::write(lab.path().join(&added), trace(FILES)).unwrap();
    run(lab.path(), &["run", "p.toml"]);
    let after = pages(&out);
    assert_eq!(after[0], before[0]);
    assert!(after[1].1.contains(&added) && !before[1].1.contains(&added));

    // A page changed by hand is made again, and is the page it was; the
    // edit keeps its length, so only the file's time tells it apart.
    overwrite(&bytes);
    let first = out.join("report/files-0001.html");
    assert!(after[0].1.contains("Page 1:"), "{}", after[0].1);
    let edited = after[0].1.replacen("Page 1:", "Page I:", 1);
    assert_eq!(edited.len(), after[0].1.len());
    std::fs::remove_file(&first).unwrap();
    std::fs::write(&first, edited).unwrap();
    std::fs::write(lab.path().join("traces/t9999.csv"), trace(3)).unwrap();
    run(lab.path(), &["run", "p.toml"]);
    assert_eq!(pages(&out)[0], before[0]);
}

/// [`lab`] with one file more, sorting last.
fn lab_with_one_more() -> tempfile::TempDir {
    let dir = lab();
    let added = dir.path().join(format!("traces/t{FILES:04}.csv"));
    std::fs::write(added, trace(FILES)).unwrap();
    dir
}

/// An output folder copied with its links followed has the pages as a
/// folder of copies: the next run replaces it with the set's link.
#[test]
fn a_copied_folder_of_pages_is_replaced_by_the_link() {
    let (lab, out) = ran();
    let split = pages(&out);
    let copy = lab.path().join("copy");
    let o = std::process::Command::new("cp")
        .args(["-rL", "out", "copy"])
        .current_dir(lab.path())
        .output()
        .unwrap();
    assert!(o.status.success());
    assert!(
        std::fs::read_link(copy.join("report")).is_err(),
        "copied as a folder"
    );
    // A trace added: the report is made again, into the copied folder.
    std::fs::write(lab.path().join("traces/t9999.csv"), trace(3)).unwrap();
    run(lab.path(), &["run", "p.toml", "--out", "copy"]);
    assert!(
        std::fs::read_link(copy.join("report")).is_ok(),
        "a link again"
    );
    let again = pages(&copy);
    assert_eq!(again.len(), split.len());
    assert!(again[1].1.contains("t9999.csv"));
}

/// A folder of the user's where the pages' link goes is never removed:
/// the run stops, naming it, and the folder keeps its files.
#[test]
fn a_folder_of_another_in_the_pages_place_stops_the_run() {
    let (lab, out) = ran();
    let pages = out.join("report");
    std::fs::remove_file(&pages).unwrap();
    std::fs::create_dir(&pages).unwrap();
    std::fs::write(pages.join("notes.txt"), "mine").unwrap();
    let o = tribo(lab.path(), &["run", "p.toml"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_ne!(o.status.code(), Some(0), "{err}");
    assert!(
        err.contains("out/report") && err.contains("did not write"),
        "{err}"
    );
    assert!(pages.join("notes.txt").exists());
}
