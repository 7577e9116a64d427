#!/usr/bin/env python3
"""Drafts Drape's garment library from a body-measurement file (GarmentCode's YAML layout, cm).

Usage: scripts/draft_patterns.py [MEASUREMENTS.yaml|.json] [-o OUTPUT_DIR]
Defaults: assets/avatars/female.yaml -> assets/patterns/.

Every garment is drafted the way a pattern maker drafts a block: girths from the measurements plus wearing
ease, vertical levels from the body's landmarks (neck base, bust, waist, hip line, crotch), curves for the
armholes, necklines, sleeve caps and crotch. Sleeve caps are solved so their length equals the armhole they
are sewn to. Panels are flat and placed in planes in front of and behind the body (and of the arms), as
GarmentCode does; the simulator sews them together. The script checks each stitch (lengths within 1%, edges
paired start-to-end) before writing. Python 3 standard library only. See assets/patterns/README.md.
"""
import argparse
import json
import math
import os
import sys

# Placement planes (cm, body faces +z). GarmentCode's average body (mean_all.obj) spans z in [-14.8, 15.3]
# (toes and buttocks included); the default mannequins are derived from it and are smaller.
Z_FRONT = 22.0       # front bodice / skirt / trouser panels
Z_BACK = -20.0       # back panels
Z_OUTER = 5.0        # extra offset of an outer layer beyond the inner one
Z_SLEEVE_FRONT = 16.0
Z_SLEEVE_BACK = -16.0


# ----------------------------------------------------------------------------------------------- measurements
def load_measurements(path):
    """Reads `body:` key: value lines (YAML subset GarmentCode writes) or a JSON file; returns a dict in cm."""
    if path.endswith(".json"):
        with open(path) as f:
            data = json.load(f)
        return {k: float(v) for k, v in data.get("body", data).items()}
    values = {}
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].rstrip()
            if not line.strip() or line.strip() == "body:":
                continue
            key, _, value = line.strip().partition(":")
            values[key.strip()] = float(value)
    return values


class Body:
    """Landmark levels (cm above the floor) and half-widths derived from the measurements."""

    def __init__(self, m):
        self.m = m
        self.neck_y = m["height"] - m["head_l"]
        self.waist_y = self.neck_y - m["waist_line"]
        self.hip_y = self.waist_y - m["hips_line"]
        self.bust_y = self.neck_y - m["vert_bust_line"]
        # On GarmentCode's average body the legs part ~3 cm below hip line - crotch_hip_diff (measured on
        # mean_all.obj: the gap between the thighs closes at y ~ 0.73 m).
        self.crotch_y = self.hip_y - m["crotch_hip_diff"] - 3.0
        self.shoulder_x = m["shoulder_w"] / 2.0
        self.neck_x = m["neck_w"] / 2.0
        self.shoulder_y = self.neck_y - (self.shoulder_x - self.neck_x) * math.tan(math.radians(m["shoulder_incl"]))
        self.arm_angle = math.radians(m["arm_pose_angle"])  # below the horizontal
        self.knee_y = self.crotch_y / 2.0 + 4.0
        # Upper-arm girth is not in GarmentCode's list: about 0.3 bust on average figures.
        self.bicep = 0.30 * m["bust"]


# ----------------------------------------------------------------------------------------------- geometry
def bezier(points, t):
    n = len(points) - 1
    x = y = 0.0
    for i, (px, py) in enumerate(points):
        c = math.comb(n, i) * (1 - t) ** (n - i) * t ** i
        x += c * px
        y += c * py
    return x, y


def curve_length(points, samples=2000):
    total, prev = 0.0, points[0]
    for i in range(1, samples + 1):
        p = bezier(points, i / samples) if len(points) > 2 else (
            points[0][0] + (points[1][0] - points[0][0]) * i / samples,
            points[0][1] + (points[1][1] - points[0][1]) * i / samples)
        total += math.dist(prev, p)
        prev = p
    return total


