//! The body of `POST /api/inverse` → the library's [`InverseRequest`], with the same
//! meaning as `isogami inverse`'s flags (a left-out field is the flag's default), checked by
//! the library (its one-line message on a bad target or value) and then against this
//! server's caps.

use super::limits::InverseLimits;
use crate::error::{ApiError, ApiResult};
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::http::StatusCode;
use isogami::inverse::{InverseRequest, Target};
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// Longest target text (or JSON) accepted.
pub const MAX_TARGET: usize = 16 * 1024;

/// What a client posts: `target` as compact text or as the JSON object of `--target`'s JSON
/// form, the rest as the CLI's flags. A job's view echoes it ([`InverseBody::echo`]).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct InverseBody {
    /// Compact text (`"isotropic + 0.5*uniform; tiles<=4"`) or the target's JSON object.
    pub target: Value,
    /// Topologies kept and refined (`--top`).
    pub top: Option<usize>,
    /// Evaluations per refined design (`--budget`).
    pub budget: Option<usize>,
    /// Pre-screened designs re-deployed (`--confirm`; left out: 16 × top).
    pub confirm: Option<usize>,
    /// Screened designs triaged (`--triage`; left out: 16 × top).
    pub triage: Option<usize>,
    /// Fresh shape samples per topology (`--samples`).
    pub samples: Option<usize>,
    /// Kerf in mean edge lengths (`--kerf`).
    pub kerf: Option<f64>,
    /// Also optimise the kerf (`--refine-kerf`).
    pub refine_kerf: Option<bool>,
}

/// 400 `bad_target`: the library's message about the target.
fn bad_target(message: String) -> ApiError {
    ApiError::new(
        StatusCode::BAD_REQUEST,
        "bad_target",
        message,
        "goals joined by +, constraints after ';', e.g. 'isotropic + 0.5*uniform; tiles<=4' \
         (see docs/INVERSE.md)",
    )
}

/// 400 `over_limit`: a count above this server's cap.
fn over_limit(what: &str, value: usize, cap: usize) -> ApiError {
    ApiError::new(
        StatusCode::BAD_REQUEST,
        "over_limit",
        format!("{what} {value} is above this server's limit of {cap}"),
        "run `isogami inverse` from the command line for larger searches",
    )
}

impl InverseBody {
    /// Reads a posted body, with a 4xx JSON error for a missing, oversized or malformed one.
    pub fn from_request(body: Result<Bytes, BytesRejection>) -> ApiResult<InverseBody> {
        let bytes = body.map_err(|e| ApiError::bad_body(&e))?;
        serde_json::from_slice(&bytes).map_err(|e| {
            ApiError::bad_parameter(format!(
                "request body is not {{\"target\": …, \"top\": …, \"budget\": …}}: {e}"
            ))
        })
    }

    /// The body as a job's view echoes it: the target text trimmed (an object as it came),
    /// every other field as given (null when left out: the CLI's default), so that a page
    /// shows the form and the command that started the job.
    pub fn echo(&self) -> InverseBody {
        let mut b = self.clone();
        if let Value::String(s) = &b.target {
            b.target = Value::String(s.trim().to_string());
        }
        b
    }

    /// The target: text as it is, an object as its JSON text; read by the library.
    fn target(&self) -> ApiResult<Target> {
        let text = match &self.target {
            Value::String(s) => s.clone(),
            Value::Object(_) => self.target.to_string(),
            _ => {
                return Err(bad_target(
                    "target must be text (e.g. \"area\") or the target's JSON object".into(),
                ))
            }
        };
        if text.len() > MAX_TARGET {
            return Err(bad_target("target longer than 16 KiB".into()));
        }
        Target::resolve(&text).map_err(|e| bad_target(e.to_string()))
    }

