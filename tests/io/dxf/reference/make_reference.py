#!/usr/bin/python3
"""Independent reference figures for the AAMA/ASTM DXF pattern files in <shared>/data/dxf.

Run with Debian's interpreter (it has python3-ezdxf):

    /usr/bin/python3 make_reference.py [SHARED_DIR]

SHARED_DIR defaults to ../../../../../shared relative to this script (i.e. /work/shared).
Writes expected.json next to this script and prints a comparison with the table in
<shared>/data/dxf/README.md.  See README.md next to this script for every definition.

Two readers are used and must agree before anything is computed:
  * ezdxf (the primary reader; all figures are computed from what it returns), and
  * a minimal tag reader written here (raw_read) that walks the group-code/value pairs.
The script aborts if they disagree about any piece block's entities, layers, coordinates,
polyline flags, bulges or texts.

Nothing here is shared with the C++ importer (it was written without looking at it).
"""

import argparse
import json
import math
import os
import re
import sys
from fractions import Fraction

import ezdxf

TOL_M = 1e-6                       # coincidence / duplicate tolerance, metres
UNIT_FACTOR = {"mm": 0.001, "inch": 0.0254}   # metres per file unit (inch exact)
LAYOUT_BLOCKS = {"$model_space", "$paper_space", "*model_space", "*paper_space"}
ASTM_QV_LAYERS = {"84", "85", "86", "87"}

# Table from <shared>/data/dxf/README.md, checked at the end of the run.
README_TABLE = {
    "simple.DXF": (4, 56, 14, "inch"),
    "MEN_CLASSIC_TEE.DXF": (7, 105, 15, "inch"),
    "WM_SLIM_TANK.DXF": (2, 28, 14, "inch"),
    "GLX4802S19_AAMA.DXF": (3, 42, 14, "mm"),
    "GLX4802S19_ASTM.DXF": (3, 42, 14, "mm"),
    "ORILEGWB_AAMA.DXF": (2, 28, 14, "mm"),
    "GMH1006F18_AAMA.DXF": (6, 90, 15, "mm"),
    "drill-holes.DXF": (8, 120, 15, "mm"),
    "mirrored.DXF": (17, 255, 15, "mm"),
    "clo-box.dxf": (1, 1, 1, "inch"),
    "clo-pattern.dxf": (9, 9, 1, "mm"),
    "Valentina_MaleShirt_AAMA_R12.dxf": (17, 17, 1, "mm"),
    "Valentina_Trousers_ASTM_R12.dxf": (11, 11, 1, "mm"),
}


def sig(x, n=10):
    """Round to n significant digits (and turn -0.0 into 0.0)."""
    if x is None:
        return None
    y = float(f"{x:.{n}g}")
    return 0.0 if y == 0 else y


# ----------------------------------------------------------------------------------------
# Reader 1: ezdxf, normalised to a plain representation
# ----------------------------------------------------------------------------------------

def norm_entity_ezdxf(e):
    t = e.dxftype()
    layer = e.dxf.layer
    if t == "POINT":
        p = e.dxf.location
        return (t, layer, (p.x, p.y))
    if t == "LINE":
        a, b = e.dxf.start, e.dxf.end
        return (t, layer, (a.x, a.y, b.x, b.y))
    if t == "POLYLINE":
        verts = tuple((v.dxf.location.x, v.dxf.location.y, v.dxf.get("bulge", 0.0)) for v in e.vertices)
        return (t, layer, (int(e.dxf.get("flags", 0)), verts))
    if t == "LWPOLYLINE":
        verts = tuple((x, y, b) for x, y, b in e.get_points("xyb"))
        return (t, layer, (int(e.dxf.get("flags", 0)), verts))
    if t in ("TEXT", "ATTDEF"):
        return (t, layer, e.dxf.text)
    if t == "MTEXT":
        return (t, layer, e.text)
    if t == "INSERT":
        d = e.dxf
        return (t, layer, (d.name, d.insert.x, d.insert.y, d.get("xscale", 1.0), d.get("yscale", 1.0),
                           d.get("rotation", 0.0)))
    return (t, layer, None)


def read_ezdxf(path):
    doc = ezdxf.readfile(path)
    blocks = []
    for b in doc.blocks:
        base = b.block.dxf.base_point
        blocks.append((b.name, (base.x, base.y), [norm_entity_ezdxf(e) for e in b]))
    msp = [norm_entity_ezdxf(e) for e in doc.modelspace()]
    return doc, blocks, msp


# ----------------------------------------------------------------------------------------
# Reader 2: minimal raw tag reader (cross-check only)
# ----------------------------------------------------------------------------------------

