# SPDX-License-Identifier: GPL-3.0-or-later
# The Debian package of libcoons: `cpack -G DEB` in a build directory gives
# libcoons_VERSION_ARCH.deb holding what `cmake --install` installs under
# /usr (the libraries, headers, coons2stl, the man pages, coons.pc and the
# CMake package). Included from the top-level CMakeLists.txt after the
# install rules.
#
# Depends: dpkg-shlibdeps reads the ELF files of the package and names the
# Debian packages of every shared library they need (libc6, and with the
# C++ layers libstdc++6, libgcc-s1, libopenmesh1, libgmp10, libmpfr6,
# lib3mf1), with their minimum versions. A static link of libcoons.a (or
# coons::coons_static) also needs the development links of those
# libraries: Suggests names their -dev packages.

# Debian wants the copyright in the package's documentation directory.
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR}
  RENAME copyright)

set(CPACK_PACKAGE_NAME libcoons)
set(CPACK_PACKAGE_VENDOR "libcoons")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "Coons curves, patches and bodies to printable meshes and solids")
set(CPACK_PACKAGE_DESCRIPTION
  "libcoons is a C11 library and the command coons2stl that turn Coons bodies,\n\
described in a JSON model, into closed boundary meshes (STL, OFF, OpenSCAD,\n\
3MF) and hexahedral volume meshes (Gmsh, VTK, CalculiX).\n\
This package holds the shared and static libraries, the headers, coons2stl,\n\
the manual pages, a pkg-config file and a CMake package.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES OFF)

set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "libcoons developers <libcoons@invalid>")
set(CPACK_DEBIAN_PACKAGE_SECTION libs)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(_coons_suggests)
if(COONS_WITH_OPENMESH)
  list(APPEND _coons_suggests libopenmesh-dev)
endif()
if(COONS_WITH_CGAL)
  list(APPEND _coons_suggests libgmp-dev libmpfr-dev)
endif()
if(COONS_WITH_LIB3MF)
  list(APPEND _coons_suggests lib3mf-dev)
endif()
list(APPEND _coons_suggests pkg-config)
string(JOIN ", " CPACK_DEBIAN_PACKAGE_SUGGESTS ${_coons_suggests})

include(CPack)