def to_relative(s, e, c):
    """Absolute control point c of the edge s -> e to GarmentCode's relative [x, y] (docs/FORMATS.md)."""
    dx, dy = e[0] - s[0], e[1] - s[1]
    d2 = dx * dx + dy * dy
    px, py = c[0] - s[0], c[1] - s[1]
    return [round((px * dx + py * dy) / d2, 5), round((px * -dy + py * dx) / d2, 5)]


def euler_xyz(m):
    """Intrinsic XYZ Euler angles (degrees) of the rotation matrix m = Rx(a) Ry(b) Rz(c)."""
    b = math.asin(max(-1.0, min(1.0, m[0][2])))
    if abs(math.cos(b)) > 1e-9:
        a = math.atan2(-m[1][2], m[2][2])
        c = math.atan2(-m[0][1], m[0][0])
    else:  # gimbal lock: put everything in a
        a = math.atan2(m[2][1], m[1][1])
        c = 0.0
    return [round(math.degrees(v), 4) + 0.0 for v in (a, b, c)]


class Panel:
    """A panel outline drafted in a 2D frame; edges are (start, end, absolute controls, name, label)."""

    def __init__(self, name):
        self.name = name
        self.points = []
        self.edges = []  # [i, j, controls(list of absolute points), name, label]
        self.ex = (1.0, 0.0, 0.0)  # 3D image of the 2D x axis
        self.ey = (0.0, 1.0, 0.0)
        self.origin = (0.0, 0.0, 0.0)  # 3D position (cm) of the 2D origin

    def loop(self, items):
        """items: list of (point, edge-to-next) where edge = dict(name=, label=, ctrl=[absolute points])."""
        n = len(items)
        self.points = [p for p, _ in items]
        self.edges = [[i, (i + 1) % n, e.get("ctrl", []), e.get("name"), e.get("label")] for i, (_, e) in
                      enumerate(items)]
        return self

    def area(self):
        a = 0.0
        for i, j, *_ in self.edges:
            a += self.points[i][0] * self.points[j][1] - self.points[j][0] * self.points[i][1]
        return a / 2.0

    def mirrored(self, name):
        """Mirror image (x -> -x) with the loop reversed so it stays counter-clockwise."""
        out = Panel(name)
        pts = [(-x, y) for x, y in self.points]
        n = len(self.edges)
        edges = []
        for k in range(n - 1, -1, -1):
            i, j, ctrl, ename, label = self.edges[k]
            edges.append([j, i, [(-x, y) for x, y in reversed(ctrl)], ename, label])
        # renumber so that vertices follow the new loop order
        order = [e[0] for e in edges]
        index = {old: new for new, old in enumerate(order)}
        out.points = [pts[old] for old in order]
        out.edges = [[index[i], index[j], c, en, lb] for i, j, c, en, lb in edges]
        return out

    def edge_points(self, k):
        i, j, ctrl, *_ = self.edges[k]
        return [self.points[i]] + list(ctrl) + [self.points[j]]

    def edge_length(self, k):
        return curve_length(self.edge_points(k))

    def edge_index(self, name):
        for k, e in enumerate(self.edges):
            if e[3] == name:
                return k
        raise KeyError(f"panel {self.name}: no edge {name}")

    def place(self, ex, origin):
        """Places the panel: 2D x axis -> ex (unit, in the xy plane or not), normal = ex x ey outward."""
        self.ex = ex
        self.origin = origin
        return self

    def rotation(self, ey):
        ex = self.ex
        n = (ex[1] * ey[2] - ex[2] * ey[1], ex[2] * ey[0] - ex[0] * ey[2], ex[0] * ey[1] - ex[1] * ey[0])
        return [[ex[r], ey[r], n[r]] for r in range(3)]

    def to3d(self, p):
        r = self.rotation(self.ey)
        return tuple(self.origin[k] + r[k][0] * p[0] + r[k][1] * p[1] for k in range(3))

    def to_json(self):
        edges = []
        for i, j, ctrl, _, label in self.edges:
            e = {"endpoints": [i, j]}
            s, t = self.points[i], self.points[j]
            if len(ctrl) == 1:
                e["curvature"] = {"type": "quadratic", "params": [to_relative(s, t, ctrl[0])]}
            elif len(ctrl) == 2:
                e["curvature"] = {"type": "cubic", "params": [to_relative(s, t, c) for c in ctrl]}
            if label:
                e["label"] = label
            edges.append(e)
        return {
            "vertices": [[round(x, 3) + 0.0, round(y, 3) + 0.0] for x, y in self.points],
            "edges": edges,
            "translation": [round(v, 3) + 0.0 for v in self.origin],
            "rotation": euler_xyz(self.rotation(self.ey)),
        }