def raw_read(path):
    """Return (comments, blocks, msp, layer_table) from the group-code/value pairs."""
    with open(path, "rb") as f:
        lines = f.read().decode("cp1252").splitlines()
    tags = []
    for i in range(0, len(lines) - 1, 2):
        tags.append((int(lines[i].strip()), lines[i + 1]))
    comments = [v for c, v in tags if c == 999]
    tags = [(c, v) for c, v in tags if c != 999]
    # where do group-42 tags occur?  (bulge on VERTEX/LWPOLYLINE, or something else)
    g42 = {}
    rec_type = None
    for c, v in tags:
        if c == 0:
            rec_type = v.strip()
        elif c == 42:
            g42[rec_type] = g42.get(rec_type, 0) + 1

    # split into records starting at group 0
    recs = []
    for c, v in tags:
        if c == 0:
            recs.append([v.strip(), []])
        elif recs:
            recs[-1][1].append((c, v))

    def first(groups, code, conv=None, default=None):
        for c, v in groups:
            if c == code:
                return conv(v) if conv else v
        return default

    def fl(v):
        return float(v.strip())

    blocks, msp, layer_table = [], [], []
    section = None
    cur_block = None
    cur_poly = None
    i = 0
    for typ, g in recs:
        if typ == "SECTION":
            section = first(g, 2, str.strip)
            continue
        if typ == "ENDSEC":
            section = None
            continue
        if section == "TABLES" and typ == "LAYER":
            layer_table.append(first(g, 2, str.strip))
            continue
        if section not in ("BLOCKS", "ENTITIES"):
            continue
        if typ == "BLOCK":
            cur_block = (first(g, 2, str.strip), (first(g, 10, fl, 0.0), first(g, 20, fl, 0.0)), [])
            blocks.append(cur_block)
            continue
        if typ == "ENDBLK":
            cur_block = None
            continue
        target = cur_block[2] if (section == "BLOCKS" and cur_block is not None) else msp
        layer = first(g, 8, str.strip)
        if typ == "VERTEX":
            cur_poly[1].append((first(g, 10, fl, 0.0), first(g, 20, fl, 0.0), first(g, 42, fl, 0.0)))
            continue
        if typ == "SEQEND":
            target.append(("POLYLINE", cur_poly[2], (cur_poly[0], tuple(cur_poly[1]))))
            cur_poly = None
            continue
        if typ == "POLYLINE":
            cur_poly = [int(first(g, 70, fl, 0)), [], layer]
            continue
        if typ == "POINT":
            target.append((typ, layer, (first(g, 10, fl), first(g, 20, fl))))
        elif typ == "LINE":
            target.append((typ, layer, (first(g, 10, fl), first(g, 20, fl), first(g, 11, fl), first(g, 21, fl))))
        elif typ in ("TEXT", "ATTDEF"):
            target.append((typ, layer, first(g, 1, default="")))
        elif typ == "LWPOLYLINE":
            xs = [fl(v) for c, v in g if c == 10]
            ys = [fl(v) for c, v in g if c == 20]
            # bulges are positional in LWPOLYLINE; none of the files has LWPOLYLINE
            target.append((typ, layer, (int(first(g, 70, fl, 0)), tuple((x, y, 0.0) for x, y in zip(xs, ys)))))
        elif typ == "INSERT":
            target.append((typ, layer, (first(g, 2, str.strip), first(g, 10, fl, 0.0), first(g, 20, fl, 0.0),
                                        first(g, 41, fl, 1.0), first(g, 42, fl, 1.0), first(g, 50, fl, 0.0))))
        else:
            target.append((typ, layer, None))
    return comments, blocks, msp, layer_table, g42


def crosscheck(name, ez_blocks, ez_msp, raw_blocks, raw_msp):
    """Both readers must see the same piece blocks and the same model-space entities."""
    ez = {b[0].upper(): b for b in ez_blocks if b[0].lower() not in LAYOUT_BLOCKS}
    raw = {b[0].upper(): b for b in raw_blocks if b[0].lower() not in LAYOUT_BLOCKS}
    problems = []
    if set(ez) != set(raw):
        problems.append(f"block sets differ: {sorted(set(ez) ^ set(raw))}")
    for k in set(ez) & set(raw):
        if ez[k][1] != raw[k][1]:
            problems.append(f"{k}: base point {ez[k][1]} vs {raw[k][1]}")
        if ez[k][2] != raw[k][2]:
            for a, b in zip(ez[k][2], raw[k][2]):
                if a != b:
                    problems.append(f"{k}: first difference ezdxf={str(a)[:200]} raw={str(b)[:200]}")
                    break
            else:
                problems.append(f"{k}: entity counts {len(ez[k][2])} vs {len(raw[k][2])}")
    if ez_msp != raw_msp:
        problems.append("model space differs")
    if problems:
        raise SystemExit(f"{name}: ezdxf and raw reader disagree:\n  " + "\n  ".join(problems[:20]))
    return [b[0] for b in raw_blocks]          # block names in file order (raw spelling)


