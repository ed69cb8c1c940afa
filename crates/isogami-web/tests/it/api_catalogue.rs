//! The catalogue endpoints against the store they read: stats, families, dictionary, pages
//! of designs (paging, every sort key both ways, facet and range filters), disjunctive facet
//! counts and scatter points. Expected answers come from the store's summaries evaluated by
//! `common::oracle`, never from the server's own SQL.

use crate::common;

use common::oracle::{
    facet_text, facet_value_text, in_order, measure, sort_key, Filter, FACETS, MEASURES, ORDER_KEYS,
};
use common::{app, catalogue, get, summaries, Reply};
use isogami::tiling::Family;
use isogami_store::DesignSummary;
use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};

/// Every row of `GET /api/designs?query`, walking pages of `limit`.
async fn all_rows(app: &axum::Router, query: &str, limit: usize) -> (u64, Vec<DesignSummary>) {
    let mut rows = Vec::new();
    let mut total = None;
    loop {
        let sep = if query.is_empty() { "" } else { "&" };
        let uri = format!(
            "/api/designs?{query}{sep}limit={limit}&offset={}",
            rows.len()
        );
        let page = get(app, &uri).await.ok();
        let t = page["total"].as_u64().unwrap();
        assert_eq!(*total.get_or_insert(t), t, "total changed between pages");
        assert_eq!(page["offset"].as_u64().unwrap(), rows.len() as u64);
        let batch: Vec<DesignSummary> = serde_json::from_value(page["rows"].clone()).unwrap();
        assert!(batch.len() <= limit);
        let done = batch.len() < limit;
        rows.extend(batch);
        if done {
            break;
        }
    }
    (total.unwrap(), rows)
}

fn specs(rows: &[DesignSummary]) -> Vec<&str> {
    rows.iter().map(|r| r.spec.as_str()).collect()
}

#[tokio::test]
async fn stats_count_what_the_store_holds() {
    let all = summaries(&catalogue().db);
    let stats = get(&app(), "/api/stats").await.ok();
    assert_eq!(stats["designs"].as_u64().unwrap(), all.len() as u64);
    assert_eq!(stats["user_designs"].as_u64().unwrap(), 0);
    assert_eq!(
        stats["work_units"].as_u64().unwrap(),
        catalogue().units as u64
    );
    let settings: Value = serde_json::from_str(&catalogue().settings).unwrap();
    assert_eq!(stats["settings"], settings, "settings as a JSON object");
    assert_eq!(stats["tool_version"], env!("CARGO_PKG_VERSION"));
    let mut per_family: BTreeMap<String, u64> = BTreeMap::new();
    let mut per_behaviour: BTreeMap<String, u64> = BTreeMap::new();
    for s in &all {
        *per_family.entry(s.family.to_string()).or_default() += 1;
        let b = s
            .behaviour
            .map_or("none".to_string(), |b| b.as_str().into());
        *per_behaviour.entry(b).or_default() += 1;
    }
    let mut units: BTreeMap<String, u64> = BTreeMap::new();
    let store =
        isogami_store::Store::open_read(&catalogue().db, isogami_store::Check::Full).unwrap();
    for (unit, _) in store.work_units().unwrap() {
        *units.entry(unit.family).or_default() += 1;
    }
    let families = stats["families"].as_object().unwrap();
    assert_eq!(families.len(), per_family.len());
    for (family, n) in &per_family {
        assert_eq!(families[family]["designs"].as_u64(), Some(*n), "{family}");
        assert_eq!(
            families[family]["units"].as_u64(),
            units.get(family).copied(),
            "{family}"
        );
    }
    assert_eq!(
        stats["cell_twins"].as_u64(),
        Some(store.cell_twins().unwrap().len() as u64)
    );
    let by_behaviour: BTreeMap<String, u64> =
        serde_json::from_value(stats["by_behaviour"].clone()).unwrap();
    assert_eq!(by_behaviour, per_behaviour);
}

