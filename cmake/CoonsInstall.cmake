# SPDX-License-Identifier: GPL-3.0-or-later
# Install rules of libcoons: libraries, public headers, the CMake package
# (find_package(coons) -> coons::coons, coons::coons_static) and coons.pc.
# Included from the top-level CMakeLists.txt after src/ and man/.
include(CMakePackageConfigHelpers)

set(COONS_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/coons)

# An installed static library carries its private dependencies in its link
# interface, as plain names that work without their CMake packages (the
# list src/CMakeLists.txt keeps).
target_link_libraries(coons_static INTERFACE "$<INSTALL_INTERFACE:${COONS_PRIVATE_NAMES}>")

install(TARGETS coons coons_static EXPORT coons-targets
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})

install(FILES ${PROJECT_SOURCE_DIR}/include/coons.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/coons/
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/coons
  FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_BINARY_DIR}/include/coons/version.h
              ${PROJECT_BINARY_DIR}/include/coons/export.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/coons)

install(EXPORT coons-targets NAMESPACE coons::
  DESTINATION ${COONS_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/coonsConfig.cmake.in
  ${PROJECT_BINARY_DIR}/cmake/coonsConfig.cmake
  INSTALL_DESTINATION ${COONS_CMAKE_DIR})
# As the soname (src/CMakeLists.txt): the same major version, and before 1.0
# the same minor version too.
if(PROJECT_VERSION_MAJOR EQUAL 0)
  set(_coons_compat SameMinorVersion)
else()
  set(_coons_compat SameMajorVersion)
endif()
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cmake/coonsConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY ${_coons_compat})
install(FILES ${PROJECT_BINARY_DIR}/cmake/coonsConfig.cmake
              ${PROJECT_BINARY_DIR}/cmake/coonsConfigVersion.cmake
  DESTINATION ${COONS_CMAKE_DIR})

# coons.pc: relocatable (paths relative to ${pcfiledir}) when the install
# directories are relative, so `cmake --install --prefix DIR` gives a working
# file; absolute directories are written as they are.
set(_pcdir ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}" OR IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  set(COONS_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
  set(COONS_PC_LIBDIR "${CMAKE_INSTALL_FULL_LIBDIR}")
  set(COONS_PC_INCLUDEDIR "${CMAKE_INSTALL_FULL_INCLUDEDIR}")
else()
  file(RELATIVE_PATH _up /prefix/${_pcdir} /prefix)
  string(REGEX REPLACE "/$" "" _up "${_up}")
  set(COONS_PC_PREFIX "\${pcfiledir}/${_up}")
  set(COONS_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
  set(COONS_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/coons.pc.in ${PROJECT_BINARY_DIR}/coons.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/coons.pc DESTINATION ${_pcdir})
