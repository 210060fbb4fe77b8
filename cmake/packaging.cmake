# What `cmake --install` puts where, and the Debian package (cpack -G DEB), docs/install.md.
#
#   bin/                     cocopp, the built-in solvers, cocoppPimpleFoam (where built)
#   libexec/cocopp/ccx       ccx with cocopp's patches (where scripts/install-calculix.sh built it)
#   include/cocopp/          the SDK's headers, under the same paths as in the source tree
#   lib/<multiarch>/         libcocopp_sdk.a, libcocopp_protocol.a, cmake/cocopp/, pkgconfig/
#   lib/python3/dist-packages/   the Python solver SDK (cocopp_sdk.py), the package cocopp/
#   share/cocopp/            the scripts cocopp calls and the plot scripts; examples/
#   share/doc/cocopp/        the docs (docs/), which cocopp's help points to
#
# Relocatable: cocopp finds its solvers, its ccx and its scripts relative to its own
# executable, cocoppConfig.cmake and cocopp-sdk.pc find the rest relative to themselves, so an
# install tree (or an unpacked package) works wherever it is put.
include(CMakePackageConfigHelpers)

install(TARGETS cocopp_protocol cocopp_sdk EXPORT cocoppTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/protocol/
        DESTINATION ${COCOPP_INSTALL_INCLUDEDIR}/core/protocol FILES_MATCHING PATTERN "*.hpp")
set(config_dir ${CMAKE_INSTALL_LIBDIR}/cmake/cocopp)
install(EXPORT cocoppTargets NAMESPACE cocopp:: DESTINATION ${config_dir})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/cocoppConfig.cmake.in
  ${CMAKE_BINARY_DIR}/cocoppConfig.cmake INSTALL_DESTINATION ${config_dir}
  PATH_VARS CMAKE_INSTALL_BINDIR COCOPP_INSTALL_PYTHONDIR)
# 0.x releases change the SDK: only the same minor version is compatible.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cocoppConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cocoppConfig.cmake ${CMAKE_BINARY_DIR}/cocoppConfigVersion.cmake
        DESTINATION ${config_dir})

# pkg-config: the prefix relative to the .pc file, for the relocatable install.
file(RELATIVE_PATH pc_to_prefix "/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/")
string(REGEX REPLACE "/$" "" pc_to_prefix "${pc_to_prefix}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/cocopp-sdk.pc.in ${CMAKE_BINARY_DIR}/cocopp-sdk.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/cocopp-sdk.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
# The plot scripts a user runs on a results file, next to the one cocopp calls itself.
install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/plot_results.py DESTINATION share/cocopp)
# Examples to copy and run (they write under their own results/): the tube cases on the
# built-in solvers and a solver project built against the installed SDK.
# What runs leave in an example (also in a developer's tree): not part of the example.
set(run_outputs PATTERN results EXCLUDE PATTERN build EXCLUDE PATTERN output EXCLUDE
                PATTERN restart EXCLUDE PATTERN "*.log" EXCLUDE PATTERN "*.fifo" EXCLUDE
                PATTERN ".cocopp.lock" EXCLUDE PATTERN __pycache__ EXCLUDE)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/tube/flow_structure
                  ${PROJECT_SOURCE_DIR}/examples/tube/flow_ringmodel
        DESTINATION share/cocopp/examples/tube ${run_outputs})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/external_solver DESTINATION share/cocopp/examples
        ${run_outputs})

# The Debian package: `cpack -G DEB` in the build directory (docs/install.md). Installs under
# /usr; the run-time libraries it needs are found by dpkg-shlibdeps.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME cocopp)
set(CPACK_PACKAGE_VENDOR "cocopp")
set(CPACK_PACKAGE_CONTACT "cocopp developers <cocopp@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "partitioned fluid-structure interaction coupler")
set(CPACK_PACKAGE_DESCRIPTION
    "A standalone coupler that drives separate fluid and structure solver executables with \
quasi-Newton coupling (IQN-ILS, IQN-MVJ, IBQN), Aitken relaxation or Gauss-Seidel, mapping \
between non-matching and sliding interface meshes. With the built-in 1D tube solvers, the \
solver SDK (C++ and Python) and, where built, the OpenFOAM and CalculiX solvers.")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# Not found by dpkg-shlibdeps: what the scripts and the Python SDK run with.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "python3, python3-numpy")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3-h5py, python3-matplotlib")
# cocoppPimpleFoam needs Debian's OpenFOAM (whose libraries declare no shlibs); the tube cases
# and the CalculiX wrapper run without it.
if(COCOPP_HAVE_OPENFOAM)
  string(APPEND CPACK_DEBIAN_PACKAGE_RECOMMENDS ", openfoam")
endif()
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "paraview")
include(CPack)
