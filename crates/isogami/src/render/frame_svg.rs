//! One deployment frame: the sheet at state q over 3×3 cells, the centre cell highlighted,
//! pin joints as dots, tiling vectors as arrows, optional extra outlines (e.g. collision
//! polygons), in a frame that can be shared by every frame of an animation.

use super::svg::SvgDoc;
use crate::kinematics::Mechanism;
use crate::math::{perp, rotation, DVec, Real, Vec2};

const PALETTE: [&str; 8] = [
    "#8ecae6", "#ffb703", "#90be6d", "#f4a3a8", "#cdb4db", "#f9c74f", "#a8dadc", "#e9c46a",
];

/// Space around the sheet, in units of the mean edge length L.
const MARGIN: Real = 0.3;
/// Extra space above the sheet for the frame label.
const LABEL_BAND: Real = 0.7;

/// An axis-aligned box in non-dimensional world coordinates (y up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewBox {
    /// Lower-left corner.
    pub min: Vec2,
    /// Upper-right corner.
    pub max: Vec2,
}

impl ViewBox {
    /// Width of the box.
    pub fn width(&self) -> Real {
        self.max.x - self.min.x
    }

    /// Height of the box.
    pub fn height(&self) -> Real {
        self.max.y - self.min.y
    }

    /// The smallest box holding both.
    pub fn union(&self, other: &ViewBox) -> ViewBox {
        ViewBox {
            min: self.min.inf(&other.min),
            max: self.max.sup(&other.max),
        }
    }

    fn around(points: impl IntoIterator<Item = Vec2>) -> Option<ViewBox> {
        points
            .into_iter()
            .filter(|p| p.x.is_finite() && p.y.is_finite())
            .fold(None, |b: Option<ViewBox>, p| {
                Some(b.map_or(ViewBox { min: p, max: p }, |b| ViewBox {
                    min: b.min.inf(&p),
                    max: b.max.sup(&p),
                }))
            })
    }

    /// The box grown by the standard margin, with a band on top for the label.
    fn framed(self) -> ViewBox {
        ViewBox {
            min: self.min - Vec2::new(MARGIN, MARGIN),
            max: self.max + Vec2::new(MARGIN, MARGIN + LABEL_BAND),
        }
    }
}

/// How [`frame_svg`] draws a frame.
#[derive(Debug, Clone)]
pub struct FrameStyle {
    /// Width of the SVG in pixels (the height follows the box's aspect ratio); a value that
    /// is not a positive number means the default, 600.
    pub width_px: Real,
    /// Fixed frame; `None` frames this state alone. Use [`view_box_for`] so that all frames
    /// of an animation share one box. Content outside a given box grows it; an empty or
    /// non-finite box is ignored.
    pub view_box: Option<ViewBox>,
    /// Extra closed outlines in world coordinates (e.g. kerf-inset collision polygons).
    pub extra_polygons: Vec<Vec<Vec2>>,
    /// SVG presentation attributes of the extra outlines.
    pub extra_style: String,
    /// Draw the pin joints.
    pub show_joints: bool,
    /// Draw the unit cell outline and the tiling vectors u, w.
    pub show_lattice: bool,
    /// Text drawn above the sheet, e.g. "t = 0.50".
    pub label: Option<String>,
    /// The SVG's `<title>`.
    pub title: String,
}

impl Default for FrameStyle {
    fn default() -> Self {
        FrameStyle {
            width_px: 600.0,
            view_box: None,
            extra_polygons: Vec::new(),
            extra_style: r##"fill="none" stroke="#d62828" stroke-width="0.012""##.to_string(),
            show_joints: true,
            show_lattice: true,
            label: None,
            title: "isogami deployment frame".to_string(),
        }
    }
}

/// Cell offsets of the 3×3 block, centre last so that it is drawn on top.
fn block() -> impl Iterator<Item = [i32; 2]> {
    (-1..=1)
        .flat_map(|ku| (-1..=1).map(move |kw| [ku, kw]))
        .filter(|k| *k != [0, 0])
        .chain(std::iter::once([0, 0]))
}

fn shift(mech: &Mechanism, q: &DVec, k: [i32; 2]) -> Vec2 {
    let (u, w) = mech.lattice(q);
    u * Real::from(k[0]) + w * Real::from(k[1])
}

/// World position of joint `j` (on tile a, centre cell) at state q.
fn joint_point(mech: &Mechanism, q: &DVec, j: usize) -> Vec2 {
    let joint = &mech.joints[j];
    let (p, th) = mech.pose(q, joint.tile_a);
    rotation(th) * joint.s_a + p
}

/// Anchor of the lattice arrows and the cell outline: tile 0's reference point, so that they
/// move with the sheet however the solver pins it.
fn anchor(mech: &Mechanism, q: &DVec) -> Vec2 {
    if mech.tile_count() == 0 {
        Vec2::zeros()
    } else {
        mech.pose(q, 0).0
    }
}

/// Everything the frame draws that must stay inside the box.
fn extent_points(mech: &Mechanism, q: &DVec) -> Vec<Vec2> {
    let mut pts = Vec::new();
    for k in block() {
        for i in 0..mech.tile_count() {
            pts.extend(mech.tile_polygon(q, i, k));
        }
    }
    let (u, w) = mech.lattice(q);
    let o = anchor(mech, q);
    pts.extend([o, o + u, o + w, o + u + w]);
    pts
}

