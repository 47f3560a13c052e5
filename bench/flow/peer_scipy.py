#!/usr/bin/python3
"""The peer of the ugs-flow benchmark: the same scheme written the way an engineer would in SciPy.

Same mesh (raw arrays from make_bench_case), same physics (eq. 3.35, K of Table 4.2, S_s from the
compressibility law at each centroid's initial effective stress), same backward Euler with lumped
storage, pool nodes on the schedule, one factorization per distinct step size (SuperLU via
scipy.sparse.linalg.splu), reactions -> cumulative influx. It writes no field files (ugs-flow writes
HDF5 for every date), so the comparison favours the peer.

    peer_scipy.py DIR            # DIR from make_bench_case
"""
import csv
import datetime as dt
import sys
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

GAMMA_W, BETA, POROSITY = 9810.0, 4.4e-10, 0.20
K = np.array([2.04e-7, 2.04e-7, 2.04e-8])
CM_A, CM_B = 1.0044e-2, 1.1347
SURFACE, GRAD_EFF = 50.0, 0.0226 - 0.00981   # m, MPa/m
P_REF = 15.2055e6


def main(d):
    t_start = time.time()
    x = np.fromfile(f"{d}/nodes.f64").reshape(-1, 3)
    tets = np.fromfile(f"{d}/tets.u32", dtype=np.uint32).reshape(-1, 4).astype(np.int64)
    pool = np.fromfile(f"{d}/pool.u8", dtype=np.uint8).astype(bool)
    n = len(x)
    # assembly over aquifer tetrahedra
    aq = tets[~pool]
    J = np.stack([x[aq[:, 1]] - x[aq[:, 0]], x[aq[:, 2]] - x[aq[:, 0]], x[aq[:, 3]] - x[aq[:, 0]]], axis=2)
    vol = np.abs(np.linalg.det(J)) / 6.0
    inv = np.linalg.inv(J)                           # rows: gradients of barycentrics 1..3
    g = np.concatenate([-inv.sum(axis=1, keepdims=True), inv], axis=1)   # (m, 4, 3)
    ke = np.einsum("mik,k,mjk->mij", g, K / GAMMA_W, g) * vol[:, None, None]
    rows = np.repeat(aq, 4, axis=1).ravel()
    cols = np.tile(aq, (1, 4)).ravel()
    A = sp.csr_matrix((ke.ravel(), (rows, cols)), shape=(n, n))
    zc = x[aq, 2].mean(axis=1)
    sigma = GRAD_EFF * (SURFACE - zc)
    s = POROSITY * BETA + CM_A * sigma ** (-CM_B) * 1e-6
    m = np.bincount(aq.ravel(), weights=np.repeat(vol * s / 4.0, 4), minlength=n)
    is_pool = np.zeros(n, bool)
    is_pool[tets[pool].ravel()] = True
    F, D = np.flatnonzero(~is_pool), np.flatnonzero(is_pool)
    AFF, AFD, AD = A[F][:, F].tocsc(), A[F][:, D].tocsr(), A[D].tocsr()
    # schedule
    dates, p = [], []
    with open(f"{d}/pressure_pool_c.csv") as fh:
        for row in csv.DictReader(fh):
            dates.append(dt.date.fromisoformat(row["date"]))
            p.append(float(row["p_norm"]))
    dp = (np.array(p) - p[0]) * P_REF
    secs = np.array([(t - dates[0]).days * 86400.0 for t in dates])
    t_setup = time.time() - t_start
    # time loop
    lu = {}
    pf = np.zeros(len(F))
    pd_old = 0.0
    influx = 0.0
    t_factor = 0.0
    for k in range(1, len(dates)):
        step = secs[k] - secs[k - 1]
        if step not in lu:
            t0 = time.time()
            # SPD matrix: symmetric ordering, no pivoting (SuperLU's symmetric mode)
            lu[step] = spla.splu(AFF + sp.diags(m[F] / step, format="csc"), permc_spec="MMD_AT_PLUS_A",
                                 diag_pivot_thresh=0.0, options=dict(SymmetricMode=True))
            t_factor += time.time() - t0
            print(f"peer scipy: factorization {len(lu)} (dt = {step / 86400:g} days): {time.time() - t0:.1f} s, "
                  f"L+U {lu[step].L.nnz + lu[step].U.nnz:.3g} nonzeros", file=sys.stderr, flush=True)
        pd = dp[k]
        pf_new = lu[step].solve(m[F] / step * pf - AFD @ np.full(len(D), pd))
        full = np.zeros(n)
        full[F], full[D] = pf_new, pd
        influx -= np.sum(m[D] * (pd - pd_old) + step * (AD @ full))
        pf, pd_old = pf_new, pd
        if k % 100 == 0:
            print(f"peer scipy: step {k}/{len(dates) - 1} ({time.time() - t_start:.0f} s)", file=sys.stderr, flush=True)
    full = np.zeros(n)
    full[F], full[D] = pf, pd_old
    total = time.time() - t_start
    print(f"peer scipy: {n} nodes, {len(dates) - 1} steps, {len(lu)} factorizations ({t_factor:.1f} s), "
          f"setup {t_setup:.1f} s, total {total:.1f} s; influx {influx:.6g} m3, stored {m @ full:.6g} m3")


if __name__ == "__main__":
    main(sys.argv[1])
