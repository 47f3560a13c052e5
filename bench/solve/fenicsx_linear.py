#!/usr/bin/python3
"""Peer of bench/solve/linear.sh: the same linear elastic solve in FEniCSx 0.5 (Debian
python3-dolfinx-real), PETSc CG + hypre BoomerAMG with ugs-solve's own options, same tolerance.

    mpirun -n 2 /usr/bin/python3 fenicsx_linear.py CASE_DIR [OUT.xdmf] [PETSc options, e.g. -ksp_view]

CASE_DIR is written by `make_thesis_case DIR --linear` (bench/solve): mesh_arrays.h5 holds the very mesh of
mesh.msh (coordinates, tetrahedra; same node order). Physics as in ugs-solve's case.toml there:
isotropic elasticity, nu = 0.3, E per element from c_M = 1.0044e-2 sigma^-1.1347 (1/MPa) at the
initial effective vertical stress sigma = (0.0226 - 0.0100) MPa/m x (50 m - z_centroid), at least
0.1 MPa; E = (1 + nu)(1 - 2 nu) / ((1 - nu) c_M); Biot forcing alpha dp = -10 MPa in the Pool C
cells (cell field dp of mesh_arrays.h5); zero displacement on the sides and bottom, free top.
Reading the mesh, partitioning, assembly, the solve and writing u are all inside the timing.
"""
import sys
import time

t_start = time.perf_counter()

import h5py  # noqa: E402
import numpy as np  # noqa: E402
import ufl  # noqa: E402
from dolfinx import fem, io, la, mesh  # noqa: E402
from dolfinx.fem.petsc import apply_lifting, assemble_matrix, assemble_vector, set_bc  # noqa: E402
from mpi4py import MPI  # noqa: E402
from petsc4py import PETSc  # noqa: E402

comm = MPI.COMM_WORLD
case = sys.argv[1]
out = sys.argv[2] if len(sys.argv) > 2 and not sys.argv[2].startswith("-") else None
extra = [a for a in sys.argv[2:] if a != out]  # PETSc options: -name [value] ...

# 1. Mesh: read on rank 0, distributed by dolfinx's partitioner.
if comm.rank == 0:
    with h5py.File(f"{case}/mesh_arrays.h5", "r") as f:
        x = f["mesh/coordinates"][:]
        cells = f["mesh/tetrahedra"][:].astype(np.int64)
        cell_dp = f["steps"][sorted(f["steps"])[0]]["cell/dp"][:]
else:
    x = np.zeros((0, 3))
    cells = np.zeros((0, 4), dtype=np.int64)
    cell_dp = None
cell_dp = comm.bcast(cell_dp, root=0)
domain = ufl.Mesh(ufl.VectorElement("Lagrange", "tetrahedron", 1))
msh = mesh.create_mesh(comm, cells, x, domain)
t_mesh = time.perf_counter()

# 2. Element data: E from the centroid depth (the case's elastic law), dp from the mesh file.
LX, LY = 42000.0, 30000.0
nu = 0.3
tdim = msh.topology.dim
ncells = msh.topology.index_map(tdim).size_local + msh.topology.index_map(tdim).num_ghosts
c2v = msh.geometry.dofmap
centroid = msh.geometry.x[c2v.array.reshape(-1, 4)[:ncells]].mean(axis=1)  # (vectorized: no Python loop per cell)
sigma = np.maximum((0.0226 - 0.0100) * (50.0 - centroid[:, 2]), 0.1)
cm = 1.0044e-2 * sigma ** -1.1347 * 1e-6
Q = fem.FunctionSpace(msh, ("DG", 0))
E = fem.Function(Q)
E.x.array[:] = (1 + nu) * (1 - 2 * nu) / ((1 - nu) * cm)
alpha_dp = fem.Function(Q)
alpha_dp.x.array[:] = cell_dp[np.asarray(msh.topology.original_cell_index)[:ncells]]

# 3. Forms: int sigma(u) : eps(v) = int alpha dp div(v).
V = fem.VectorFunctionSpace(msh, ("Lagrange", 1))
u, v = ufl.TrialFunction(V), ufl.TestFunction(V)
mu = E / (2 * (1 + nu))
lam = E * nu / ((1 + nu) * (1 - 2 * nu))


def eps(w):
    return ufl.sym(ufl.grad(w))


def sig(w):
    return 2 * mu * eps(w) + lam * ufl.tr(eps(w)) * ufl.Identity(3)


a = fem.form(ufl.inner(sig(u), eps(v)) * ufl.dx)
L = fem.form(alpha_dp * ufl.div(v) * ufl.dx)


