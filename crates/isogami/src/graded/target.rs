//! What the opened sheet should look like: an outline, star-shaped about its centre, given
//! as its radius in every direction (a disc, an ellipse, or a simple polygon seen whole from
//! its centroid). The fit measures radial error: a point p of the opened boundary is off by
//! |p| − ρ(φ(p)), and a relative error (|p| − ρ)/ρ is what "within 2 %" means.

use super::error::GradedError;
use crate::geometry::signed_area;
use crate::math::{cross, Real, Vec2};
use crate::settings_error::short_real;
use std::f64::consts::PI;

/// Most elongated outline taken: an ellipse's longer semi-axis over its shorter, and for a
/// polygon its bounding box's squared diagonal over its area (about length over width for a
/// thin one; a square has 2). Thinner outlines are no shapes a sheet of tiles can fill, and
/// scaled to the sheet's area they overflow the numbers.
pub const MAX_ELONGATION: Real = 100.0;

/// A target outline centred on the origin. Sizes are relative: the optimisation scales the
/// outline to the area the design's own opened sheet covers.
#[derive(Debug, Clone, PartialEq)]
pub enum Outline {
    /// A disc.
    Disc,
    /// An ellipse with semi-axes along x and y in this ratio.
    Ellipse {
        /// Semi-axis along x.
        a: Real,
        /// Semi-axis along y.
        b: Real,
    },
    /// A simple polygon, every point of which its centroid sees (star-shaped).
    Polygon(Vec<Vec2>),
}

impl Outline {
    /// Checks the outline: positive finite axes; a polygon of at least three points,
    /// non-zero area, star-shaped about its centroid; neither more elongated than
    /// [`MAX_ELONGATION`]. A polygon comes back centred and
    /// counter-clockwise.
    pub fn validated(self) -> Result<Outline, GradedError> {
        match self {
            Outline::Disc => Ok(Outline::Disc),
            Outline::Ellipse { a, b } => {
                if !(a.is_finite() && b.is_finite() && a > 0.0 && b > 0.0) {
                    return Err(GradedError::BadTarget(format!(
                        "an ellipse needs two positive semi-axes, not {}, {}",
                        short_real(a),
                        short_real(b)
                    )));
                }
                let elongation = a.max(b) / a.min(b);
                if elongation.is_nan() || elongation > MAX_ELONGATION {
                    return Err(GradedError::BadTarget(format!(
                        "an ellipse of semi-axes {}, {} is {} times longer than wide; \
                         at most {MAX_ELONGATION} is taken",
                        short_real(a),
                        short_real(b),
                        short_real((elongation * 100.0).round() / 100.0)
                    )));
                }
                Ok(Outline::Ellipse { a, b })
            }
            Outline::Polygon(mut p) => {
                if p.len() < 3 || p.iter().any(|v| !v.x.is_finite() || !v.y.is_finite()) {
                    return Err(GradedError::BadTarget(
                        "an outline needs at least three finite points".into(),
                    ));
                }
                let area = signed_area(&p);
                let diag = bbox_diag(&p);
                if !(area.is_finite() && diag.is_finite()) {
                    return Err(GradedError::BadTarget(
                        "the outline's size overflows (coordinates too large)".into(),
                    ));
                }
                if area.abs() <= 1e-12 * diag.powi(2) {
                    return Err(GradedError::BadTarget(
                        "the outline encloses no area".into(),
                    ));
                }
                let elongation = diag.powi(2) / area.abs();
                if elongation.is_nan() || elongation > MAX_ELONGATION {
                    return Err(GradedError::BadTarget(format!(
                        "the outline is too thin (bounding-box diagonal² / area = {}; at most \
                         {MAX_ELONGATION} is taken)",
                        short_real((elongation * 100.0).round() / 100.0)
                    )));
                }
                if area < 0.0 {
                    p.reverse();
                }
                let c = polygon_centroid(&p);
                for v in &mut p {
                    *v -= c;
                }
                // Star-shaped about the centroid: every edge turns counter-clockwise as seen
                // from it (the centroid is strictly inside each edge's half-plane).
                let n = p.len();
                let scale = bbox_diag(&p);
                for k in 0..n {
                    if cross(&p[k], &p[(k + 1) % n]) <= 1e-9 * scale * scale {
                        return Err(GradedError::BadTarget(format!(
                            "the outline is not seen whole from its centroid (edge {k}); \
                             give a star-shaped outline"
                        )));
                    }
                }
                Ok(Outline::Polygon(p))
            }
        }
    }

    /// The outline drawn at `scale`: the polygon's own corners, or `samples` points around a
    /// disc or an ellipse, counter-clockwise.
    pub fn boundary(&self, scale: Real, samples: usize) -> Vec<[Real; 2]> {
        match self {
            Outline::Polygon(p) => p.iter().map(|v| [scale * v.x, scale * v.y]).collect(),
            _ => (0..samples.max(3))
                .map(|k| {
                    let phi = 2.0 * PI * k as Real / samples.max(3) as Real;
                    let dir = Vec2::new(phi.cos(), phi.sin());
                    let rho = scale * self.radius(dir).0;
                    [rho * dir.x, rho * dir.y]
                })
                .collect(),
        }
    }