# ----------------------------------------------------------------------------------------
# Texts
# ----------------------------------------------------------------------------------------

KEY_RE = re.compile(r"^\s*([^:]+?)\s*:(.*)$", re.S)


def split_key(text):
    """'Piece Name: X ' -> ('piece name', 'X'); texts without ':' -> (None, text.strip())."""
    m = KEY_RE.match(text)
    if not m:
        return None, text.strip()
    return re.sub(r"\s+", " ", m.group(1)).lower(), m.group(2).strip()


# ----------------------------------------------------------------------------------------
# Geometry
# ----------------------------------------------------------------------------------------

def dist(a, b):
    return math.hypot(a[0] - b[0], a[1] - b[1])


def chain_parts(parts, tol):
    """parts: list of (closed_flag, [(x, y), ...]) in file units.

    Start with the first part as stored; repeatedly append the unused part whose start or end
    coincides (<= tol) with the current end (reversed if its end matches); when nothing matches
    at the end, try to prepend at the start the same way.  Nearest candidate wins; more than one
    distinct candidate part within tol is counted as an ambiguous join.
    Returns (points, used_flags, max_join_gap, ambiguous_joins).
    """
    used = [False] * len(parts)
    used[0] = True
    pts = list(parts[0][1])
    max_gap = 0.0
    ambiguous = 0
    for at_end in (True, False):
        while True:
            ref = pts[-1] if at_end else pts[0]
            cands = []
            for i, (_, p) in enumerate(parts):
                if used[i] or not p:
                    continue
                ds, de = dist(p[0], ref), dist(p[-1], ref)
                if ds <= tol:
                    cands.append((ds, i, "start"))
                if de <= tol:
                    cands.append((de, i, "end"))
            if not cands:
                break
            if len({c[1] for c in cands}) > 1:
                ambiguous += 1
            cands.sort()
            d, i, which = cands[0]
            used[i] = True
            max_gap = max(max_gap, d)
            p = list(parts[i][1])
            if at_end:
                pts.extend(p if which == "start" else p[::-1])
            else:
                pts[:0] = (p[::-1] if which == "start" else p)
    return pts, used, max_gap, ambiguous


def dedupe(pts, tol):
    """Drop vertices within tol of the previously kept one; then drop trailing copies of the first."""
    out = []
    for p in pts:
        if out and dist(p, out[-1]) <= tol:
            continue
        out.append(p)
    while len(out) > 1 and dist(out[-1], out[0]) <= tol:
        out.pop()
    return out


def shoelace2_exact(pts):
    """Twice the signed area, exact (Fractions of the stored doubles)."""
    s = Fraction(0)
    n = len(pts)
    for i in range(n):
        x1, y1 = pts[i]
        x2, y2 = pts[(i + 1) % n]
        s += Fraction(x1) * Fraction(y2) - Fraction(x2) * Fraction(y1)
    return s


def orient(a, b, c):
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def sign(x):
    return (x > 0) - (x < 0)


def on_segment(a, b, p):
    """p collinear with a-b assumed; is p within the closed box of a-b?"""
    return min(a[0], b[0]) <= p[0] <= max(a[0], b[0]) and min(a[1], b[1]) <= p[1] <= max(a[1], b[1])


def segments_touch(p1, p2, p3, p4):
    """Exact closed-segment intersection test (points are tuples of Fractions)."""
    d1, d2 = sign(orient(p3, p4, p1)), sign(orient(p3, p4, p2))
    d3, d4 = sign(orient(p1, p2, p3)), sign(orient(p1, p2, p4))
    if d1 * d2 < 0 and d3 * d4 < 0:
        return True
    if d1 == 0 and on_segment(p3, p4, p1):
        return True
    if d2 == 0 and on_segment(p3, p4, p2):
        return True
    if d3 == 0 and on_segment(p1, p2, p3):
        return True
    if d4 == 0 and on_segment(p1, p2, p4):
        return True
    return False


def point_seg_dist(p, a, b):
    ax, ay = a
    dx, dy = b[0] - ax, b[1] - ay
    L2 = dx * dx + dy * dy
    if L2 == 0:
        return dist(p, a)
    t = max(0.0, min(1.0, ((p[0] - ax) * dx + (p[1] - ay) * dy) / L2))
    return math.hypot(p[0] - (ax + t * dx), p[1] - (ay + t * dy))


