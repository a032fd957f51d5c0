#!/usr/bin/python3
"""The finite-element check of report.json and data/cells.csv, redone without HQView.

An independent implementation (numpy and scipy from Debian, meshes read by
token readers and meshio, nothing of lib/hqview) of docs/analysis.md's
"Finite-element check":
  - K_e of every hex: Q1 on [-1, 1]^3, 2 x 2 x 2 Gauss, batched numpy
    (np.linalg.inv, np.linalg.det), eigenvalues by np.linalg.eigvalsh;
    kappa_e = lambda_8 / lambda_2; det J at the Gauss points. Compared with
    cells.csv fem_kappa, fem_lambda_max, fem_det_j_min, fem_det_j_max
    (relative 1e-12 kappa_e) on two shared meshes, and num_invalid;
  - the Poisson check on meshes of up to a few thousand hexes: K assembled
    by scipy.sparse, the boundary (faces used once) fixed to u, the interior
    solved by scipy's direct solver; relative L2, H1 and nodal errors by
    3 x 3 x 3 Gauss (1e-7 relative); the extreme eigenvalues of the
    Jacobi-scaled D^-1/2 K_ff D^-1/2 by eigsh (1e-6 relative); lambda_max(K_ff)
    by eigsh against HQView's Lanczos estimate and Fried's bound;
  - the frame the solutions are placed in (principal axes of the volume,
    signs by third moments, the bounding box in it) redone from the docs,
    and the turned kitten's and its mirror image's errors equal kitten_1's;
  - skipped checks: a mirrored copy (every hex inverted) and a one-layer box.

Usage: check_fem.py HQVIEW OUTPUT_DIR [SHARED_DATA_DIR]
Exit 0: passed; 1: failed; 77: numpy, scipy or meshio missing, or no shared data (skipped).
"""

import csv
import json
import os
import shutil
import subprocess
import sys

try:
    import numpy as np
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla
except ImportError as e:
    print(f"SKIP: {e}; scripts/setup installs python3-numpy and python3-scipy")
    sys.exit(77)

SIGNS = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                  [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
HEX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from oracle_support import check, failures, read_medit  # noqa: E402


def write_medit(path, points, hexes):
    with open(path, "w") as f:
        f.write(f"MeshVersionFormatted 2\nDimension 3\nVertices\n{len(points)}\n")
        for p in points:
            f.write(f"{p[0]!r} {p[1]!r} {p[2]!r} 0\n")
        f.write(f"Hexahedra\n{len(hexes)}\n")
        for h in hexes:
            f.write(" ".join(str(int(v) + 1) for v in h) + " 0\n")
        f.write("End\n")


def box(n, perturbation=0.0, nz=None, seed=7):
    nz = n if nz is None else nz
    idx = np.arange((n + 1) * (n + 1) * (nz + 1)).reshape(nz + 1, n + 1, n + 1)
    z, y, x = np.meshgrid(np.arange(nz + 1), np.arange(n + 1), np.arange(n + 1), indexing="ij")
    points = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1).astype(float)
    if perturbation > 0:
        rng = np.random.default_rng(seed)
        interior = np.all((points > 0) & (points < [n, n, nz]), axis=1)
        points[interior] += perturbation * rng.uniform(-1, 1, (interior.sum(), 3))
    points /= n
    c = idx[:-1, :-1, :-1].ravel()
    sx, sy, sz = 1, n + 1, (n + 1) * (n + 1)
    hexes = np.stack([c, c + sx, c + sx + sy, c + sy, c + sz, c + sx + sz, c + sx + sy + sz, c + sy + sz], axis=1)
    return points, hexes


def reference_gradients(xi):
    """dN_a/dxi at the points xi (G, 3): (G, 8, 3); and N (G, 8)."""
    f = 1 + xi[:, None, :] * SIGNS[None, :, :]  # (G, 8, 3)
    n = f.prod(axis=2) / 8
    d = np.empty_like(f)
    d[:, :, 0] = SIGNS[:, 0] * f[:, :, 1] * f[:, :, 2] / 8
    d[:, :, 1] = SIGNS[:, 1] * f[:, :, 0] * f[:, :, 2] / 8
    d[:, :, 2] = SIGNS[:, 2] * f[:, :, 0] * f[:, :, 1] / 8
    return d, n


def jacobians(corners, dref):
    """J[n, g, i, j] = sum_a P[n, a, i] dN_a/dxi_j at point g."""
    return np.einsum("nai,gaj->ngij", corners, dref)