    /// Area of the outline at scale 1.
    pub fn area(&self) -> Real {
        match self {
            Outline::Disc => PI,
            Outline::Ellipse { a, b } => PI * a * b,
            Outline::Polygon(p) => signed_area(p),
        }
    }

    /// How much longer than wide: the square root of the ratio of the outline's principal
    /// second moments of area about its centroid (an ellipse's axis ratio; 1 for a disc).
    pub fn elongation(&self) -> Real {
        match self {
            Outline::Disc => 1.0,
            Outline::Ellipse { a, b } => a.max(*b) / a.min(*b),
            Outline::Polygon(p) => {
                let c = polygon_centroid(p);
                let (mut xx, mut yy, mut xy) = (0.0, 0.0, 0.0);
                let n = p.len();
                for k in 0..n {
                    let (u, v) = (p[k] - c, p[(k + 1) % n] - c);
                    let w = cross(&u, &v);
                    xx += w * (u.y * u.y + u.y * v.y + v.y * v.y);
                    yy += w * (u.x * u.x + u.x * v.x + v.x * v.x);
                    xy += w * (u.x * v.y + 2.0 * u.x * u.y + 2.0 * v.x * v.y + v.x * u.y);
                }
                // Second moments (the common factor 1/12, 1/24 for xy, cancels in the ratio).
                let (ixx, iyy, ixy) = (xx / 12.0, yy / 12.0, xy / 24.0);
                let mean = 0.5 * (ixx + iyy);
                let spread = (0.25 * (ixx - iyy) * (ixx - iyy) + ixy * ixy).sqrt();
                let (big, small) = (mean + spread, mean - spread);
                if small > 0.0 {
                    (big / small).sqrt()
                } else {
                    Real::INFINITY
                }
            }
        }
    }

    /// Radius ρ(φ) of the outline at scale 1 in the direction of `p` (not the origin), and
    /// its gradient with respect to p.
    pub fn radius(&self, p: Vec2) -> (Real, Vec2) {
        let r2 = p.norm_squared();
        // dφ/dp = (−y, x)/|p|²
        let dphi = Vec2::new(-p.y, p.x) / r2;
        match self {
            Outline::Disc => (1.0, Vec2::zeros()),
            Outline::Ellipse { a, b } => {
                // ρ(φ) = ab / sqrt(b²cos²φ + a²sin²φ)
                let phi = p.y.atan2(p.x);
                let (s, c) = phi.sin_cos();
                let d = b * b * c * c + a * a * s * s;
                let rho = a * b / d.sqrt();
                let dd = 2.0 * s * c * (a * a - b * b);
                let drho = -0.5 * a * b * d.powf(-1.5) * dd;
                (rho, dphi * drho)
            }
            Outline::Polygon(poly) => {
                let n = poly.len();
                let dir = p / r2.sqrt();
                for k in 0..n {
                    let (a, b) = (poly[k], poly[(k + 1) % n]);
                    // The ray from the origin along dir meets edge a→b where
                    // ρ = cross(a, b) / cross(dir, b − a).
                    // The ray lies between a and b: counter-clockwise of a, clockwise of b.
                    if cross(&a, &dir) >= 0.0 && cross(&dir, &b) >= 0.0 {
                        let e = b - a;
                        let den = cross(&dir, &e);
                        if den.abs() < 1e-300 {
                            continue;
                        }
                        let rho = cross(&a, &b) / den;
                        // d(dir)/dφ = perp(dir); dρ/dφ = −ρ·cross(perp(dir), e)/den
                        let pd = Vec2::new(-dir.y, dir.x);
                        let drho = -rho * cross(&pd, &e) / den;
                        return (rho, dphi * drho);
                    }
                }
                // Unreachable for a validated star-shaped polygon; a safe answer otherwise.
                (
                    poly.iter().map(|v| v.norm()).fold(0.0, Real::max),
                    Vec2::zeros(),
                )
            }
        }
    }
}

fn bbox_diag(p: &[Vec2]) -> Real {
    let (mut lo, mut hi) = (p[0], p[0]);
    for v in p {
        lo = lo.inf(v);
        hi = hi.sup(v);
    }
    (hi - lo).norm()
}

fn polygon_centroid(p: &[Vec2]) -> Vec2 {
    let n = p.len();
    let mut c = Vec2::zeros();
    let mut a = 0.0;
    for k in 0..n {
        let (u, v) = (p[k], p[(k + 1) % n]);
        let w = cross(&u, &v);
        a += w;
        c += (u + v) * w;
    }
    c / (3.0 * a)
}