def seg_seg_dist(a, b, c, d):
    return min(point_seg_dist(a, c, d), point_seg_dist(b, c, d), point_seg_dist(c, a, b), point_seg_dist(d, a, b))


def self_intersections(pts, near_tol):
    """Closed polygon pts (no repeated last vertex).  Edge i = pts[i] -> pts[i+1 mod n].

    Returns (pairs, near_pairs, spikes):
      pairs      - non-adjacent edge pairs (i, j) that intersect or touch, exact arithmetic;
      near_pairs - non-adjacent pairs that do not touch but come within near_tol (file units);
      spikes     - adjacent edges that fold back onto each other (collinear, opposite direction).
    Candidates are found with a sweep over x-sorted edge bounding boxes (grown by near_tol).
    """
    n = len(pts)
    if n < 3:
        return [], [], 0
    F = [(Fraction(x), Fraction(y)) for x, y in pts]
    edges = []
    for i in range(n):
        a, b = pts[i], pts[(i + 1) % n]
        edges.append((min(a[0], b[0]) - near_tol, max(a[0], b[0]) + near_tol,
                      min(a[1], b[1]) - near_tol, max(a[1], b[1]) + near_tol, i))
    edges.sort()
    pairs, near = [], []
    for k in range(len(edges)):
        x0, x1, y0, y1, i = edges[k]
        for m in range(k + 1, len(edges)):
            u0, u1, v0, v1, j = edges[m]
            if u0 > x1:
                break
            if v0 > y1 or v1 < y0:
                continue
            a, b = sorted((i, j))
            if b - a == 1 or (a == 0 and b == n - 1):
                continue                      # adjacent edges share a vertex by construction
            if segments_touch(F[a], F[(a + 1) % n], F[b], F[(b + 1) % n]):
                pairs.append((a, b))
            elif seg_seg_dist(pts[a], pts[(a + 1) % n], pts[b], pts[(b + 1) % n]) <= near_tol:
                near.append((a, b))
    spikes = 0
    for i in range(n):
        a, b, c = F[i - 1], F[i], F[(i + 1) % n]
        if orient(a, b, c) == 0 and ((b[0] - a[0]) * (c[0] - b[0]) + (b[1] - a[1]) * (c[1] - b[1])) < 0:
            spikes += 1
    return sorted(pairs), sorted(near), spikes


# ----------------------------------------------------------------------------------------
# Per file
# ----------------------------------------------------------------------------------------

