//! The samples manifest of the Coulomb fits: per sample, its apparent
//! area, pattern and area fraction, where the friction table has none.

use std::collections::BTreeMap;
use std::path::Path;

use crate::error::{Error, Result};
use crate::ingest::manifest::Manifest;

/// Per-sample facts from a samples manifest.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SampleInfo {
    /// A_th, m².
    pub apparent_area_m2: Option<f64>,
    /// Pattern name (`F` for flat, `A`, `B`, ...).
    pub pattern: Option<String>,
    /// AF = 1 − A_holes / A_th.
    pub area_fraction: Option<f64>,
}

/// Reads a samples manifest CSV (header line; comma-separated; `sample_id`
/// required; `apparent_area_m2`, `pattern`, `area_fraction` used when
/// present, other columns ignored).
pub fn read_samples_csv(path: &Path) -> Result<BTreeMap<String, SampleInfo>> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    samples_of(path, &bytes)
}

/// [`read_samples_csv`] of a file already in memory.
pub fn samples_of(path: &Path, bytes: &[u8]) -> Result<BTreeMap<String, SampleInfo>> {
    let m = Manifest::keyed_from_bytes(path, bytes, "sample_id")?;
    m.rows
        .iter()
        .map(|row| {
            let info = SampleInfo {
                apparent_area_m2: m.f64(row, "apparent_area_m2")?,
                pattern: row.fields.get("pattern").cloned(),
                area_fraction: m.f64(row, "area_fraction")?,
            };
            Ok((row.key.clone(), info))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_table_is_read_by_sample_id_with_typed_columns() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("samples.csv");
        std::fs::write(
            &p,
            "sample_id;pattern;apparent_area_m2;area_fraction;note\n\
             F1;F;4e-4;;flat\nB2;B;4e-4;0.56;\n",
        )
        .unwrap();
        let s = read_samples_csv(&p).unwrap();
        assert_eq!(s.len(), 2);
        assert_eq!(s["F1"].pattern.as_deref(), Some("F"));
        assert_eq!(s["F1"].area_fraction, None);
        assert_eq!(s["B2"].area_fraction, Some(0.56));
        assert_eq!(s["B2"].apparent_area_m2, Some(4e-4));
        std::fs::write(&p, "sample_id,apparent_area_m2\nF1,big\n").unwrap();
        let e = read_samples_csv(&p).unwrap_err().to_string();
        assert!(
            e.contains("line 2") && e.contains("apparent_area_m2") && e.contains("big"),
            "{e}"
        );
        std::fs::write(&p, "id,apparent_area_m2\nF1,1\n").unwrap();
        let e = read_samples_csv(&p).unwrap_err().to_string();
        assert!(e.contains("'sample_id'"), "{e}");
    }
}