def element_data(points, hexes):
    corners = points[hexes]  # (N, 8, 3)
    gauss = SIGNS / np.sqrt(3)
    dref, _ = reference_gradients(gauss)
    jac = jacobians(corners, dref)
    det = np.linalg.det(jac)  # (N, 8)
    valid = np.all(det > 0, axis=1)
    k = np.zeros((len(hexes), 8, 8))
    if valid.any():
        inv = np.linalg.inv(jac[valid])
        grads = np.einsum("gaj,ngji->ngai", dref, inv)  # row dN @ J^-1
        k[valid] = np.einsum("ng,ngai,ngbi->nab", det[valid], grads, grads)
    return k, det, valid


def boundary_vertices(hexes, num_points):
    quads = hexes[:, HEX_FACES].reshape(-1, 4)
    _, inverse, counts = np.unique(np.sort(quads, axis=1), axis=0, return_inverse=True, return_counts=True)
    on = np.zeros(num_points, dtype=bool)
    on[quads[counts[inverse.ravel()] == 1].ravel()] = True
    return on


def principal_frame(points, hexes):
    """The frame of docs/analysis.md "Finite-element check": (axes (3, 3) rows, center, diagonal, axes_from_input,
    signs_from_input). The volume's moments by 2 x 2 x 2 Gauss on each hex's trilinear map."""
    used = np.zeros(len(points), dtype=bool)
    used[hexes.ravel()] = True
    p = points[used]
    dref, shape = reference_gradients(SIGNS / np.sqrt(3))
    corners = points[hexes]
    w = np.linalg.det(jacobians(corners, dref)).ravel()  # weights 1
    x = np.einsum("ga,nai->ngi", shape, corners).reshape(-1, 3)
    volume = w.sum()
    centroid = (w[:, None] * x).sum(axis=0) / volume
    y = x - centroid
    cov = np.einsum("m,mi,mj->ij", w, y, y) / volume
    lam, vec = np.linalg.eigh(cov)
    lam, vec = lam[::-1], vec[:, ::-1].T  # descending; rows
    mean = p.mean(axis=0)
    point_sigma3 = np.mean(np.sum((p - mean) ** 2, axis=1)) ** 1.5
    signs_from_input = 0

    def signed(a):
        nonlocal signs_from_input
        for m3, sigma3 in ((np.sum(w * (y @ a) ** 3) / volume, lam.sum() ** 1.5),
                           (np.mean(((p - mean) @ a) ** 3), point_sigma3)):
            if abs(m3) > 1e-8 * sigma3:
                return a if m3 > 0 else -a
        signs_from_input += 1
        return a if a[np.argmax(np.abs(a))] > 0 else -a

    def plane(n):
        e = np.eye(3)[np.argmin(np.abs(n))]
        a = e - (e @ n) * n
        a /= np.linalg.norm(a)
        return a, np.cross(n, a)

    tol = 1e-5 * lam[0]
    top, bottom = lam[0] - lam[1] <= tol, lam[1] - lam[2] <= tol
    if top and bottom:
        axes, from_input = np.eye(3), 3
    elif top:
        c = signed(vec[2])
        axes, from_input = np.array([*plane(c), c]), 2
    elif bottom:
        a = signed(vec[0])
        axes, from_input = np.array([a, *plane(a)]), 2
    else:
        axes, from_input = np.array([signed(v) for v in vec]), 0
    q = (p - centroid) @ axes.T
    lo, hi = q.min(axis=0), q.max(axis=0)
    return axes, centroid + ((lo + hi) / 2) @ axes, np.linalg.norm(hi - lo), from_input, signs_from_input


def solutions(points, frame):
    """u and grad u (physical) of exp_x, exp_y, exp_z at points (M, 3): (3, M), (3, M, 3)."""
    axes, center, diagonal = frame[:3]
    xn = (points - center) @ axes.T / diagonal
    values, grads = [], []
    for a in range(3):
        b, c = (a + 1) % 3, (a + 2) % 3
        e = np.exp(np.pi * xn[:, a])
        theta = np.pi * (xn[:, b] + xn[:, c]) / np.sqrt(2)
        values.append(e * np.cos(theta))
        g = np.zeros((len(points), 3))
        g[:, a] = np.pi * e * np.cos(theta)
        g[:, b] = g[:, c] = -np.pi / np.sqrt(2) * e * np.sin(theta)
        grads.append(g @ axes / diagonal)
    return np.array(values), np.array(grads)