#[tokio::test]
async fn families_are_the_81_and_each_is_a_valid_filter() {
    let app = app();
    let families = get(&app, "/api/families").await.ok();
    let families = families.as_array().unwrap();
    assert_eq!(families.len(), 81);
    let names: BTreeSet<&str> = families
        .iter()
        .map(|f| f["name"].as_str().unwrap())
        .collect();
    assert_eq!(names.len(), 81, "names are distinct");
    let all = summaries(&catalogue().db);
    for f in families {
        let name = f["name"].as_str().unwrap();
        let family: Family = name.parse().unwrap();
        assert_eq!(f["number"].as_u64(), Some(u64::from(family.number())));
        assert_eq!(
            f["param_count"].as_u64().unwrap() as usize,
            f["default_params"].as_array().unwrap().len(),
            "{name}"
        );
        let page = get(&app, &format!("/api/designs?family={name}")).await.ok();
        let expected = all.iter().filter(|s| s.family == family).count();
        assert_eq!(page["total"].as_u64(), Some(expected as u64), "{name}");
    }
}

#[tokio::test]
async fn dictionary_names_exactly_the_fields_of_a_row_with_their_types() {
    let app = app();
    let dictionary = get(&app, "/api/dictionary").await.ok();
    let page = get(&app, "/api/designs?limit=500").await.ok();
    let rows = page["rows"].as_array().unwrap();
    assert!(!rows.is_empty());
    let fields: BTreeSet<&str> = dictionary
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["field"].as_str().unwrap())
        .collect();
    assert_eq!(
        fields.len(),
        dictionary.as_array().unwrap().len(),
        "no repeats"
    );
    for row in rows {
        let keys: BTreeSet<&str> = row
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        assert_eq!(keys, fields);
        for d in dictionary.as_array().unwrap() {
            let (field, kind) = (d["field"].as_str().unwrap(), d["type"].as_str().unwrap());
            let v = &row[field];
            let ok = kind.split('|').any(|k| match k {
                "string" => v.is_string(),
                "integer" => v.is_u64(),
                "number" => v.is_number(),
                "null" => v.is_null(),
                "number[]" => v.as_array().is_some_and(|a| a.iter().all(Value::is_number)),
                "[integer, integer]" => v
                    .as_array()
                    .is_some_and(|a| a.len() == 2 && a.iter().all(Value::is_u64)),
                other => panic!("type {other} of {field} unknown to this test"),
            });
            assert!(ok, "{field} = {v} is not {kind}");
            assert!(!d["meaning"].as_str().unwrap().is_empty());
        }
    }
}

#[tokio::test]
async fn pages_cover_every_design_once() {
    let app = app();
    let all = summaries(&catalogue().db);
    assert!(all.len() >= 10, "the fixture has {} designs", all.len());
    for limit in [1, 3, 500] {
        let (total, rows) = all_rows(&app, "", limit).await;
        assert_eq!(total, all.len() as u64);
        assert_eq!(rows.len(), all.len(), "limit {limit}");
        let got: BTreeSet<&str> = specs(&rows).into_iter().collect();
        assert_eq!(got.len(), rows.len(), "no design twice (limit {limit})");
        let want: BTreeSet<&str> = all.iter().map(|s| s.spec.as_str()).collect();
        assert_eq!(got, want);
        // Rows are the store's rows, unchanged.
        for r in &rows {
            assert_eq!(Some(r), all.iter().find(|s| s.spec == r.spec));
        }
    }
    // Past the end: no rows, same total.
    let page = get(&app, &format!("/api/designs?offset={}", all.len() + 5))
        .await
        .ok();
    assert_eq!(page["total"].as_u64(), Some(all.len() as u64));
    assert!(page["rows"].as_array().unwrap().is_empty());
    // The default order is by spec, ascending.
    let (_, rows) = all_rows(&app, "", 500).await;
    let mut sorted = specs(&rows);
    sorted.sort();
    assert_eq!(specs(&rows), sorted);
}

