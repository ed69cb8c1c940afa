//! Target outlines drawn in a vector editor (`--target @outline.svg`): the one closed shape
//! of an SVG document as an [`Outline::Polygon`].
//!
//! The shape is a `<path>` (every command, relative or absolute), a `<polygon>`, a closed
//! `<polyline>`, a `<rect>` (rounded corners too), a `<circle>` or an `<ellipse>`. The
//! `transform`s of the shape and of its ancestors are applied and SVG's y-down is flipped to
//! y-up, so the outline looks as drawn. Curves are flattened to a polyline within
//! [`FLATTEN_TOLERANCE`] of the shape's size (arcs, circles and ellipses go through cubic
//! Béziers first, a quarter turn each at most: within 2.7e-4 of their radius). Only the
//! shape counts: position and size are dropped (the optimisation scales the outline to the
//! sheet), so the document's viewBox and units do not matter.
//!
//! A document with several shapes is refused, naming them, rather than one of them picked:
//! a frame, a background or a guide is often the largest shape of a drawing, and grading
//! towards it by mistake would go unnoticed. Not counted: shapes in `<defs>`, `<clipPath>`,
//! `<mask>`, `<marker>`, `<pattern>` or `<symbol>` (not drawn where they stand), under
//! `display="none"`, or in another XML namespace (an editor's own data); `<use>` and
//! `<text>` are ignored.
//!
//! Parsing is `roxmltree` (XML) and `svgtypes` (path data, points, transforms, lengths). No
//! I/O: the front ends read the file (bounded by [`MAX_SVG_BYTES`]).
//!
//! Hostile documents are refused before they cost anything, whichever front end passes them
//! on: a text longer than [`MAX_SVG_BYTES`], entities whose expansion could exceed
//! [`MAX_EXPANDED_BYTES`] (bounded from the declarations before parsing, see
//! [`entity_expansion_bound`]), more than [`MAX_NODES`] XML nodes, elements nested deeper
//! than [`MAX_DEPTH`], or an outline of more than [`MAX_OUTLINE_VERTICES`] vertices.

use super::error::GradedError;
use super::target::Outline;
use crate::geometry::{is_simple_problem, SimplicityProblem};
use crate::math::{Real, Vec2};
use std::str::FromStr;
use svgtypes::{Length, LengthUnit, PointsParser, SimplePathSegment, SimplifyingPathParser};

/// Curves are flattened to within this fraction of the shape's size (the diagonal of its
/// bounding box).
pub const FLATTEN_TOLERANCE: Real = 1e-4;

/// Most line segments one curve is flattened into.
const MAX_PIECES: usize = 512;

/// Longest SVG text read (bytes).
pub const MAX_SVG_BYTES: usize = 16 << 20;

/// Most bytes the document's entity references may expand to (an upper bound computed from
/// the declarations before parsing).
pub const MAX_EXPANDED_BYTES: usize = 4 << 20;

/// Most XML nodes (elements, text, comments) in the document.
pub const MAX_NODES: u32 = 1_000_000;

/// Deepest nesting of drawn elements below the root.
pub const MAX_DEPTH: usize = 256;

/// Most vertices of the outline after curves are flattened: a path of more pieces is
/// refused, curves that would flatten to more are flattened more coarsely.
pub const MAX_OUTLINE_VERTICES: usize = 4096;

/// Arm length of the cubic Bézier of a quarter ellipse, as a fraction of its radius.
const KAPPA: Real = 0.552_284_749_830_793_4;

const SVG_NS: &str = "http://www.w3.org/2000/svg";

/// Elements whose content is not drawn where it stands (or holds no shapes).
const NOT_DRAWN: [&str; 13] = [
    "defs",
    "clipPath",
    "mask",
    "marker",
    "pattern",
    "symbol",
    "metadata",
    "title",
    "desc",
    "style",
    "script",
    "foreignObject",
    "text",
];

/// The shape elements.
const SHAPES: [&str; 7] = [
    "path", "polygon", "polyline", "rect", "circle", "ellipse", "line",
];