def analyse_file(path):
    fname = os.path.basename(path)
    doc, ez_blocks, ez_msp = read_ezdxf(path)
    comments, raw_blocks, raw_msp, layer_table, g42 = raw_read(path)
    order = crosscheck(fname, ez_blocks, ez_msp, raw_blocks, raw_msp)

    # ---- model space texts and inserts
    ms_keys = {}
    ms_texts = []
    inserts = []
    for t, layer, d in ez_msp:
        if t == "TEXT":
            ms_texts.append(d)
            k, v = split_key(d)
            if k is not None and k not in ms_keys:
                ms_keys[k] = v
        elif t == "INSERT":
            inserts.append(d)
    non_identity_inserts = [d[0] for d in inserts if (d[1], d[2], d[3], d[4], d[5]) != (0.0, 0.0, 1.0, 1.0, 0.0)]
    inserted = {d[0].upper() for d in inserts}

    by_name = {b[0].upper(): b for b in ez_blocks}
    layout = [n for n in order if n.lower() in LAYOUT_BLOCKS]
    piece_names_order = [n for n in order if n.lower() not in LAYOUT_BLOCKS]
    not_inserted = [n for n in piece_names_order if n.upper() not in inserted]
    missing_blocks = sorted({d[0] for d in inserts if d[0].upper() not in by_name})

    # ---- units
    all_texts = list(ms_texts) + [d for b in ez_blocks for (t, l, d) in b[2] if t == "TEXT"]
    units_stated = ms_keys.get("units")
    units_where = "model space" if units_stated is not None else None
    if units_stated is None:
        for tx in all_texts:
            k, v = split_key(tx)
            if k == "units":
                units_stated, units_where = v, "block"
                break
    if units_stated is None:
        units = "mm"
    elif units_stated.upper() == "METRIC":
        units = "mm"
    elif units_stated.upper() == "ENGLISH":
        units = "inch"
    else:
        raise SystemExit(f"{fname}: unknown units {units_stated!r}")
    f = UNIT_FACTOR[units]
    tol = TOL_M / f                               # tolerance in file units

    # ---- producer
    author, product, version = ms_keys.get("author"), ms_keys.get("product"), ms_keys.get("version")
    appids = [e.dxf.name for e in doc.appids] if hasattr(doc, "appids") else []
    raw_has_valentina_appid = False
    with open(path, "rb") as fh:
        raw_has_valentina_appid = b"\nVALENTINA" in fh.read().replace(b"\r", b"")
    if author:
        producer = " ; ".join(x for x in (author, product, version) if x)
        if "CLO" in author.upper():
            family = "CLO Virtual Fashion"
        elif "GERBER" in author.upper():
            family = "Gerber AccuMark"
        else:
            family = author
        producer_evidence = "model-space texts Author/PRODUCT/VERSION"
    elif comments:
        producer = " ; ".join(comments)
        family = "Valentina (libdxfrw)" if raw_has_valentina_appid else "libdxfrw"
        producer_evidence = "999 comment" + (" + APPID table entry VALENTINA" if raw_has_valentina_appid else "")
    else:
        producer, family, producer_evidence = None, None, "none"

    # ---- flavour
    layer_entity_counts = {}
    for b in ez_blocks:
        for t, l, d in b[2]:
            layer_entity_counts[l] = layer_entity_counts.get(l, 0) + 1
    astm_texts = [tx for tx in all_texts if "ASTM" in tx.upper()]
    qv_layers = sorted((l for l in layer_entity_counts if l in ASTM_QV_LAYERS), key=int)
    evidence = []
    if astm_texts:
        evidence.append("text " + " | ".join(repr(t) for t in astm_texts[:2]))
    if qv_layers:
        evidence.append("entities on layers " + ",".join(f"{l}({layer_entity_counts[l]})" for l in qv_layers))
    flavour = "ASTM" if evidence else "AAMA"
    if not evidence:
        evidence.append("no ASTM text, no entities on layers 84-87")
    table_qv = [l for l in layer_table if l in ASTM_QV_LAYERS]
    if table_qv:
        evidence.append("LAYER table lists " + ",".join(table_qv))

    sample_size = ms_keys.get("sample size")

    # ---- blocks
    out_blocks = []
    stats = dict(max_join_gap_m=0.0, parts_min=None, parts_max=0, dup_removed=0, bulge_vertices=0,
                 ambiguous_joins=0, closed_flag_parts=0, closed_flag_parts_repeating_first=0,
                 closed_flag_in_multipart=0, near_touch_blocks=[], spike_blocks=[],
                 max_notch_off_boundary_m=0.0, notches_off_boundary=0,
                 max_mirror_end_to_vertex_m=0.0, mirror_ends=0, multi_grain=[], multi_mirror=[],
                 attdefs=0, lwpolylines=0, mtexts=0, duplicate_keys=[], keyless_texts={},
                 ambiguous_blocks=[], duplicate_notches=[], notch_off=[], closed_internal_polylines=0,
                 piece_src={}, size_src={},
                 l84=dict(blocks=0, vertices_layer1=0, vertices_layer84=0, max_rel_area_diff=0.0,
                          closed_flag_parts=0, closed_flag_parts_repeating_first=0))
    intersections_detail = {}
    for bname in piece_names_order:
        _, base, ents = by_name[bname.upper()]
        keys = {}
        layer15 = []
        parts = []
        counts = dict(notches=0, turn_points=0, curve_points=0, drill_holes=0)
        il = dict(line=0, polyline=0, text=0, other=0)
        mirror, grain = [], []
        notch_pts = []
        internal_segs = []
        parts84 = []
        for t, layer, d in ents:
            if t == "ATTDEF":
                stats["attdefs"] += 1
            if t == "MTEXT":
                stats["mtexts"] += 1
            if t == "LWPOLYLINE":
                stats["lwpolylines"] += 1
            if t == "TEXT":
                k, v = split_key(d)
                if k is None:
                    key = (layer, re.sub(r"\d+", "n", v))
                    stats["keyless_texts"][str(key)] = stats["keyless_texts"].get(str(key), 0) + 1
                    if layer == "15":
                        layer15.append(v)
                elif k in keys:
                    stats["duplicate_keys"].append(f"{bname}: {k}")
                else:
                    keys[k] = v
            if layer == "84" and t in ("POLYLINE", "LWPOLYLINE"):
                parts84.append((bool(d[0] & 1), [(v[0], v[1]) for v in d[1]]))
            if layer == "1" and t in ("POLYLINE", "LWPOLYLINE"):
                flags, verts = d
                stats["bulge_vertices"] += sum(1 for v in verts if v[2] != 0)
                parts.append((bool(flags & 1), [(v[0], v[1]) for v in verts]))
            elif t == "POINT":
                if layer == "4":
                    counts["notches"] += 1
                    notch_pts.append(d)
                elif layer == "2":
                    counts["turn_points"] += 1
                elif layer == "3":
                    counts["curve_points"] += 1
                elif layer == "13":
                    counts["drill_holes"] += 1
            if layer == "8":
                if t == "LINE":
                    il["line"] += 1
                    internal_segs.append(((d[0], d[1]), (d[2], d[3])))
                elif t in ("POLYLINE", "LWPOLYLINE"):
                    il["polyline"] += 1
                    vs = [(v[0], v[1]) for v in d[1]]
                    if d[0] & 1:
                        stats["closed_internal_polylines"] += 1
                        vs = vs + vs[:1]
                    internal_segs.extend(zip(vs, vs[1:]))
                elif t == "TEXT":
                    il["text"] += 1
                else:
                    il["other"] += 1
            if t == "LINE" and layer == "6":
                mirror.append(d)
            if t == "LINE" and layer == "7":
                grain.append(d)

        # --- boundary
        rec = {"block": bname}
        nparts = len(parts)
        stats["parts_min"] = nparts if stats["parts_min"] is None else min(stats["parts_min"], nparts)
        stats["parts_max"] = max(stats["parts_max"], nparts)
        for cf, p in parts:
            if cf:
                stats["closed_flag_parts"] += 1
                if len(p) > 1 and p[0] == p[-1]:
                    stats["closed_flag_parts_repeating_first"] += 1
                if nparts > 1:
                    stats["closed_flag_in_multipart"] += 1
        if nparts == 0:
            pts, used, gap_join, amb = [], [], 0.0, 0
        else:
            pts, used, gap_join, amb = chain_parts(parts, tol)
        stats["ambiguous_joins"] += amb
        if amb:
            stats["ambiguous_blocks"].append(bname)
        stats["max_join_gap_m"] = max(stats["max_join_gap_m"], gap_join * f)
        raw_n = len(pts)
        unjoined = used.count(False)
        if nparts == 1 and parts[0][0]:
            closed = True
            gap = 0.0
        elif nparts:
            gap = dist(pts[-1], pts[0])
            closed = unjoined == 0 and gap <= tol
        else:
            closed, gap = False, None
        outline = dedupe(pts, tol)
        stats["dup_removed"] += raw_n - len(outline)
        n = len(outline)
        if n >= 3:
            a2 = shoelace2_exact(outline)
            area = abs(float(a2)) / 2 * f * f
            winding = "ccw" if a2 > 0 else ("cw" if a2 < 0 else "degenerate")
            perim = math.fsum(dist(outline[i], outline[(i + 1) % n]) for i in range(n)) * f
            pairs, near, spikes = self_intersections(outline, tol)
        else:
            area, winding, perim, pairs, near, spikes = None, None, None, [], [], 0
        if pairs:
            intersections_detail[bname] = [
                (i, j, [sig(c * f) for c in outline[i]], [sig(c * f) for c in outline[j]]) for i, j in pairs]
        if near:
            stats["near_touch_blocks"].append(bname)
        if spikes:
            stats["spike_blocks"].append(bname)

        # --- layer 84 (ASTM quality-validation copy of the boundary): for information only
        if parts84 and n >= 3:
            o84 = dedupe(chain_parts(parts84, tol)[0], tol)
            a84 = abs(float(shoelace2_exact(o84))) / 2 * f * f if len(o84) >= 3 else 0.0
            s84 = stats["l84"]
            s84["blocks"] += 1
            s84["vertices_layer1"] += n
            s84["vertices_layer84"] += len(o84)
            s84["max_rel_area_diff"] = max(s84["max_rel_area_diff"], abs(a84 - area) / area)
            for cf, p in parts84:
                if cf:
                    s84["closed_flag_parts"] += 1
                    if len(p) > 1 and p[0] == p[-1]:
                        s84["closed_flag_parts_repeating_first"] += 1

        # --- notch distance to boundary, mirror ends vs vertices
        for q in notch_pts:
            dmin = min(point_seg_dist(q, outline[i], outline[(i + 1) % n]) for i in range(n)) * f if n >= 2 else None
            if dmin is not None:
                stats["max_notch_off_boundary_m"] = max(stats["max_notch_off_boundary_m"], dmin)
                if dmin > TOL_M:
                    stats["notches_off_boundary"] += 1
                    dint = min((point_seg_dist(q, a, b) for a, b in internal_segs), default=None)
                    stats["notch_off"].append({"block": bname, "xy_m": [sig(q[0] * f), sig(q[1] * f)],
                                               "to_boundary_m": sig(dmin),
                                               "to_internal_line_m": sig(dint * f) if dint is not None else None})
        if len(set(notch_pts)) != len(notch_pts):
            stats["duplicate_notches"].append(f"{bname}: {len(notch_pts) - len(set(notch_pts))}")
        for m in mirror:
            for e in ((m[0], m[1]), (m[2], m[3])):
                stats["mirror_ends"] += 1
                if outline:
                    stats["max_mirror_end_to_vertex_m"] = max(
                        stats["max_mirror_end_to_vertex_m"], min(dist(e, v) for v in outline) * f)
        if len(grain) > 1:
            stats["multi_grain"].append(bname)
        if len(mirror) > 1:
            stats["multi_mirror"].append(bname)

        if grain:
            g = grain[0]
            ang = math.degrees(math.atan2(g[3] - g[1], g[2] - g[0]))
            if ang <= -180.0:
                ang = 180.0
            grain_angle = sig(ang)
        else:
            grain_angle = None

        piece = keys.get("piece name")
        src = "Piece Name text" if piece is not None else "block name"
        stats["piece_src"][src] = stats["piece_src"].get(src, 0) + 1
        src = "Size text in block" if "size" in keys else ("model-space Sample Size" if sample_size else "none (empty)")
        stats["size_src"][src] = stats["size_src"].get(src, 0) + 1
        rec.update({
            "piece": piece if piece is not None else bname,
            "size": keys["size"] if "size" in keys else (sample_size or ""),
            "quantity": keys.get("quantity"), "category": keys.get("category"),
            "annotation": keys.get("annotation"), "fabric": keys.get("fabric"),
            "attrs_own": any(k in keys for k in ("quantity", "category", "annotation", "fabric")),
            "layer15_text": " | ".join(layer15) if layer15 else None,
            "parts": nparts, "unjoined_parts": unjoined, "raw_vertices": raw_n,
            "boundary_vertices": n, "closed": closed,
            "closing_gap_m": None if closed else (sig(gap * f) if gap is not None else None),
            "area_m2": sig(area), "perimeter_m": sig(perim), "winding": winding,
            "self_intersecting": bool(pairs), "intersecting_edge_pairs": len(pairs),
            "near_touch_pairs": len(near), "spikes": spikes,
            "grain_angle_deg": grain_angle, "grain_lines": len(grain),
            "notches": counts["notches"], "turn_points": counts["turn_points"],
            "curve_points": counts["curve_points"],
            "internal_lines": {"line": il["line"], "polyline": il["polyline"],
                               "total": il["line"] + il["polyline"], "text": il["text"]},
            "drill_holes": counts["drill_holes"],
            "mirror_line": [[sig(m[0] * f), sig(m[1] * f), sig(m[2] * f), sig(m[3] * f)] for m in mirror] or None,
        })
        out_blocks.append(rec)

    # ---- propagate piece attributes from the block that carries them (the sample size)
    carriers = {}
    for r in out_blocks:
        if r["attrs_own"]:
            carriers.setdefault(r["piece"], []).append(r)
    multi_carrier = [p for p, rs in carriers.items() if len(rs) > 1]
    for r in out_blocks:
        if not r["attrs_own"] and r["piece"] in carriers:
            src = carriers[r["piece"]][0]
            for k in ("quantity", "category", "annotation", "fabric"):
                r[k] = src[k]

    # ---- summary
    pieces = []
    sizes = []
    for r in out_blocks:
        if r["piece"] not in pieces:
            pieces.append(r["piece"])
        if r["size"] not in sizes:
            sizes.append(r["size"])
    summary = {
        "producer": producer, "producer_family": family, "producer_evidence": producer_evidence,
        "flavour": flavour, "flavour_evidence": "; ".join(evidence),
        "style_name": ms_keys.get("style name"),
        "units_stated": units_stated, "units_where": units_where, "units": units, "metres_per_unit": f,
        "sample_size": sample_size,
        "pieces": len(pieces), "piece_names": pieces,
        "blocks": len(out_blocks), "sizes": sizes, "n_sizes": len(sizes),
        "layout_blocks": layout, "not_inserted": not_inserted, "inserts_of_missing_blocks": missing_blocks,
        "non_identity_inserts": non_identity_inserts,
        "not_closed": [f"{r['block']} ({r['size']})" for r in out_blocks if not r["closed"]],
        "self_intersecting": [f"{r['block']} ({r['size']})" for r in out_blocks if r["self_intersecting"]],
        "blocks_with_near_touches": stats["near_touch_blocks"],
        "blocks_with_spikes": stats["spike_blocks"],
        "parts_per_block": [stats["parts_min"], stats["parts_max"]],
        "max_join_gap_m": sig(stats["max_join_gap_m"]),
        "ambiguous_joins": stats["ambiguous_joins"], "ambiguous_join_blocks": stats["ambiguous_blocks"],
        "piece_name_source": stats["piece_src"], "size_source": stats["size_src"],
        "duplicate_vertices_removed": stats["dup_removed"],
        "closed_flag_parts": stats["closed_flag_parts"],
        "closed_flag_parts_repeating_first": stats["closed_flag_parts_repeating_first"],
        "closed_flag_parts_in_multipart_outlines": stats["closed_flag_in_multipart"],
        "bulge_vertices": stats["bulge_vertices"],
        "attdef": stats["attdefs"], "lwpolyline": stats["lwpolylines"], "mtext": stats["mtexts"],
        "layers_with_entities": sorted(layer_entity_counts, key=lambda s: (not s.isdigit(), int(s) if s.isdigit() else 0, s)),
        "layer_table": layer_table,
        "max_notch_off_boundary_m": sig(stats["max_notch_off_boundary_m"]),
        "notches_off_boundary_gt_tol": stats["notches_off_boundary"],
        "notches_off_boundary": stats["notch_off"],
        "blocks_with_duplicate_notch_points": stats["duplicate_notches"],
        "closed_internal_polylines": stats["closed_internal_polylines"],
        "group42_by_record": g42,
        "layer84_outline_vs_layer1": ({k: (sig(v) if isinstance(v, float) else v) for k, v in stats["l84"].items()}
                                      if stats["l84"]["blocks"] else None),
        "max_mirror_end_to_vertex_m": sig(stats["max_mirror_end_to_vertex_m"]) if stats["mirror_ends"] else None,
        "blocks_with_several_grain_lines": stats["multi_grain"],
        "blocks_with_several_mirror_lines": stats["multi_mirror"],
        "pieces_with_attributes_in_several_blocks": multi_carrier,
        "duplicate_keys_in_block": stats["duplicate_keys"],
        "keyless_texts_in_blocks": stats["keyless_texts"],
        "self_intersection_edges": {k: v for k, v in intersections_detail.items()},
        "crosscheck": "ezdxf and raw tag reader agree",
    }
    return {"summary": summary, "blocks": out_blocks}


