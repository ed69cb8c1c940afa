//! The closed sheet over 3×3 cells with the unit cell highlighted, edges numbered, joint
//! positions marked and the tiling vectors drawn.

use super::svg::SvgDoc;
use crate::cell::{End, UnitCell};
use crate::math::{perp, Real, Vec2};
use crate::topology::JointChoice;

const PALETTE: [&str; 8] = [
    "#8ecae6", "#ffb703", "#90be6d", "#f4a3a8", "#cdb4db", "#f9c74f", "#a8dadc", "#e9c46a",
];

/// SVG of `cell` in its closed state; `joints`, when given, marks the pin joints.
pub fn cell_svg(cell: &UnitCell, joints: Option<&[JointChoice]>) -> String {
    let l = cell.mean_edge_length();
    let sw = 0.02 * l;
    let mut doc = SvgDoc::default();
    for ku in -1..=1 {
        for kw in -1..=1 {
            let centre = ku == 0 && kw == 0;
            for (i, t) in cell.tiles.iter().enumerate() {
                let poly = cell.tile_polygon_at(i, [ku, kw]);
                let fill = PALETTE[t.aspect % PALETTE.len()];
                let style = if centre {
                    format!(r#"fill="{fill}" stroke="black" stroke-width="{sw:.5}""#)
                } else {
                    format!(
                        r##"fill="{fill}" fill-opacity="0.35" stroke="#777" stroke-width="{:.5}""##,
                        sw * 0.5
                    )
                };
                doc.polygon(&poly, &style);
            }
        }
    }
    // Unit cell outline (parallelogram spanned by u, w from the origin).
    let o = Vec2::zeros();
    let cell_poly = [o, cell.u, cell.u + cell.w, cell.w];
    doc.polygon(
        &cell_poly,
        &format!(
            r##"fill="none" stroke="#d62828" stroke-width="{:.5}" stroke-dasharray="{:.5}""##,
            sw * 2.0,
            l * 0.1
        ),
    );
    arrow(&mut doc, &o, &cell.u, "u", l);
    arrow(&mut doc, &o, &cell.w, "w", l);
    // Tile numbers and edge numbers.
    for (i, t) in cell.tiles.iter().enumerate() {
        doc.text(
            &t.centroid,
            0.3 * l,
            &format!("T{i}"),
            r#"font-weight="bold""#,
        );
    }
    for k in 0..cell.edges.len() {
        let a = cell.endpoint(k, End::A);
        let b = cell.endpoint(k, End::B);
        let mid = (a + b) * 0.5;
        let inward = perp(&(b - a)).normalize() * (0.12 * l);
        doc.circle(
            &(mid + inward),
            0.11 * l,
            r##"fill="white" stroke="#1d3557" stroke-width="0.004""##,
        );
        doc.text(
            &(mid + inward),
            0.14 * l,
            &k.to_string(),
            r##"fill="#1d3557""##,
        );
        if let Some(js) = joints {
            for &end in js[k].ends() {
                let p = cell.endpoint(k, end);
                doc.circle(
                    &p,
                    0.07 * l,
                    r##"fill="#e63946" stroke="black" stroke-width="0.01""##,
                );
            }
        }
    }
    let title = format!("{} {:?} cell {}", cell.family, cell.params, cell.dims);
    doc.finish(0.3 * l, 900.0, &title)
}

fn arrow(doc: &mut SvgDoc, from: &Vec2, vec: &Vec2, label: &str, l: Real) {
    let to = from + vec;
    let dir = vec.normalize();
    let side = perp(&dir);
    let head = 0.15 * l;
    doc.line(
        from,
        &to,
        &format!(r##"stroke="#0077b6" stroke-width="{:.5}""##, 0.04 * l),
    );
    doc.polygon(
        &[
            to,
            to - dir * head + side * head * 0.5,
            to - dir * head - side * head * 0.5,
        ],
        r##"fill="#0077b6""##,
    );
    doc.text(
        &(to + side * 0.2 * l),
        0.3 * l,
        label,
        r##"fill="#0077b6" font-style="italic""##,
    );
}
