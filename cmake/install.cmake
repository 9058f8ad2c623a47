# What `cmake --install build --prefix P` puts where, the CMake package and pkg-config file that
# let other projects use the installed library, and the Debian packages cpack builds from the
# same rules (docs/install.md). Four components:
#   library  libibl.so.<version> with its SONAME link: Debian package `libibl<SONAME version>`
#            (libibl0.1), named after the SONAME as Debian's policy asks;
#   runtime  the command (P/bin/ibl), man pages and shell completions
#            (cmake/manual_pages.cmake): `ibl`;
#   dev      the headers, libibl.so, the CMake package and ibl.pc: `ibl-dev`;
#   python   the Python module (python/CMakeLists.txt): `python3-ibl`.
# Each package carries share/doc/<package>/copyright (cmake/debian/copyright, machine-readable:
# the code's and the bundled data's licenses) and changelog.gz, which `lintian` asks for.
# The command needs nothing else at run time: the shaders and the default environment are
# compiled into the library.
include(CMakePackageConfigHelpers)

set(IBL_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ibl)

# The command finds the library relative to itself, wherever the prefix is.
file(RELATIVE_PATH ibl_bin_to_lib ${CMAKE_INSTALL_FULL_BINDIR} ${CMAKE_INSTALL_FULL_LIBDIR})
set_target_properties(ibl_cli PROPERTIES INSTALL_RPATH "$ORIGIN/${ibl_bin_to_lib}")

install(TARGETS ibl_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
install(TARGETS ibl EXPORT iblTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT library NAMELINK_COMPONENT dev)
install(DIRECTORY include/ibl DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev
        FILES_MATCHING PATTERN "*.hpp" PATTERN "*.h")
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/generated/ibl/core/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/ibl/core COMPONENT dev)

# The install tests (tests/install) copy what these targets make.
foreach(made ibl_manual ibl_python)
  if(TARGET ibl_install_tests AND TARGET ${made})
    add_dependencies(ibl_install_tests ${made})
  endif()
endforeach()

# find_package(ibl CONFIG): the imported target ibl::ibl and the dependencies its public headers
# include (glm, oneTBB), found again by the consumer.
install(EXPORT iblTargets NAMESPACE ibl:: DESTINATION ${IBL_CMAKE_INSTALL_DIR} COMPONENT dev)
configure_package_config_file(cmake/iblConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/iblConfig.cmake
                              INSTALL_DESTINATION ${IBL_CMAKE_INSTALL_DIR})
# Before 1.0 a minor version may break the API: 0.1 accepts 0.1.x only.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/iblConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/iblConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/iblConfigVersion.cmake
        DESTINATION ${IBL_CMAKE_INSTALL_DIR} COMPONENT dev)

# pkg-config --cflags --libs ibl; the prefix is found from the file's own place.
file(RELATIVE_PATH ibl_pc_to_prefix ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
file(RELATIVE_PATH ibl_pc_libdir ${CMAKE_INSTALL_PREFIX} ${CMAKE_INSTALL_FULL_LIBDIR})
file(RELATIVE_PATH ibl_pc_includedir ${CMAKE_INSTALL_PREFIX} ${CMAKE_INSTALL_FULL_INCLUDEDIR})
configure_file(cmake/ibl.pc.in ${CMAKE_CURRENT_BINARY_DIR}/ibl.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/ibl.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
        COMPONENT dev)

# cpack -G DEB: libibl0.1_<version>_<arch>.deb, ibl_..., ibl-dev_... and python3-ibl_..., the
# shared-library dependencies computed by dpkg-shlibdeps.
set(IBL_DEB_MAINTAINER "ibl developers <ibl@example.org>"
    CACHE STRING "The Maintainer of the Debian packages: a name and a mail address")
get_target_property(ibl_soversion ibl SOVERSION)
set(IBL_DEB_LIBRARY_PACKAGE libibl${ibl_soversion})  # libibl0.1 for libibl.so.0.1
set(ibl_deb_packages library ${IBL_DEB_LIBRARY_PACKAGE} runtime ibl dev ibl-dev)
if(TARGET ibl_python)
  list(APPEND ibl_deb_packages python python3-ibl)
endif()

# Each package's copyright and changelog (a native package's, compressed: gzip -9n).
string(TIMESTAMP IBL_DEB_DATE "%a, %d %b %Y %H:%M:%S +0000" UTC)  # or SOURCE_DATE_EPOCH's
configure_file(cmake/debian/changelog.in ${CMAKE_CURRENT_BINARY_DIR}/debian/changelog @ONLY)
find_program(IBL_GZIP gzip REQUIRED)
execute_process(COMMAND ${IBL_GZIP} -9nc ${CMAKE_CURRENT_BINARY_DIR}/debian/changelog
                OUTPUT_FILE ${CMAKE_CURRENT_BINARY_DIR}/debian/changelog.gz COMMAND_ERROR_IS_FATAL ANY)
while(ibl_deb_packages)
  list(POP_FRONT ibl_deb_packages ibl_component ibl_package)
  install(FILES cmake/debian/copyright ${CMAKE_CURRENT_BINARY_DIR}/debian/changelog.gz
          DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/${ibl_package} COMPONENT ${ibl_component})
endwhile()

set(CPACK_PACKAGE_NAME ibl)
set(CPACK_PACKAGE_VENDOR "ibl developers")
set(CPACK_PACKAGE_CONTACT "${IBL_DEB_MAINTAINER}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Image-based lighting: bake HDR environments, render, compare")
set(CPACK_PACKAGE_DESCRIPTION
    "ibl bakes HDR environments into the assets real-time renderers read (prefiltered specular and irradiance cube maps, SH9, DFG tables) for Filament, the glTF Sample Viewer, Babylon.js and DDS engines, renders scenes with them and with a path-traced reference, and compares the two.")
set(CPACK_PACKAGE_HOMEPAGE_URL "https://example.org/ibl")
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)  # Debian ships stripped binaries
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL library runtime dev)
if(TARGET ibl_python)
  list(APPEND CPACK_COMPONENTS_ALL python)