def in_plane(angle_deg_of_x, facing_front):
    """ex, ey for a panel in a z = const plane: 2D x at angle (degrees, about +z as seen from the front)."""
    a = math.radians(angle_deg_of_x)
    ex = (math.cos(a), math.sin(a), 0.0)
    return ex, (-math.sin(a), math.cos(a), 0.0) if facing_front else (math.sin(a), -math.cos(a), 0.0)


class Garment:
    def __init__(self, name, description):
        self.name = name
        self.description = description
        self.panels = {}
        self.stitches = []  # ((panel, edge name), (panel, edge name))
        self.labels = {}

    def add(self, panel, ex_ey, origin, label=None):
        panel.ex, panel.ey = ex_ey
        panel.origin = origin
        if panel.area() <= 0:
            raise ValueError(f"{self.name}: panel {panel.name} is not counter-clockwise")
        self.panels[panel.name] = panel
        if label:
            self.labels[panel.name] = label
        return panel

    def sew(self, a, ea, b, eb):
        self.stitches.append(((a, ea), (b, eb)))

    def check(self):
        """Every stitch: arc lengths within 1%, and a's start lies nearer b's end than b's start in 3D."""
        for (a, ea), (b, eb) in self.stitches:
            pa, pb = self.panels[a], self.panels[b]
            ka, kb = pa.edge_index(ea), pb.edge_index(eb)
            la, lb = pa.edge_length(ka), pb.edge_length(kb)
            if abs(la - lb) > 0.01 * max(la, lb):
                raise ValueError(f"{self.name}: {a}.{ea} ({la:.2f}) vs {b}.{eb} ({lb:.2f}) differ")
            a0, a1 = pa.to3d(pa.edge_points(ka)[0]), pa.to3d(pa.edge_points(ka)[-1])
            b0, b1 = pb.to3d(pb.edge_points(kb)[0]), pb.to3d(pb.edge_points(kb)[-1])
            if math.dist(a0, b1) + math.dist(a1, b0) > math.dist(a0, b0) + math.dist(a1, b1):
                raise ValueError(f"{self.name}: {a}.{ea} and {b}.{eb} would be sewn twisted")

    def to_json(self):
        self.check()
        panels = {}
        for name, p in self.panels.items():
            panels[name] = p.to_json()
            if name in self.labels:
                panels[name]["label"] = self.labels[name]
        stitches = [[{"panel": a, "edge": self.panels[a].edge_index(ea)},
                     {"panel": b, "edge": self.panels[b].edge_index(eb)}] for (a, ea), (b, eb) in self.stitches]
        return {
            "pattern": {"panels": panels, "stitches": stitches, "panel_order": list(self.panels)},
            "parameters": {},
            "properties": {"units_in_meter": 100, "curvature_coords": "relative",
                           "name": self.name, "description": self.description,
                           "licence": "Drape project (original draft, scripts/draft_patterns.py)"},
        }