/// Parses a target outline's text: `disc`, `ellipse:A,B`, or `polygon:x,y;x,y;…`.
pub fn parse_outline(text: &str) -> Result<Outline, GradedError> {
    let bad = |m: &str| GradedError::BadTarget(format!("{m} (target {text:?})"));
    let (kind, rest) = text.split_once(':').unwrap_or((text, ""));
    let numbers = |s: &str| -> Result<Vec<Real>, GradedError> {
        s.split(',')
            .map(|v| {
                v.trim()
                    .parse::<Real>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| bad("a number is not a finite number"))
            })
            .collect()
    };
    let outline = match kind {
        "disc" if rest.is_empty() => Outline::Disc,
        "ellipse" => match numbers(rest)?[..] {
            [a, b] => Outline::Ellipse { a, b },
            _ => return Err(bad("an ellipse is ellipse:A,B")),
        },
        "polygon" => Outline::Polygon(
            rest.split(';')
                .map(|pair| match numbers(pair)?[..] {
                    [x, y] => Ok(Vec2::new(x, y)),
                    _ => Err(bad("a polygon is polygon:x,y;x,y;…")),
                })
                .collect::<Result<_, _>>()?,
        ),
        _ => return Err(bad("a target is disc, ellipse:A,B or polygon:x,y;x,y;…")),
    };
    outline.validated()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Elongation from second moments: an ellipse's axis ratio, and the same for an
    /// ellipse drawn as a polygon at any turn; a 3 × 1 rectangle's is 3; a disc's and a
    /// square's 1.
    #[test]
    fn elongation_is_the_axis_ratio() {
        assert_eq!(Outline::Disc.elongation(), 1.0);
        assert_eq!(Outline::Ellipse { a: 1.0, b: 4.0 }.elongation(), 4.0);
        for turn in [0.0, 0.4, 1.3] {
            let (a, b) = (2.5, 1.0);
            let (s, c) = Real::sin_cos(turn);
            let p: Vec<Vec2> = (0..720)
                .map(|k| {
                    let t = std::f64::consts::TAU * k as Real / 720.0;
                    let (x, y) = (a * t.cos(), b * t.sin());
                    Vec2::new(c * x - s * y, s * x + c * y)
                })
                .collect();
            let e = Outline::Polygon(p).elongation();
            assert!((e - a / b).abs() < 1e-3, "turn {turn}: {e}");
        }
        let rect = parse_outline("polygon:0,0;3,0;3,1;0,1").unwrap();
        assert!((rect.elongation() - 3.0).abs() < 1e-12);
        let square = parse_outline("polygon:0,0;1,0;1,1;0,1").unwrap();
        assert!((square.elongation() - 1.0).abs() < 1e-12);
    }

    /// The radius gradient of every outline matches central differences.
    #[test]
    fn radius_gradients_match_finite_differences() {
        let outlines = [
            Outline::Disc,
            Outline::Ellipse { a: 2.0, b: 0.7 },
            parse_outline("polygon:0,-1;2,0;1,2;-1,2;-2,0").unwrap(),
            parse_outline("polygon:-1,-1;2,-1;2,2;-1,2").unwrap(),
        ];
        for o in &outlines {
            for k in 0..24 {
                let phi = 0.1 + k as Real * 0.26;
                let p = Vec2::new(phi.cos(), phi.sin()) * (0.5 + 0.1 * k as Real);
                let (_, g) = o.radius(p);
                let h = 1e-6;
                for d in 0..2 {
                    let mut e = Vec2::zeros();
                    e[d] = h;
                    let fd = (o.radius(p + e).0 - o.radius(p - e).0) / (2.0 * h);
                    assert!(
                        (fd - g[d]).abs() < 1e-5 * (1.0 + fd.abs()),
                        "{o:?} at {p:?}: {fd} vs {}",
                        g[d]
                    );
                }
            }
        }
    }

    /// A polygon's radius is where the ray meets its boundary: the points ρ(φ)·dir lie on the
    /// square's edges.
    #[test]
    fn a_square_outline_has_its_edges_as_radius() {
        let o = parse_outline("polygon:-1,-1;1,-1;1,1;-1,1").unwrap();
        for k in 0..36 {
            let phi = k as Real * PI / 18.0 + 0.01;
            let dir = Vec2::new(phi.cos(), phi.sin());
            let rho = o.radius(dir).0;
            assert!(rho > 0.0, "{rho} at {phi}");
            let q = dir * rho;
            assert!((q.x.abs().max(q.y.abs()) - 1.0).abs() < 1e-12, "{q:?}");
        }
    }

    #[test]
    fn bad_targets_are_refused_in_words() {
        for text in [
            "circle",
            "ellipse:1",
            "ellipse:1,-2",
            "polygon:0,0;1,0",
            "polygon:0,0;4,0;4,4;3,4;3,1;1,1;1,4;0,4",
            // Issue 42: scaled to the sheet's area, these overflowed to infinity.
            "ellipse:1,1e-300",
            "ellipse:1e300,1",
            "ellipse:100.5,1",
            "polygon:0,0;1e308,0;0,1e308",
            "polygon:0,0;1000,0;1000,1;0,1",
        ] {
            let e = parse_outline(text).unwrap_err();
            assert!(
                e.to_string().contains("target") || e.to_string().contains("outline"),
                "{e}"
            );
            assert_eq!(e.to_string().lines().count(), 1, "{e}");
        }
        // At the limit, and a square, are taken.
        for text in ["ellipse:100,1", "ellipse:1,100", "polygon:0,0;1,0;1,1;0,1"] {
            parse_outline(text).unwrap();
        }
    }
}