/// Every sort key, both ways: the full list is in order (missing values last, ties by
/// insertion order in the sort's direction), and walking it one row per page (where the store
/// walks an index) gives the same list as one large page (where it sorts).
#[tokio::test]
async fn every_sort_key_orders_rows_both_ways() {
    let app = app();
    let all = summaries(&catalogue().db);
    let index = |spec: &str| all.iter().position(|s| s.spec == spec).unwrap();
    let keys = ORDER_KEYS.iter().chain(MEASURES.iter());
    for key in keys {
        for descending in [false, true] {
            let sort = format!("sort={}{key}", if descending { "-" } else { "" });
            let (total, rows) = all_rows(&app, &sort, 500).await;
            assert_eq!(total as usize, all.len());
            assert_eq!(rows.len(), all.len(), "{sort}");
            for pair in rows.windows(2) {
                let (a, b) = (&pair[0], &pair[1]);
                assert!(
                    in_order(
                        (&sort_key(a, key), index(&a.spec)),
                        (&sort_key(b, key), index(&b.spec)),
                        descending
                    ),
                    "{sort}: {} ({:?}) before {} ({:?})",
                    a.spec,
                    sort_key(a, key),
                    b.spec,
                    sort_key(b, key)
                );
            }
            let (_, one_by_one) = all_rows(&app, &sort, 1).await;
            assert_eq!(
                specs(&one_by_one),
                specs(&rows),
                "{sort}: paged walk differs"
            );
        }
    }
}

/// Keys that hold at least two values in the fixture, with two of them.
fn two_values(all: &[DesignSummary], facet: &str) -> Option<(String, String)> {
    let values: BTreeSet<String> = all.iter().filter_map(|s| facet_text(s, facet)).collect();
    let mut it = values.into_iter();
    Some((it.next()?, it.next()?))
}

#[tokio::test]
async fn facet_filters_keep_exactly_the_matching_rows() {
    let app = app();
    let all = summaries(&catalogue().db);
    let mut checked = 0;
    for (facet, _) in FACETS {
        let values: BTreeSet<String> = all.iter().filter_map(|s| facet_text(s, facet)).collect();
        for value in &values {
            let filter = Filter::default().select(facet, value);
            let (total, rows) = all_rows(&app, &filter.query(), 500).await;
            assert_eq!(total as usize, filter.count(&all), "{}", filter.query());
            assert!(total > 0);
            assert!(rows.iter().all(|r| filter.matches(r)), "{}", filter.query());
            checked += 1;
        }
        // Repeated keys select several values of one facet: the union.
        if let Some((a, b)) = two_values(&all, facet) {
            let either = Filter::default().select(facet, &a).select(facet, &b);
            let (total, rows) = all_rows(&app, &either.query(), 500).await;
            let one = |v: &str| Filter::default().select(facet, v).count(&all);
            assert_eq!(total as usize, one(&a) + one(&b), "{}", either.query());
            assert!(rows.iter().all(|r| either.matches(r)));
        }
    }
    assert!(
        checked >= 12,
        "the fixture varies in {checked} facet values only"
    );
    // Facets hold together (AND): two families and one behaviour.
    let (f1, f2) = two_values(&all, "family").unwrap();
    let b = facet_text(&all[0], "behaviour").unwrap();
    let both = Filter::default()
        .select("family", &f1)
        .select("family", &f2)
        .select("behaviour", &b);
    let (total, rows) = all_rows(&app, &both.query(), 500).await;
    assert_eq!(total as usize, both.count(&all));
    assert!(rows.iter().all(|r| both.matches(r)));
    // A valid value no design has: nothing.
    let page = get(&app, "/api/designs?family=IH1&cell=4x4").await.ok();
    assert_eq!(page["total"], 0);
}

