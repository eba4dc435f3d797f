//! One glob over every real export of `../shared/data/real` and `real2`
//! (linked into one folder), as a lab would point tribo at a folder it was
//! sent: each file's row of `files.parquet` says what became of it, file
//! by file — processed by the stage of its kind (and in that stage's
//! table), failed with the error that names what to give, read as the
//! companion of its data file, or not taken with the reason (READMEs,
//! licences, a results table computed elsewhere) — and is in the report's
//! first table. Skips, saying so, when the shared data are absent.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use crate::common;

/// What a file must become in the run.
enum Expect {
    /// Read by `format` as `kind` and processed by `stage`.
    Processed {
        format: &'static str,
        kind: &'static str,
        stage: &'static str,
    },
    /// Read by `format`, taken by `stage`, failed with an error holding
    /// `why`.
    Failed {
        format: &'static str,
        stage: &'static str,
        why: &'static str,
    },
    /// Read with the data file `of` (a path under the data folder).
    Companion { of: &'static str },
    /// Taken by no stage, for a reason holding each of `why`.
    NotTaken { why: &'static [&'static str] },
}

use Expect::*;

const NOT_DATA: Expect = NotTaken {
    why: &["no numeric table", "no data found"],
};

/// Every file of the two folders (paths under the linked `data/`), and
/// what it must become.
const EXPECTED: &[(&str, Expect)] = &[
    // The mechanical exports of real2: processed by the tensile stage,
    // except the catman test, whose section only a manifest can give.
    (
        "real2/hbm_catman_hot_tensile/DD11_7_1.ASC",
        Failed {
            format: "hbm-catman",
            stage: "tensile",
            why: "force column but no section",
        },
    ),
    (
        "real2/instron5569_elastomer_srmd/Dragon Skin 20.csv",
        Processed {
            format: "instron-parameters",
            kind: "tensile_curve",
            stage: "tensile",
        },
    ),
    (
        "real2/rail_steel_tension_csv/exemplo1.csv",
        Processed {
            format: "delimited",
            kind: "tensile_curve",
            stage: "tensile",
        },
    ),
    (
        "real2/zwick_testxpert_and_mts793_matolab/example.csv",
        Processed {
            format: "zwick-testxpert",
            kind: "tensile_curve",
            stage: "tensile",
        },
    ),
    ("real/README.md", NOT_DATA),
    ("real/nanotensile_t150/LICENSE.txt", NOT_DATA),
    (
        "real/nanotensile_t150/B_4_IS_1.txt",
        Processed {
            format: "t150-nanosuite",
            kind: "tensile_curve",
            stage: "tensile",
        },
    ),
    ("real/profile_dektak/LICENSE.md", NOT_DATA),
    (
        "real/profile_dektak/dektak-1.csv",
        Processed {
            format: "dektak",
            kind: "profile",
            stage: "roughness",
        },
    ),
    // `"Distance","Profile"` with no unit anywhere: the `trib` R
    // package's layout, read in its units (mm, µm) with `assumed_unit`
    // (tests/roughness_cli.rs checks the numbers against units given).
    ("real/profile_pin_on_disc_track/C1.csv", TRACK),
    ("real/profile_pin_on_disc_track/C2.csv", TRACK),
    ("real/tensile_bluehill/LICENSE.txt", NOT_DATA),
    (
        "real/tensile_bluehill/Tens_No_Yield/Specimen_RawData_1.csv",
        BLUEHILL,
    ),
    (
        "real/tensile_bluehill/Tens_No_Yield/Specimen_RawData_3.csv",
        BLUEHILL,
    ),
    (
        "real/tensile_bluehill/Tens_Yield/Specimen_RawData_1.csv",
        BLUEHILL,
    ),
    (
        "real/tensile_bluehill/Tens_Yield/Specimen_RawData_3.csv",
        BLUEHILL,
    ),
    ("real/topography_nanovea/LICENSE.txt", NOT_DATA),
    ("real/topography_nanovea/test1.txt", NANOVEA),
    ("real/topography_nanovea/test2.txt", NANOVEA),
    ("real/tribometer_cetr_umt/LICENSE.txt", NOT_DATA),
    ("real/tribometer_cetr_umt/HT-2n-6-4_2_001.csv", CETR),
    ("real/tribometer_cetr_umt/HT-2n-6-4_2_002.csv", CETR),
    ("real/tribometer_cetr_umt/HT-2n-6-4_2_003.csv", CETR),
    ("real/tribometer_cetr_umt/HT-2n-6-4_2_010.csv", CETR),
    ("real/tribometer_cetr_umt/HT-2n-6-4_2_050.csv", CETR),
    ("real/tribometer_pin_on_disc_tsv/c1.csv", POD),
    ("real/tribometer_pin_on_disc_tsv/c2.csv", POD),
    ("real2/README.md", NOT_DATA),
    // The job file of test 3; the folder holds test 1's data only.
    (
        "real2/hbm_catman_hot_tensile/DD11_7_3.TSX",
        NotTaken {
            why: &["CATMAN TEST FILE", "DD11_7_3.ASC (absent)", "a companion"],
        },
    ),
    (
        "real2/pcs_mtm_ehd/demo-mtm-output.txt",
        Processed {
            format: "pcs-mtm",
            kind: "friction_trace",
            stage: "friction",
        },
    ),
    (
        "real2/rtec_rotary_saintgobain/013_FX2_316SS_0.25in_Rotary_3N_4tests_75-300mm-s_6-15mm-radius_3min-each.csv",
        Processed {
            format: "rtec",
            kind: "friction_trace",
            stage: "friction",
        },
    ),
    (
        "real2/surfacetopography_text/opdx-3.txt",
        Processed {
            format: "xz-line-scan",
            kind: "profile",
            stage: "roughness",
        },
    ),
    ("real2/surfcom_tx_profile/GrupoI_EspeI/3.tx1", SURFCOM),
    ("real2/surfcom_tx_profile/GrupoI_EspeI/3.tx2", SURFCOM),
    (
        "real2/surfcom_tx_profile/GrupoI_EspeI/3.tx3",
        Companion {
            of: "real2/surfcom_tx_profile/GrupoI_EspeI/3.tx1",
        },
    ),
    (
        "real2/surfcom_tx_profile/GrupoI_EspeI/resultados_rugosidad.csv",
        NotTaken {
            why: &[
                "a table of roughness results",
                "Ra = 3.066",
                "computed from a profile elsewhere",
            ],
        },
    ),
];

