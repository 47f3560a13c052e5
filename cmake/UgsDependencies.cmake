# Every external library ugs uses, as imported targets. All come from Debian 12 packages
# (scripts/install-deps). Two HDF5 builds exist on Debian: GDAL and VTK link the serial one,
# PETSc the OpenMPI one. We expose both and each executable links exactly one (docs/hdf5-split.md).
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)
find_package(ZLIB REQUIRED)
find_package(fmt REQUIRED)
find_package(toml11 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(GDAL REQUIRED)

# gmsh SDK: Debian ships the header and library without a CMake config.
find_path(GMSH_INCLUDE_DIR gmsh.h REQUIRED)
find_library(GMSH_LIBRARY gmsh REQUIRED)
add_library(ugs_ext_gmsh INTERFACE)
target_include_directories(ugs_ext_gmsh SYSTEM INTERFACE ${GMSH_INCLUDE_DIR})
target_link_libraries(ugs_ext_gmsh INTERFACE ${GMSH_LIBRARY})
add_library(ugs::gmsh ALIAS ugs_ext_gmsh)

# HDF5, serial flavour (same as GDAL/VTK).
find_path(HDF5_SERIAL_INCLUDE_DIR hdf5.h PATHS /usr/include/hdf5/serial NO_DEFAULT_PATH REQUIRED)
find_library(HDF5_SERIAL_LIBRARY hdf5 PATHS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/hdf5/serial NO_DEFAULT_PATH REQUIRED)
add_library(ugs_ext_hdf5_serial INTERFACE)
target_include_directories(ugs_ext_hdf5_serial SYSTEM INTERFACE ${HDF5_SERIAL_INCLUDE_DIR})
target_link_libraries(ugs_ext_hdf5_serial INTERFACE ${HDF5_SERIAL_LIBRARY})
add_library(ugs::hdf5_serial ALIAS ugs_ext_hdf5_serial)

# HDF5, OpenMPI flavour (same as PETSc).
find_path(HDF5_MPI_INCLUDE_DIR hdf5.h PATHS /usr/include/hdf5/openmpi NO_DEFAULT_PATH REQUIRED)
find_library(HDF5_MPI_LIBRARY hdf5 PATHS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/hdf5/openmpi NO_DEFAULT_PATH REQUIRED)
find_package(MPI REQUIRED COMPONENTS C)
add_library(ugs_ext_hdf5_mpi INTERFACE)
target_include_directories(ugs_ext_hdf5_mpi SYSTEM INTERFACE ${HDF5_MPI_INCLUDE_DIR})
target_link_libraries(ugs_ext_hdf5_mpi INTERFACE ${HDF5_MPI_LIBRARY} MPI::MPI_C)
add_library(ugs::hdf5_mpi ALIAS ugs_ext_hdf5_mpi)

# PETSc (with MPI, hypre, MUMPS, SuiteSparse) through its pkg-config file.
pkg_check_modules(PETSC REQUIRED IMPORTED_TARGET PETSc)
add_library(ugs::petsc ALIAS PkgConfig::PETSC)

# SuiteSparse CHOLMOD for single-process sparse Cholesky.
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
add_library(ugs_ext_cholmod INTERFACE)
target_include_directories(ugs_ext_cholmod SYSTEM INTERFACE ${CHOLMOD_INCLUDE_DIR})
target_link_libraries(ugs_ext_cholmod INTERFACE ${CHOLMOD_LIBRARY})
add_library(ugs::cholmod ALIAS ugs_ext_cholmod)

find_package(CGAL REQUIRED)
find_package(NLopt REQUIRED)

# opm-common's EclIO reads ECLIPSE / OPM Flow binary output (ugs-import-eclipse). Debian's CMake
# config of opm-common wants targets (OpenMP, Boost::system, fmt) we do not otherwise need: the
# header folder and the library are all EclIO uses.
find_path(OPM_COMMON_INCLUDE_DIR opm/io/eclipse/EGrid.hpp REQUIRED)
find_library(OPM_COMMON_LIBRARY opmcommon REQUIRED)
add_library(ugs_ext_opm_common INTERFACE)
target_include_directories(ugs_ext_opm_common SYSTEM INTERFACE ${OPM_COMMON_INCLUDE_DIR})
target_link_libraries(ugs_ext_opm_common INTERFACE ${OPM_COMMON_LIBRARY})
add_library(ugs::opm_common ALIAS ugs_ext_opm_common)