/// Range bounds taken from the data itself, so inclusive and exclusive bounds differ.
#[tokio::test]
async fn range_filters_are_inclusive_and_skip_missing_values() {
    let app = app();
    let all = summaries(&catalogue().db);
    for m in MEASURES {
        let mut values: Vec<f64> = all.iter().filter_map(|s| measure(s, m)).collect();
        values.sort_by(f64::total_cmp);
        let bounds = match values.len() {
            0 => vec![(Some(0.0), None), (None, Some(1.0))],
            n => vec![
                (Some(values[n / 3]), None),
                (None, Some(values[n / 2])),
                (Some(values[n / 4]), Some(values[(3 * n) / 4])),
                (Some(values[0]), Some(values[0])),
            ],
        };
        for (lo, hi) in bounds {
            let filter = Filter::default().range(m, lo, hi);
            let (total, rows) = all_rows(&app, &filter.query(), 500).await;
            assert_eq!(total as usize, filter.count(&all), "{}", filter.query());
            assert!(rows.iter().all(|r| filter.matches(r)), "{}", filter.query());
        }
    }
    // Ranges and facets together.
    let (f1, _) = two_values(&all, "family").unwrap();
    let filter = Filter::default()
        .select("family", &f1)
        .range("max_area_ratio", Some(1.5), None)
        .range("steps", None, Some(100.0));
    let (total, rows) = all_rows(&app, &filter.query(), 500).await;
    assert_eq!(total as usize, filter.count(&all));
    assert!(rows.iter().all(|r| filter.matches(r)));
}

/// Each count of `/api/facets?filters` equals the designs total with the value selected in
/// place of its facet's own selection, and equals what the summaries say.
async fn check_facets(app: &axum::Router, all: &[DesignSummary], filter: &Filter) {
    let facets = get(app, &format!("/api/facets?{}", filter.query()))
        .await
        .ok();
    let facets = facets.as_object().unwrap();
    assert_eq!(facets.len(), FACETS.len(), "{}", filter.query());
    for (key, name) in FACETS {
        let counts = facets[name].as_array().unwrap();
        let others = filter.without(key);
        let expected: BTreeSet<String> = all
            .iter()
            .filter(|s| others.matches(s))
            .filter_map(|s| facet_text(s, key))
            .collect();
        let listed: BTreeSet<String> = counts
            .iter()
            .map(|c| facet_value_text(&c["value"]).unwrap())
            .collect();
        assert_eq!(listed, expected, "{name} values under {}", filter.query());
        for c in counts {
            let value = facet_value_text(&c["value"]).unwrap();
            let with = others.clone().select(key, &value);
            let page = get(app, &format!("/api/designs?{}&limit=1", with.query()))
                .await
                .ok();
            assert_eq!(
                c["count"],
                page["total"],
                "{name}={value} under {}",
                filter.query()
            );
            assert_eq!(c["count"].as_u64().unwrap() as usize, with.count(all));
        }
        // Most frequent first.
        let n: Vec<u64> = counts
            .iter()
            .map(|c| c["count"].as_u64().unwrap())
            .collect();
        assert!(n.windows(2).all(|w| w[0] >= w[1]), "{name}: {n:?}");
    }
}

#[tokio::test]
async fn facet_counts_are_disjunctive() {
    let app = app();
    let all = summaries(&catalogue().db);
    check_facets(&app, &all, &Filter::default()).await;
    let (f1, f2) = two_values(&all, "family").unwrap();
    let (b1, _) = two_values(&all, "behaviour").unwrap();
    let filters = [
        Filter::default().select("family", &f1),
        Filter::default()
            .select("family", &f1)
            .select("family", &f2)
            .select("behaviour", &b1),
        Filter::default()
            .select("tiles", "2")
            .range("max_area_ratio", Some(2.0), None),
    ];
    for f in &filters {
        check_facets(&app, &all, f).await;
    }
    // Unfiltered, each facet's counts add up to every design.
    let facets = get(&app, "/api/facets").await.ok();
    for (_, name) in FACETS {
        let sum: u64 = facets[name]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["count"].as_u64().unwrap())
            .sum();
        assert_eq!(sum as usize, all.len(), "{name}");
    }
}

