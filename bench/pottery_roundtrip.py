#!/usr/bin/env python3
"""The round trip of issue 42 on real pottery drawings: each drawing -> "Vessel from Profile
Drawing" -> "Vessel Axis and Profile" (through reliefkit-batch and MeshLab), then the profile the
second filter cuts from the vessel against the outline the first one read from the drawing.

Per drawing: the profile's distance from the drawing's outline (median and 90th percentile, as a
share of the vessel's largest radius), the axis' tilt from the drawing's vertical, what decided
up, the rim diameter and the wall's thickness. The held-out part is the drawing corpus' own
(docs/drawing_corpus.md: the first 30 % of each kind by the SHA-1 of the file name), reported
apart.

  python3 bench/pottery_roundtrip.py [--shared ../shared/data] [--keep DIR]
"""
import argparse
import hashlib
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCRIPT = """<!DOCTYPE FilterScript>
<FilterScript>
 <filter name="Vessel from Profile Drawing">
  <Param type="RichOpenFile" name="drawing" value="{input}" exts_cardinality="0" description="Drawing image" tooltip=""/>
  <Param type="RichFloat" name="dpi" value="300" description="Drawing resolution (DPI)" tooltip=""/>
  <Param type="RichFloat" name="scale" value="1" description="Drawing scale (object : drawing)" tooltip=""/>
  <Param type="RichFloat" name="axis" value="-1" description="Axis position (px, -1: found)" tooltip=""/>
  <Param type="RichEnum" name="side" value="0" enum_cardinality="3" enum_val0="Found in the drawing" enum_val1="Left of the axis" enum_val2="Right of the axis" description="Section side" tooltip=""/>
  <Param type="RichInt" name="segments" value="0" description="Segments around the axis (0: auto)" tooltip=""/>
 </filter>
 <filter name="Vessel Axis and Profile">
 </filter>
</FilterScript>
"""


def held_out(names):
    """The corpus' held-out rule: the first 30 % of the kind in the order of the SHA-1 of the name."""
    ordered = sorted(names, key=lambda n: hashlib.sha1(n.encode()).hexdigest())
    return set(ordered[: round(0.3 * len(ordered))])


def read_obj_lines(path):
    points, segments = [], []
    with open(path) as f:
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == 'v':
                points.append(tuple(float(x) for x in t[1:4]))
            elif t[0] == 'l':
                ids = [int(x.split('/')[0]) - 1 for x in t[1:]]
                segments += list(zip(ids, ids[1:]))
    return points, segments


def distance_to_segments(q, segs):
    best = math.inf
    for (ax, ay), (bx, by) in segs:
        dx, dy = bx - ax, by - ay
        l2 = dx * dx + dy * dy
        t = 0 if l2 == 0 else max(0, min(1, ((q[0] - ax) * dx + (q[1] - ay) * dy) / l2))
        best = min(best, math.hypot(q[0] - ax - t * dx, q[1] - ay - t * dy))
    return best


def percentile(v, q):
    v = sorted(v)
    return v[min(len(v) - 1, int(q * (len(v) - 1)))] if v else math.nan


