#!/usr/bin/env python3
"""Writes a DXF-AAMA test file with ezdxf (an independent DXF writer) for tests/io/dxf_aama_test.cpp.

usage: write_aama.py OUT.dxf --case NAME

For the readable cases it also writes OUT.json, the geometry a reader must find, worked out here in Python:
{"units_in_meter": u, "pieces": [{"name", "vertices" (counter-clockwise, closing point dropped), "grain" or null,
"notches", "internal_lines", "arcs": [{"edge", "center", "radius", "middle"}]}]}, coordinates in file units.
"""
import argparse
import json
import math
import sys

import ezdxf
from ezdxf.math import Vec2, bulge_to_arc


def signed_area(points):
    return 0.5 * sum(a[0] * b[1] - b[0] * a[1] for a, b in zip(points, points[1:] + points[:1]))


def counter_clockwise(points):
    return list(points) if signed_area(points) > 0 else list(reversed(points))


def new_doc(version="R2000", insunits=None):
    doc = ezdxf.new(version)
    for layer in ("1", "4", "7", "8"):
        doc.layers.new(layer)
    if insunits is not None:
        doc.header["$INSUNITS"] = insunits
    elif "$INSUNITS" in doc.header:  # ezdxf gives new drawings $INSUNITS = 6 (metres)
        del doc.header["$INSUNITS"]
    return doc


def add_text(block, text, at=(0, 0)):
    block.add_text(text, dxfattribs={"layer": "1", "height": 5, "insert": at})


def add_boundary(block, points, close=True, lw=True, bulges=None):
    attribs = {"layer": "1"}
    if lw and bulges:
        block.add_lwpolyline([(x, y, b) for (x, y), b in zip(points, bulges)], format="xyb", close=close,
                             dxfattribs=attribs)
    elif lw:
        block.add_lwpolyline(points, format="xy", close=close, dxfattribs=attribs)
    else:
        block.add_polyline2d(points, close=close, dxfattribs=attribs)


def piece(name, vertices, grain=None, notches=(), internal=(), arcs=()):
    return {"name": name, "vertices": [list(map(float, v)) for v in vertices],
            "grain": [list(map(float, p)) for p in grain] if grain else None,
            "notches": [list(map(float, p)) for p in notches],
            "internal_lines": [[list(map(float, p)) for p in line] for line in internal], "arcs": list(arcs)}


def case_two_pieces(doc_path):
    """FRONT and BACK in millimetres: grain lines, notches (POINT and LINE), internal lines, LWPOLYLINE boundaries."""
    doc = new_doc("R2000", insunits=4)
    msp = doc.modelspace()
    add_text(msp, "UNITS: METRIC", (0, -20))
    front = [(0, 0), (500, 0), (520, 300), (450.25, 620.5), (60, 640), (-20, 300)]
    b = doc.blocks.new("B_FRONT")
    add_boundary(b, front)
    b.add_line((250, 100), (250, 500), dxfattribs={"layer": "7"})
    b.add_point((250, 0), dxfattribs={"layer": "4"})
    # a slit notch written from the inside out: the reader keeps the end on the boundary
    b.add_line((505, 150 - 8), (510, 150), dxfattribs={"layer": "4"})
    b.add_lwpolyline([(200, 620), (230, 450), (260, 618)], dxfattribs={"layer": "8"})  # a dart
    b.add_line((100, 300), (400, 300), dxfattribs={"layer": "8"})
    add_text(b, "Piece Name: FRONT", (200, 200))
    add_text(b, "Size: M", (200, 190))
    add_text(b, "Quantity: 2", (200, 180))
    msp.add_blockref("B_FRONT", (0, 0))

    back = [(0, 0), (480, 0), (480, 600), (0, 600), (0, 0)]  # closing point repeated
    c = doc.blocks.new("B_BACK")
    add_boundary(c, back)
    c.add_lwpolyline([(240, 80), (240, 520)], dxfattribs={"layer": "7"})
    c.add_point((480, 300), dxfattribs={"layer": "4"})
    add_text(c, "PIECE NAME: BACK")
    msp.add_blockref("B_BACK", (700, 0))
    doc.saveas(doc_path)
    # (510, 150) lies on the edge (500, 0)-(520, 300)
    return {"units_in_meter": 1000.0, "pieces": [
        piece("FRONT", counter_clockwise(front), [(250, 100), (250, 500)], [(250, 0), (510, 150)],
              [[(200, 620), (230, 450), (260, 618)], [(100, 300), (400, 300)]]),
        piece("BACK", counter_clockwise(back[:-1]), [(240, 80), (240, 520)], [(480, 300)])]}


def case_inches(doc_path):
    """One piece in inches ("UNITS: ENGLISH"), R12 POLYLINE boundary, no $INSUNITS."""
    doc = new_doc("R12")
    msp = doc.modelspace()
    add_text(msp, "UNITS: ENGLISH")
    yoke = [(0, 0), (10, 0), (10, 5), (0, 5)]
    b = doc.blocks.new("YOKE_BLOCK")
    add_boundary(b, yoke, lw=False)
    b.add_line((1, 2.5), (9, 2.5), dxfattribs={"layer": "7"})
    add_text(b, "Piece Name: YOKE")
    msp.add_blockref("YOKE_BLOCK", (0, 0))
    doc.saveas(doc_path)
    return {"units_in_meter": 1.0 / 0.0254, "pieces": [piece("YOKE", yoke, [(1, 2.5), (9, 2.5)])]}


