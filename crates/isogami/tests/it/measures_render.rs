//! Measures on exact rotating-squares states, frame SVGs, plots, PNG and GIF output.
//!
//! Set ISOGAMI_RENDER_OUT=/some/dir to also write the rendered files there for a look.
//! Needs the `render` feature (see Cargo.toml).

use isogami::kinematics::Mechanism;
use isogami::math::{DVec, Real};
use isogami::measure::{classify, expansion_profile, BehaviourClass, FrameMeasures};
use isogami::render::{
    expansion_plot_svg, frame_svg, gif_from_svgs, png_from_svg, polar_plot_svg, view_box_for,
    Fonts, FrameStyle, RenderError,
};
use isogami::topology::Design;
use resvg::tiny_skia::Pixmap;
use resvg::usvg;
use std::sync::OnceLock;

/// The system fonts, scanned once for the whole test binary.
fn fonts() -> &'static Fonts {
    static FONTS: OnceLock<Fonts> = OnceLock::new();
    FONTS.get_or_init(Fonts::system)
}

fn rotating_squares() -> Mechanism {
    let d = Design::resolve("rotating-squares").unwrap();
    let cell = d.cell().unwrap();
    Mechanism::new(&cell, &d.joints).unwrap()
}

/// q(φ) = rest with positions and lattice scaled by s = cos φ + sin φ and tile i turned by
/// σᵢ φ: rotating squares open as a pure stretch. The signs σ are found by brute force (the
/// pattern with zero joint residual), so this also checks the mechanism.
fn open_state(mech: &Mechanism, signs: &[Real], phi: Real) -> DVec {
    let s = phi.cos() + phi.sin();
    let mut q = &mech.rest * s;
    for (i, sign) in signs.iter().enumerate() {
        q[mech.layout.tile(i) + 2] = mech.rest[mech.layout.tile(i) + 2] + sign * phi;
    }
    q
}

