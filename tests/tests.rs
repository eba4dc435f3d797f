//! One integration-test binary (as ripgrep and nalgebra do): every extra
//! test binary links polars again. Each file in `tests/` is a module here;
//! `every_test_file_is_a_module` fails when one is left out.

mod alsfm_2d_sampling;
mod alsfm_closed_form;
mod alsfm_contact_map;
mod alsfm_effects;
mod alsfm_figures;
mod alsfm_scene;
mod alsfm_stability;
mod binary_arrays;
mod binary_datx;
mod binary_gwy;
mod binary_keyence;
mod binary_optical;
mod binary_real;
mod binary_real_afm;
mod binary_real_keyence;
mod binary_spm;
mod binary_sur;
mod binary_x3p;
mod cli;
mod cli_pipeline;
mod common;
mod files_table;
mod film_stage;
mod fit_cli;
mod fit_coulomb;
mod fit_gauss_newton;
mod fit_ice;
mod fit_lm;
mod friction_cycles;
mod friction_fixtures;
mod friction_mu_only;
mod friction_rpm;
mod friction_series;
mod function_length;
mod fuzz_regressions;
mod golden_tables;
mod layering;
mod nist_strd;
mod pipeline_cache;
mod pipeline_lab;
mod pipeline_overrides;
mod pipeline_stages;
mod readers_friction;
mod readers_surface;
mod real2_friction;
mod real2_surface;
mod real_all_files;
mod real_files;
mod real_roles;
mod reliability;
mod report;
mod report_numbers;
mod report_pages;
mod report_visual;
mod roughness_analytic;
mod roughness_areal;
mod roughness_cli;
mod roughness_golden;
mod roughness_mask;
mod roughness_random;
mod roughness_spectra_golden;
mod roughness_texture;
mod scheduling;
mod slurm;
mod spring_block_cli;
mod spring_block_closed_forms;
mod spring_block_golden;
mod spring_block_lattice;
mod spring_block_park;
mod spring_block_single;
mod spring_block_sweep;
mod tables;
mod tensile_cli;
mod tensile_general;
mod tensile_invariants;
mod tensile_real2;
mod tensile_real_files;
mod tensile_synthetic;
mod tensile_thesis_tables;
mod tensile_variants;
mod variants_friction;
mod variants_locale;
mod variants_surface;
mod wear;

#[test]
fn every_test_file_is_a_module() {
    let this = include_str!("tests.rs");
    let dir = crate::common::root().join("tests");
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        if path.extension().is_some_and(|e| e == "rs") && stem != "tests" {
            assert!(
                this.contains(&format!("\nmod {stem};\n")),
                "tests/{stem}.rs is not declared in tests/tests.rs, so it never runs"
            );
        }
    }
}
