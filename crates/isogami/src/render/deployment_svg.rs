//! Every frame of a deployment as an SVG in one shared view box, the centre cell's collision
//! polygons outlined and each frame labelled with its t: the frames of `isogami deploy
//! --frames/--gif` and of the browser's GIF download.

use super::frame_svg::{frame_svg, view_box_for, FrameStyle};
use crate::contact::ContactModel;
use crate::deploy::FrameRecord;
use crate::kinematics::Mechanism;
use crate::math::Real;

/// One SVG per frame, `width_px` wide, all in the view box of the whole deployment.
pub fn deployment_frame_svgs(
    mech: &Mechanism,
    contact: &ContactModel,
    frames: &[FrameRecord],
    width_px: Real,
) -> Vec<String> {
    let states: Vec<_> = frames.iter().map(|f| f.q.clone()).collect();
    let view = view_box_for(mech, &states);
    frames
        .iter()
        .map(|f| {
            let style = FrameStyle {
                width_px,
                view_box: Some(view),
                extra_polygons: contact
                    .collision_polygons(mech, &f.q)
                    .into_iter()
                    .filter(|(_, o, _)| *o == [0, 0])
                    .map(|(_, _, p)| p)
                    .collect(),
                label: Some(format!("t = {:.2}", f.t)),
                ..FrameStyle::default()
            };
            frame_svg(mech, &f.q, &style)
        })
        .collect()
}
