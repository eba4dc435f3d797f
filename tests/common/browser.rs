//! Headless Chromium for the report's browser tests: Debian's, or the one
//! `TRIBO_CHROMIUM` names; a test without it says so and skips.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The browser, or `None` after saying on stderr why the test skips.
pub fn chromium() -> Option<PathBuf> {
    let given = std::env::var_os("TRIBO_CHROMIUM").map(PathBuf::from);
    let found = given
        .into_iter()
        .chain(["/usr/bin/chromium", "/usr/bin/chromium-browser"].map(PathBuf::from))
        .find(|p| p.exists());
    if found.is_none() {
        eprintln!(
            "skipped: headless Chromium not found (install it with scripts/install-chromium.sh, \
             or set TRIBO_CHROMIUM); the report was not checked in a browser"
        );
    }
    found
}

/// Runs the browser headless on `page` with `args`.
pub fn headless(browser: &Path, args: &[&str], page: &Path) -> std::process::Output {
    Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
        ])
        .args(args)
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("run chromium")
}
