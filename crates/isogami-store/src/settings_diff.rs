//! The settings that differ between a database and a run (or two databases), named one by one
//! for the message that refuses to mix them: "max_edges 16 in the file, 20 in this run".

use serde_json::{Map, Value};

/// The differing settings of two fingerprints (JSON objects of the library's
/// `CatalogSettings::fingerprint`), each as `name A in <a_label>, B in <b_label>`, joined by
/// "; ". A fingerprint that is not a JSON object is shown whole.
pub(crate) fn settings_difference(a: &str, a_label: &str, b: &str, b_label: &str) -> String {
    let parse = |s: &str| serde_json::from_str::<Map<String, Value>>(s).ok();
    let (Some(ma), Some(mb)) = (parse(a), parse(b)) else {
        return format!("{a} in {a_label}, {b} in {b_label}");
    };
    let show = |v: Option<&Value>| v.map_or_else(|| "unset".to_string(), Value::to_string);
    let mut names: Vec<&String> = ma.keys().chain(mb.keys()).collect();
    names.sort();
    names.dedup();
    let parts: Vec<String> = names
        .into_iter()
        .filter(|k| ma.get(*k) != mb.get(*k))
        .map(|k| {
            format!(
                "{k} {} in {a_label}, {} in {b_label}",
                show(ma.get(k)),
                show(mb.get(k))
            )
        })
        .collect();
    if parts.is_empty() {
        // Equal values written differently (never by this build): show both texts.
        format!("{a} in {a_label}, {b} in {b_label}")
    } else {
        parts.join("; ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_each_differing_setting() {
        let a = r#"{"threshold":0.1,"max_edges":16,"kerf":0.01}"#;
        let b = r#"{"threshold":0.1,"max_edges":20,"kerf":0.02}"#;
        assert_eq!(
            settings_difference(a, "the file", b, "this run"),
            "kerf 0.01 in the file, 0.02 in this run; max_edges 16 in the file, 20 in this run"
        );
        let c = r#"{"threshold":0.1}"#;
        assert_eq!(
            settings_difference(c, "x", a, "y"),
            "kerf unset in x, 0.01 in y; max_edges unset in x, 16 in y"
        );
        assert_eq!(
            settings_difference("7", "x", a, "y"),
            format!("7 in x, {a} in y")
        );
    }
}
