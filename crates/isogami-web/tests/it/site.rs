//! `write_site`: the static site holds every design with the same data the API serves,
//! replaces an earlier site whole, and refuses (untouched) a folder that is not one, or a
//! database that does not exist.

use crate::common;

use common::{app, catalogue, enc, get, summaries, Scratch};
use isogami_web::assets::ASSETS;
use isogami_web::site::{SiteError, MARKER};
use isogami_web::{slug, write_site};
use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Every file under `dir`: relative path → bytes.
fn files(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeMap<PathBuf, Vec<u8>>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(root, &path, out);
            } else {
                let bytes = std::fs::read(&path).unwrap();
                out.insert(path.strip_prefix(root).unwrap().to_path_buf(), bytes);
            }
        }
    }
    let mut out = BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

/// Names in a folder.
fn names(dir: &Path) -> BTreeSet<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

fn json(path: &Path) -> Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

#[tokio::test]
async fn the_site_holds_what_the_api_serves() {
    let scratch = Scratch::new("site-whole");
    let out = scratch.path().join("site");
    let all = summaries(&catalogue().db);
    let mut calls = Vec::new();
    let report = write_site(&catalogue().db, &out, &mut |k, n| calls.push((k, n))).unwrap();
    assert_eq!(report.designs, all.len());
    let expected: Vec<(usize, usize)> = (1..=all.len()).map(|k| (k, all.len())).collect();
    assert_eq!(calls, expected, "progress after each design");
    assert_eq!(names(scratch.path()), BTreeSet::from(["site".to_string()]));

    let written = files(&out);
    assert_eq!(report.files, written.len());
    let bytes: usize = written.values().map(Vec::len).sum();
    assert_eq!(report.bytes, bytes as u64);
    assert!(written.contains_key(Path::new(MARKER)));
    for (name, content) in ASSETS {
        assert_eq!(
            written.get(Path::new(name)),
            Some(&content.to_vec()),
            "{name}"
        );
    }

    assert_eq!(
        json(&out.join("data/designs.json")),
        serde_json::to_value(&all).unwrap(),
        "designs.json is the store's summaries"
    );
    let app = app();
    let site = json(&out.join("data/site.json"));
    assert_eq!(site["mode"], "static");
    assert_eq!(site["stats"]["designs"].as_u64(), Some(all.len() as u64));
    assert_eq!(site["families"], get(&app, "/api/families").await.ok());
    assert_eq!(site["dictionary"], get(&app, "/api/dictionary").await.ok());
    assert_eq!(site["measures"], get(&app, "/api/measures").await.ok());

    let stems: BTreeSet<String> = all.iter().map(|s| slug(&s.spec)).collect();
    assert_eq!(stems.len(), all.len(), "slugs are distinct");
    for s in &all {
        let stem = slug(&s.spec);
        assert!(!stem.contains(['/', '\\', ':']) && !stem.starts_with('.'));
        let view = get(&app, &format!("/api/design?spec={}", enc(&s.spec)))
            .await
            .ok();
        assert_eq!(
            json(&out.join(format!("data/design/{stem}.json"))),
            view,
            "{}",
            s.spec
        );
        let thumb = get(&app, &format!("/api/thumbnail?spec={}", enc(&s.spec))).await;
        assert_eq!(
            written.get(&PathBuf::from(format!("thumbs/{stem}.svg"))),
            Some(&thumb.body),
            "{}",
            s.spec
        );
    }
    // Nothing else: markers, assets, three data files (site, designs, motions) and two files
    // per design.
    assert!(written.contains_key(&PathBuf::from("data/motions.json")));
    assert_eq!(written.len(), 1 + ASSETS.len() + 3 + 2 * all.len());
}

#[test]
fn a_second_write_replaces_the_site() {
    let scratch = Scratch::new("site-again");
    let out = scratch.path().join("site");
    write_site(&catalogue().db, &out, &mut |_, _| {}).unwrap();
    let first = files(&out);
    std::fs::write(out.join("data/design/stale.json"), b"{}").unwrap();
    std::fs::write(out.join("data/designs.json"), b"[]").unwrap();
    write_site(&catalogue().db, &out, &mut |_, _| {}).unwrap();
    assert_eq!(
        files(&out),
        first,
        "the second site is the first, stale files gone"
    );
    assert_eq!(names(scratch.path()), BTreeSet::from(["site".to_string()]));
    // An empty folder is taken too.
    let empty = scratch.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    write_site(&catalogue().db, &empty, &mut |_, _| {}).unwrap();
    assert_eq!(files(&empty), first);
}

#[test]
fn a_folder_that_is_not_a_site_is_refused_untouched() {
    let scratch = Scratch::new("site-foreign");
    let out = scratch.path().join("photos");
    std::fs::create_dir_all(out.join("2024")).unwrap();
    std::fs::write(out.join("notes.txt"), b"keep me\n").unwrap();
    std::fs::write(out.join("2024/cat.jpg"), [0xff, 0xd8, 0xff, 0xe0]).unwrap();
    let file = scratch.path().join("a-file");
    std::fs::write(&file, b"not a folder").unwrap();
    let before = files(scratch.path());
    for target in [&out, &file] {
        let e = write_site(&catalogue().db, target, &mut |_, _| {}).unwrap_err();
        assert!(matches!(e, SiteError::NotOurs(_)), "{e}");
        assert!(!e.to_string().contains('\n'));
    }
    assert_eq!(files(scratch.path()), before, "something was touched");
    assert_eq!(
        names(scratch.path()),
        BTreeSet::from(["photos".to_string(), "a-file".to_string()])
    );
}

#[test]
fn a_missing_database_is_an_error_and_creates_nothing() {
    let scratch = Scratch::new("site-no-db");
    let db = scratch.path().join("missing.db");
    let out = scratch.path().join("site");
    let e = write_site(&db, &out, &mut |_, _| {}).unwrap_err();
    assert!(matches!(e, SiteError::Store { .. }), "{e}");
    assert!(e.to_string().contains("missing.db"), "{e}");
    assert!(
        names(scratch.path()).is_empty(),
        "{:?}",
        names(scratch.path())
    );
}