# ----------------------------------------------------------------------------------------------- blocks
def bodice(body, name, front, opts):
    """A full-width (both sides) bodice panel seen from outside, x = 0 at the centre line.

    opts: bust_ease, hip_ease, waist_ease (None: straight side), hem_y, flare (cm added at the hem per side),
    neck_widen, neck_depth_front, neck_depth_back, shoulder_ext, armhole_drop.
    """
    m = body.m
    half = lambda girth: girth / 4.0
    nx = body.neck_x + opts["neck_widen"]
    sx = body.shoulder_x + opts["shoulder_ext"]
    slope = math.tan(math.radians(m["shoulder_incl"]))
    ny = body.neck_y + 0.5
    sy = ny - (sx - nx) * slope
    ua_y = body.shoulder_y - m["armscye_depth"] - opts["armhole_drop"]
    ua_x = half(m["bust"] + opts["bust_ease"])
    hip_x = max(ua_x, half(m["hips"] + opts["hip_ease"])) if opts.get("waist_ease") is None else \
        half(m["hips"] + opts["hip_ease"])
    hem_y = opts["hem_y"]
    # side seam from the hem up to the underarm, as a list of (point, controls of the edge below it)
    side = []  # points from the hem upwards (right side, x > 0)
    if opts.get("waist_ease") is None:
        hem_x = max(ua_x, hip_x) + opts.get("flare", 0.0)
        side = [(hem_x, hem_y), (ua_x, ua_y)]
        side_ctrl = [[]]
        side_names = ["side0"]
    else:
        waist_x = half(m["waist"] + opts["waist_ease"])
        hem_x = hip_x + opts.get("flare", 0.0)
        side = [(hem_x, hem_y), (hip_x, body.hip_y), (waist_x, body.waist_y), (ua_x, ua_y)]
        side_ctrl = [[], [(hip_x, body.hip_y + 0.55 * (body.waist_y - body.hip_y))],
                     [(waist_x, body.waist_y + 0.4 * (ua_y - body.waist_y))]]
        side_names = ["side0", "side1", "side2"]
    dx, dy = ua_x - sx, sy - ua_y
    if front:
        arm_ctrl = [(ua_x - 0.62 * dx, ua_y + 0.02 * dy), (sx - 0.12 * dx, ua_y + 0.42 * dy)]
        depth = opts["neck_depth_front"]
    else:
        arm_ctrl = [(ua_x - 0.5 * dx, ua_y + 0.04 * dy), (sx - 0.02 * dx, ua_y + 0.48 * dy)]
        depth = opts["neck_depth_back"]
    k = 4.0 / 3.0 * depth
    # hem: rises towards the sides when the side seam flares (so the hem hangs level)
    hem_rise = 0.0
    if opts.get("flare", 0.0) > 0.0:
        top = side[1]
        hem_rise = opts["flare"] ** 2 / (2.0 * max(1.0, top[1] - hem_y))
    side[0] = (side[0][0], hem_y + hem_rise)
    hem_ctrl = [(0.0, hem_y - hem_rise)] if hem_rise > 0 else []
    items = [((-side[0][0], side[0][1]), {"name": "hem", "ctrl": hem_ctrl, "label": "hem"})]
    for i in range(len(side) - 1):
        items.append((side[i], {"name": f"r_{side_names[i]}", "ctrl": side_ctrl[i]}))
    items += [
        ((ua_x, ua_y), {"name": "r_armhole", "ctrl": arm_ctrl, "label": "armhole"}),
        ((sx, sy), {"name": "r_shoulder"}),
        ((nx, ny), {"name": "neck", "ctrl": [(nx, ny - k), (-nx, ny - k)], "label": "neck"}),
        ((-nx, ny), {"name": "l_shoulder"}),
        ((-sx, sy), {"name": "l_armhole", "ctrl": [(-x, y) for x, y in reversed(arm_ctrl)], "label": "armhole"}),
    ]
    for i in range(len(side) - 1, 0, -1):
        ctrl = side_ctrl[i - 1]
        items.append(((-side[i][0], side[i][1]), {"name": f"l_{side_names[i - 1]}", "ctrl": ctrl}))
    # fix controls of the left side: they were drafted for the right side going up
    panel = Panel(name).loop(items)
    for e in panel.edges:
        if e[3] and e[3].startswith("l_side"):
            e[2] = [(-x, y) for x, y in reversed(e[2])]
    return panel, side_names


