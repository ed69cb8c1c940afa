//! `GET /api/motions` (issue 24, item 2: mechanisms first): the matching designs grouped by
//! motion class, checked against the store's summaries and classes evaluated here — filters by
//! `common::oracle`, order by its sort semantics, classes from `Store::motion_classes` — never
//! against the server's own SQL.

use crate::common;

use common::oracle::{in_order, sort_key, Filter};
use common::{app, app_with, assert_client_error, catalogue, get, private_db, summaries};
use isogami_store::{Check, DesignSummary, Store};
use isogami_web::ServerSettings;
use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};

/// topology → representative of the fixture's classes.
fn class_map(db: &std::path::Path) -> BTreeMap<String, String> {
    let classes = Store::open_read(db, Check::Full)
        .unwrap()
        .motion_classes()
        .unwrap()
        .expect("the fixture has classes");
    classes
        .iter()
        .flat_map(|c| {
            c.variants
                .iter()
                .map(|v| (v.topology.clone(), c.representative.clone()))
        })
        .collect()
}

/// The designs passing `filter`, in the order of `key` (insertion order on ties, in the sort's
/// direction; missing last).
fn ordered(all: &[DesignSummary], filter: &Filter, key: &str, desc: bool) -> Vec<DesignSummary> {
    let mut rows: Vec<(usize, &DesignSummary)> = all
        .iter()
        .enumerate()
        .filter(|(_, s)| filter.matches(s))
        .collect();
    rows.sort_by(|a, b| {
        let (ka, kb) = (sort_key(a.1, key), sort_key(b.1, key));
        if in_order((&ka, a.0), (&kb, b.0), desc) {
            std::cmp::Ordering::Less
        } else {
            std::cmp::Ordering::Greater
        }
    });
    rows.into_iter().map(|(_, s)| s.clone()).collect()
}

/// (representative or "-", member specs) per group as expected.
fn expected_groups(
    rows: &[DesignSummary],
    classes: &BTreeMap<String, String>,
) -> (Vec<(String, Vec<String>)>, Vec<String>) {
    let mut groups: Vec<(String, Vec<String>)> = Vec::new();
    let mut unclassified = Vec::new();
    for r in rows {
        match classes.get(&r.topology) {
            Some(rep) => match groups.iter_mut().find(|(g, _)| g == rep) {
                Some((_, m)) => m.push(r.spec.clone()),
                None => groups.push((rep.clone(), vec![r.spec.clone()])),
            },
            None => unclassified.push(r.spec.clone()),
        }
    }
    (groups, unclassified)
}

fn members(group: &Value) -> Vec<String> {
    group["members"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["spec"].as_str().unwrap().to_string())
        .collect()
}

/// Counts and spans of `group` agree with its members' summaries.
fn check_group(group: &Value, by_spec: &BTreeMap<&str, &DesignSummary>) {
    let rows: Vec<&DesignSummary> = members(group).iter().map(|s| by_spec[s.as_str()]).collect();
    assert_eq!(group["designs"].as_u64().unwrap(), rows.len() as u64);
    let distinct = |f: &dyn Fn(&DesignSummary) -> String| {
        rows.iter().map(|r| f(r)).collect::<BTreeSet<_>>().len() as u64
    };
    assert_eq!(
        group["topologies"].as_u64().unwrap(),
        distinct(&|r| r.topology.clone())
    );
    assert_eq!(
        group["families"].as_array().unwrap().len() as u64,
        distinct(&|r| r.family.to_string())
    );
    assert_eq!(
        group["cells"].as_array().unwrap().len() as u64,
        distinct(&|r| r.cell.to_string())
    );
    let span = |name: &str, f: &dyn Fn(&DesignSummary) -> f64| {
        let lo = rows.iter().map(|r| f(r)).fold(f64::INFINITY, f64::min);
        let hi = rows.iter().map(|r| f(r)).fold(f64::NEG_INFINITY, f64::max);
        assert_eq!(group[name]["min"].as_f64().unwrap(), lo, "{name}");
        assert_eq!(group[name]["max"].as_f64().unwrap(), hi, "{name}");
    };
    span("max_area_ratio", &|r| r.max_area_ratio);
    span("max_expansion", &|r| r.max_expansion);
    span("min_expansion", &|r| r.min_expansion);
    let counted: u64 = group["behaviours"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b["count"].as_u64().unwrap())
        .sum();
    assert_eq!(counted, rows.len() as u64);
}

#[tokio::test]
async fn groups_are_the_classes_of_the_matching_designs_in_the_sort_order() {
    let db = &catalogue().db;
    let all = summaries(db);
    let classes = class_map(db);
    let by_spec: BTreeMap<&str, &DesignSummary> =
        all.iter().map(|s| (s.spec.as_str(), s)).collect();
    let family = all[0].family.to_string();
    let filters = [
        Filter::default(),
        Filter::default().select("family", &family),
        Filter::default().range("max_area_ratio", Some(1.05), None),
    ];
    let app = app();
    for filter in &filters {
        for (key, desc) in [("max_area_ratio", true), ("spec", false), ("family", false)] {
            let sign = if desc { "-" } else { "" };
            let q = filter.query();
            let sep = if q.is_empty() { "" } else { "&" };
            let answer = get(&app, &format!("/api/motions?{q}{sep}sort={sign}{key}"))
                .await
                .ok();
            let rows = ordered(&all, filter, key, desc);
            let (groups, unclassified) = expected_groups(&rows, &classes);
            assert!(answer["computed"].as_bool().unwrap());
            assert_eq!(answer["total"].as_u64().unwrap(), rows.len() as u64);
            let got: Vec<(String, Vec<String>)> = answer["groups"]
                .as_array()
                .unwrap()
                .iter()
                .map(|g| {
                    (
                        g["representative"].as_str().unwrap().to_string(),
                        members(g),
                    )
                })
                .collect();
            assert_eq!(got, groups, "{q} sort {sign}{key}");
            match &answer["unclassified"] {
                Value::Null => assert!(unclassified.is_empty()),
                g => {
                    assert!(g["representative"].is_null());
                    assert_eq!(members(g), unclassified);
                }
            }
            for g in answer["groups"].as_array().unwrap() {
                check_group(g, &by_spec);
            }
        }
    }
    // Several designs share a class in the fixture (otherwise grouping shows nothing).
    let answer = get(&app, "/api/motions").await.ok();
    assert!(answer["groups"].as_array().unwrap().len() < all.len());
    assert!(answer["groups"]
        .as_array()
        .unwrap()
        .iter()
        .any(|g| g["designs"].as_u64().unwrap() > 1));
}

#[tokio::test]
async fn a_file_without_classes_lists_every_design_unclassified_and_bad_keys_are_refused() {
    let (_guard, db) = private_db("motions-none");
    rusqlite::Connection::open(&db)
        .unwrap()
        .execute_batch("DROP TABLE motion_classes")
        .unwrap();
    let all = summaries(&db);
    let app = app_with(&db, ServerSettings::default());
    let answer = get(&app, "/api/motions?sort=spec").await.ok();
    assert!(!answer["computed"].as_bool().unwrap());
    assert!(answer["groups"].as_array().unwrap().is_empty());
    let mut specs: Vec<String> = all.iter().map(|s| s.spec.clone()).collect();
    specs.sort();
    assert_eq!(members(&answer["unclassified"]), specs);
    assert_client_error(&get(&app, "/api/motions?colour=red").await, "unknown key");
    assert_client_error(&get(&app, "/api/motions?family=IH999").await, "bad family");
}