def poisson(points, hexes, k_e):
    used = np.zeros(len(points), dtype=bool)
    used[hexes.ravel()] = True
    frame = principal_frame(points, hexes)
    fixed = boundary_vertices(hexes, len(points))
    free = used & ~fixed
    rows = np.repeat(hexes, 8, axis=1).ravel()
    cols = np.tile(hexes, (1, 8)).ravel()
    k = sp.csr_matrix((k_e.ravel(), (rows, cols)), shape=(len(points), len(points)))
    fi = np.nonzero(free)[0]
    bi = np.nonzero(fixed)[0]
    k_ff = k[fi][:, fi].tocsc()
    k_fb = k[fi][:, bi]
    u_nodes, _ = solutions(points, frame)
    solved = u_nodes.copy()
    lu = spla.splu(k_ff)
    for s in range(3):
        solved[s, fi] = lu.solve(-(k_fb @ u_nodes[s, bi]))
    # Errors by 3 x 3 x 3 Gauss.
    g1 = np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)])
    w1 = np.array([5 / 9, 8 / 9, 5 / 9])
    xi = np.array([[a, b, c] for a in g1 for b in g1 for c in g1])
    w = np.array([a * b * c for a in w1 for b in w1 for c in w1])
    dref, shape = reference_gradients(xi)
    corners = points[hexes]
    jac = jacobians(corners, dref)  # (N, 27, 3, 3)
    det = np.abs(np.linalg.det(jac))
    grads = np.einsum("gaj,ngji->ngai", dref, np.linalg.inv(jac))
    x = np.einsum("ga,nai->ngi", shape, corners).reshape(-1, 3)
    u, gu = solutions(x, frame)
    weight = (det * w).ravel()
    result = {}
    for s, name in enumerate(["exp_x", "exp_y", "exp_z"]):
        nodal = solved[s][hexes]  # (N, 8)
        uh = np.einsum("ga,na->ng", shape, nodal).ravel()
        guh = np.einsum("ngai,na->ngi", grads, nodal).reshape(-1, 3)
        l2 = np.sqrt(np.sum(weight * (uh - u[s]) ** 2) / np.sum(weight * u[s] ** 2))
        h1 = np.sqrt(np.sum(weight * np.sum((guh - gu[s]) ** 2, axis=1)) / np.sum(weight * np.sum(gu[s] ** 2, axis=1)))
        nodal_error = np.max(np.abs(solved[s, used] - u_nodes[s, used])) / np.max(np.abs(u_nodes[s, used]))
        result[name] = (l2, h1, nodal_error)
    d = 1 / np.sqrt(k_ff.diagonal())
    scaled = sp.diags(d) @ k_ff @ sp.diags(d)
    lam_max = spla.eigsh(scaled, k=1, which="LA", return_eigenvectors=False, tol=1e-12)[0]
    lam_min = spla.eigsh(scaled.tocsc(), k=1, sigma=0, which="LM", return_eigenvectors=False, tol=1e-12)[0]
    k_max = spla.eigsh(k_ff, k=1, which="LA", return_eigenvectors=False, tol=1e-12)[0]
    return result, lam_min, lam_max, k_max, int(free.sum()), frame


def run(hqview, mesh, bundle, extra):
    shutil.rmtree(bundle, ignore_errors=True)
    result = subprocess.run([hqview, "analyze", mesh, "--no-render", "--no-overlap", "-q", "--data", "csv", "-o", bundle]
                            + extra, capture_output=True, text=True)
    if result.returncode != 0:
        check(False, f"{mesh}: hqview exit {result.returncode}: {result.stderr.strip()}")
        return None, None
    with open(os.path.join(bundle, "report.json")) as f:
        report = json.load(f)
    with open(os.path.join(bundle, "data", "cells.csv")) as f:
        cells = list(csv.DictReader(f))
    return report, cells


def column(cells, name):
    return np.array([float(c[name]) if c[name] != "" else np.nan for c in cells])