def sleeve_half(name, top_is_v_positive, cap_length, body, opts):
    """Half a sleeve (front or back of the arm) in a frame with u along the arm from the shoulder point.

    The cap runs from the shoulder point T = (0, 0) to the underarm point U = (cap_h, -hw); cap_h is solved
    so the cap is as long as the armhole it is sewn to (cap_length).
    """
    hw = (body.bicep + opts["bicep_ease"]) / 2.0  # each half covers half the sleeve's girth
    cuff = (body.bicep * opts["cuff_ratio"] + opts["bicep_ease"]) / 2.0
    length = opts["sleeve_length"]

    def cap(cap_h, bulge):
        return [(0.0, 0.0), (-bulge * cap_h, -0.45 * hw), (0.45 * cap_h, -1.0 * hw), (cap_h, -hw)]

    def solve(f, lo, hi, target):
        if f(lo) > target or f(hi) < target:
            raise ValueError(f"{name}: cannot fit a sleeve cap of length {target:.1f} cm")
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if f(mid) < target else (lo, mid)
        return 0.5 * (lo + hi)

    # cap height for the mean armhole with the default bulge, then this half's bulge for its own armhole, so
    # the front and back halves share the underarm point and their underarm seams match
    cap_h = solve(lambda h: curve_length(cap(h, 0.25)), 0.1, 40.0, opts["mean_armhole"])
    bulge = solve(lambda b: curve_length(cap(cap_h, b)), -0.5, 1.5, cap_length)
    pts = cap(cap_h, bulge)
    cap_h = pts[-1][0]
    T, U = pts[0], pts[3]
    C1, C2 = (length, 0.0), (length, -cuff)
    p = Panel(name).loop([
        (T, {"name": "cap", "ctrl": [pts[1], pts[2]]}),
        (U, {"name": "under"}),
        (C2, {"name": "cuff", "label": "cuff"}),
        (C1, {"name": "top"}),
    ])
    if top_is_v_positive:
        return p
    # v flipped: mirror in v (y -> -y) and reverse so it stays counter-clockwise
    q = Panel(name)
    flipped = Panel("tmp")
    flipped.points = [(x, -y) for x, y in p.points]
    flipped.edges = [[i, j, [(x, -y) for x, y in c], n, l] for i, j, c, n, l in p.edges]
    # reverse by mirroring twice: mirrored() negates x, so negate x first
    flipped.points = [(-x, y) for x, y in flipped.points]
    flipped.edges = [[i, j, [(-x, y) for x, y in c], n, l] for i, j, c, n, l in flipped.edges]
    q = flipped.mirrored(name)
    return q


def add_top(g, body, opts, z_front, z_back, prefix=""):
    """Front and back bodice with two sleeve halves per arm (when opts['sleeve_length'] > 0).

    Each sleeve half is placed in its plane with its top seam along the arm, starting sleeve_offset cm out along
    the arm from the shoulder point and sleeve_raise cm above the arm's line. The stitches pull each seam closed
    along the straight line between its two sides, so the underarm seam must pass below the arm and beside the
    torso, and the top seam above the arm (tests/unit/garment/garment_library_test.cpp checks every stitch pair's line
    against the body).
    """
    front, sides = bodice(body, prefix + "front", True, opts)
    back, _ = bodice(body, prefix + "back", False, opts)
    g.add(front, in_plane(0, True), (0.0, 0.0, z_front), label=opts.get("label"))
    # seen from behind, the panel's 2D x runs along -X
    g.add(back, ((-1.0, 0.0, 0.0), (0.0, 1.0, 0.0)), (0.0, 0.0, z_back), label=opts.get("label"))
    f, b = prefix + "front", prefix + "back"
    for s in sides:  # front right (+X) meets back left (+X)
        g.sew(f, "r_" + s, b, "l_" + s)
        g.sew(f, "l_" + s, b, "r_" + s)
    g.sew(f, "r_shoulder", b, "l_shoulder")
    g.sew(f, "l_shoulder", b, "r_shoulder")
    if opts.get("sleeve_length", 0) <= 0:
        return
    a = math.degrees(body.arm_angle) - opts.get("sleeve_lift", 0.0)
    fa = front.edge_length(front.edge_index("r_armhole"))
    ba = back.edge_length(back.edge_index("l_armhole"))
    sx = front.points[front.edge_index("r_shoulder")][0]
    sy = front.points[front.edge_index("r_shoulder")][1]
    opts = dict(opts, mean_armhole=0.5 * (fa + ba))
    for side, sign in (("l", 1.0), ("r", -1.0)):  # body's left arm at +X
        # front half: seen from the front, the left arm runs down to the right
        angle_front = -a if sign > 0 else 180.0 + a
        angle_back = 180.0 + a if sign > 0 else -a  # seen from behind (2D x = -X)
        fs = sleeve_half(f"{prefix}{side}_sleeve_front", sign > 0, fa, body, opts)
        bs = sleeve_half(f"{prefix}{side}_sleeve_back", sign < 0, ba, body, opts)
        ar = math.radians(a)  # the arm runs at -a from the horizontal, away from the body
        d_out, d_up = opts.get("sleeve_offset", 0.0), opts.get("sleeve_raise", 0.0)
        ox = sign * (sx + d_out * math.cos(ar) + d_up * math.sin(ar))
        oy = sy - d_out * math.sin(ar) + d_up * math.cos(ar)
        g.add(fs, in_plane(angle_front, True), (ox, oy, Z_SLEEVE_FRONT), label=opts.get("label"))
        ex, ey = in_plane(angle_back, True)
        ex3, ey3 = (-ex[0], ex[1], 0.0), (-ey[0], ey[1], 0.0)  # back view: mirror X
        g.add(bs, (ex3, ey3), (ox, oy, Z_SLEEVE_BACK), label=opts.get("label"))
        fe = "r_armhole" if sign > 0 else "l_armhole"
        be = "l_armhole" if sign > 0 else "r_armhole"
        g.sew(f, fe, fs.name, "cap")
        g.sew(b, be, bs.name, "cap")
        g.sew(fs.name, "top", bs.name, "top")
        g.sew(fs.name, "under", bs.name, "under")