#[tokio::test]
async fn scatter_points_are_the_filtered_rows_measures() {
    let app = app();
    let all = summaries(&catalogue().db);
    let (f1, f2) = two_values(&all, "family").unwrap();
    let cases = [
        ("max_expansion", "max_area_ratio", Filter::default()),
        ("v1", "poisson_min", Filter::default().select("family", &f1)),
        (
            "steps",
            "v2",
            Filter::default()
                .select("family", &f1)
                .select("family", &f2)
                .range("max_tile_rotation", Some(0.3), None),
        ),
    ];
    for (x, y, filter) in cases {
        let uri = format!("/api/scatter?x={x}&y={y}&{}", filter.query());
        let reply: Reply = get(&app, &uri).await;
        let points = reply.ok();
        let points = points.as_array().unwrap();
        let expected: Vec<&DesignSummary> = all
            .iter()
            .filter(|s| filter.matches(s) && measure(s, x).is_some() && measure(s, y).is_some())
            .collect();
        let got: Vec<&str> = points.iter().map(|p| p["spec"].as_str().unwrap()).collect();
        let want: Vec<&str> = expected.iter().map(|s| s.spec.as_str()).collect();
        assert_eq!(got, want, "{uri}: the matching designs in insertion order");
        for (p, s) in points.iter().zip(&expected) {
            assert_eq!(p["x"].as_f64(), measure(s, x), "{uri} {}", s.spec);
            assert_eq!(p["y"].as_f64(), measure(s, y), "{uri} {}", s.spec);
            assert_eq!(p["family"], serde_json::json!(s.family), "{uri} {}", s.spec);
            assert_eq!(
                p["behaviour"],
                serde_json::json!(s.behaviour),
                "{uri} {}",
                s.spec
            );
        }
    }
}

/// `GET /api/measures` names exactly the numeric fields of a row the API ranges and sorts by
/// (each with its dictionary entry), the parameter slots v0…v5 after them: a range on each
/// passes exactly the rows that have it, and every other numeric field of the dictionary is
/// refused as a measure. The browser builds its range filters, sort keys, scatter axes and
/// table columns from this list.
#[tokio::test]
async fn measures_are_exactly_what_ranges_and_sorts_take() {
    let app = app();
    let measures = get(&app, "/api/measures").await.ok();
    let dictionary = get(&app, "/api/dictionary").await.ok();
    let all = summaries(&catalogue().db);
    let rows: Vec<Value> = all
        .iter()
        .map(|s| serde_json::to_value(s).unwrap())
        .collect();
    let names: Vec<&str> = measures
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["name"].as_str().unwrap())
        .collect();
    assert!(names.contains(&"finite_raw_dof") && names.contains(&"finite_covered"));
    assert_eq!(
        &names[names.len() - 6..],
        ["v0", "v1", "v2", "v3", "v4", "v5"]
    );
    for m in measures.as_array().unwrap() {
        let name = m["name"].as_str().unwrap();
        assert!(!m["meaning"].as_str().unwrap().is_empty(), "{name}");
        let value = |row: &Value| -> Value {
            match name.strip_prefix('v').and_then(|k| k.parse::<usize>().ok()) {
                Some(k) => row["params"].get(k).cloned().unwrap_or(Value::Null),
                None => row[name].clone(),
            }
        };
        if !name.starts_with('v') {
            let entry = dictionary
                .as_array()
                .unwrap()
                .iter()
                .find(|d| d["field"] == name)
                .unwrap_or_else(|| panic!("{name} is not in the dictionary"));
            assert_eq!(m["type"], entry["type"], "{name}");
            assert_eq!(m["unit"], entry["unit"], "{name}");
            assert_eq!(m["meaning"], entry["meaning"], "{name}");
        }
        let having = rows.iter().filter(|r| !value(r).is_null()).count();
        let page = get(
            &app,
            &format!("/api/designs?range={name}:-1e300:&sort=-{name}&limit=1"),
        )
        .await
        .ok();
        assert_eq!(page["total"].as_u64(), Some(having as u64), "{name}");
    }
    for d in dictionary.as_array().unwrap() {
        let (field, kind) = (d["field"].as_str().unwrap(), d["type"].as_str().unwrap());
        let numeric = kind.split('|').any(|k| k == "number" || k == "integer");
        if numeric && !names.contains(&field) {
            let reply = get(&app, &format!("/api/designs?range={field}:0:")).await;
            assert_eq!(
                reply.status.as_u16(),
                400,
                "{field} is a measure the list lacks"
            );
        }
    }
}
