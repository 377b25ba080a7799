# SuiteSparse's CHOLMOD (Debian libsuitesparse-dev), for the implicit lab's
# provided supernodal solver (framework/drivers/implicit/fast_backward_euler.cpp,
# through Eigen's CholmodSupport). Optional: without it the provided path uses
# Eigen's SimplicialLDLT and conjugate gradients, and says so when a scene asks
# for "cholmod". Debian 12's SuiteSparse 5 ships no CMake package: headers and
# libraries are looked up directly.
#
# Defines the INTERFACE target wb_cholmod: empty, or CHOLMOD's include
# directory, libraries and WB_HAVE_CHOLMOD=1. Sets WB_CHOLMOD_FOUND.
option(WB_CHOLMOD "Use SuiteSparse's CHOLMOD (libsuitesparse-dev) when it is installed" ON)
set(WB_CHOLMOD_FOUND FALSE)
add_library(wb_cholmod INTERFACE)
if(WB_CHOLMOD)
  find_path(WB_CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
  find_library(WB_CHOLMOD_LIBRARY cholmod)
  find_library(WB_SUITESPARSECONFIG_LIBRARY suitesparseconfig)
  if(WB_CHOLMOD_INCLUDE_DIR AND WB_CHOLMOD_LIBRARY AND WB_SUITESPARSECONFIG_LIBRARY)
    set(WB_CHOLMOD_FOUND TRUE)
    target_include_directories(wb_cholmod SYSTEM INTERFACE ${WB_CHOLMOD_INCLUDE_DIR})
    target_link_libraries(wb_cholmod INTERFACE ${WB_CHOLMOD_LIBRARY}
                                               ${WB_SUITESPARSECONFIG_LIBRARY})
    target_compile_definitions(wb_cholmod INTERFACE WB_HAVE_CHOLMOD=1)
    message(STATUS "CHOLMOD: ${WB_CHOLMOD_LIBRARY} (the implicit lab's supernodal solver)")
  else()
    message(STATUS "CHOLMOD: not found (libsuitesparse-dev): the implicit lab's provided "
                   "path uses Eigen's solvers only")
  endif()
else()
  message(STATUS "CHOLMOD: off (WB_CHOLMOD=OFF)")
endif()
