//! The canonical text form of a target: every weight and tolerance written, numbers in
//! Rust's shortest round-trip form, so that it parses back to an equal target.

use crate::inverse::target::{Constraints, Goal, Target};
use std::fmt;

impl fmt::Display for Goal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Goal::Area { ratio: None } => f.write_str("area"),
            Goal::Area { ratio: Some(r) } => write!(f, "area({r})"),
            Goal::Uniform {} => f.write_str("uniform"),
            Goal::Expansion {
                angle_deg,
                value: None,
            } => write!(f, "expansion({angle_deg})"),
            Goal::Expansion {
                angle_deg,
                value: Some(e),
            } => write!(f, "expansion({angle_deg},{e})"),
            Goal::Poisson { nu } => write!(f, "poisson({nu})"),
            Goal::LockF { f: m } => {
                write!(f, "lock-f({},{},{},{})", m[0][0], m[0][1], m[1][0], m[1][1])
            }
            Goal::Lock {
                min,
                max,
                angle_deg,
            } => match angle_deg {
                Some(a) => write!(f, "lock({min},{max},{a})"),
                None => write!(f, "lock({min},{max})"),
            },
            Goal::Path { points } => {
                let p: Vec<String> = points
                    .iter()
                    .map(|p| format!("{}:{}:{}", p.t, p.min, p.max))
                    .collect();
                write!(f, "path({})", p.join(","))
            }
        }
    }
}

impl fmt::Display for Constraints {
    /// The constraints as `; key op value` items (empty when there are none).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let join = |v: Vec<String>| v.join(",");
        if !self.families.is_empty() {
            let names = self.families.iter().map(|x| x.to_string()).collect();
            write!(f, "; families={}", join(names))?;
        }
        if !self.cells.is_empty() {
            write!(
                f,
                "; cells={}",
                join(self.cells.iter().map(|x| x.to_string()).collect())
            )?;
        }
        if let Some(n) = self.min_tiles {
            write!(f, "; tiles>={n}")?;
        }
        if let Some(n) = self.max_tiles {
            write!(f, "; tiles<={n}")?;
        }
        if let Some(r) = self.min_rotation_deg {
            write!(f, "; rotation>={r}")?;
        }
        if let Some(k) = self.min_kerf {
            write!(f, "; kerf>={k}")?;
        }
        if let Some(h) = self.min_hinge {
            write!(f, "; hinge>={h}")?;
        }
        Ok(())
    }
}

impl fmt::Display for Target {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let terms: Vec<String> = self
            .terms
            .iter()
            .map(|t| match t.tolerance {
                Some(tol) => format!("{}*{}~{tol}", t.weight, t.goal),
                None => format!("{}*{}", t.weight, t.goal),
            })
            .collect();
        write!(f, "{}{}", terms.join(" + "), self.constraints)
    }
}