def check_elements(name, points, hexes, report, cells):
    k, det, valid = element_data(points, hexes)
    num_invalid = int((~valid).sum())
    check(report["fem"]["element"]["num_invalid"] == num_invalid,
          f"{name}: num_invalid {report['fem']['element']['num_invalid']} != {num_invalid}")
    # Not invertible: det J <= 0 at a corner (xi = +-1) or invalid.
    corner_det = np.linalg.det(jacobians(points[hexes], reference_gradients(SIGNS)[0]))
    num_not_invertible = int((~valid | np.any(corner_det <= 0, axis=1)).sum())
    check(report["fem"]["element"]["num_not_invertible"] == num_not_invertible,
          f"{name}: num_not_invertible {report['fem']['element']['num_not_invertible']} != {num_not_invertible}")
    ev = np.linalg.eigvalsh(k[valid])
    kappa = ev[:, 7] / ev[:, 1]
    hq_kappa, hq_lmax = column(cells, "fem_kappa"), column(cells, "fem_lambda_max")
    check(np.all(np.isnan(hq_kappa[~valid])), f"{name}: fem_kappa not empty for an invalid hex")
    err_kappa = np.max(np.abs(hq_kappa[valid] - kappa) / (kappa * kappa)) if valid.any() else 0
    err_lmax = np.max(np.abs(hq_lmax[valid] - ev[:, 7]) / (ev[:, 7] * kappa)) if valid.any() else 0
    scale = np.max(np.abs(det))
    err_det = max(np.max(np.abs(column(cells, "fem_det_j_min") - det.min(axis=1))),
                  np.max(np.abs(column(cells, "fem_det_j_max") - det.max(axis=1)))) / scale
    print(f"{name}: {len(hexes)} hexes, {num_invalid} invalid; max relative error / kappa: kappa {err_kappa:.2e}, "
          f"lambda_max {err_lmax:.2e}; det J {err_det:.2e}")
    check(err_kappa <= 1e-12, f"{name}: kappa differs by {err_kappa:.3e} kappa relative")
    check(err_lmax <= 1e-12, f"{name}: lambda_max differs by {err_lmax:.3e} kappa relative")
    check(err_det <= 1e-12, f"{name}: det J differs by {err_det:.3e}")
    return k, valid


def close(a, b, tolerance):
    return a is not None and abs(a - b) <= tolerance * abs(b)