/// The outline of `svg_text`'s one closed shape, centred and counter-clockwise (see the
/// module's documentation). Errors name the problem in one line: not SVG, no shape, several
/// shapes (how many, which), an open path or one of several loops, a self-intersecting
/// shape, one not star-shaped about its centroid ([`Outline::validated`]), a non-finite
/// coordinate.
pub fn outline_from_svg(svg_text: &str) -> Result<Outline, GradedError> {
    if svg_text.len() > MAX_SVG_BYTES {
        return Err(bad(format!(
            "the SVG is {} bytes, more than the {} MiB read",
            svg_text.len(),
            MAX_SVG_BYTES >> 20
        )));
    }
    let bound = entity_expansion_bound(svg_text);
    if bound > MAX_EXPANDED_BYTES {
        return Err(bad(format!(
            "the SVG's entities could expand to {bound} bytes, more than the {} MiB allowed",
            MAX_EXPANDED_BYTES >> 20
        )));
    }
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        nodes_limit: MAX_NODES,
        ..roxmltree::ParsingOptions::default()
    };
    let doc = roxmltree::Document::parse_with_options(svg_text, options).map_err(|e| match e {
        roxmltree::Error::NodesLimitReached => bad(format!(
            "the SVG has more than {MAX_NODES} XML nodes; keep only the outline"
        )),
        e => bad(format!("not an SVG document ({e})")),
    })?;
    let root = doc.root_element();
    if !in_svg(root) || root.tag_name().name() != "svg" {
        return Err(bad(format!(
            "not an SVG document (its root element is <{}>, not <svg>)",
            root.tag_name().name()
        )));
    }
    let mut found = Vec::new();
    collect(root, transform_of(root)?, 0, &mut found)?;
    let (node, transform) = match found[..] {
        [] => {
            return Err(bad(
                "the SVG has no shape (a path, polygon, rect, circle or ellipse) to take as the outline",
            ))
        }
        [one] => one,
        _ => {
            let mut names: Vec<String> = found.iter().take(4).map(|f| describe(f.0)).collect();
            if found.len() > 4 {
                names.push("…".into());
            }
            return Err(bad(format!(
                "the SVG has {} shapes ({}): keep only the outline, one closed shape",
                found.len(),
                names.join(", ")
            )));
        }
    };
    let what = describe(node);
    let polygon = flatten(&segments(node)?, transform, &what)?;
    Outline::Polygon(polygon).validated().map_err(|e| match e {
        GradedError::BadTarget(m) => bad(format!("{what}: {m}")),
        other => other,
    })
}

/// An upper bound on the bytes `text`'s general entity references can expand to, from the
/// document's internal DTD subset alone (no parsing): every reference in the document to a
/// name other than XML's five predefined ones counts as the whole subset's length, times
/// the 256 references roxmltree resolves at most below one reference when declarations
/// refer to other entities. Zero for a document that declares no entity.
pub fn entity_expansion_bound(text: &str) -> usize {
    let Some(open) = text.find("<!DOCTYPE") else {
        return 0;
    };
    let after = &text[open..];
    // The internal subset: from the first `[` before the DOCTYPE's `>` to the `]>` after it.
    let Some(start) = after
        .find(['[', '>'])
        .filter(|&k| after.as_bytes()[k] == b'[')
    else {
        return 0;
    };
    let Some(len) = after[start..].find("]") else {
        return usize::MAX;
    };
    let subset = &after[start + 1..start + len];
    if !subset.contains("<!ENTITY") {
        return 0;
    }
    let body = &after[start + len..];
    let nested = entity_references(subset) > 0;
    let per_reference = subset.len().saturating_mul(if nested { 256 } else { 1 });
    entity_references(body).saturating_mul(per_reference)
}

/// How many general entity references (`&name;`, not a character reference nor one of
/// XML's predefined five) `text` holds, or parameter entity references (`%name;`).
fn entity_references(text: &str) -> usize {
    const PREDEFINED: [&str; 5] = ["amp;", "lt;", "gt;", "quot;", "apos;"];
    text.match_indices(['&', '%'])
        .filter(|&(k, mark)| {
            let rest = &text[k + 1..];
            let name = rest
                .split(|c: char| !(c.is_alphanumeric() || matches!(c, '_' | ':' | '-' | '.')))
                .next()
                .unwrap_or("");
            let starts = name
                .chars()
                .next()
                .is_some_and(|c| c.is_alphabetic() || c == '_' || c == ':');
            let closed = rest[name.len()..].starts_with(';');
            starts && closed && (mark == "%" || !PREDEFINED.iter().any(|p| rest.starts_with(p)))
        })
        .count()
}

fn bad(message: impl Into<String>) -> GradedError {
    GradedError::BadTarget(message.into())
}

/// An element of the SVG namespace (or of none: hand-written files often omit it).
fn in_svg(node: roxmltree::Node<'_, '_>) -> bool {
    node.is_element() && matches!(node.tag_name().namespace(), None | Some(SVG_NS))
}

/// `<path id="outline">`, for messages.
fn describe(node: roxmltree::Node<'_, '_>) -> String {
    match node.attribute("id") {
        Some(id) => format!("<{} id=\"{id}\">", node.tag_name().name()),
        None => format!("<{}>", node.tag_name().name()),
    }
}

/// An affine map x' = a x + c y + e, y' = b x + d y + f (SVG's matrix order).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Affine([Real; 6]);

impl Affine {
    const IDENTITY: Affine = Affine([1.0, 0.0, 0.0, 1.0, 0.0, 0.0]);

    /// `self` after `inner`: a point goes through `inner` first.
    fn after(&self, inner: &Affine) -> Affine {
        let [a, b, c, d, e, f] = self.0;
        let [a2, b2, c2, d2, e2, f2] = inner.0;
        Affine([
            a * a2 + c * b2,
            b * a2 + d * b2,
            a * c2 + c * d2,
            b * c2 + d * d2,
            a * e2 + c * f2 + e,
            b * e2 + d * f2 + f,
        ])
    }

    fn apply(&self, p: Vec2) -> Vec2 {
        let [a, b, c, d, e, f] = self.0;
        Vec2::new(a * p.x + c * p.y + e, b * p.x + d * p.y + f)
    }
}

