#!/usr/bin/env python3
"""ReliefKit vs MeshLab's own curvature filters, inside the real meshlabserver.

accuracy: a jittered 128 K-face torus (R = 3, r = 1); each filter writes k1 / k2 into vertex
          quality; prints the median error of k1 and k2 as a percentage of max|k| = 1/r.
speed:    synthetic relief tori of ~100 K, 1 M and 4 M faces; one meshlabserver process runs
          ReliefKit (jet fit), ReliefKit (per-face fit), MeshLab Pseudoinverse Quadric Fitting and
          MeshLab Taubin on the same mesh; wall time of each filter (from the time stamps of the
          "filter:" lines meshlabserver prints) and peak RSS growth during it (sampled every 2 ms).

demarcating: the whole "Demarcating Curves" filter (defaults) on the 1 M and 4 M meshes, next to
          MeshLab's Pseudoinverse Quadric Fitting in the same process.
ratios:   the three curve filters most used (curvature, Demarcating Curves, Relief Edges; the
          parameters of examples/*.mlx) as ratios of MeshLab's Pseudoinverse Quadric Fitting run in
          the same process, twice, on a clean 1 M-face relief torus and on the shared real scans
          (../shared/data/meshes, converted to PLY).

first-call: the curve filters in two orders in one process (is the first ReliefKit filter of a
          process slower, and which one pays).

chapters: chapters 5 and 6 (multi-scale and prominent filters) as ratios of the quadric fitting,
          on a regular 1 M-face relief torus and on a decimated, irregular one.

scans:    single- against multi-scale curves at defaults (build/bench/bench_multiscale_scans) on
          the shared scans, on copies decimated by MeshLab to half their faces and on irregular
          copies (a quarter of the faces, thin triangles allowed).

Usage: bench/compare_meshlab.py [accuracy] [speed] [demarcating] [ratios] [first-call] [chapters] [scans]
       [--sizes 100000,1000000,4000000] [--keep DIR] [--only NAME,...]
Needs a build (scripts/build.sh). Runs its own Xvfb.
"""
import argparse
import math
import os
import struct
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BUILD = os.environ.get("RELIEFKIT_BUILD_DIR", os.path.join(ROOT, "build"))
SERVER = os.path.join(BUILD, "prefix", "bin", "meshlabserver")
MAKE = os.path.join(BUILD, "tests", "rk_make_mesh")

OURS = "Compute Curvature Tensor and Derivatives"
MESHLAB = "Compute curvature principal directions"


def p_enum(name, value, n):
    vals = " ".join(f'enum_val{i}="{i}"' for i in range(n))
    return f'<Param type="RichEnum" name="{name}" value="{value}" enum_cardinality="{n}" {vals}/>'


def ours(estimator, quality):
    return (OURS, [p_enum("estimator", estimator, 2),
                   '<Param type="RichString" name="presmoothing" value="0"/>',
                   p_enum("quality", quality, 6)])


def meshlab(method, quality):  # method 0 Taubin, 3 PQF; quality 2 writes K1, 3 writes K2
    return (MESHLAB, [p_enum("Method", method, 4), p_enum("CurvColorMethod", quality, 7),
                      '<Param type="RichBool" name="Autoclean" value="false"/>'])


def demarcating(presmoothing):
    return ("Demarcating Curves", ['<Param type="RichFloat" name="threshold" value="1"/>',
                                   f'<Param type="RichString" name="presmoothing" value="{presmoothing}"/>',
                                   '<Param type="RichFloat" name="min_length" value="4"/>',
                                   '<Param type="RichBool" name="per_vertex" value="true"/>',
                                   '<Param type="RichBool" name="quality" value="false"/>',
                                   '<Param type="RichFloat" name="lift" value="0.2"/>'])


SENTINEL = ("Select None", ['<Param type="RichBool" name="allFaces" value="true"/>',
                            '<Param type="RichBool" name="allVerts" value="true"/>'])


# meshlabserver sets up a GL context and rendering data before every filter; a trivial filter
# run first measures that share of each filter's time.
OVERHEAD = "(meshlabserver per-filter set-up: Select None)"


def script(filters):
    body = "".join(f' <filter name="{n}">\n' + "".join(f"  {p}\n" for p in ps) + " </filter>\n"
                   for n, ps in filters)
    return "<!DOCTYPE FilterScript>\n<FilterScript>\n" + body + "</FilterScript>\n"