def check_poisson(name, points, hexes, report, k_e):
    p = report["fem"]["poisson"]
    check(p["skipped"] is None, f"{name}: skipped: {p['skipped']}")
    if p["skipped"] is not None:
        return
    result, lam_min, lam_max, k_max, num_free, frame = poisson(points, hexes, k_e)
    norm = p["normalization"]
    axes, center, diagonal, from_input, signs = frame
    err_frame = max(np.max(np.abs(np.array(norm["axes"]) - axes)), abs(norm["diagonal"] - diagonal) / diagonal,
                    np.max(np.abs(np.array(norm["center"]) - center)) / diagonal)
    check(err_frame <= 1e-9, f"{name}: frame differs from numpy's by {err_frame:.1e}")
    check(norm["axes_from_input"] == from_input and norm["signs_from_input"] == signs,
          f"{name}: axes/signs from input {norm['axes_from_input']}, {norm['signs_from_input']} != {from_input}, {signs}")
    check(p["num_free_vertices"] == num_free, f"{name}: {p['num_free_vertices']} free vertices, numpy {num_free}")
    worst = 0.0
    for s, (l2, h1, nodal) in result.items():
        mine = p["solutions"][s]
        for key, value in (("l2_error", l2), ("h1_error", h1), ("nodal_error", nodal)):
            worst = max(worst, abs(mine[key] - value) / value)
            check(close(mine[key], value, 1e-7), f"{name}: {s} {key} {mine[key]!r} != scipy {value!r}")
    sm = p["scaled_matrix"]
    e_min, e_max = abs(sm["lambda_min"] - lam_min) / lam_min, abs(sm["lambda_max"] - lam_max) / lam_max
    print(f"{name}: frame {err_frame:.1e} (from input: {from_input} axes, {signs} signs); {num_free} free; errors vs "
          f"scipy max relative {worst:.1e}; scaled eigenvalues "
          f"[{lam_min:.6g}, {lam_max:.6g}] relative {e_min:.1e}, {e_max:.1e}; lambda_max(K) {k_max:.6g}, "
          f"Lanczos {p['stiffness']['lambda_max']:.6g}, Fried {p['stiffness']['fried_bound']:.6g}")
    check(e_min <= 1e-6, f"{name}: scaled lambda_min {sm['lambda_min']!r} != eigsh {lam_min!r}")
    check(e_max <= 1e-6, f"{name}: scaled lambda_max {sm['lambda_max']!r} != eigsh {lam_max!r}")
    st = p["stiffness"]
    check(st["lambda_max"] <= k_max * (1 + 1e-9) and st["lambda_max"] >= 0.9 * k_max,
          f"{name}: Lanczos lambda_max(K) {st['lambda_max']!r} vs eigsh {k_max!r}")
    check(k_max <= st["fried_bound"] * (1 + 1e-12), f"{name}: lambda_max(K) {k_max!r} above Fried's bound")


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    hqview, out = sys.argv[1], sys.argv[2]
    data = sys.argv[3] if len(sys.argv) > 3 else os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "data")
    meshes = os.path.join(data, "meshes")
    if not os.path.isdir(meshes):
        print(f"SKIP: no shared data at {data}")
        return 77
    os.makedirs(out, exist_ok=True)
    cases = []  # (name, path, points, hexes, solve?)
    for rel, solve in (("livesu2016_skeleton/armadillo.mesh", True), ("livesu2015_edgecone/bunny_in.mesh", False),
                       ("gao2016_sweeping/kitten_1.mesh", True), ("li2012_srf/fandisk.mesh", True),
                       ("gao2016_sweeping/hand7_1.mesh", True)):
        points, hexes = read_medit(os.path.join(meshes, rel))
        cases.append((os.path.basename(rel), os.path.join(meshes, rel), points, hexes, solve))
    # Made here: a perturbed box, a rotated and scaled kitten, and two meshes that must be skipped.
    points, hexes = box(7, perturbation=0.3)
    cases.append(("perturbed_box_7.mesh", None, points, hexes, True))
    kp, kh = read_medit(os.path.join(meshes, "gao2016_sweeping/kitten_1.mesh"))
    angle = 0.7
    rot = np.array([[np.cos(angle), -np.sin(angle), 0], [np.sin(angle), np.cos(angle), 0], [0, 0, 1]])
    cases.append(("kitten_rotated_scaled.mesh", None, 40.0 * kp @ rot.T + [5, -3, 100], kh, True))
    cases.append(("kitten_mirrored.mesh", None, kp * [-1, 1, 1], kh, "skip"))
    cases.append(("kitten_mirrored_valid.mesh", None, kp * [-1, 1, 1], kh[:, [4, 5, 6, 7, 0, 1, 2, 3]], True))
    points, hexes = box(6, nz=1)
    cases.append(("one_layer_box.mesh", None, points, hexes, "skip"))
    errors = {}  # name: the report's errors, for the placement check
    for name, path, points, hexes, solve in cases:
        if path is None:
            path = os.path.join(out, name)
            write_medit(path, points, hexes)
        extra = ["--simulate"] if solve else ["--metrics", "all,fem_element"]
        report, cells = run(hqview, path, os.path.join(out, name + ".bundle"), extra)
        if report is None:
            continue
        k_e, valid = check_elements(name, points, hexes, report, cells)
        if solve == "skip":
            skipped = report["fem"]["poisson"]["skipped"]
            print(f"{name}: skipped: {skipped}")
            check(skipped is not None, f"{name}: not skipped")
            check(report["fem"]["poisson"]["mean"]["l2_error"] is None, f"{name}: a skipped check has errors")
        elif solve:
            check_poisson(name, points, hexes, report, k_e)
            solutions = report["fem"]["poisson"]["solutions"] or {}
            errors[name] = [s[k] for s in solutions.values() for k in ("l2_error", "h1_error", "nodal_error")]
    # Issue 48: the turned, scaled and moved kitten and its mirror image score as the kitten.
    for copy in ("kitten_rotated_scaled.mesh", "kitten_mirrored_valid.mesh"):
        compared = bool(errors.get("kitten_1.mesh")) and len(errors.get(copy, [])) == len(errors["kitten_1.mesh"])
        check(compared, f"{copy}: placement check not run (no solutions of it or of kitten_1.mesh, or not as many)")
        if not compared:
            continue
        a, b = np.array(errors["kitten_1.mesh"]), np.array(errors[copy])
        spread = np.max(np.abs(a - b) / a)
        print(f"{copy}: errors vs kitten_1.mesh max relative {spread:.1e}")
        check(spread <= 1e-8, f"{copy}: errors differ from kitten_1.mesh's by {spread:.1e} relative")
    print("fem oracle:", "FAILED" if failures else "passed", f"({len(failures)} failures)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
