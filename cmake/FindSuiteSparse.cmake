# Finds the SuiteSparse pieces closurelab uses (CHOLMOD, SPQR) on systems whose SuiteSparse
# ships no CMake package files (Debian 12: SuiteSparse 5.12). Defines imported targets
# SuiteSparse::CHOLMOD and SuiteSparse::SPQR.
include(FindPackageHandleStandardArgs)
find_path(SuiteSparse_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
find_library(SuiteSparse_CONFIG_LIBRARY suitesparseconfig)
find_library(SuiteSparse_CHOLMOD_LIBRARY cholmod)
find_library(SuiteSparse_SPQR_LIBRARY spqr)
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
  foreach(_c CHOLMOD SPQR)
    if(SuiteSparse_${_c}_FOUND)
      add_library(SuiteSparse::${_c} UNKNOWN IMPORTED)
      set_target_properties(SuiteSparse::${_c} PROPERTIES IMPORTED_LOCATION "${SuiteSparse_${_c}_LIBRARY}"
                            INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}"
                            INTERFACE_LINK_LIBRARIES SuiteSparse::config)
    endif()
  endforeach()
  set_property(TARGET SuiteSparse::SPQR APPEND PROPERTY INTERFACE_LINK_LIBRARIES SuiteSparse::CHOLMOD)
endif()
mark_as_advanced(SuiteSparse_INCLUDE_DIR SuiteSparse_CONFIG_LIBRARY SuiteSparse_CHOLMOD_LIBRARY SuiteSparse_SPQR_LIBRARY)