def skirt_panel(body, name, opts):
    """A-line skirt panel (front or back), full width, seen from outside; 2D y = height above the floor."""
    m = body.m
    wx = (m["waist"] + opts["waist_ease"]) / 4.0
    hx = (m["hips"] + opts["hip_ease"]) / 4.0
    wy, hy = body.waist_y, body.hip_y
    hem_c = wy - opts["length"]
    flare = opts["flare"]
    side_top = math.dist((wx, wy), (hx, hy))
    # the side seam is longer than the centre line; the hem rises at the sides so it hangs level
    rise = flare ** 2 / (2.0 * (hy - hem_c))
    hem_x = hx + flare
    return Panel(name).loop([
        ((-hem_x, hem_c + rise), {"name": "hem", "ctrl": [(0.0, hem_c - rise)], "label": "hem"}),
        ((hem_x, hem_c + rise), {"name": "r_side0"}),
        ((hx, hy), {"name": "r_side1", "ctrl": [(hx, hy + 0.6 * (wy - hy))]}),
        ((wx, wy + 0.5), {"name": "waist", "ctrl": [(0.0, wy - 0.5)], "label": "waist"}),
        ((-wx, wy + 0.5), {"name": "l_side1", "ctrl": [(-hx, hy + 0.6 * (wy - hy))]}),
        ((-hx, hy), {"name": "l_side0"}),
    ]), side_top


def add_skirt(g, body, opts, z_front, z_back, prefix="", label=None):
    front, _ = skirt_panel(body, prefix + "front", opts)
    back, _ = skirt_panel(body, prefix + "back", opts)
    g.add(front, in_plane(0, True), (0.0, 0.0, z_front), label=label)
    g.add(back, ((-1.0, 0.0, 0.0), (0.0, 1.0, 0.0)), (0.0, 0.0, z_back), label=label)
    for s in ("side0", "side1"):
        g.sew(prefix + "front", "r_" + s, prefix + "back", "l_" + s)
        g.sew(prefix + "front", "l_" + s, prefix + "back", "r_" + s)


