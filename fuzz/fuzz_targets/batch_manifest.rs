//! Arbitrary bytes as a batch manifest: parsing never panics, and every accepted item has an
//! id that names one folder inside the output folder (no separator, not hidden), unique.
#![no_main]

use std::collections::HashSet;
use std::path::{Component, Path};

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(items) = envelope::batch::parse_manifest(text, Path::new("m.jsonl"), None) else {
        return;
    };
    let mut seen = HashSet::new();
    for item in &items {
        let components: Vec<_> = Path::new(&item.id).components().collect();
        assert!(
            matches!(components[..], [Component::Normal(_)]) && !item.id.starts_with('.'),
            "id {:?} is not one plain folder name",
            item.id
        );
        assert!(seen.insert(item.id.clone()), "id {:?} twice", item.id);
    }
});
