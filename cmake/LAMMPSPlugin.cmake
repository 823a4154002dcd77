# Interface target `lammps_headers`: what a plugin needs to compile against a LAMMPS source tree
# whose shared library was built with BUILD_MPI=on and the default integer sizes (smallbig).
# Symbols resolve at load time from the lmp executable and liblammps.so, as for LAMMPS's own
# examples/plugins.
find_package(MPI REQUIRED COMPONENTS CXX)
add_library(lammps_headers INTERFACE)
target_include_directories(lammps_headers INTERFACE "${LAMMPS_SOURCE_DIR}")
target_compile_definitions(lammps_headers INTERFACE LAMMPS_SMALLBIG OMPI_SKIP_MPICXX
  MPICH_SKIP_MPICXX)
target_link_libraries(lammps_headers INTERFACE MPI::MPI_CXX)

# perisissm_add_plugin(<name> <sources...>): a LAMMPS plugin module <name>.so
function(perisissm_add_plugin name)
  add_library(${name} MODULE ${ARGN})
  target_link_libraries(${name} PRIVATE lammps_headers perisissm_core)
  set_target_properties(${name} PROPERTIES PREFIX "" SUFFIX ".so"
    LIBRARY_OUTPUT_DIRECTORY "${CMAKE_BINARY_DIR}" LINK_FLAGS "-rdynamic")
endfunction()