fn rotation_signs(mech: &Mechanism) -> Vec<Real> {
    let n = mech.tile_count();
    let best = (0..1u32 << n)
        .map(|bits| {
            let signs: Vec<Real> = (0..n)
                .map(|i| if bits >> i & 1 == 1 { 1.0 } else { -1.0 })
                .collect();
            let r = mech.residual(&open_state(mech, &signs, 0.3)).amax();
            (r, signs)
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap();
    assert!(
        best.0 < 1e-12,
        "no exact rotating-squares state: residual {}",
        best.0
    );
    best.1
}

fn trajectory(mech: &Mechanism, frames: usize) -> Vec<(Real, Real, DVec)> {
    let signs = rotation_signs(mech);
    (0..frames)
        .map(|k| {
            let t = k as Real / (frames - 1) as Real;
            let phi = t * std::f64::consts::FRAC_PI_4;
            let q = open_state(mech, &signs, phi);
            assert!(mech.residual(&q).amax() < 1e-12);
            (t, phi, q)
        })
        .collect()
}

fn parse_svg(svg: &str) -> usvg::Tree {
    usvg::Tree::from_str(svg, &usvg::Options::default()).expect("valid SVG")
}

fn dump(name: &str, bytes: &[u8]) {
    if let Ok(dir) = std::env::var("ISOGAMI_RENDER_OUT") {
        std::fs::write(std::path::Path::new(&dir).join(name), bytes).unwrap();
    }
}

fn non_white_pixels(png: &[u8]) -> usize {
    let pix = Pixmap::decode_png(png).expect("valid PNG");
    pix.pixels()
        .iter()
        .filter(|p| (p.red(), p.green(), p.blue()) != (255, 255, 255))
        .count()
}

fn measures(mech: &Mechanism, traj: &[(Real, Real, DVec)]) -> Vec<FrameMeasures> {
    traj.iter()
        .map(|(t, _, q)| FrameMeasures::from_states(mech, &mech.rest, q, *t).unwrap())
        .collect()
}

#[test]
fn rotating_squares_measures_are_analytic() {
    let mech = rotating_squares();
    let traj = trajectory(&mech, 11);
    let fm = measures(&mech, &traj);
    for (m, (_, phi, _)) in fm.iter().zip(&traj) {
        let s = phi.cos() + phi.sin();
        assert!((m.min_expansion - (s - 1.0)).abs() < 1e-12, "{m:?}");
        assert!((m.max_expansion - (s - 1.0)).abs() < 1e-12, "{m:?}");
        assert!((m.area_ratio - s * s).abs() < 1e-12);
        assert!(m.lattice_rotation.abs() < 1e-12);
        assert!((m.max_tile_rotation - phi).abs() < 1e-12);
        if *phi > 0.0 {
            assert!((m.poisson_ratio().unwrap() + 1.0).abs() < 1e-9);
        }
    }
    // At φ = 45° the stretch is √2.
    let last = fm.last().unwrap();
    assert!((last.max_expansion + 1.0 - 2f64.sqrt()).abs() < 1e-12);
    assert_eq!(classify(&fm), Some(BehaviourClass::IsotropicAuxetic));
}

#[test]
fn frame_svg_draws_the_3x3_block() {
    let mech = rotating_squares();
    let n = mech.tile_count();
    assert_eq!(n, 4);
    let style = FrameStyle {
        label: Some("t = 0.00".into()),
        ..FrameStyle::default()
    };
    let svg = frame_svg(&mech, &mech.rest, &style);
    let tree = parse_svg(&svg);
    assert!(tree.size().width() > 0.0 && tree.size().height() > 0.0);
    assert_eq!(svg.matches(r#"class="tile""#).count(), 9 * n);
    assert_eq!(
        svg.matches(r#"class="joint""#).count(),
        9 * mech.joints.len()
    );
    assert!(!svg.contains("NaN"));
    // Extra outlines are drawn when given.
    let extra = FrameStyle {
        extra_polygons: (0..n)
            .map(|i| mech.tile_polygon(&mech.rest, i, [0, 0]))
            .collect(),
        ..FrameStyle::default()
    };
    let svg2 = frame_svg(&mech, &mech.rest, &extra);
    assert_eq!(svg2.matches(r#"class="extra""#).count(), n);
    parse_svg(&svg2);
    // A broken state leaves elements out instead of writing NaN.
    let mut broken = mech.rest.clone();
    broken[mech.layout.tile(1) + 2] = Real::NAN;
    let svg3 = frame_svg(&mech, &broken, &FrameStyle::default());
    assert!(!svg3.contains("NaN"));
    assert_eq!(svg3.matches(r#"class="tile""#).count(), 9 * (n - 1));
    parse_svg(&svg3);
    let png = png_from_svg(&svg, 400, fonts()).unwrap();
    assert!(png.starts_with(b"\x89PNG"));
    assert!(non_white_pixels(&png) > 1000);
    dump("frame_rest.svg", svg.as_bytes());
    dump("frame_rest.png", &png);
}

#[test]
fn fixed_view_box_is_shared_by_all_frames() {
    let mech = rotating_squares();
    let traj = trajectory(&mech, 5);
    let states: Vec<DVec> = traj.iter().map(|x| x.2.clone()).collect();
    let vb = view_box_for(&mech, &states);
    let headers: Vec<String> = states
        .iter()
        .map(|q| {
            let svg = frame_svg(
                &mech,
                q,
                &FrameStyle {
                    view_box: Some(vb),
                    ..FrameStyle::default()
                },
            );
            let start = svg.find("<svg").unwrap();
            let end = start + svg[start..].find('>').unwrap();
            svg[start..end].to_string()
        })
        .collect();
    assert!(headers.iter().all(|h| h == &headers[0]), "{headers:#?}");
    // The open sheet is larger than the closed one, and the shared box holds it.
    let closed = view_box_for(&mech, &states[..1]);
    assert!(vb.width() > closed.width() && vb.height() > closed.height());
}

#[test]
fn gif_has_every_frame() {
    let mech = rotating_squares();
    let traj = trajectory(&mech, 6);
    let states: Vec<DVec> = traj.iter().map(|x| x.2.clone()).collect();
    let vb = view_box_for(&mech, &states);
    let svgs: Vec<String> = traj
        .iter()
        .map(|(t, _, q)| {
            let style = FrameStyle {
                view_box: Some(vb),
                label: Some(format!("t = {t:.2}")),
                ..FrameStyle::default()
            };
            frame_svg(&mech, q, &style)
        })
        .collect();
    let width = 240u32;
    let gif_bytes = gif_from_svgs(&svgs, width, 8, fonts()).unwrap();
    assert!(gif_bytes.starts_with(b"GIF89a"));
    dump("rotating_squares.gif", &gif_bytes);
    dump(
        "frame_open.png",
        &png_from_svg(&svgs[5], 400, fonts()).unwrap(),
    );
    let expected_h = (Real::from(width) * vb.height() / vb.width()).round() as u16;
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::RGBA);
    let mut dec = opts.read_info(gif_bytes.as_slice()).unwrap();
    assert_eq!(dec.width(), width as u16);
    assert!((i32::from(dec.height()) - i32::from(expected_h)).abs() <= 1);
    assert_eq!(dec.repeat(), gif::Repeat::Infinite);
    let (gw, gh) = (dec.width(), dec.height());
    let mut count = 0;
    while let Some(frame) = dec.read_next_frame().unwrap() {
        assert_eq!(frame.delay, 8);
        assert_eq!((frame.width, frame.height), (gw, gh));
        // The palette-quantised frame looks like the direct render of its SVG.
        let direct =
            Pixmap::decode_png(&png_from_svg(&svgs[count], width, fonts()).unwrap()).unwrap();
        assert_eq!(direct.data().len(), frame.buffer.len());
        let diff: u64 = direct
            .data()
            .iter()
            .zip(frame.buffer.iter())
            .map(|(a, b)| u64::from(a.abs_diff(*b)))
            .sum();
        let mean = diff as Real / frame.buffer.len() as Real;
        assert!(
            mean < 4.0,
            "frame {count} differs from its SVG by {mean} per channel"
        );
        if count == 3 {
            let img = Pixmap::from_vec(
                frame.buffer.to_vec(),
                resvg::tiny_skia::IntSize::from_wh(width, u32::from(gh)).unwrap(),
            )
            .unwrap();
            dump("gif_frame3.png", &img.encode_png().unwrap());
        }
        count += 1;
    }
    assert_eq!(count, svgs.len());
    let none = Fonts::empty();
    assert_eq!(
        gif_from_svgs(&[], width, 8, &none),
        Err(RenderError::NoFrames)
    );
    let bad = [svgs[0].clone(), "<svg".to_string()];
    assert!(matches!(
        gif_from_svgs(&bad, width, 8, &none),
        Err(RenderError::InvalidSvg { frame: Some(1), .. })
    ));
    assert!(matches!(
        gif_from_svgs(&svgs, 0, 8, &none),
        Err(RenderError::Width { width: 0, .. })
    ));
}

#[test]
fn plots_are_valid_svg_without_nan() {
    let mech = rotating_squares();
    let traj = trajectory(&mech, 21);
    let fm = measures(&mech, &traj);
    let t: Vec<Real> = fm.iter().map(|m| m.t).collect();
    let lo: Vec<Real> = fm.iter().map(|m| m.min_expansion).collect();
    let hi: Vec<Real> = fm.iter().map(|m| m.max_expansion).collect();
    let plot = expansion_plot_svg(&t, &lo, &hi, "rotating squares").unwrap();
    parse_svg(&plot);
    assert!(!plot.contains("NaN"));
    assert!(plot.contains("rotating squares") && plot.contains("deployment parameter t"));

    // A sheared U gives a non-circular profile next to the isotropic one.
    let sheared = isogami::math::Mat2::new(1.4, 0.2, 0.2, 0.85);
    let profiles = vec![
        ("t = 0.50", expansion_profile(&fm[10].u_matrix(), 180)),
        ("t = 1.00", expansion_profile(&fm[20].u_matrix(), 180)),
        ("sheared", expansion_profile(&sheared, 180)),
    ];
    let polar = polar_plot_svg(&profiles).unwrap();
    parse_svg(&polar);
    assert!(!polar.contains("NaN"));
    assert!(polar.contains("unit circle"));

    let png = png_from_svg(&plot, 800, fonts()).unwrap();
    assert!(non_white_pixels(&png) > 1000);
    dump("expansion.svg", plot.as_bytes());
    dump("expansion.png", &png);
    dump("polar.png", &png_from_svg(&polar, 640, fonts()).unwrap());
}

#[test]
fn plots_reject_bad_input_by_name() {
    let t = [0.0, 0.5, 1.0];
    let ok = [0.0, 0.1, 0.2];
    let bad = [0.0, 0.1, Real::NAN];
    let e = expansion_plot_svg(&t, &bad, &ok, "x")
        .unwrap_err()
        .to_string();
    assert!(e.contains("min[2]"), "{e}");
    let e = expansion_plot_svg(&t, &ok, &[0.0], "x")
        .unwrap_err()
        .to_string();
    assert!(e.contains("max 1"), "{e}");
    assert!(expansion_plot_svg(&[], &[], &[], "x").is_err());
    let e = polar_plot_svg(&[("p", vec![(0.0, Real::INFINITY)])])
        .unwrap_err()
        .to_string();
    assert!(e.contains("'p'") && e.contains("sample 0"), "{e}");
    assert!(polar_plot_svg(&[("empty", Vec::new())]).is_err());
    // No profiles at all is still a plot (just the unit circle).
    let none: &[(&str, Vec<(Real, Real)>)] = &[];
    assert!(polar_plot_svg(none).is_ok());
}

#[test]
fn text_is_rasterised_with_an_installed_font() {
    let font = fonts().sans_family();
    assert!(
        font.is_some(),
        "no system font found: text would vanish from PNG/GIF output"
    );
    let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="200" height="60"><text x="10" y="40" font-size="30" font-family="sans-serif">Text</text></svg>"#;
    let png = png_from_svg(svg, 200, fonts()).unwrap();
    assert!(non_white_pixels(&png) > 50, "font {font:?} drew nothing");
    // Without fonts the text is left out: nothing is drawn, and nothing fails.
    let empty = Fonts::empty();
    assert_eq!((empty.sans_family(), empty.face_count()), (None, 0));
    let blank = png_from_svg(svg, 200, &empty).unwrap();
    assert_eq!(non_white_pixels(&blank), 0);
}
