# `cmake --install build --prefix P`: the headers (under P/include, by their tree paths core/..., strategies/...,
# experiments/...), the static libraries, the `closurelab` executable, and the CMake package closurelab
# (P/lib/cmake/closurelab) whose imported targets closurelab::core, closurelab::strategies and closurelab::runner
# carry their dependencies. find_package(closurelab) then lets another project register its own strategies
# (examples/custom_deconvolver/). No installed header includes the generated build_info/git_info headers.
include(CMakePackageConfigHelpers)
set(CLOSURELAB_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/closurelab)

foreach(_dir core strategies experiments/kinds experiments/runner experiments/testproblems)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${_dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${_dir}
          FILES_MATCHING PATTERN "*.hpp" PATTERN "hdf5_handle.hpp" EXCLUDE)  # includes <hdf5.h>: private
endforeach()
install(TARGETS closurelab_core closurelab_strategies closurelab_runner EXPORT closurelab_targets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS closurelab RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT closurelab_targets NAMESPACE closurelab:: FILE closurelab_targets.cmake
        DESTINATION ${CLOSURELAB_CMAKE_DIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/closurelabConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/closurelabConfig.cmake INSTALL_DESTINATION ${CLOSURELAB_CMAKE_DIR})
# 0.x: a minor version may break the interface.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/closurelabConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/closurelabConfig.cmake ${PROJECT_BINARY_DIR}/closurelabConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/FindSuiteSparse.cmake
        DESTINATION ${CLOSURELAB_CMAKE_DIR})