def start_xvfb():
    for d in range(91, 120):
        if os.path.exists(f"/tmp/.X{d}-lock"):
            continue
        p = subprocess.Popen(["Xvfb", f":{d}", "-screen", "0", "1024x768x24", "-nolisten", "tcp", "-noreset"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(1.0)
        if p.poll() is None:
            return p, f":{d}"
    sys.exit("cannot start Xvfb")


def read_ply_quality(path):
    with open(path, "rb") as f:
        header, props, nv = [], [], 0
        while True:
            line = f.readline().decode().strip()
            header.append(line)
            if line.startswith("element vertex"):
                nv = int(line.split()[2])
                cur = props
            elif line.startswith("element"):
                cur = None
            elif line.startswith("property") and cur is not None:
                cur.append(line.split())
            if line == "end_header":
                break
        assert "format binary_little_endian 1.0" in header, header
        fmt = {"float": "f", "double": "d", "uchar": "B", "int": "i", "uint": "I"}
        rec = "<" + "".join(fmt[p[1]] for p in props)
        size = struct.calcsize(rec)
        names = [p[2] for p in props]
        data = f.read(size * nv)
        pts, q = [], []
        for i in range(nv):
            r = dict(zip(names, struct.unpack_from(rec, data, i * size)))
            pts.append((r["x"], r["y"], r["z"]))
            q.append(r.get("quality", float("nan")))
        return pts, q


def median(v):
    v = sorted(v)
    return v[len(v) // 2]


def run(display, mesh, filters, out=None, timed=False):
    with tempfile.NamedTemporaryFile("w", suffix=".mlx", delete=False) as f:
        f.write(script(([SENTINEL] if timed else []) + filters + ([SENTINEL] if timed else [])))
        mlx = f.name
    cmd = ["stdbuf", "-oL", SERVER, "-i", mesh, "-s", mlx] + (["-o", out, "-m", "vq"] if out else [])
    env = dict(os.environ, DISPLAY=display)
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env, text=True, bufsize=1)
    samples, stop = [], threading.Event()

    def sample():
        while not stop.is_set():
            try:
                with open(f"/proc/{p.pid}/status") as s:
                    for line in s:
                        if line.startswith("VmRSS:"):
                            samples.append((time.monotonic(), int(line.split()[1])))
            except OSError:
                pass
            time.sleep(0.002)

    th = threading.Thread(target=sample)
    th.start()
    starts, log = [], []
    for line in p.stdout:
        t = time.monotonic()
        log.append(line)
        if "filter: " in line:
            starts.append((t, line.split("filter: ", 1)[1].strip()))
    p.wait()
    stop.set()
    th.join()
    os.unlink(mlx)
    if p.returncode != 0:
        raise RuntimeError("meshlabserver failed:\n" + "".join(log[-30:]))
    phases = []
    for (t0, name), (t1, _) in zip(starts, starts[1:]):
        inside = [kb for (t, kb) in samples if t0 <= t <= t1]
        before = [kb for (t, kb) in samples if t <= t0]
        base = before[-1] if before else (inside[0] if inside else 0)
        phases.append((name, t1 - t0, (max(inside) - base) / 1024 if inside else 0.0))
    return phases, log


def accuracy(display, tmp):
    mesh = os.path.join(tmp, "torus128k.ply")
    subprocess.run([MAKE, "torus", "3", "1", "400", "160", "0.5", "7", mesh], check=True)
    print("Accuracy on a jittered 128,000-face torus (R = 3, r = 1): median |error| / max|k|")
    print(f"{'method':48s} {'k1 %':>8s} {'k2 %':>8s}")
    cases = [("ReliefKit, cubic jet fit (default)", lambda q: ours(0, q), 2, 3),
             ("ReliefKit, per-face fit (Rusinkiewicz)", lambda q: ours(1, q), 2, 3),
             # MeshLab 2020.09's "Min Curvature" colouring writes K1 (the maximal one) and
             # "Max Curvature" writes K2: measured, see vcg UpdateQuality::VertexFromMinCurvatureDir.
             ("MeshLab, Pseudoinverse Quadric Fitting", lambda q: meshlab(3, q), 2, 3),
             ("MeshLab, Taubin approximation", lambda q: meshlab(0, q), 2, 3)]
    for name, flt, qmax, qmin in cases:
        vals = {}
        for which, q in (("max", qmax), ("min", qmin)):
            out = os.path.join(tmp, f"acc_{which}.ply")
            run(display, mesh, [flt(q)], out)
            vals[which] = read_ply_quality(out)
        pts = vals["max"][0]
        errs = {}
        for sign in (1, -1):  # MeshLab's sign convention may be the opposite one
            e1, e2 = [], []
            kmax = vals["max"][1] if sign == 1 else [-x for x in vals["min"][1]]
            kmin = vals["min"][1] if sign == 1 else [-x for x in vals["max"][1]]
            for (x, y, z), a, b in zip(pts, kmax, kmin):
                v = math.atan2(z, math.hypot(x, y) - 3)
                e1.append(abs(a - 1.0))
                e2.append(abs(b - math.cos(v) / (3 + math.cos(v))))
            errs[sign] = (100 * median(e1), 100 * median(e2))
        best = min(errs.values(), key=sum)
        print(f"{name:48s} {best[0]:8.3f} {best[1]:8.3f}")


def speed(display, tmp, sizes):
    print("Speed inside meshlabserver (same process, same mesh): wall time and peak RSS growth")
    print(f"{'faces':>10s}  {'filter':48s} {'time s':>8s} {'s/M faces':>10s} {'+MiB':>8s}")
    labels = [OVERHEAD, "ReliefKit jet fit: curvature + derivatives", "ReliefKit per-face fit: curvature + derivatives",
              "MeshLab Pseudoinverse Quadric Fitting", "MeshLab Taubin approximation"]
    for n in sizes:
        mesh = os.path.join(tmp, f"relief{n}.ply")
        out = subprocess.run([MAKE, "relief-torus", str(n), mesh], check=True, capture_output=True, text=True).stdout
        faces = int(out.split()[1])
        phases, _ = run(display, mesh, [ours(0, 0), ours(1, 0), meshlab(3, 0), meshlab(0, 0)], timed=True)
        for label, (name, secs, mib) in zip(labels, phases):
            print(f"{faces:10d}  {label:48s} {secs:8.3f} {secs / (faces / 1e6):10.3f} {mib:8.1f}")


def demarcating_speed(display, tmp, sizes):
    print("Demarcating Curves (filter defaults) inside meshlabserver, next to MeshLab's Pseudoinverse Quadric "
          "Fitting on the same mesh in the same process")
    print(f"{'faces':>10s}  {'filter':48s} {'time s':>8s} {'s/M faces':>10s} {'+MiB':>8s}")
    labels = [OVERHEAD, "ReliefKit Demarcating Curves (whole filter)", "MeshLab Pseudoinverse Quadric Fitting"]
    for n in sizes:
        mesh = os.path.join(tmp, f"relief{n}.ply")
        out = subprocess.run([MAKE, "relief-torus", str(n), mesh], check=True, capture_output=True, text=True).stdout
        faces, edge = int(out.split()[1]), float(out.split()[3])
        phases, _ = run(display, mesh, [demarcating("auto"), meshlab(3, 0)], timed=True)
        for label, (name, secs, mib) in zip(labels, phases):
            print(f"{faces:10d}  {label:48s} {secs:8.3f} {secs / (faces / 1e6):10.3f} {mib:8.1f}")


def example_filter(script_name, filter_name):
    """The <filter> block of an example script, as (name, [param lines])."""
    import re
    text = open(os.path.join(ROOT, "examples", script_name)).read()
    block = re.search(r'<filter name="%s">(.*?)</filter>' % re.escape(filter_name), text, re.S).group(1)
    return (filter_name, [line.strip() for line in block.splitlines() if line.strip().startswith("<Param")])


def shared_scans(tmp):
    folder = os.path.join(ROOT, "..", "shared", "data", "meshes")
    scans = []
    for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
        ply = os.path.join(tmp, os.path.splitext(name)[0] + ".ply")
        subprocess.run([MAKE, "convert", os.path.join(folder, name), ply], check=True, capture_output=True)
        scans.append((os.path.splitext(name)[0], ply))
    return scans


def ratios(display, tmp, repeats=2):
    curves = [("curvature", example_filter("curvature.mlx", OURS)),
              ("demarcating", example_filter("demarcating_shading.mlx", "Demarcating Curves")),
              ("relief edges", example_filter("relief_edges.mlx", "Relief Edges"))]
    mesh = os.path.join(tmp, "relief1000000.ply")
    subprocess.run([MAKE, "relief-torus", "1000000", mesh], check=True, capture_output=True)
    print("Each filter's time / MeshLab Pseudoinverse Quadric Fitting's, same process, same mesh "
          f"(run {repeats} times; targets: curvature <= 0.15, demarcating <= 0.2, relief edges <= 0.6)")
    print(f"{'mesh':24s} {'faces':>9s} {'PQF s':>7s}  " + "  ".join(f"{n:>14s}" for n, _ in curves))
    for label, path in [("relief torus (clean)", mesh)] + shared_scans(tmp):
        faces = count_faces(path)
        for _ in range(repeats):
            try:
                phases, _ = run(display, path, [meshlab(3, 0)] + [f for _, f in curves] + [meshlab(3, 0)], timed=True)
            except RuntimeError:
                print(f"{label:24s} {faces:9d}  MeshLab's quadric fitting stops meshlabserver on this mesh: no ratio")
                break
            times = [secs for _, secs, _ in phases[1:]]
            pqf = 0.5 * (times[0] + times[-1])
            cells = "  ".join(f"{t / pqf:6.3f} ({t:5.2f}s)" for t in times[1:-1])
            print(f"{label:24s} {faces:9d} {pqf:7.3f}  {cells}", flush=True)


def first_call(display, tmp, repeats=2):
    """Each curve filter first and again later in one process: the first ReliefKit filter of a
    process pays for memory new to the process (see docs/benchmarks.md)."""
    curvature = example_filter("curvature.mlx", OURS)
    dem = example_filter("demarcating_shading.mlx", "Demarcating Curves")
    edges = example_filter("relief_edges.mlx", "Relief Edges")
    mesh = os.path.join(tmp, "relief1000000.ply")
    subprocess.run([MAKE, "relief-torus", "1000000", mesh], check=True, capture_output=True)
    orders = {"curvature first": [meshlab(3, 0), curvature, dem, edges, curvature, meshlab(3, 0)],
              "demarcating first": [meshlab(3, 0), dem, curvature, edges, dem, meshlab(3, 0)]}
    print("Filter times in seconds, in the order run, one process per line (1 M-face relief torus)")
    for label, filters in orders.items():
        for _ in range(repeats):
            phases, _ = run(display, mesh, filters, timed=True)
            print(f"{label:18s} " + "  ".join(f"{name[:20]:>20s} {secs:5.2f}" for name, secs, _ in phases[1:]),
                  flush=True)


DECIMATE = ("Simplification: Quadric Edge Collapse Decimation", None)


def decimate(display, source, faces, out, quality=0.3):
    """MeshLab's quadric edge collapse of `source` to `faces` faces: the irregular triangles of a
    decimated scan (long and short edges, valences 3 to 12). A lower `quality` threshold lets the
    collapse leave thinner triangles."""
    params = [f'<Param type="RichInt" name="TargetFaceNum" value="{faces}"/>',
              '<Param type="RichFloat" name="TargetPerc" value="0"/>',
              f'<Param type="RichFloat" name="QualityThr" value="{quality}"/>',
              '<Param type="RichBool" name="PreserveBoundary" value="false"/>',
              '<Param type="RichFloat" name="BoundaryWeight" value="1"/>',
              '<Param type="RichBool" name="PreserveNormal" value="true"/>',
              '<Param type="RichBool" name="PreserveTopology" value="true"/>',
              '<Param type="RichBool" name="OptimalPlacement" value="true"/>',
              '<Param type="RichBool" name="PlanarQuadric" value="false"/>',
              '<Param type="RichFloat" name="PlanarWeight" value="0.001"/>',
              '<Param type="RichBool" name="QualityWeight" value="false"/>',
              '<Param type="RichBool" name="AutoClean" value="true"/>',
              '<Param type="RichBool" name="Selected" value="false"/>']
    raw = out + ".raw.ply"
    run(display, source, [(DECIMATE[0], params)], out=raw)
    # Positions and faces only (meshlabserver saved vertex quality too, which made its buffer
    # accounting refuse the quadric fitting on the copy: "no additional memory available").
    subprocess.run([MAKE, "convert", raw, out], check=True, capture_output=True)
    os.unlink(raw)


def chapters(display, tmp, repeats=2):
    """Chapters 5 and 6 (the parameters of examples/multiscale.mlx and examples/prominent.mlx) as
    ratios of the quadric fitting in the same process, on a regular 1 M-face relief torus and on
    an irregular one of the same surface (4 M faces decimated to 1 M by MeshLab)."""
    filters = [(n, example_filter(script, n)) for script, names in
               [("multiscale.mlx", ["Compute Optimal Scale", "Multi-scale Ridges and Valleys",
                                    "Multi-scale Relief Edges"]),
                ("prominent.mlx", ["Prominent Field", "Prominent Coloring", "Prominent Enhancement"])]
               for n in names]
    regular = os.path.join(tmp, "relief1000000.ply")
    fine, irregular = os.path.join(tmp, "relief4000000.ply"), os.path.join(tmp, "relief_decimated.ply")
    subprocess.run([MAKE, "relief-torus", "1000000", regular], check=True, capture_output=True)
    subprocess.run([MAKE, "relief-torus", "4000000", fine], check=True, capture_output=True)
    decimate(display, fine, 1000000, irregular)
    os.unlink(fine)
    print("Each filter's time / MeshLab Pseudoinverse Quadric Fitting's, same process, same mesh "
          f"(run {repeats} times; issue 22: multi-scale <= 5, Prominent Field and Coloring <= 0.5)")
    print(f"{'mesh':22s} {'faces':>8s} {'PQF s':>6s}  " + "  ".join(f"{n[:16]:>16s}" for n, _ in filters))
    for label, path in [("relief torus", regular), ("decimated relief", irregular)]:
        faces = count_faces(path)
        for _ in range(repeats):
            phases, _ = run(display, path, [meshlab(3, 0)] + [f for _, f in filters] + [meshlab(3, 0)], timed=True)
            times = [secs for _, secs, _ in phases[1:]]
            pqf = 0.5 * (times[0] + times[-1])
            print(f"{label:22s} {faces:8d} {pqf:6.2f}  " +
                  "  ".join(f"{t / pqf:6.2f} ({t:5.1f}s)" for t in times[1:-1]), flush=True)


def count_faces(ply):
    with open(ply, "rb") as f:
        for line in f:
            if line.startswith(b"element face"):
                return int(line.split()[2])
            if line.startswith(b"end_header"):
                return 0


def scans(display, tmp, only=None):
    """The multi-scale fidelity figures on the shared scans, on copies decimated to half their faces
    and on irregular copies (a quarter of the faces, thin triangles allowed: quality threshold 0.05)."""
    meshes = []
    for name, ply in shared_scans(tmp):
        if only and not any(o in name for o in only):
            continue
        half = os.path.join(tmp, name + "_decimated.ply")
        decimate(display, ply, count_faces(ply) // 2, half)
        irregular = os.path.join(tmp, name + "_irregular.ply")
        decimate(display, ply, count_faces(ply) // 4, irregular, quality=0.05)
        meshes += [ply, half, irregular]
    subprocess.run([os.path.join(BUILD, "bench", "bench_multiscale_scans")] + meshes, check=True)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("what", nargs="*", default=["accuracy", "speed", "demarcating"])
    ap.add_argument("--sizes", default="100000,1000000,4000000")
    ap.add_argument("--keep", help="keep the meshes made (converted scans, decimated copies) in this folder")
    ap.add_argument("--only", help="scans: only those whose names contain one of these (comma-separated)")
    a = ap.parse_args()
    for f in (SERVER, MAKE):
        if not os.path.exists(f):
            sys.exit(f"{f} missing: build first (scripts/build.sh)")
    xv, display = start_xvfb()
    try:
        with tempfile.TemporaryDirectory() as scratch:
            tmp = a.keep or scratch
            os.makedirs(tmp, exist_ok=True)
            print(f"CPU threads: {os.cpu_count()}")
            if "accuracy" in a.what:
                accuracy(display, tmp)
            if "ratios" in a.what:
                ratios(display, tmp)
            if "first-call" in a.what:
                first_call(display, tmp)
            if "chapters" in a.what:
                chapters(display, tmp)
            if "scans" in a.what:
                scans(display, tmp, a.only.split(",") if a.only else None)
            if "speed" in a.what:
                speed(display, tmp, [int(s) for s in a.sizes.split(",")])
            if "demarcating" in a.what:
                demarcating_speed(display, tmp, [int(s) for s in a.sizes.split(",") if int(s) >= 1000000])
    finally:
        xv.terminate()


if __name__ == "__main__":
    main()