def on_fixed(p):
    tol = 1e-6
    return (np.isclose(p[0], 0, atol=tol) | np.isclose(p[0], LX, atol=tol) | np.isclose(p[1], 0, atol=tol)
            | np.isclose(p[1], LY, atol=tol) | np.isclose(p[2], -10000.0, atol=tol))


zero = fem.Function(V)
bc = fem.dirichletbc(zero, fem.locate_dofs_geometrical(V, on_fixed))
A = assemble_matrix(a, bcs=[bc])
A.assemble()
b = assemble_vector(L)
apply_lifting(b, [a], bcs=[[bc]])
b.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
set_bc(b, [bc])
t_assembly = time.perf_counter()

# 4. Rigid-body near-null space (as the dolfinx elasticity demo builds it).
index_map = V.dofmap.index_map
bs = V.dofmap.index_map_bs
ns = [la for la in (PETSc.Vec().createMPI((index_map.size_local * bs, PETSc.DECIDE), bsize=bs, comm=comm) for _ in range(6))]
arrays = [w.getArray() for w in ns]
xg = V.tabulate_dof_coordinates()
nloc = index_map.size_local
for i in range(3):
    arrays[i][i::3] = 1.0
arrays[3][0::3], arrays[3][1::3] = -xg[:nloc, 1], xg[:nloc, 0]
arrays[4][1::3], arrays[4][2::3] = -xg[:nloc, 2], xg[:nloc, 1]
arrays[5][0::3], arrays[5][2::3] = xg[:nloc, 2], -xg[:nloc, 0]
for w, arr in zip(ns, arrays):
    w.setArray(arr)
la.orthonormalize(ns)
nsp = PETSc.NullSpace().create(vectors=ns)
A.setNearNullSpace(nsp)

# 5. The Krylov method and preconditioner of ugs-solve's default (--solver cg-hypre,
# solver/mechanics/src/linear_solve.cpp): CG on the unpreconditioned residual, BoomerAMG with nodal
# coarsening of the 3 x 3 blocks (the matrix has block size 3 here as there), HMIS, ext+i
# interpolation capped at 4 entries, aggressive coarsening on two levels, one forward and one
# backward Gauss-Seidel sweep. ugs-solve's single Newton iteration of a linear problem solves to
# 0.5 x its Newton tolerance 1e-8 (newton.cpp), so the same relative residual here. bench/solve/run.sh
# prints both -ksp_view and compares them.
opts = PETSc.Options()
for i, a in enumerate(extra):
    if a.startswith("-") and not a[1:2].isdigit():
        value = extra[i + 1] if i + 1 < len(extra) and not extra[i + 1].startswith("-") else ""
        opts[a[1:]] = value
for key, value in [("ksp_type", "cg"), ("ksp_rtol", 5e-9), ("ksp_atol", 1e-300), ("ksp_norm_type", "unpreconditioned"),
                   ("ksp_max_it", 5000), ("pc_type", "hypre"), ("pc_hypre_type", "boomeramg"),
                   ("pc_hypre_boomeramg_nodal_coarsen", 6), ("pc_hypre_boomeramg_coarsen_type", "HMIS"),
                   ("pc_hypre_boomeramg_interp_type", "ext+i"), ("pc_hypre_boomeramg_P_max", 4),
                   ("pc_hypre_boomeramg_agg_nl", 2), ("pc_hypre_boomeramg_strong_threshold", 0.5),
                   ("pc_hypre_boomeramg_relax_type_down", "SOR/Jacobi"),
                   ("pc_hypre_boomeramg_relax_type_up", "backward-SOR/Jacobi")]:
    if not opts.hasName(key):  # (options given on the command line win, as in ugs-solve)
        opts[key] = value
ksp = PETSc.KSP().create(comm)
ksp.setOperators(A)
ksp.setFromOptions()
uh = fem.Function(V)
ksp.solve(b, uh.vector)
uh.x.scatter_forward()
t_solve = time.perf_counter()

if out:
    with io.XDMFFile(comm, out, "w") as xf:
        xf.write_mesh(msh)
        xf.write_function(uh)
t_end = time.perf_counter()

uz = uh.x.array[2::3]
uz_min = comm.allreduce(uz.min() if uz.size else 0.0, op=MPI.MIN)
if comm.rank == 0:
    print(f"fenicsx: {comm.size} processes, {V.dofmap.index_map.size_global * bs} dofs, {ksp.getIterationNumber()} CG iterations "
          f"({ksp.getConvergedReason()}), min u_z {uz_min * 1e3:.4f} mm", flush=True)
    print(f"fenicsx: time: imports+mesh {t_mesh - t_start:.2f} s, assembly {t_assembly - t_mesh:.2f} s, "
          f"solve {t_solve - t_assembly:.2f} s, output {t_end - t_solve:.2f} s, total {t_end - t_start:.2f} s", flush=True)