def case_clockwise(doc_path):
    """A boundary drawn clockwise, with a notch and $INSUNITS = 4."""
    doc = new_doc("R2000", insunits=4)
    cw = [(0, 0), (0, 300), (200, 400), (400, 300), (400, 0)]
    assert signed_area(cw) < 0
    b = doc.blocks.new("CW")
    add_boundary(b, cw)
    b.add_point((100, 350), dxfattribs={"layer": "4"})
    add_text(b, "Piece Name: SLEEVE")
    doc.modelspace().add_blockref("CW", (0, 0))
    doc.saveas(doc_path)
    return {"units_in_meter": 1000.0, "pieces": [piece("SLEEVE", counter_clockwise(cw), None, [(100, 350)])]}


def case_cm_insunits(doc_path):
    """Centimetres from $INSUNITS = 5 alone; no INSERT (every named block is a candidate); an unnamed piece."""
    doc = new_doc("R2000", insunits=5)
    pocket = [(0, 0), (15, 0), (15, 18), (7.5, 21), (0, 18)]
    b = doc.blocks.new("POCKET")
    add_boundary(b, pocket)
    doc.saveas(doc_path)
    return {"units_in_meter": 100.0, "pieces": [piece("POCKET", pocket)]}


def case_names(doc_path):
    """No units; a boundary of four LINEs (one reversed); two pieces called SLEEVE; a bulge (half circle)."""
    doc = new_doc("R2000")
    msp = doc.modelspace()
    a = doc.blocks.new("A1")
    square = [(0, 0), (100, 0), (100, 100), (0, 100)]
    for p, q in [(square[0], square[1]), (square[2], square[1]), (square[2], square[3]), (square[3], square[0])]:
        a.add_line(p, q, dxfattribs={"layer": "1"})
    msp.add_blockref("A1", (0, 0))
    for block in ("S1", "S2"):
        s = doc.blocks.new(block)
        add_boundary(s, [(0, 0), (200, 0), (200, 100), (0, 100)])
        add_text(s, "Piece Name: SLEEVE")
        msp.add_blockref(block, (0, 0))
    # a rectangle whose top edge is a half circle: bulge 1 (counter-clockwise) from (100, 50) to (0, 50)
    dome = [(0, 0), (100, 0), (100, 50), (0, 50)]
    arc = doc.blocks.new("ARC")
    add_boundary(arc, dome, bulges=[0, 0, 1, 0])
    add_text(arc, "Piece Name: DOME")
    msp.add_blockref("ARC", (0, 0))
    center, start, end, radius = bulge_to_arc(dome[2], dome[3], 1)  # counter-clockwise from start to end
    middle = center + Vec2.from_angle(0.5 * (start + (end if end > start else end + 2 * math.pi)), radius)
    doc.saveas(doc_path)
    rect = [(0, 0), (200, 0), (200, 100), (0, 100)]
    return {"units_in_meter": 1000.0, "pieces": [
        piece("A1", square), piece("SLEEVE", rect), piece("SLEEVE_2", rect),
        piece("DOME", dome, arcs=[{"edge": 2, "center": [center.x, center.y], "radius": radius,
                                        "middle": [middle.x, middle.y]}])]}


def malformed(doc_path, name):
    doc = new_doc("R2000", insunits=4)
    msp = doc.modelspace()
    b = doc.blocks.new("P")
    if name == "no_boundary":
        add_text(b, "Piece Name: CUFF")
        b.add_line((0, 0), (100, 0), dxfattribs={"layer": "7"})
    elif name == "two_points":
        add_boundary(b, [(0, 0), (100, 0), (100, 0)])
        add_text(b, "Piece Name: STRAP")
    elif name == "self_intersecting":
        add_boundary(b, [(0, 0), (100, 100), (100, 0), (0, 100)])
        add_text(b, "Piece Name: BOWTIE")
    elif name == "sliver":
        add_boundary(b, [(0, 0), (1000, 0), (500, 1e-7)])
        add_text(b, "Piece Name: SLIVER")
    elif name == "nan":
        add_boundary(b, [(0, 0), (100, 0), (100, 100)])
        b.add_line((float("nan"), 0), (10, 10), dxfattribs={"layer": "7"})
        add_text(b, "Piece Name: GHOST")
    elif name == "open_chain":
        b.add_line((0, 0), (100, 0), dxfattribs={"layer": "1"})
        b.add_line((100, 0), (100, 100), dxfattribs={"layer": "1"})
        b.add_line((50, 150), (0, 0), dxfattribs={"layer": "1"})
        add_text(b, "Piece Name: GAP")
    elif name == "far_notch":
        add_boundary(b, [(0, 0), (100, 0), (100, 100)])
        b.add_point((0, 200100), dxfattribs={"layer": "4"})
        add_text(b, "Piece Name: FAR")
    elif name == "no_pieces":
        msp.add_lwpolyline([(0, 0), (100, 0), (100, 100)], close=True, dxfattribs={"layer": "1"})
    if name != "no_pieces":
        msp.add_blockref("P", (0, 0))
    doc.saveas(doc_path)
    if name == "truncated":
        with open(doc_path, "rb") as f:
            data = f.read()
        with open(doc_path, "wb") as f:
            f.write(data[: len(data) // 2])


CASES = {"two_pieces": case_two_pieces, "inches": case_inches, "clockwise": case_clockwise,
         "cm_insunits": case_cm_insunits, "names": case_names}
MALFORMED = ("no_boundary", "two_points", "self_intersecting", "sliver", "nan", "open_chain", "far_notch", "no_pieces",
             "truncated")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--case", required=True, choices=sorted(CASES) + sorted(MALFORMED))
    args = parser.parse_args()
    if args.case in CASES:
        expected = CASES[args.case](args.out)
        with open(args.out[:-4] + ".json" if args.out.endswith(".dxf") else args.out + ".json", "w") as f:
            json.dump(expected, f, indent=1)
    else:
        malformed(args.out, args.case)
    return 0


if __name__ == "__main__":
    sys.exit(main())