def dump(result):
    """Compact JSON: one block per line."""
    lines = ["{", '  "generated_by": "make_reference.py (ezdxf %s + raw tag reader cross-check)",' % ezdxf.__version__,
             '  "tolerance_m": %s,' % json.dumps(TOL_M), '  "files": {']
    names = list(result)
    for fi, name in enumerate(names):
        fr = result[name]
        lines.append(f"    {json.dumps(name)}: {{")
        lines.append(f'      "summary": {json.dumps(fr["summary"], ensure_ascii=False)},')
        lines.append('      "blocks": [')
        for bi, b in enumerate(fr["blocks"]):
            lines.append("        " + json.dumps(b, ensure_ascii=False, separators=(",", ":")) + ("," if bi + 1 < len(fr["blocks"]) else ""))
        lines.append("      ]")
        lines.append("    }" + ("," if fi + 1 < len(names) else ""))
    lines.append("  }")
    lines.append("}")
    return "\n".join(lines) + "\n"


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("shared", nargs="?", default=os.path.normpath(os.path.join(here, "../../../../../shared")))
    ap.add_argument("-o", "--output", default=os.path.join(here, "expected.json"))
    args = ap.parse_args()
    ddir = os.path.join(args.shared, "data", "dxf")
    files = sorted(fn for fn in os.listdir(ddir) if fn.lower().endswith(".dxf"))
    result = {}
    for fn in files:
        result[fn] = analyse_file(os.path.join(ddir, fn))
    # re-parse to make sure the output is valid JSON
    text = dump(result)
    json.loads(text)
    with open(args.output, "w", encoding="utf-8") as fh:
        fh.write(text)

    print(f"wrote {args.output} ({len(text)} bytes)")
    print(f"{'file':36} {'pieces':>6} {'blocks':>6} {'sizes':>5} {'units':>5} {'flav':>4} {'!closed':>7} {'selfX':>5}  README check")
    for fn in files:
        s = result[fn]["summary"]
        exp = README_TABLE.get(fn)
        got = (s["pieces"], s["blocks"], s["n_sizes"], s["units"])
        check = "n/a" if exp is None else ("ok" if exp == got else f"DIFFERS (README {exp})")
        print(f"{fn:36} {s['pieces']:6} {s['blocks']:6} {s['n_sizes']:5} {s['units']:>5} {s['flavour']:>4} "
              f"{len(s['not_closed']):7} {len(s['self_intersecting']):5}  {check}")


if __name__ == "__main__":
    main()