const TRACK: Expect = Processed {
    format: "profile-csv",
    kind: "profile",
    stage: "roughness",
};
const BLUEHILL: Expect = Processed {
    format: "instron-bluehill",
    kind: "tensile_curve",
    stage: "tensile",
};
const NANOVEA: Expect = Processed {
    format: "nanovea",
    kind: "areal_map",
    stage: "roughness",
};
const CETR: Expect = Processed {
    format: "cetr-umt",
    kind: "friction_trace",
    stage: "friction",
};
const POD: Expect = Processed {
    format: "csm-pin-on-disc",
    kind: "friction_trace",
    stage: "friction",
};
const SURFCOM: Expect = Processed {
    format: "surfcom-tx",
    kind: "profile",
    stage: "roughness",
};

/// Every file under `dir` (following links), as paths relative to `base`.
fn walk(dir: &Path, base: &Path, out: &mut BTreeSet<String>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p: PathBuf = e.unwrap().path();
        if p.is_dir() {
            walk(&p, base, out);
        } else {
            let rel = p.strip_prefix(base).unwrap();
            out.insert(rel.to_string_lossy().replace('\\', "/"));
        }
    }
}

#[test]
fn one_glob_over_every_real_export_accounts_for_each_file() {
    let (Some(real), Some(real2)) = (common::shared_real(""), common::shared_real2("")) else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    std::fs::create_dir(&data).unwrap();
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(&real, data.join("real")).unwrap();
        std::os::unix::fs::symlink(&real2, data.join("real2")).unwrap();
    }
    #[cfg(not(unix))]
    {
        common::copy_tree(&real, &data.join("real"));
        common::copy_tree(&real2, &data.join("real2"));
    }
    let toml = "stages = [\"friction\", \"tensile\", \"roughness\"]\n[input]\n\
                files = [\"data/**/*\"]\n[output]\ndir = \"out\"\n";
    std::fs::write(dir.path().join("p.toml"), toml).unwrap();
    let plan = tribo::pipeline::Plan::from_file(&dir.path().join("p.toml")).unwrap();
    let report = tribo::pipeline::run(&plan, "test", &|| {}).unwrap();
    let out = dir.path().join("out");
    let rows = common::files_table(&out);

    // Every file on disk is one row, and has an expectation.
    let mut on_disk = BTreeSet::new();
    walk(&data, &data, &mut on_disk);
    let rel = |source: &str| -> String {
        Path::new(source)
            .strip_prefix(&data)
            .unwrap_or_else(|_| panic!("{source} is not under the data folder"))
            .to_string_lossy()
            .replace('\\', "/")
    };
    let in_table: BTreeSet<String> = rows.keys().map(|s| rel(s)).collect();
    assert_eq!(in_table, on_disk, "files.parquet lists every file once");
    let expected: BTreeSet<String> = EXPECTED.iter().map(|(p, _)| p.to_string()).collect();
    assert_eq!(
        on_disk, expected,
        "the shared data changed: give each new file its expected outcome"
    );

    // The report's first table has every input too.
    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    let first = &html[..html.find("</table>").unwrap()];
    for source in rows.keys() {
        let shown = tribo::plot::escape(source);
        assert!(
            first.contains(&shown),
            "{source} not in the report's first table"
        );
    }
    // The run read each file's figures from its cache part; `tribo report`
    // reads the published figure tables whole: the same report.
    tribo::pipeline::report::rewrite(&out, std::time::Duration::ZERO).unwrap();
    let again = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert!(html.matches("<svg").count() > 100, "the files' figures");
    assert_eq!(again, html, "the report tribo report makes again");

    let tables = |t: &str| common::sources(&out, t);
    let name_of = |p: &str| {
        Path::new(p)
            .file_name()
            .unwrap()
            .to_string_lossy()
            .to_string()
    };
    for (source, row) in &rows {
        let path = rel(source);
        let size = std::fs::metadata(source).unwrap().len().to_string();
        assert_eq!(row["size_bytes"], size, "{path}");
        let (_, want) = EXPECTED.iter().find(|(p, _)| *p == path).unwrap();
        let what = format!("{path}: {row:?}");
        match want {
            Processed {
                format,
                kind,
                stage,
            } => {
                assert_eq!(row["outcome"], "processed", "{what}");
                assert_eq!(
                    (row["format"].as_str(), row["kind"].as_str()),
                    (*format, *kind),
                    "{what}"
                );
                assert_eq!(row["stages"], *stage, "{what}");
                assert_eq!(row["reason"], "", "{what}");
                assert!(tables(stage).contains(&name_of(&path)), "{what}");
            }
            Failed { format, stage, why } => {
                assert_eq!(row["outcome"], "failed", "{what}");
                assert_eq!(row["format"], *format, "{what}");
                assert_eq!(row["stages"], *stage, "{what}");
                assert!(row["reason"].contains(why), "{what}");
                assert!(row["reason"].contains(source.as_str()), "{what}");
            }
            Companion { of } => {
                assert_eq!(row["outcome"], "companion", "{what}");
                assert_eq!(rel(&row["companion_of"]), *of, "{what}");
                assert_eq!(row["stages"], "", "{what}");
            }
            NotTaken { why } => {
                assert_eq!(row["outcome"], "not_taken", "{what}");
                assert_eq!(row["stages"], "", "{what}");
                for w in *why {
                    assert!(row["reason"].contains(w), "{w:?} not in {what}");
                }
                // The reason is the run's own, and names the file.
                let (_, said) = report.unrouted.iter().find(|(f, _)| f == source).unwrap();
                assert_eq!(&row["reason"], said, "{what}");
                assert!(said.contains(source.as_str()), "{what}");
            }
        }
    }
}