/// The element's own `transform` attribute (identity without one).
fn transform_of(node: roxmltree::Node<'_, '_>) -> Result<Affine, GradedError> {
    let Some(text) = node.attribute("transform") else {
        return Ok(Affine::IDENTITY);
    };
    let t = svgtypes::Transform::from_str(text).map_err(|e| {
        bad(format!(
            "{}: transform=\"{text}\" cannot be read ({e})",
            describe(node)
        ))
    })?;
    Ok(Affine([t.a, t.b, t.c, t.d, t.e, t.f]))
}

/// `display="none"`, as an attribute or in `style`.
fn hidden(node: roxmltree::Node<'_, '_>) -> bool {
    let none = |v: &str| v.trim() == "none";
    node.attribute("display").is_some_and(none)
        || node.attribute("style").is_some_and(|s| {
            s.split(';').any(|decl| {
                decl.split_once(':')
                    .is_some_and(|(k, v)| k.trim() == "display" && none(v))
            })
        })
}

/// Every drawn shape below `node` (at `depth` below the root), with its transform to the
/// document's coordinates. Refused past [`MAX_DEPTH`] levels (the recursion's bound).
fn collect<'a, 'input>(
    node: roxmltree::Node<'a, 'input>,
    transform: Affine,
    depth: usize,
    found: &mut Vec<(roxmltree::Node<'a, 'input>, Affine)>,
) -> Result<(), GradedError> {
    if depth >= MAX_DEPTH {
        return Err(bad(format!(
            "the SVG nests elements deeper than {MAX_DEPTH} levels"
        )));
    }
    for child in node.children().filter(|c| in_svg(*c)) {
        let name = child.tag_name().name();
        if NOT_DRAWN.contains(&name) || hidden(child) {
            continue;
        }
        let t = transform.after(&transform_of(child)?);
        if SHAPES.contains(&name) {
            found.push((child, t));
        } else {
            collect(child, t, depth + 1, found)?;
        }
    }
    Ok(())
}

/// One piece of a shape's boundary, in the shape's own coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Seg {
    Move(Vec2),
    Line(Vec2),
    Quad(Vec2, Vec2),
    Cubic(Vec2, Vec2, Vec2),
    Close,
}

/// A length attribute in user units (`default` when absent).
fn length(node: roxmltree::Node<'_, '_>, attr: &str, default: Real) -> Result<Real, GradedError> {
    let Some(text) = node.attribute(attr) else {
        return Ok(default);
    };
    let what = || format!("{}: {attr}=\"{text}\"", describe(node));
    let l = Length::from_str(text).map_err(|_| bad(format!("{} is not a length", what())))?;
    let unit = match l.unit {
        LengthUnit::None | LengthUnit::Px => 1.0,
        LengthUnit::In => 96.0,
        LengthUnit::Cm => 96.0 / 2.54,
        LengthUnit::Mm => 96.0 / 25.4,
        LengthUnit::Pt => 4.0 / 3.0,
        LengthUnit::Pc => 16.0,
        LengthUnit::Em | LengthUnit::Ex | LengthUnit::Percent => {
            return Err(bad(format!(
                "{}: give an absolute length (user units, px, mm, cm, in, pt or pc)",
                what()
            )))
        }
    };
    Ok(l.number * unit)
}