def compare(folder, name, axis_line):
    """Distances (share of the largest radius) of this filter's profile from the drawing's outline."""
    stem = os.path.splitext(name)[0]
    drawn_pts, drawn_segs = read_obj_lines(os.path.join(folder, stem, stem + '-profile.obj'))
    ours_pts, _ = read_obj_lines(os.path.join(folder, stem, stem + '-vessel-profile.obj'))
    # The drawing's outline is in its plane (x right, y up); the axis found by the filter runs
    # through `axis_line` (point, direction) of the vessel, which the drawing filter made in that plane.
    (px, py, _), (dx, dy, _) = axis_line
    ax = px + (0 - py) * dx / dy if abs(dy) > 1e-9 else px
    y0 = min(p[1] for p in drawn_pts)
    drawn = [((abs(a[0] - ax), a[1] - y0), (abs(b[0] - ax), b[1] - y0))
             for a, b in ((drawn_pts[i], drawn_pts[j]) for i, j in drawn_segs)]
    largest = max(abs(p[0] - ax) for p in drawn_pts)
    ours = [(p[0], p[2]) for p in ours_pts]
    top = max(q[1] for q in ours)
    step = max(1, len(ours) // 400)
    d = [distance_to_segments(q, drawn) / largest for q in ours[::step]]
    # the same profile turned over: when "up" was decided wrong, the shape is still compared
    turned = [distance_to_segments((q[0], top - q[1]), drawn) / largest for q in ours[::step]]
    up_right = percentile(d, 0.5) <= percentile(turned, 0.5)
    if not up_right:
        d = turned
    tilt = math.degrees(math.acos(min(1.0, abs(dy) / math.sqrt(dx * dx + dy * dy + axis_line[1][2] ** 2))))
    return percentile(d, 0.5), percentile(d, 0.9), tilt, up_right


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--shared', default=os.path.join(ROOT, '..', 'shared', 'data'))
    ap.add_argument('--keep', help='keep the outputs in this folder')
    a = ap.parse_args()
    corpus = os.path.join(a.shared, 'drawings', 'corpus', 'pottery')
    names = sorted(os.listdir(corpus))
    held = held_out(names)
    work = a.keep or tempfile.mkdtemp(prefix='rk_pottery_')
    drawings = os.path.join(work, 'drawings')
    shutil.rmtree(drawings, ignore_errors=True)
    os.makedirs(drawings)
    for n in names:
        shutil.copy(os.path.join(corpus, n), drawings)
    shutil.copy(os.path.join(a.shared, 'drawings', 'pottery_bowl_half_section.jpg'), drawings)
    with open(os.path.join(work, 'roundtrip.mlx'), 'w') as f:
        f.write(SCRIPT)
    out = os.path.join(work, 'out')
    shutil.rmtree(out, ignore_errors=True)
    cmd = ['xvfb-run', '-a', os.path.join(ROOT, 'build', 'prefix', 'bin', 'reliefkit-batch'), '-j', '2',
           '-s', os.path.join(work, 'roundtrip.mlx'), '--extensions', 'png,jpg', drawings, out]
    log = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_WAIT_POLICY='PASSIVE')).stdout
    lines = {}
    for line in log.splitlines():
        m = re.match(r'\[\d+/\d+ ([^\]]+)\] (.*)', line)
        if m:
            lines.setdefault(m.group(1), []).append(m.group(2))
    rows = {'tuning': [], 'held-out': []}
    for n in names + ['pottery_bowl_half_section.jpg']:
        text = lines.get(n, [])
        failed = [t for t in text if t.startswith('failed')]
        part = 'held-out' if n in held else 'tuning'
        if failed:
            rows[part].append((n, None, failed[0][:150]))
            continue
        axis = next(t for t in text if 'Axis (in the input' in t)
        nums = [float(x) for x in re.findall(r'-?\d+\.?\d*(?:e-?\d+)?', axis.split('through')[1])]
        median, p90, tilt, up_right = compare(out, n, ((nums[0], nums[1], nums[2]), (nums[3], nums[4], nums[5])))
        up = next((t.split('Up: ')[1].split(':')[0].split(' (')[0] for t in text if 'Up: ' in t), '?')
        up = ('' if up_right else 'UPSIDE DOWN, ') + up
        rim = next((t.split('Profile: ')[1] for t in text if 'Rim diameter' in t or 'No rim' in t), '?')
        thick = next((t.split('Profile: ')[1] for t in text if 'Wall thickness' in t), '?')
        rows[part].append((n, (median, p90, tilt, up_right), f'up: {up}; {rim.split(";")[0]}; {thick}'))
    for part in ('tuning', 'held-out'):
        ok = [r for r in rows[part] if r[1]]
        within = [r for r in ok if r[1][1] <= 0.01]
        up_right = [r for r in ok if r[1][3]]
        print(f'\n## {part}: {len(rows[part])} drawings, {len(ok)} made into vessels and recorded; '
              f'profile within 1 % of the largest radius (90th percentile) on {len(within)} of {len(ok)}; '
              f'up decided right on {len(up_right)} of {len(ok)}')
        print('| drawing | profile median / 90th pct | axis tilt | record |')
        print('|---|---|---|---|')
        for n, fig, what in rows[part]:
            if fig:
                print(f'| {n} | {100 * fig[0]:.2f} % / {100 * fig[1]:.2f} % | {fig[2]:.3f} deg | {what} |')
            else:
                print(f'| {n} | — | — | {what} |')
    if not a.keep:
        shutil.rmtree(work)


if __name__ == '__main__':
    sys.exit(main())