    /// The library's request, checked by the library and against `limits`.
    pub fn request(&self, limits: &InverseLimits) -> ApiResult<InverseRequest> {
        let mut r = InverseRequest::new(self.target()?);
        for (name, given) in [("confirm", self.confirm), ("triage", self.triage)] {
            if given == Some(0) {
                return Err(ApiError::bad_parameter(format!(
                    "{name} must be at least 1 (leave it out for the default, 16 × top)"
                )));
            }
        }
        r.top = self.top.unwrap_or(r.top);
        r.budget = self.budget.unwrap_or(r.budget);
        r.confirm = self.confirm.unwrap_or(0);
        r.triage = self.triage.unwrap_or(0);
        r.samples = self.samples.unwrap_or(0);
        if let Some(k) = self.kerf {
            r.kerf = k;
        }
        r.refine_kerf = self.refine_kerf.unwrap_or(false);
        r.validate()
            .map_err(|e| ApiError::bad_parameter(e.to_string()))?;
        let caps = [
            ("top", r.top, limits.max_top),
            ("budget", r.budget, limits.max_budget),
            ("confirm", r.confirm_count(), limits.max_confirm),
            ("triage", r.triage_count(), limits.max_triage),
            ("samples", r.samples, limits.max_samples),
        ];
        for (what, value, cap) in caps {
            if value > cap {
                return Err(over_limit(what, value, cap));
            }
        }
        Ok(r)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn body(v: Value) -> InverseBody {
        serde_json::from_value(v).unwrap()
    }

    #[test]
    fn fields_mean_what_the_cli_flags_mean() {
        let limits = InverseLimits::default();
        let r = body(json!({"target": "area"})).request(&limits).unwrap();
        let d = InverseRequest::new(Target::parse("area").unwrap());
        assert_eq!(r, d, "left-out fields are the CLI's defaults");
        let r = body(json!({
            "target": {"terms": [{"goal": {"kind": "poisson", "nu": -1.0}}]},
            "top": 2, "budget": 6, "confirm": 7, "triage": 9, "samples": 3, "kerf": 0.02,
            "refine_kerf": true
        }))
        .request(&limits);
        let r = match r {
            Ok(r) => r,
            Err(e) => panic!("{}", e.message),
        };
        assert_eq!(r.target, Target::parse("isotropic").unwrap());
        assert_eq!(
            (
                r.top,
                r.budget,
                r.confirm,
                r.triage,
                r.samples,
                r.kerf,
                r.refine_kerf
            ),
            (2, 6, 7, 9, 3, 0.02, true)
        );
    }

    #[test]
    fn bad_values_and_values_over_the_caps_are_refused() {
        let limits = InverseLimits::default();
        let e = body(json!({"target": "aera"}))
            .request(&limits)
            .unwrap_err();
        assert_eq!((e.status, e.kind), (StatusCode::BAD_REQUEST, "bad_target"));
        assert_eq!(e.message, Target::parse("aera").unwrap_err().to_string());
        let e = body(json!({"target": 3})).request(&limits).unwrap_err();
        assert_eq!(e.kind, "bad_target");
        let e = body(json!({"target": "area", "triage": 0}))
            .request(&limits)
            .unwrap_err();
        assert!(e.message.starts_with("triage must be at least 1"), "{e:?}");
        let e = body(json!({"target": "area", "top": 0}))
            .request(&limits)
            .unwrap_err();
        assert!(e.message.contains("top 0"), "{e:?}");
        let e = body(json!({"target": "area", "budget": 201}))
            .request(&limits)
            .unwrap_err();
        assert_eq!(e.kind, "over_limit");
        assert_eq!(e.message, "budget 201 is above this server's limit of 200");
        // The library's default triage (16 × top) counts against the cap.
        let tight = InverseLimits {
            max_triage: 40,
            ..limits
        };
        let e = body(json!({"target": "area", "top": 3}))
            .request(&tight)
            .unwrap_err();
        assert_eq!(e.message, "triage 48 is above this server's limit of 40");
    }
}