/// The boundary of a shape element.
fn segments(node: roxmltree::Node<'_, '_>) -> Result<Vec<Seg>, GradedError> {
    let what = describe(node);
    let v = Vec2::new;
    let no_area = |detail: String| bad(format!("{what} encloses no area ({detail})"));
    let mut out = Vec::new();
    match node.tag_name().name() {
        "path" => {
            let d = node.attribute("d").unwrap_or("");
            for seg in SimplifyingPathParser::from(d) {
                let seg =
                    seg.map_err(|e| bad(format!("{what}: its path data cannot be read ({e})")))?;
                out.push(match seg {
                    SimplePathSegment::MoveTo { x, y } => Seg::Move(v(x, y)),
                    SimplePathSegment::LineTo { x, y } => Seg::Line(v(x, y)),
                    SimplePathSegment::Quadratic { x1, y1, x, y } => Seg::Quad(v(x1, y1), v(x, y)),
                    SimplePathSegment::CurveTo {
                        x1,
                        y1,
                        x2,
                        y2,
                        x,
                        y,
                    } => Seg::Cubic(v(x1, y1), v(x2, y2), v(x, y)),
                    SimplePathSegment::ClosePath => Seg::Close,
                });
            }
        }
        name @ ("polygon" | "polyline") => {
            let points: Vec<Vec2> = PointsParser::from(node.attribute("points").unwrap_or(""))
                .map(|(x, y)| v(x, y))
                .collect();
            for (k, p) in points.into_iter().enumerate() {
                out.push(if k == 0 { Seg::Move(p) } else { Seg::Line(p) });
            }
            if name == "polygon" {
                out.push(Seg::Close);
            }
        }
        "line" => {
            out.push(Seg::Move(v(
                length(node, "x1", 0.0)?,
                length(node, "y1", 0.0)?,
            )));
            out.push(Seg::Line(v(
                length(node, "x2", 0.0)?,
                length(node, "y2", 0.0)?,
            )));
        }
        "rect" => {
            let (x, y) = (length(node, "x", 0.0)?, length(node, "y", 0.0)?);
            let (w, h) = (length(node, "width", 0.0)?, length(node, "height", 0.0)?);
            if !(w > 0.0 && h > 0.0) {
                return Err(no_area(format!("width {w}, height {h}")));
            }
            // An absent rx or ry is the other one; each at most half the side.
            let rx = node
                .attribute("rx")
                .map(|_| length(node, "rx", 0.0))
                .transpose()?;
            let ry = node
                .attribute("ry")
                .map(|_| length(node, "ry", 0.0))
                .transpose()?;
            let rx = rx.or(ry).unwrap_or(0.0).clamp(0.0, w / 2.0);
            let ry = ry.or(Some(rx)).unwrap_or(0.0).clamp(0.0, h / 2.0);
            if rx > 0.0 && ry > 0.0 {
                let corners = [v(x + w, y), v(x + w, y + h), v(x, y + h), v(x, y)];
                let (ex, ey) = (v(rx, 0.0), v(0.0, ry));
                // Each side from after one corner's rounding to before the next's.
                let ends = [
                    (v(x + rx, y), v(x + w - rx, y)),
                    (corners[0] + ey, corners[1] - ey),
                    (corners[1] - ex, corners[2] + ex),
                    (corners[2] - ey, corners[3] + ey),
                ];
                out.push(Seg::Move(ends[0].0));
                for k in 0..4 {
                    out.push(Seg::Line(ends[k].1));
                    out.push(quarter(ends[k].1, corners[k], ends[(k + 1) % 4].0));
                }
            } else {
                out.push(Seg::Move(v(x, y)));
                out.push(Seg::Line(v(x + w, y)));
                out.push(Seg::Line(v(x + w, y + h)));
                out.push(Seg::Line(v(x, y + h)));
            }
            out.push(Seg::Close);
        }
        name @ ("circle" | "ellipse") => {
            let (cx, cy) = (length(node, "cx", 0.0)?, length(node, "cy", 0.0)?);
            let (rx, ry) = if name == "circle" {
                let r = length(node, "r", 0.0)?;
                (r, r)
            } else {
                // SVG 2: an absent (or auto) radius is the other one.
                let given = |a: &str| match node.attribute(a) {
                    None | Some("auto") => Ok(None),
                    Some(_) => length(node, a, 0.0).map(Some),
                };
                let (rx, ry) = (given("rx")?, given("ry")?);
                (rx.or(ry).unwrap_or(0.0), ry.or(rx).unwrap_or(0.0))
            };
            if !(rx > 0.0 && ry > 0.0) {
                return Err(no_area(format!("radii {rx}, {ry}")));
            }
            let c = v(cx, cy);
            let (ex, ey) = (v(rx, 0.0), v(0.0, ry));
            let ends = [c + ex, c + ey, c - ex, c - ey];
            out.push(Seg::Move(ends[0]));
            for k in 0..4 {
                let corner = ends[k] + ends[(k + 1) % 4] - c;
                out.push(quarter(ends[k], corner, ends[(k + 1) % 4]));
            }
            out.push(Seg::Close);
        }
        _ => unreachable!("only shape elements are collected"),
    }
    Ok(out)
}

/// The cubic Bézier of a quarter ellipse from `from` to `to` about the corner of their
/// bounding box `corner`.
fn quarter(from: Vec2, corner: Vec2, to: Vec2) -> Seg {
    Seg::Cubic(
        from + KAPPA * (corner - from),
        to + KAPPA * (corner - to),
        to,
    )
}

