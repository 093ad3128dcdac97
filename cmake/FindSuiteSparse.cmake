# Finds the SuiteSparse piece closurelab uses (CHOLMOD, for the Tikhonov strategy's sparse normal equations and the
# direct SPH's linearised steady state) on systems whose SuiteSparse ships no CMake package files (Debian 12:
# SuiteSparse 5.12). Defines the imported target SuiteSparse::CHOLMOD.
include(FindPackageHandleStandardArgs)
find_path(SuiteSparse_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(SuiteSparse_CONFIG_LIBRARY suitesparseconfig)
find_library(SuiteSparse_CHOLMOD_LIBRARY cholmod)
foreach(_c IN LISTS SuiteSparse_FIND_COMPONENTS)
  if(SuiteSparse_${_c}_LIBRARY)
    set(SuiteSparse_${_c}_FOUND TRUE)
  endif()
endforeach()
find_package_handle_standard_args(SuiteSparse
  REQUIRED_VARS SuiteSparse_INCLUDE_DIR SuiteSparse_CONFIG_LIBRARY HANDLE_COMPONENTS)
if(SuiteSparse_FOUND AND NOT TARGET SuiteSparse::config)
  add_library(SuiteSparse::config UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::config PROPERTIES IMPORTED_LOCATION "${SuiteSparse_CONFIG_LIBRARY}"
                        INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}")
  if(SuiteSparse_CHOLMOD_FOUND)
    add_library(SuiteSparse::CHOLMOD UNKNOWN IMPORTED)
    set_target_properties(SuiteSparse::CHOLMOD PROPERTIES IMPORTED_LOCATION "${SuiteSparse_CHOLMOD_LIBRARY}"
                          INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}"
                          INTERFACE_LINK_LIBRARIES SuiteSparse::config)
  endif()
endif()
mark_as_advanced(SuiteSparse_INCLUDE_DIR SuiteSparse_CONFIG_LIBRARY SuiteSparse_CHOLMOD_LIBRARY)
