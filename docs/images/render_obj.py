#!/usr/bin/env python3
"""A stopgap software rasteriser for README pictures (until vgd's own headless
renderer): orthographic views of OBJ meshes, z-buffered, flat-shaded, as PNG.
Standard library only.

  render_obj.py OUT.png VIEWS MESH.obj [MESH.obj ...]
  VIEWS: comma-separated front, side, back (one panel each, side by side)
"""
import math
import os, struct, sys, zlib

COLOURS = [(205, 190, 170), (60, 100, 190), (190, 70, 70), (70, 160, 80)]
PANEL_W, PANEL_H = 300, 520


def load(path):
    verts, faces = [], []
    for line in open(path):
        if line.startswith('v '):
            verts.append(tuple(map(float, line.split()[1:4])))
        elif line.startswith('f '):
            faces.append(tuple(int(t.split('/')[0]) - 1 for t in line.split()[1:4]))
    return verts, faces


def turn(v, view):
    x, y, z = v
    if view == 'side':
        return (-z, y, x)
    if view == 'back':
        return (-x, y, -z)
    return (x, y, z)


def render(meshes, view, box):
    (xmin, xmax, ymin, ymax) = box
    s = min((PANEL_H - 20) / (ymax - ymin), (PANEL_W - 20) / (xmax - xmin))
    cx = (xmin + xmax) / 2
    img = [[(255, 255, 255)] * PANEL_W for _ in range(PANEL_H)]
    zb = [[-1e9] * PANEL_W for _ in range(PANEL_H)]
    light = (0.3, 0.5, 0.8)
    ln = math.sqrt(sum(c * c for c in light))
    light = tuple(c / ln for c in light)
    for k, (verts, faces) in enumerate(meshes):
        pts = [turn(v, view) for v in verts]
        colour = COLOURS[k % len(COLOURS)]
        for f in faces:
            a, b, c = pts[f[0]], pts[f[1]], pts[f[2]]
            u = [b[i] - a[i] for i in range(3)]
            w = [c[i] - a[i] for i in range(3)]
            n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
            nl = math.sqrt(sum(t * t for t in n)) or 1.0
            shade = abs(sum(n[i] * light[i] for i in range(3)) / nl) * 0.75 + 0.25
            p = [((q[0] - cx) * s + PANEL_W / 2, (ymax - q[1]) * s + 10, q[2]) for q in (a, b, c)]
            (ax, ay, az), (bx, by, bz), (qx, qy, qz) = p
            d = (by - qy) * (ax - qx) + (qx - bx) * (ay - qy)
            if abs(d) < 1e-12:
                continue
            for y in range(max(0, int(min(ay, by, qy))), min(PANEL_H - 1, int(max(ay, by, qy)) + 1) + 1):
                for x in range(max(0, int(min(ax, bx, qx))), min(PANEL_W - 1, int(max(ax, bx, qx)) + 1) + 1):
                    l1 = ((by - qy) * (x - qx) + (qx - bx) * (y - qy)) / d
                    l2 = ((qy - ay) * (x - qx) + (ax - qx) * (y - qy)) / d
                    l3 = 1 - l1 - l2
                    if l1 < 0 or l2 < 0 or l3 < 0:
                        continue
                    z = l1 * az + l2 * bz + l3 * qz
                    if z > zb[y][x]:
                        zb[y][x] = z
                        img[y][x] = tuple(int(ch * shade) for ch in colour)
    return img


def main():
    out, views, paths = sys.argv[1], sys.argv[2].split(','), sys.argv[3:]
    meshes = [load(p) for p in paths]
    panels = []
    for view in views:
        pts = [turn(v, view) for verts, _ in meshes for v in verts]
        if 'RENDER_Y' in os.environ:  # crop to a height range (m), e.g. RENDER_Y=1.0,1.6
            lo, hi = map(float, os.environ['RENDER_Y'].split(','))
            pts = [p for p in pts if lo <= p[1] <= hi]
        box = (min(p[0] for p in pts), max(p[0] for p in pts), min(p[1] for p in pts), max(p[1] for p in pts))
        panels.append(render(meshes, view, box))
    rows = [b''.join(bytes(c for px in panel[y] for c in px) for panel in panels) for y in range(PANEL_H)]
    raw = b''.join(b'\x00' + r for r in rows)

    def chunk(tag, data):
        return struct.pack('>I', len(data)) + tag + data + struct.pack('>I', zlib.crc32(tag + data) & 0xffffffff)

    with open(out, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', PANEL_W * len(panels), PANEL_H, 8, 2, 0, 0, 0))
                + chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))


if __name__ == '__main__':
    main()
