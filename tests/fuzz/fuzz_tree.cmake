# The fuzz tree (cmake -DUGS_FUZZ=ON with clang; docs/fuzzing.md): only the libraries the libFuzzer
# targets of tests/fuzz need, and the targets, all built with -fsanitize=fuzzer-no-link,address,undefined.
# Included from the top-level CMakeLists.txt, which returns after it.
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "UGS_FUZZ=ON needs clang (libFuzzer): -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14")
endif()
set(UGS_FUZZ_FLAGS -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
    -fno-omit-frame-pointer -g -O1)
add_compile_options(${UGS_FUZZ_FLAGS})
set(CGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE TRUE)  # Debug on purpose: assertions on
add_link_options(-fsanitize=address,undefined)

# ugs_formats and ugs_fields_serial as in the normal build (only what a target links is built).
add_subdirectory(formats)

# The readers of meshing/, solver/flow, analysis/insar and analysis/runner with exactly the sources they reach
# (strata -> natural neighbours, surface stack, fault traces; ps_data -> crs; case_params -> the
# case file of ugs_formats).
set(_m ${PROJECT_SOURCE_DIR}/meshing)
add_library(ugs_fuzz_readers STATIC
  ${_m}/layers/src/strata.cpp ${_m}/layers/src/natural_neighbour.cpp ${_m}/layers/src/surface_stack.cpp
  ${_m}/layers/src/horizon_grids.cpp ${_m}/common/src/surface_checks.cpp
  ${_m}/common/src/fault_surface_input.cpp
  ${_m}/plan/src/plan.cpp ${_m}/plan/src/plan_inputs.cpp
  ${_m}/common/src/fault_traces.cpp ${_m}/common/src/fault_traces_ogr.cpp ${_m}/common/src/geodata.cpp
  ${PROJECT_SOURCE_DIR}/solver/flow/src/schedule.cpp
  ${PROJECT_SOURCE_DIR}/analysis/insar/src/ps_data.cpp ${PROJECT_SOURCE_DIR}/analysis/insar/src/crs.cpp
  ${PROJECT_SOURCE_DIR}/analysis/runner/src/case_params.cpp)
get_target_property(_ugs_gdal_includes GDAL::GDAL INTERFACE_INCLUDE_DIRECTORIES)
target_include_directories(ugs_fuzz_readers SYSTEM PUBLIC ${_ugs_gdal_includes} ${GMSH_INCLUDE_DIR})
target_include_directories(ugs_fuzz_readers PUBLIC
  ${_m}/common/include ${_m}/plan/include ${_m}/layers/include ${PROJECT_SOURCE_DIR}/solver/include
  ${PROJECT_SOURCE_DIR}/solver/flow/include ${PROJECT_SOURCE_DIR}/analysis/insar/include
  ${PROJECT_SOURCE_DIR}/analysis/runner/include)
target_link_libraries(ugs_fuzz_readers PUBLIC ugs_formats GDAL::GDAL PRIVATE CGAL::CGAL Eigen3::Eigen)

# The ensemble file and its designs (analysis/ensemble: spec, design, morris; OpenTURNS from Debian,
# found as analysis/ensemble/CMakeLists.txt does). Only fuzz_ensemble_spec links it.
find_package(OpenTURNS REQUIRED CONFIG)
set(_e ${PROJECT_SOURCE_DIR}/analysis/ensemble/src)
add_library(ugs_fuzz_ensemble STATIC ${_e}/spec.cpp ${_e}/design.cpp ${_e}/morris.cpp)
target_include_directories(ugs_fuzz_ensemble PUBLIC ${PROJECT_SOURCE_DIR}/analysis/ensemble/include)
target_link_libraries(ugs_fuzz_ensemble PUBLIC ugs_fuzz_readers ugs_formats PRIVATE OT)

# The seismicity readers and model (analysis/seismicity; its HDF5 reader needs ugs_fields_serial).
set(_s ${PROJECT_SOURCE_DIR}/analysis/seismicity/src)
add_library(ugs_fuzz_seismicity STATIC ${_s}/histories.cpp ${_s}/forecast.cpp ${_s}/rate_state.cpp)
target_include_directories(ugs_fuzz_seismicity PUBLIC ${PROJECT_SOURCE_DIR}/analysis/seismicity/include)
target_link_libraries(ugs_fuzz_seismicity PUBLIC ugs_formats ugs_fields_serial)

set(_ugs_fuzz_targets "")
foreach(name msh hdf5_fields csv ps case_file schedule strata ogr ensemble_spec case_params horizon_grid tsurf zmap seismicity
             grdecl fault_sticks)
  add_executable(fuzz_${name} ${CMAKE_CURRENT_LIST_DIR}/targets/fuzz_${name}.cpp)
  target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer)
  target_link_libraries(fuzz_${name} PRIVATE ugs_fuzz_readers ugs_formats)
  list(APPEND _ugs_fuzz_targets fuzz_${name})
endforeach()
target_link_libraries(fuzz_hdf5_fields PRIVATE ugs_fields_serial)
target_link_libraries(fuzz_ensemble_spec PRIVATE ugs_fuzz_ensemble)
target_link_libraries(fuzz_seismicity PRIVATE ugs_fuzz_seismicity)
add_custom_target(ugs_fuzz_targets DEPENDS ${_ugs_fuzz_targets})