def trouser_leg(body, name, back, crotch_drop=2.0):
    """One trouser leg half (front or back) for the body's left leg, drafted with x growing outwards from the
    crotch point (x = 0 at the crotch point, y = height above the floor)."""
    m = body.m
    hip_q = (m["hips"] + 4.0) / 4.0 + (1.0 if back else -1.0)
    waist_q = (m["waist"] + 2.0) / 4.0 + (0.5 if back else -0.5)
    ext = m["hips"] / (10.0 if back else 16.0)  # crotch extension
    crease = (ext + hip_q) / 2.0
    knee_h = (m["leg_circ"] * 0.72 + 6.0) / 4.0 + (0.5 if back else -0.5)  # half knee width of this panel
    hem_h = knee_h - 0.5
    wy = body.waist_y + (2.5 if back else 0.0)  # back rises at the centre
    cy = body.crotch_y - crotch_drop  # crotch seam below the body
    hem_y = 3.0
    ky = body.knee_y
    cf_top = (ext + (1.5 if back else 0.5), wy)
    cf_hip = (ext, body.hip_y)
    side_waist = (cf_top[0] + waist_q, body.waist_y + 0.5)
    side_hip = (ext + hip_q, body.hip_y)
    knee_out, knee_in = (crease + knee_h, ky), (crease - knee_h, ky)
    hem_out, hem_in = (crease + hem_h, hem_y), (crease - hem_h, hem_y)
    cp = (0.0, cy)
    crotch_ctrl = [(ext, cy + 0.35 * (body.hip_y - cy)), (ext * 0.35, cy)]
    return Panel(name).loop([
        (hem_in, {"name": "hem", "label": "hem"}),
        (hem_out, {"name": "out0"}),
        (knee_out, {"name": "out1", "ctrl": [(side_hip[0], ky + 0.75 * (body.hip_y - ky))]}),
        (side_hip, {"name": "out2", "ctrl": [(side_hip[0], body.hip_y + 0.55 * (side_waist[1] - body.hip_y))]}),
        (side_waist, {"name": "waist", "label": "waist"}),
        (cf_top, {"name": "centre0"}),
        (cf_hip, {"name": "centre1", "ctrl": crotch_ctrl}),
        (cp, {"name": "in1", "ctrl": [(knee_in[0] - 0.5, cy - 0.5 * (cy - ky))]}),
        (knee_in, {"name": "in0"}),
    ])


def crotch_point(p):
    """The vertex shared by a trouser panel's crotch curve (centre1) and inseam (in1)."""
    c, i = p.edges[p.edge_index("centre1")], p.edges[p.edge_index("in1")]
    shared = {c[0], c[1]} & {i[0], i[1]}
    return p.points[shared.pop()]


def add_trousers(g, body):
    gap = 0.4  # cm: crotch points this far from the centre line
    for back in (False, True):
        leg = trouser_leg(body, "left_back" if back else "left_front", back)
        if back:  # lower or raise the back crotch point so the inseams match the front's
            front_in = trouser_leg(body, "f", False)
            target = front_in.edge_length(front_in.edge_index("in1"))
            lo, hi = -3.0, 8.0
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                t = trouser_leg(body, "b", True, mid)
                lo, hi = (lo, mid) if t.edge_length(t.edge_index("in1")) < target else (mid, hi)
            leg = trouser_leg(body, "left_back", True, 0.5 * (lo + hi))
        # tilt the leg about the crotch point so the inseam hangs vertically between the legs
        cp = leg.points[leg.edge_index("in1")]
        hem_in = leg.points[leg.edge_index("hem")]
        tilt = math.degrees(math.atan2(hem_in[0] - cp[0], cp[1] - hem_in[1]))
        z = Z_BACK if back else Z_FRONT
        for side, sign in (("left", 1.0), ("right", -1.0)):
            # seen from outside, the leg grows outwards along +x of its view (front left, back right) or -x
            mirror = (sign > 0) == back
            p = leg.mirrored("tmp") if mirror else leg
            p.name = f"{side}_{'back' if back else 'front'}"
            angle = tilt if mirror else -tilt
            ex, ey = in_plane(angle, True)
            if back:  # seen from behind: 2D x runs along -X
                ex, ey = (-ex[0], ex[1], 0.0), (-ey[0], ey[1], 0.0)
            # the crotch point sits at X = sign * gap, y = its own height
            cpp = crotch_point(p)
            origin = (sign * gap - (ex[0] * cpp[0] + ey[0] * cpp[1]), cpp[1] - (ex[1] * cpp[0] + ey[1] * cpp[1]), z)
            g.add(p, (ex, ey), origin)
    for side in ("left", "right"):
        f, b = f"{side}_front", f"{side}_back"
        outer, inner = (("out0", "out1", "out2"), ("in0", "in1"))
        for e in outer + inner:
            g.sew(f, e, b, e)
    g.sew("left_front", "centre0", "right_front", "centre0")
    g.sew("left_front", "centre1", "right_front", "centre1")
    g.sew("left_back", "centre0", "right_back", "centre0")
    g.sew("left_back", "centre1", "right_back", "centre1")


