//! Lists the repository keeps by hand, checked against what they list: every test file is
//! described in docs/testing.md, its table of the Rust test crates names each crate's modules
//! as its `main.rs` declares them, and the package descriptions (the `matte` and `matte-brdf`
//! crates, pyproject.toml) name every registered model.

use crate::common::repo;

fn read(path: &str) -> String {
    std::fs::read_to_string(repo().join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn docs_testing_names_every_test_file() {
    let doc = read("docs/testing.md");
    let mut missing = Vec::new();
    for suite in std::fs::read_dir(repo().join("tests")).unwrap() {
        let suite = suite.unwrap().path();
        if !suite.is_dir() {
            continue;
        }
        for file in std::fs::read_dir(&suite).unwrap() {
            let name = file.unwrap().file_name().into_string().unwrap();
            let is_test = (name.ends_with(".rs") && name != "main.rs") || name.ends_with(".py");
            if is_test && !doc.contains(&format!("{name}`")) {
                missing.push(format!("{}/{name}", suite.file_name().unwrap().to_string_lossy()));
            }
        }
    }
    assert!(missing.is_empty(), "docs/testing.md does not describe: {missing:?}");
}

#[test]
fn docs_testing_lists_each_test_crates_modules() {
    let doc = read("docs/testing.md");
    for krate in ["kernels", "scene_file", "render", "tools"] {
        let declared: std::collections::BTreeSet<String> = read(&format!("tests/{krate}/main.rs"))
            .lines()
            .filter_map(|l| l.strip_prefix("mod ")?.strip_suffix(';').map(str::to_string))
            .filter(|m| m != "common")
            .collect();
        let row = doc
            .lines()
            .find(|l| l.starts_with(&format!("| `tests/{krate}/` |")))
            .unwrap_or_else(|| panic!("docs/testing.md: no row for tests/{krate}/"));
        let modules = row.rsplit('|').nth(1).expect("a modules column");
        let listed: std::collections::BTreeSet<String> =
            modules.split(',').map(|m| m.trim().trim_matches('`').to_string()).collect();
        assert_eq!(listed, declared, "docs/testing.md's modules of tests/{krate}/ against its main.rs");
    }
}

#[test]
fn package_descriptions_name_every_registered_model() {
    for file in ["rust/Cargo.toml", "rust/brdf/Cargo.toml", "pyproject.toml"] {
        let text = read(file);
        let line =
            text.lines().find(|l| l.starts_with("description")).unwrap_or_else(|| panic!("{file}: no description"));
        let line = line.to_lowercase();
        for model in matte_brdf::BSDF_TYPES {
            let named = line.contains(&model.replace('_', "-")) || line.contains(&model.replace('_', " "));
            assert!(named, "{file}'s description does not name {model}: {line}");
        }
    }
}
