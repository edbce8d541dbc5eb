# Debian package of the command-line tool and the C++ library (issue #30, item 3), by CPack:
#   cpack --config <build>/CPackConfig.cmake -G DEB        ->  interfere_<version>_<arch>.deb
# It holds what `cmake --install` installs except the Python module and interfere-mpi (bin/interfere,
# libexec/interfere/interfere-cad, the static libraries, headers, the CMake package, the feature
# data, LICENSE and NOTICE in share/doc/interfere), under /usr. The Python module is its own
# install: `pip install --no-build-isolation .` (README, Install), because its directory
# (lib/pythonX.Y/dist-packages for /usr/local, lib/python3/dist-packages for a Debian package)
# and its ABI follow the interpreter, not this package.
# Depends: computed from the executables by dpkg-shlibdeps (CPACK_DEBIAN_PACKAGE_SHLIBDEPS);
# Recommends: the -dev packages that interfereConfig.cmake's find_dependency calls need.
# Tested by tests/package/test_deb.py (ctest package_deb).

install(FILES ${PROJECT_SOURCE_DIR}/LICENSE ${PROJECT_SOURCE_DIR}/NOTICE DESTINATION ${CMAKE_INSTALL_DOCDIR})

set(CPACK_PACKAGE_NAME "interfere")
set(CPACK_PACKAGE_VENDOR "The interfere authors")
set(CPACK_PACKAGE_CONTACT "The interfere authors")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "exact, parallel interference (clash) checking: command-line tool and C++ library")
set(CPACK_PACKAGE_DESCRIPTION
    "interfere checks meshes, FE models and STEP assemblies for interference and clearance with exact predicates. This package holds the `interfere` command-line tool (and interfere-cad, which it runs for STEP input), the static C++ libraries with their headers and the CMake package (find_package(interfere)). The Python module is installed separately (pip install .).")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGE_FILE_NAME "${CPACK_PACKAGE_NAME}-${PROJECT_VERSION}-${CMAKE_SYSTEM_NAME}")
set(CPACK_GENERATOR DEB)
set(CPACK_STRIP_FILES TRUE)  # (executables only: CMake never strips static archives)

# Every component but `python` (python/CMakeLists.txt) and `mpi` (apps/mpi: interfere-mpi would make
# the package depend on OpenMPI; `cmake --install` installs it), in one package.
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
set(CPACK_COMPONENTS_ALL Unspecified)

set(CPACK_DEBIAN_PACKAGE_NAME "interfere")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION "science")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libtbb-dev, zlib1g-dev, nlohmann-json3-dev, libpng-dev")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "python3-numpy")
set(CPACK_DEBIAN_COMPRESSION_TYPE gzip)  # (fast to build in the test; xz halves the size)

include(CPack)