# ----------------------------------------------------------------------------------------------- garments
def garments(body):
    m = body.m
    out = []
    # T-shirt: jersey, 10 cm ease at the bust, hip length, short sleeves.
    tee = Garment("tshirt", "Short-sleeved T-shirt, 10 cm bust ease, hip length")
    add_top(tee, body, dict(bust_ease=10.0, hip_ease=8.0, waist_ease=None, hem_y=body.hip_y - 4.0, neck_widen=1.0,
                            neck_depth_front=7.0, neck_depth_back=2.0, shoulder_ext=1.0, armhole_drop=9.0,
                            sleeve_length=20.0, sleeve_offset=12.0, sleeve_raise=2.0, bicep_ease=8.0, cuff_ratio=0.9),
            Z_FRONT, Z_BACK)
    out.append(tee)
    skirt = Garment("aline_skirt", "A-line skirt, knee length, 2 cm waist ease, 8 cm flare per side seam")
    add_skirt(skirt, body, dict(waist_ease=2.0, hip_ease=4.0, length=m["waist_line"] * 0 + 58.0, flare=8.0),
              Z_FRONT - 2.0, Z_BACK)
    out.append(skirt)
    trousers = Garment("trousers", "Straight trousers, full length, 4 cm hip ease")
    add_trousers(trousers, body)
    out.append(trousers)
    dress = Garment("sleeveless_dress", "Sleeveless A-line dress, knee length, shaped at the waist")
    add_top(dress, body, dict(bust_ease=8.0, hip_ease=6.0, waist_ease=8.0, hem_y=body.waist_y - 58.0, flare=7.0,
                              neck_widen=2.0, neck_depth_front=9.0, neck_depth_back=3.0, shoulder_ext=-3.0,
                              armhole_drop=8.0, sleeve_length=0.0), Z_FRONT, Z_BACK)
    out.append(dress)
    outfit = Garment("shirt_over_skirt", "Two layers: a loose elbow-sleeve shirt (outer) over the A-line skirt")
    add_skirt(outfit, body, dict(waist_ease=2.0, hip_ease=4.0, length=58.0, flare=8.0), Z_FRONT - 2.0, Z_BACK,
              prefix="skirt_", label="inner")
    add_top(outfit, body, dict(bust_ease=14.0, hip_ease=14.0, waist_ease=None, hem_y=body.hip_y - 6.0,
                               neck_widen=1.5, neck_depth_front=8.0, neck_depth_back=2.0, shoulder_ext=1.5,
                               armhole_drop=10.0, sleeve_length=30.0, bicep_ease=10.0, cuff_ratio=0.85,
                               sleeve_offset=12.0, sleeve_raise=2.0, label="outer"),
            Z_FRONT + Z_OUTER, Z_BACK - Z_OUTER, prefix="shirt_")
    out.append(outfit)
    return out


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.dirname(here)
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("measurements", nargs="?", default=os.path.join(root, "assets/avatars/female.yaml"))
    ap.add_argument("-o", "--output", default=os.path.join(root, "assets/patterns"))
    args = ap.parse_args()
    body = Body(load_measurements(args.measurements))
    os.makedirs(args.output, exist_ok=True)
    for g in garments(body):
        data = g.to_json()
        data["properties"]["measurements"] = os.path.basename(args.measurements)
        path = os.path.join(args.output, g.name + ".json")
        with open(path + ".tmp", "w") as f:
            json.dump(data, f, indent=1)
            f.write("\n")
        os.replace(path + ".tmp", path)
        print(f"{path}: {len(g.panels)} panels, {len(g.stitches)} stitches")
    return 0


if __name__ == "__main__":
    sys.exit(main())
