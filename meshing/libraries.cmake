# Third-party links of the meshing rooms: GDAL/OGR (common: rasters, vector files, CRS; plan: its
# inputs), the gmsh SDK (plan: the graded plan mesh) and CGAL (layers: natural-neighbour
# interpolation of picks, with GMP/MPFR). Each room asks for what its own code calls:
#   ugs_meshing_link(<room target> [GDAL] [GMSH] [CGAL])
#
# GDAL loads the serial HDF5. Executables that use only the structured box meshes of meshing
# (solver tests that also link PETSc and its MPI HDF5) must not load it, so gmsh and GDAL are linked
# "as needed": an executable records them only if it uses code that calls them.
# A program's link also pulls an archive member for a weak copy of libstdc++'s own code that an
# earlier item references (std::string's, from libgtest.a): a member that calls GDAL would bring
# GDAL in (the ugs_meshing umbrella links libstdc++ first for that). Check with readelf -d (NEEDED)
# on a test that links only box meshes.
# The feature is looked up in the directory of each executable that links us: define it in the
# top-level scope too (meshing/ is added before solver/, tools/ and tests/).
set(CMAKE_LINK_LIBRARY_USING_ugs_as_needed "LINKER:--push-state,--as-needed" "<LINK_ITEM>" "LINKER:--pop-state")
set(CMAKE_LINK_LIBRARY_USING_ugs_as_needed_SUPPORTED TRUE)
set(CMAKE_LINK_LIBRARY_USING_ugs_as_needed "${CMAKE_LINK_LIBRARY_USING_ugs_as_needed}" PARENT_SCOPE)
set(CMAKE_LINK_LIBRARY_USING_ugs_as_needed_SUPPORTED TRUE PARENT_SCOPE)

find_library(UGS_GMP_LIBRARY gmp REQUIRED)
find_library(UGS_MPFR_LIBRARY mpfr REQUIRED)
if(GDAL_LIBRARY)
  set(_ugs_gdal_file ${GDAL_LIBRARY})
else()
  get_target_property(_ugs_gdal_file GDAL::GDAL LOCATION)
endif()
# The real file names (libgmsh.so.4.8.4): the same library linked plainly elsewhere (ugs::gmsh) is
# then another link item, so CMake does not refuse the two features for one item.
get_filename_component(_ugs_gdal_file ${_ugs_gdal_file} REALPATH)
get_filename_component(_ugs_gmsh_file ${GMSH_LIBRARY} REALPATH)
get_target_property(_ugs_gdal_includes GDAL::GDAL INTERFACE_INCLUDE_DIRECTORIES)

function(ugs_meshing_link target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "GDAL;GMSH;CGAL" "" "")
  set(files "")
  if(arg_GDAL)
    target_include_directories(${target} SYSTEM PRIVATE ${_ugs_gdal_includes})
    list(APPEND files ${_ugs_gdal_file})
  endif()
  if(arg_GMSH)
    target_include_directories(${target} SYSTEM PRIVATE ${GMSH_INCLUDE_DIR})
    list(APPEND files ${_ugs_gmsh_file})
  endif()
  if(files)
    list(JOIN files "," items)
    target_link_libraries(${target} PUBLIC "$<BUILD_INTERFACE:$<LINK_LIBRARY:ugs_as_needed,${items}>>"
                                           "$<INSTALL_INTERFACE:${files}>")
  endif()
  if(arg_CGAL)
    target_link_libraries(${target} PRIVATE $<BUILD_INTERFACE:CGAL::CGAL>
                          PUBLIC "$<INSTALL_INTERFACE:${UGS_MPFR_LIBRARY};${UGS_GMP_LIBRARY}>")
  endif()
endfunction()
