//! Issue 40: the behaviour class is stable under small moves of the shape.
//!
//! A 1e-4 move of a shape parameter changes a deployment's expansions by O(1e-4) of the
//! largest one; the class must then stay the same, or the design must say it lies at a class
//! boundary. Before this rule 68 of 73 isotropic designs changed class under such a move,
//! decided by near-closed states at the end of the path that the Poisson-like range leaves out.

use isogami::api::{deploy, resolve_design, DeployRequest};
use isogami::deploy::DeploymentReport;
use isogami::measure::BehaviourClass;

fn report(spec: &str) -> Result<DeploymentReport, String> {
    let design = resolve_design(spec).map_err(|e| format!("{spec}: {e}"))?;
    deploy(&design, &DeployRequest::default(), &mut |_| true)
        .map(|run| run.report)
        .map_err(|e| format!("{spec}: {e}"))
}

/// `spec` with shape parameter `k` moved by `by`.
fn moved(spec: &str, k: usize, by: f64) -> String {
    let parts: Vec<&str> = spec.splitn(4, ':').collect();
    let params: Vec<String> = parts[1]
        .split(',')
        .enumerate()
        .map(|(i, p)| {
            let v: f64 = p.parse().unwrap();
            if i == k {
                format!("{}", v + by)
            } else {
                p.to_string()
            }
        })
        .collect();
    format!(
        "{}:{}:{}:{}",
        parts[0],
        params.join(","),
        parts[2],
        parts[3]
    )
}

fn describe(r: &DeploymentReport) -> String {
    format!(
        "{:?} boundary {} {:?} poisson {:?}",
        r.behaviour,
        r.behaviour_boundary,
        r.behaviour_figures,
        r.poisson_range()
    )
}

/// The issue's reproducer: 1e-4 from the symmetric shape, the Poisson-like range stays in
/// [−1, −0.96], and the old rule called it orthotropic from its near-closed final states.
#[test]
fn issue_40_ih57_moved_by_1e_4_stays_isotropic() {
    let at = report("IH57:0.230769230769,0.5:4x2:-aaabbbaaabbbbab").unwrap();
    let off = report("IH57:0.230769230769,0.4999:4x2:-aaabbbaaabbbbab").unwrap();
    let (lo, hi) = off.poisson_range().unwrap();
    assert!(lo >= -1.0 && hi <= -0.9, "{}", describe(&off));
    for r in [&at, &off] {
        assert_eq!(
            r.behaviour,
            Some(BehaviourClass::IsotropicAuxetic),
            "{}",
            describe(r)
        );
        assert!(!r.behaviour_boundary, "{}", describe(r));
    }
}

/// Every 25th classified design with shape parameters of the default exploration (`isogami
/// explore`, in database order: 30 designs of 20 families, 8 of which changed class under the
/// old rule), each moved by +1e-4 in each parameter in turn. A moved shape that is rigid, or
/// that opens by less than 1e-3 (a motion that exists only at the exact shape), has a
/// different motion rather than a different class, and is left out.
const EVERY_25TH: [&str; 30] = [
    "IH21:0.104512294489,0.65:1x1:---ab-aa-aba-ba",
    "IH23:0.230769230769,0.5,0.225335752741,0.5:3x1:--babb-bb---aaa",
    "IH26:0.155769230769,0.225335752741:3x1:-b-abb--b-bbaaa",
    "IH43:0.305769230769,0.5:4x1:-aaabbbbbaaaabbb",
    "IH47:0.155769230769,0.35:4x1:-aaabbbbbaaaabbb",
    "IH54:0.230769230769,0.230769230769:1x2:aaaabbbbbabbbaaa",
    "IH58:0.155769230769,0.5:4x1:-aaabbbbbaaaabbb",
    "IH67:0.305769230769,0.869565217391:1x4:-aaabbaaaaaaaaaa",
    "IH44:0.5,0.102564102564:2x2:-aaabbbaaabbaaba",
    "IH1:0.04739750492,0.5,0.143395479017,0.4375:1x4:--aaa-bb-aa-",
    "IH2:0.19739750492,0.35,0.150335752741,0.150335752741:2x1:---aab---baa",
    "IH9:0.12239750492,0.35,0.150335752741:1x2:--aaabb--aa-",
    "IH9:0.19739750492,0.65,0.150335752741:2x1:---abb--a-bb",
    "IH13:0.04739750492,0.225335752741,0.5:2x1:---abb-a--bb",
    "IH15:0.04739750492,0.150335752741,0.150335752741:2x1:--a-b-b--aaa",
    "IH44:0.5,0.177564102564:1x3:-aaabbaaaaaa",
    "IH69:0.5,0.027564102564:1x3:-aaabbaaaaaa",
    "IH27:0.216304,0.465108,0.534891:1x1:-aaaaaaaa-",
    "IH8:0.04739750492,0.5,0.143395479017,0.4375:2x2:--a-aaaaaa--",
    "IH17:0.12239750492,0.225335752741:2x2:--a--aa-a-aa",
    "IH28:0.452827026611,0.35:1x1:a-b--b-bbb",
    "IH53:0.5,0.102564102564,0.102564102564:1x1:aaaabbbb",
    "IH41:0.305769230769,0.5:2x2:aaaabbbb",
    "IH51:0.5,0.5,0.78:1x1:aaaabbbb",
    "IH68:0.105263157895:2x2:aaaabbbb",
    "IH8:0.12239750492,0.5,0.143395479017,0.625:1x2:-aaaa-",
    "IH13:0.12239750492,0.225335752741,0.5:1x1:-aaaa-",
    "IH86:0.196416770201:1x1:aaabbb",
    "IH26:0.155769230769,0.225335752741:1x1:aa-a-",
    "IH84:0.35,0.121416770201:1x1:aaa",
];

#[test]
fn issue_40_class_is_stable_under_1e_4_moves() {
    let mut failures = Vec::new();
    let mut compared = 0;
    for spec in EVERY_25TH {
        let at = report(spec).unwrap();
        assert!(at.behaviour.is_some(), "{spec}: {}", describe(&at));
        let params = spec.split(':').nth(1).unwrap().split(',').count();
        for k in 0..params {
            let other = moved(spec, k, 1e-4);
            let Ok(off) = report(&other) else {
                continue; // rigid at the moved shape
            };
            if off.max_expansion < 1e-3 {
                continue; // a motion of the exact shape only
            }
            compared += 1;
            let boundary = at.behaviour_boundary || off.behaviour_boundary;
            if off.behaviour != at.behaviour && !boundary {
                failures.push(format!(
                    "{spec}\n    {}\n  {other}\n    {}",
                    describe(&at),
                    describe(&off)
                ));
            }
        }
    }
    assert!(compared >= 60, "only {compared} moves compared");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
