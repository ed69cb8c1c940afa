"""Laser DXF of `isogami export` read by ezdxf (a second reader next to the Rust dxf crate):
the audit passes, units are millimetres, layers CUT, SCORE and OUTLINE exist, outline
polylines are closed and lie round every cut."""

import ezdxf
import pytest
from shapely.geometry import Polygon, box

from conftest import DESIGNS, WIDTH_MM


@pytest.mark.parametrize("design", DESIGNS)
def test_dxf_reads_audits_and_has_the_layers(files, design):
    path = files(design).path("dxf")
    doc = ezdxf.readfile(path)
    auditor = doc.audit()
    assert not auditor.has_errors, [str(e) for e in auditor.errors]
    assert doc.header["$INSUNITS"] == 4  # millimetres
    layers = {layer.dxf.name for layer in doc.layers}
    assert {"CUT", "SCORE", "OUTLINE"} <= layers, layers
    msp = doc.modelspace()
    outlines = list(msp.query('POLYLINE LWPOLYLINE[layer=="OUTLINE"]'))
    assert outlines, design
    rings = []
    for pl in outlines:
        assert pl.is_closed, design
        pts = [tuple(v)[:2] for v in pl.points()]
        ring = Polygon(pts)
        assert ring.is_valid and ring.area > 0, design
        rings.append(ring)
    cuts = list(msp.query('LINE[layer=="CUT"]'))
    assert cuts, design
    sheet = max(rings, key=lambda r: r.area)
    for line in cuts:
        a, b = line.dxf.start, line.dxf.end
        seg = box(min(a.x, b.x), min(a.y, b.y), max(a.x, b.x), max(a.y, b.y))
        assert sheet.buffer(1e-6).contains(seg.centroid), design
    # The outline cut runs half the default kerf (0.2 mm) outside the asked width (mitred, so
    # further at acute corners of other outlines).
    if design == "rotating-squares":
        x0, _, x1, _ = sheet.bounds
        assert x1 - x0 == pytest.approx(WIDTH_MM + 0.2, abs=1e-6)
