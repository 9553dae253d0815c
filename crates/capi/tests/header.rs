//! The C header in the repository is what cbindgen makes of the crate today.

use std::path::Path;

#[test]
fn the_header_in_the_repository_is_current() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(dir.join("cbindgen.toml")).unwrap();
    let bindings = cbindgen::Builder::new()
        .with_crate(dir)
        .with_config(config)
        .generate()
        .expect("cbindgen reads the crate");
    let mut made = Vec::new();
    bindings.write(&mut made);
    let path = dir.join("include/bwc.h");
    if std::env::var_os("BWC_WRITE_HEADER").is_some() {
        std::fs::write(&path, &made).unwrap();
    }
    let kept = std::fs::read(&path).unwrap_or_default();
    assert!(
        kept == made,
        "{} is stale: regenerate it with `BWC_WRITE_HEADER=1 cargo test -p bwc-capi --test \
         capi header` and commit it",
        path.display()
    );
}