endif()
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The library package's own library, for the shared-library dependencies of the command and of
# the Python module.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS
    ${CMAKE_CURRENT_BINARY_DIR})
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)  # the shlibs file: libibl 0.1 libibl0.1 (= version)
set(CPACK_DEBIAN_LIBRARY_PACKAGE_NAME ${IBL_DEB_LIBRARY_PACKAGE})
set(CPACK_DEBIAN_LIBRARY_PACKAGE_SECTION libs)
# dpkg's ldconfig trigger (CPack's own postinst and postrm call ldconfig as well).
file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/debian/triggers "activate-noawait ldconfig\n")
set(CPACK_DEBIAN_LIBRARY_PACKAGE_CONTROL_EXTRA ${CMAKE_CURRENT_BINARY_DIR}/debian/triggers)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME ibl)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS "${IBL_DEB_LIBRARY_PACKAGE} (= ${PROJECT_VERSION})")
set(CPACK_DEBIAN_DEV_PACKAGE_NAME ibl-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
    "${IBL_DEB_LIBRARY_PACKAGE} (= ${PROJECT_VERSION}), libglm-dev, libtbb-dev")
# (The internal header ibl/io/json_file.hpp includes nlohmann's; a program that includes it
# installs nlohmann-json3-dev itself.)
set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-ibl)
set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
if(TARGET ibl_python)
  # The module's file name carries the Python ABI it was built for (ibl.cpython-311-...).
  string(REPLACE "." ";" ibl_python_version "${IBL_PYTHON_VERSION}")
  list(GET ibl_python_version 0 ibl_python_major)
  list(GET ibl_python_version 1 ibl_python_minor)
  math(EXPR ibl_python_next "${ibl_python_minor} + 1")
  set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS
      "${IBL_DEB_LIBRARY_PACKAGE} (= ${PROJECT_VERSION}), python3 (>= ${IBL_PYTHON_VERSION}), python3 (<< ${ibl_python_major}.${ibl_python_next}), python3-numpy")
endif()
# Each package's extended description (after the summary): what ibl does, then what the package
# holds, in lines of Debian's width.
set(ibl_deb_about
    "ibl bakes HDR environments into the assets real-time renderers read\n"
    "(prefiltered specular and irradiance cube maps, SH9, DFG tables) for\n"
    "Filament, the glTF Sample Viewer, Babylon.js and DDS engines, renders\n"
    "scenes with them and with a path-traced reference, and compares the two.\n\n")
string(CONCAT CPACK_COMPONENT_LIBRARY_DESCRIPTION ${ibl_deb_about}
       "This package holds the shared library, libibl.so.${ibl_soversion}.")
string(CONCAT CPACK_COMPONENT_RUNTIME_DESCRIPTION ${ibl_deb_about}
       "This package holds the ibl command, its manual pages and its bash and\n"
       "zsh completions.")
string(CONCAT CPACK_COMPONENT_DEV_DESCRIPTION ${ibl_deb_about}
       "This package holds the headers, the CMake package (find_package(ibl))\n"
       "and the pkg-config file of libibl.")
string(CONCAT CPACK_COMPONENT_PYTHON_DESCRIPTION ${ibl_deb_about}
       "This package holds the Python 3 module ibl: NumPy arrays in and out.")
include(CPack)