/// The shape's one closed loop as a polygon in y-up coordinates: transformed, flattened,
/// repeated points dropped, checked simple.
fn flatten(segs: &[Seg], transform: Affine, what: &str) -> Result<Vec<Vec2>, GradedError> {
    // y-down to y-up after the shape's transforms.
    let to_world = Affine([1.0, 0.0, 0.0, -1.0, 0.0, 0.0]).after(&transform);
    // Subpaths: a start, what follows it, closed or not. A lone move draws nothing.
    let mut loops: Vec<(Vec2, Vec<Seg>, bool)> = Vec::new();
    for seg in segs {
        match *seg {
            Seg::Move(p) => loops.push((to_world.apply(p), Vec::new(), false)),
            Seg::Close => {
                if let Some(last) = loops.last_mut() {
                    last.2 = true;
                }
            }
            other => {
                let map = |p: Vec2| to_world.apply(p);
                let moved = match other {
                    Seg::Line(p) => Seg::Line(map(p)),
                    Seg::Quad(c, p) => Seg::Quad(map(c), map(p)),
                    Seg::Cubic(c1, c2, p) => Seg::Cubic(map(c1), map(c2), map(p)),
                    Seg::Move(_) | Seg::Close => unreachable!(),
                };
                match loops.last_mut() {
                    Some(last) => last.1.push(moved),
                    None => {
                        return Err(bad(format!("{what}: its path data starts without a move")))
                    }
                }
            }
        }
    }
    loops.retain(|l| !l.1.is_empty());
    let (start, pieces, closed) = match &loops[..] {
        [] => return Err(bad(format!("{what} draws nothing"))),
        [one] => one,
        more => {
            return Err(bad(format!(
                "{what} is {} separate pieces: an outline is one closed loop (no holes, no parts)",
                more.len()
            )))
        }
    };
    let mut controls = vec![*start];
    for seg in pieces {
        match *seg {
            Seg::Line(p) => controls.push(p),
            Seg::Quad(c, p) => controls.extend([c, p]),
            Seg::Cubic(c1, c2, p) => controls.extend([c1, c2, p]),
            Seg::Move(_) | Seg::Close => {}
        }
    }
    if controls
        .iter()
        .any(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        return Err(bad(format!(
            "{what}: a coordinate is not a finite number (NaN or infinite)"
        )));
    }
    let (mut lo, mut hi) = (controls[0], controls[0]);
    for p in &controls {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    let size = (hi - lo).norm();
    if !(size > 0.0 && size.is_finite()) {
        return Err(bad(format!("{what} encloses no area")));
    }
    // A start and one end per piece: vertices as drawn when every curve is one chord, so
    // coarsening the curves always brings an outline of at most that many within the limit.
    let vertices = pieces.len() + 1;
    if vertices > MAX_OUTLINE_VERTICES {
        return Err(bad(format!(
            "{what} has {vertices} vertices; an outline may have at most \
             {MAX_OUTLINE_VERTICES}: simplify it in your editor"
        )));
    }
    // Curves flattened within FLATTEN_TOLERANCE of the size, or coarser when that would give
    // more than MAX_OUTLINE_VERTICES points (a curve's pieces go as 1/√tolerance).
    let mut tol = FLATTEN_TOLERANCE * size;
    let mut points = flattened(*start, pieces, tol);
    while points.len() > MAX_OUTLINE_VERTICES {
        let over = points.len() as Real / MAX_OUTLINE_VERTICES as Real;
        tol *= 1.2 * over * over;
        points = flattened(*start, pieces, tol);
    }
    let same = |a: &Vec2, b: &Vec2| (a - b).norm() <= 1e-9 * size;
    let end = *points.last().expect("a start");
    if !closed && !same(&end, start) {
        return Err(bad(format!(
            "{what} is open (it ends away from where it starts): close it (Z) so that it bounds a shape"
        )));
    }
    points.dedup_by(|b, a| same(a, b));
    while points.len() > 1 && same(&points[0], points.last().expect("points")) {
        points.pop();
    }
    match is_simple_problem(&points, 1e-9 * size) {
        None => Ok(points),
        Some(SimplicityProblem::SelfIntersection { a, b }) => Err(bad(format!(
            "{what} crosses itself (pieces {a} and {b} of its flattened outline meet): an outline is a simple closed curve"
        ))),
        Some(_) => Err(bad(format!("{what} encloses no area"))),
    }
}

/// The polyline through `start` and `pieces` with every curve cut into uniform pieces whose
/// chords are within `tol` of it.
fn flattened(start: Vec2, pieces: &[Seg], tol: Real) -> Vec<Vec2> {
    let mut points = vec![start];
    for seg in pieces {
        let p0 = *points.last().expect("a start");
        match *seg {
            Seg::Line(p) => points.push(p),
            Seg::Quad(c, p) => {
                // Uniform pieces: the chord is off by at most |B''| / (8 n²), |B''| = 2|p0 − 2c + p|.
                let n = pieces_for((p0 - 2.0 * c + p).norm() / (4.0 * tol));
                points.extend((1..=n).map(|k| {
                    let t = k as Real / n as Real;
                    let s = 1.0 - t;
                    s * s * p0 + 2.0 * s * t * c + t * t * p
                }));
            }
            Seg::Cubic(c1, c2, p) => {
                // |B''| ≤ 6 max(|p0 − 2c1 + c2|, |c1 − 2c2 + p|).
                let m = (p0 - 2.0 * c1 + c2).norm().max((c1 - 2.0 * c2 + p).norm());
                let n = pieces_for(0.75 * m / tol);
                points.extend((1..=n).map(|k| {
                    let t = k as Real / n as Real;
                    let s = 1.0 - t;
                    s * s * s * p0 + 3.0 * s * s * t * c1 + 3.0 * s * t * t * c2 + t * t * t * p
                }));
            }
            Seg::Move(_) | Seg::Close => {}
        }
    }
    points
}

/// Uniform pieces for a curve whose squared count is `n2`, at least one.
fn pieces_for(n2: Real) -> usize {
    (n2.sqrt().ceil() as usize).clamp(1, MAX_PIECES)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn svg(body: &str) -> String {
        format!(r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">{body}</svg>"#)
    }

    fn polygon(body: &str) -> Vec<Vec2> {
        match outline_from_svg(&svg(body)) {
            Ok(Outline::Polygon(p)) => p,
            other => panic!("{body}: {other:?}"),
        }
    }

    fn error(text: &str) -> String {
        match outline_from_svg(text) {
            Err(e) => e.to_string(),
            Ok(o) => panic!("{text}: accepted as {o:?}"),
        }
    }

    /// The polygon's corners, sorted, rounded to 1e-9 (for comparing sets of corners).
    fn corners(p: &[Vec2]) -> Vec<(i64, i64)> {
        let mut c: Vec<_> = p
            .iter()
            .map(|v| ((v.x * 1e9).round() as i64, (v.y * 1e9).round() as i64))
            .collect();
        c.sort_unstable();
        c
    }

    fn rect_corners(w: Real, h: Real) -> Vec<(i64, i64)> {
        corners(&[
            Vec2::new(-w / 2.0, -h / 2.0),
            Vec2::new(w / 2.0, -h / 2.0),
            Vec2::new(w / 2.0, h / 2.0),
            Vec2::new(-w / 2.0, h / 2.0),
        ])
    }

    /// Largest relative spread of the corners' distances from the centre.
    fn radius_spread(p: &[Vec2]) -> Real {
        let r: Vec<Real> = p.iter().map(|v| v.norm()).collect();
        let mean = r.iter().sum::<Real>() / r.len() as Real;
        r.iter()
            .map(|x| (x - mean).abs() / mean)
            .fold(0.0, Real::max)
    }

    /// A circle drawn as two arcs (absolute and relative commands) is a polygon whose radius
    /// is constant within 1e-3, with enough corners to be round.
    #[test]
    fn a_circle_of_arcs_is_round() {
        for d in [
            "M 60 50 A 10 10 0 0 1 40 50 A 10 10 0 0 1 60 50 Z",
            "m 60 50 a 10 10 0 0 1 -20 0 a 10 10 0 0 1 20 0 z",
            "M 5000 0 A 5000 5000 0 1 0 5000 0.001 Z",
        ] {
            let p = polygon(&format!(r#"<path d="{d}"/>"#));
            assert!(p.len() >= 32, "{d}: {} corners", p.len());
            let spread = radius_spread(&p);
            assert!(spread < 1e-3, "{d}: radius spread {spread}");
        }
        for body in [
            r#"<circle cx="3" cy="4" r="0.01"/>"#,
            r#"<ellipse cx="3" cy="4" rx="2" ry="2"/>"#,
        ] {
            let spread = radius_spread(&polygon(body));
            assert!(spread < 1e-3, "{body}: radius spread {spread}");
        }
    }

    /// A rect is its four corners, centred; a rounded one keeps its straight sides.
    #[test]
    fn a_rect_is_its_corners() {
        let p = polygon(r#"<rect x="5" y="5" width="40" height="20"/>"#);
        assert_eq!(corners(&p), rect_corners(40.0, 20.0));
        let p = polygon(r#"<rect x="5" y="5" width="40mm" height="20mm" rx="3mm"/>"#);
        let mm = 96.0 / 25.4;
        let (lo, hi) = p
            .iter()
            .fold((Vec2::zeros(), Vec2::zeros()), |(lo, hi), v| {
                (lo.inf(v), hi.sup(v))
            });
        assert!(((hi - lo) - Vec2::new(40.0 * mm, 20.0 * mm)).norm() < 1e-9);
        assert!(p.len() > 8, "rounded corners: {} corners", p.len());
        // The corner itself is cut off by the rounding.
        let corner = Vec2::new(20.0 * mm, 10.0 * mm);
        let nearest = p
            .iter()
            .map(|v| (v - corner).norm())
            .fold(Real::MAX, Real::min);
        assert!(nearest > 0.5 * mm, "{nearest}");
    }

    /// Transforms of the shape and its ancestors apply in SVG's order: the innermost first.
    #[test]
    fn transforms_are_applied() {
        // A 40 × 20 rectangle turned a quarter turn: 20 wide, 40 tall.
        let p = polygon(r#"<g transform="rotate(90)"><path d="M0 0 H 40 V 20 H 0 Z"/></g>"#);
        assert_eq!(corners(&p), rect_corners(20.0, 40.0));
        // Translated, then scaled 2 along x by the group: 20 × 10 (a translation alone moves
        // nothing: the outline is centred).
        let p = polygon(
            r#"<g transform="scale(2,1)"><rect transform="translate(30,4)" width="10" height="10"/></g>"#,
        );
        assert_eq!(corners(&p), rect_corners(20.0, 10.0));
        // Rotated then scaled is not scaled then rotated.
        let p = polygon(
            r#"<g transform="scale(2,1)"><g transform="rotate(90)"><rect width="10" height="10"/></g></g>"#,
        );
        assert_eq!(corners(&p), rect_corners(20.0, 10.0));
        let p = polygon(
            r#"<g transform="rotate(90)"><g transform="scale(2,1)"><rect width="10" height="10"/></g></g>"#,
        );
        assert_eq!(corners(&p), rect_corners(10.0, 20.0));
        // A skew makes a parallelogram: opposite sides parallel, corners not right angles.
        let p = polygon(r#"<rect transform="skewX(30)" width="10" height="10"/>"#);
        assert_eq!(p.len(), 4);
        let e0 = p[1] - p[0];
        let e1 = p[2] - p[1];
        assert!(e0.dot(&e1).abs() > 1.0);
    }

    /// SVG's y points down: a triangle drawn with its flat side on top keeps it on top.
    #[test]
    fn y_is_flipped() {
        let p = polygon(r#"<path d="M0 0 L 10 0 L 0 10 Z"/>"#);
        let top = p.iter().filter(|v| v.y > 0.0).count();
        assert_eq!(top, 2, "{p:?}");
        // Counter-clockwise after the flip.
        assert!(crate::geometry::signed_area(&p) > 0.0);
        // A y-down path that goes up to the right goes up to the right.
        let p = polygon(r#"<polygon points="0,10 10,0 12,2 2,12"/>"#);
        let far = p.iter().max_by(|a, b| a.x.total_cmp(&b.x)).unwrap();
        assert!(far.y > 0.0, "{p:?}");
    }

    /// Shapes not drawn where they stand, hidden, or in another namespace are not counted;
    /// the one drawn shape is the outline.
    #[test]
    fn only_drawn_shapes_count() {
        let body = r##"<defs><rect id="r" width="5" height="5"/></defs>
            <clipPath><circle r="3"/></clipPath>
            <g style="fill:red; display : none"><circle r="1"/></g>
            <path display="none" d="M0 0 H 1 V 1 Z"/>
            <text>label</text>
            <use href="#r"/>
            <g id="layer1"><polygon points="0,0 10,0 10,10 0,10"/></g>"##;
        let text = format!(
            r#"<?xml version="1.0"?>
            <!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" "http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd">
            <svg xmlns="http://www.w3.org/2000/svg" xmlns:x="urn:editor"><x:guide><x:rect/></x:guide>{body}</svg>"#
        );
        let Outline::Polygon(p) = outline_from_svg(&text).unwrap() else {
            panic!("a polygon");
        };
        assert_eq!(corners(&p), rect_corners(10.0, 10.0));
        // Without a namespace (hand-written files) too.
        assert!(outline_from_svg(r#"<svg><circle r="2"/></svg>"#).is_ok());
        // A polyline back at its start is closed.
        assert!(outline_from_svg(&svg(r#"<polyline points="0,0 4,0 4,4 0,0"/>"#)).is_ok());
    }

    /// Each refusal is one line naming its problem.
    #[test]
    fn bad_documents_are_refused_in_one_line() {
        let cases = [
            ("just text".to_string(), "not an SVG document"),
            ("<html><body/></html>".into(), "root element is <html>"),
            (svg(""), "no shape"),
            (svg(r#"<defs><circle r="2"/></defs>"#), "no shape"),
            (
                svg(
                    r#"<rect id="frame" width="9" height="9"/><circle r="2"/><g><circle r="1"/></g>"#,
                ),
                "3 shapes (<rect id=\"frame\">, <circle>, <circle>)",
            ),
            (
                svg(r#"<path id="a" d="M0 0 L 10 0 L 10 10"/>"#),
                "<path id=\"a\"> is open",
            ),
            (svg(r#"<polyline points="0,0 4,0 4,4"/>"#), "is open"),
            (svg(r#"<line x2="4" y2="3"/>"#), "is open"),
            (
                svg(r#"<path d="M0 0 L 10 10 L 10 0 L 0 10 Z"/>"#),
                "crosses itself",
            ),
            (
                svg(r#"<path d="M0 0 H 10 V 10 H 0 Z M 2 2 H 8 V 8 H 2 Z"/>"#),
                "2 separate pieces",
            ),
            (
                svg(r#"<polygon points="0,0 30,0 30,30 20,30 20,10 10,10 10,30 0,30"/>"#),
                "not seen whole from its centroid",
            ),
            (
                svg(r#"<rect width="1e308" height="1" transform="scale(10)"/>"#),
                "not a finite number",
            ),
            (svg(r#"<rect width="0" height="3"/>"#), "encloses no area"),
            (svg(r#"<circle r="-1"/>"#), "encloses no area"),
            (svg(r#"<rect width="50%" height="3"/>"#), "absolute length"),
            (
                svg(r#"<rect width="3" height="3" transform="spin(3)"/>"#),
                "transform",
            ),
            (svg(r#"<path d="M 0 0 L 4 0 L 4 q Z"/>"#), "path data"),
        ];
        for (text, needle) in cases {
            let e = error(&text);
            assert!(e.starts_with("bad target: "), "{text}: {e}");
            assert!(e.contains(needle), "{text}: {e:?} does not say {needle:?}");
            assert_eq!(e.lines().count(), 1, "{text}: {e}");
        }
    }

    /// A nesting, entity or size that would cost the reader its stack, memory or time is
    /// refused in one line before the work (issue 42: 6,000 nested groups overflowed a server
    /// worker's stack; one 20 KB entity used 6,000 times expanded to 120 MB). The nested
    /// documents are read on a thread with a quarter of a server worker's stack.
    #[test]
    fn hostile_documents_are_refused_before_the_work() {
        let nested = |n: usize| {
            format!(
                r#"<svg xmlns="http://www.w3.org/2000/svg">{}<circle r="3"/>{}</svg>"#,
                "<g>".repeat(n),
                "</g>".repeat(n)
            )
        };
        let entity = |size: usize, uses: usize| {
            format!(
                r#"<?xml version="1.0"?><!DOCTYPE svg [<!ENTITY big "{}">]><svg xmlns="http://www.w3.org/2000/svg"><desc>{}</desc><circle r="3"/></svg>"#,
                "x".repeat(size),
                "&big;".repeat(uses)
            )
        };
        let laughs = format!(
            r#"<!DOCTYPE svg [<!ENTITY a "{}"><!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;">]><svg xmlns="http://www.w3.org/2000/svg"><desc>{}</desc><circle r="3"/></svg>"#,
            "y".repeat(1000),
            "&b;".repeat(100)
        );
        let cases = [
            (nested(6_000), "deeper than 256 levels"),
            (nested(100_000), "deeper than 256 levels"),
            (entity(20_000, 6_000), "entities could expand"),
            (laughs, "entities could expand"),
            (
                format!("{}<svg/>", " ".repeat(MAX_SVG_BYTES)),
                "more than the 16 MiB",
            ),
        ];
        let refused = std::thread::Builder::new()
            .stack_size(512 << 10)
            .spawn(move || {
                cases
                    .iter()
                    .map(|(text, needle)| (error(text), *needle))
                    .collect::<Vec<_>>()
            })
            .unwrap()
            .join()
            .expect("no stack overflow");
        for (e, needle) in refused {
            assert!(e.starts_with("bad target: "), "{e}");
            assert!(e.contains(needle), "{e:?} does not say {needle:?}");
            assert_eq!(e.lines().count(), 1, "{e}");
        }
        // Just inside the limits, the same documents are read.
        assert!(outline_from_svg(&nested(MAX_DEPTH - 2)).is_ok());
        assert!(outline_from_svg(&entity(100, 100)).is_ok());
    }

    /// An editor's own entities (Illustrator declares its namespaces so) are read; the bound
    /// counts only references to declared entities, not XML's predefined ones or characters.
    #[test]
    fn small_entities_are_read_and_the_bound_counts_references() {
        let text = r#"<?xml version="1.0"?>
<!DOCTYPE svg PUBLIC "-//W3C//DTD SVG 1.1//EN" "http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd" [
  <!ENTITY ns_svg "http://www.w3.org/2000/svg">
  <!ENTITY ns_ai "http://ns.adobe.com/AdobeIllustrator/10.0/">
]>
<svg xmlns="&ns_svg;" xmlns:i="&ns_ai;"><title>a &amp; b &#38; &lt;c&gt;</title><circle r="3"/></svg>"#;
        assert!(matches!(outline_from_svg(text), Ok(Outline::Polygon(_))));
        let subset = text[text.find('[').unwrap()..text.find(']').unwrap()].len() - 1;
        assert_eq!(entity_expansion_bound(text), 2 * subset);
        assert_eq!(entity_expansion_bound(&svg(r#"<circle r="3"/>"#)), 0);
        assert_eq!(entity_references("&amp;&lt;&#38;&#x26;&a;%p; 100%;&b"), 2);
    }

    /// Issue 42: a path target of 10,000 vertices took 6 s, 100,000 more than a minute, with
    /// no word. A path of more pieces than an outline may have is refused; curves that would
    /// flatten to more points are flattened more coarsely, and the outline stays round.
    #[test]
    fn big_paths_are_refused_and_many_curves_coarsened() {
        let ngon = |n: usize| {
            let mut d = String::from("M 100 0");
            for k in 1..n {
                let a = std::f64::consts::TAU * k as Real / n as Real;
                d += &format!(" L {:.6} {:.6}", 100.0 * a.cos(), 100.0 * a.sin());
            }
            svg(&format!(r#"<path d="{d} Z"/>"#))
        };
        for n in [MAX_OUTLINE_VERTICES + 1, 10_000, 100_000] {
            let e = error(&ngon(n));
            assert!(e.contains(&format!("has {n} vertices")), "{e}");
            assert!(e.contains("at most 4096"), "{e}");
        }
        match outline_from_svg(&ngon(MAX_OUTLINE_VERTICES)) {
            Ok(Outline::Polygon(p)) => assert_eq!(p.len(), MAX_OUTLINE_VERTICES),
            other => panic!("{other:?}"),
        }
        // 400 scallops of a circle of radius 100, each a cubic bump 15 high: about 21 pieces
        // each at the default tolerance (8,400 points), so flattened more coarsely.
        let n = 400;
        let at = |k: usize| {
            let a = std::f64::consts::TAU * k as Real / n as Real;
            Vec2::new(100.0 * a.cos(), 100.0 * a.sin())
        };
        let mut d = format!("M {} {}", at(0).x, at(0).y);
        for k in 0..n {
            let (p, q) = (at(k), at(k + 1));
            let out = (p + q).normalize() * 20.0;
            let (c1, c2) = (p + (q - p) / 3.0 + out, p + 2.0 * (q - p) / 3.0 + out);
            d += &format!(" C {} {} {} {} {} {}", c1.x, c1.y, c2.x, c2.y, q.x, q.y);
        }
        let p = polygon(&format!(r#"<path d="{d} Z"/>"#));
        assert!(
            (2 * n..MAX_OUTLINE_VERTICES).contains(&p.len()),
            "{} points",
            p.len()
        );
        let reach = p.iter().map(|v| v.norm()).fold(0.0, Real::max);
        assert!((110.0..=116.0).contains(&reach), "{reach}");
    }
}