/// A box that holds every state in `states` (margins and label band included), for a
/// fixed-frame animation. Non-finite coordinates are ignored; with no usable state, the box
/// of the closed state `mech.rest`.
pub fn view_box_for(mech: &Mechanism, states: &[DVec]) -> ViewBox {
    let usable = states.iter().filter(|q| q.len() == mech.layout.len());
    let boxed = ViewBox::around(usable.flat_map(|q| extent_points(mech, q)))
        .or_else(|| ViewBox::around(extent_points(mech, &mech.rest)))
        .unwrap_or(ViewBox {
            min: Vec2::zeros(),
            max: Vec2::zeros(),
        });
    boxed.framed()
}

/// SVG of the deployed sheet at state `q` (non-dimensional coordinates). Every tile polygon
/// carries `class="tile"` (9 × tiles of them), extra outlines `class="extra"`, joints
/// `class="joint"`. `q` must have `mech.layout.len()` entries (as for [`Mechanism`]'s own
/// methods); elements with a non-finite coordinate are left out rather than written as NaN.
pub fn frame_svg(mech: &Mechanism, q: &DVec, opts: &FrameStyle) -> String {
    let usable = |b: &ViewBox| all_finite(&[b.min, b.max]) && b.width() > 0.0 && b.height() > 0.0;
    let vb = opts.view_box.filter(usable).unwrap_or_else(|| {
        ViewBox::around(extent_points(mech, q))
            .unwrap_or(ViewBox {
                min: Vec2::zeros(),
                max: Vec2::zeros(),
            })
            .framed()
    });
    let mut doc = SvgDoc::default();
    // An invisible box: the document's bounds are exactly the view box when all content
    // lies inside it, which view_box_for guarantees.
    doc.polygon(
        &[
            vb.min,
            Vec2::new(vb.max.x, vb.min.y),
            vb.max,
            Vec2::new(vb.min.x, vb.max.y),
        ],
        r#"fill="none" stroke="none" class="frame""#,
    );
    let sw = 0.02;
    for k in block() {
        let centre = k == [0, 0];
        for i in 0..mech.tile_count() {
            let fill = PALETTE[i % PALETTE.len()];
            let style = if centre {
                format!(r#"class="tile" fill="{fill}" stroke="black" stroke-width="{sw}""#)
            } else {
                format!(
                    r##"class="tile" fill="{fill}" fill-opacity="0.45" stroke="#555" stroke-width="{}""##,
                    sw * 0.5
                )
            };
            let poly = mech.tile_polygon(q, i, k);
            if all_finite(&poly) {
                doc.polygon(&poly, &style);
            }
        }
    }
    for poly in &opts.extra_polygons {
        if poly.len() >= 2 && all_finite(poly) {
            doc.polygon(poly, &format!(r#"class="extra" {}"#, opts.extra_style));
        }
    }
    let (u, w) = mech.lattice(q);
    let o = anchor(mech, q);
    if opts.show_lattice && all_finite(&[o, u, w]) {
        doc.polygon(
            &[o, o + u, o + u + w, o + w],
            r##"class="cell" fill="none" stroke="#d62828" stroke-width="0.03" stroke-dasharray="0.1""##,
        );
        arrow(&mut doc, &o, &u, "u");
        arrow(&mut doc, &o, &w, "w");
    }
    if opts.show_joints {
        for k in block() {
            let centre = k == [0, 0];
            let d = shift(mech, q, k);
            for j in 0..mech.joints.len() {
                let p = joint_point(mech, q, j) + d;
                if !all_finite(&[p]) {
                    continue;
                }
                if centre {
                    doc.circle(
                        &p,
                        0.05,
                        r##"class="joint" fill="#e63946" stroke="black" stroke-width="0.01""##,
                    );
                } else {
                    doc.circle(&p, 0.035, r##"class="joint" fill="#9d4b52""##);
                }
            }
        }
    }
    if let Some(label) = &opts.label {
        let at = Vec2::new(0.5 * (vb.min.x + vb.max.x), vb.max.y - 0.5 * LABEL_BAND);
        doc.text(&at, 0.4, label, r#"fill="black""#);
    }
    let width = if opts.width_px.is_finite() && opts.width_px > 0.0 {
        opts.width_px
    } else {
        FrameStyle::default().width_px
    };
    doc.finish(0.0, width, &opts.title)
}

fn all_finite(pts: &[Vec2]) -> bool {
    pts.iter().all(|p| p.x.is_finite() && p.y.is_finite())
}

fn arrow(doc: &mut SvgDoc, from: &Vec2, vec: &Vec2, label: &str) {
    let len = vec.norm();
    if !(len > 1e-9 && len.is_finite()) {
        return;
    }
    let to = from + vec;
    let dir = vec / len;
    let side = perp(&dir);
    let head = 0.15_f64.min(0.5 * len);
    doc.line(
        from,
        &(to - dir * head * 0.5),
        r##"class="lattice" stroke="#0077b6" stroke-width="0.04""##,
    );
    doc.polygon(
        &[
            to,
            to - dir * head + side * head * 0.5,
            to - dir * head - side * head * 0.5,
        ],
        r##"class="lattice" fill="#0077b6""##,
    );
    doc.text(
        &(to - dir * 0.25 + side * 0.2),
        0.3,
        label,
        r##"fill="#0077b6" font-style="italic""##,
    );
}
