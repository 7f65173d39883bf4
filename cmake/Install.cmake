# What `cmake --install` puts under the prefix (paths from GNUInstallDirs),
# and the Debian package `cpack -G DEB` makes of the same files:
#   lib/libstrata_<room>.a   the room libraries (static), in engine/CMakeLists.txt's STRATA_ROOMS
#   lib/cmake/strata/        find_package(strata): the rooms as strata::<room> (strataConfig.cmake.in)
#   lib/pkgconfig/strata.pc  the same for pkg-config (strata.pc.in)
#   include/strata/          the public headers
#   bin/                     strata-render, strata-view, strata-bench
#   share/doc/strata/        the README, docs/, the results log and the licence
# The shaders are compiled into strata_gpu, so an installed program or host
# reads nothing from the source tree.
include(CMakePackageConfigHelpers)

set(STRATA_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/strata)
list(TRANSFORM STRATA_ROOMS PREPEND strata_ OUTPUT_VARIABLE strata_room_targets)

install(TARGETS ${strata_room_targets} EXPORT strataTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/strata DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS strata-render strata-view strata-bench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The manual as the repository lays it out, so that its links resolve: the
# README, docs/, and the results log its figures link to.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)
install(FILES ${PROJECT_SOURCE_DIR}/results/log.md DESTINATION ${CMAKE_INSTALL_DOCDIR}/results)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})

# The libraries' link lines name their dependencies' imported targets (glm::glm
# publicly; CGAL::CGAL, embree, PkgConfig::EPOXY ... privately, which a static
# library's user links too); strataConfig.cmake finds them again. Our own
# warning flags (strata_warnings) stay out: the rooms name it in $<BUILD_INTERFACE:>.
install(EXPORT strataTargets NAMESPACE strata:: DESTINATION ${STRATA_CMAKE_DIR})
# The pkg-config modules behind the rooms' PkgConfig::<NAME> targets, which
# strataConfig.cmake looks up again under the same names; configuring fails
# here when a room links one this list lacks.
set(STRATA_PKG_CONFIG_TARGETS
  "POLYCLIPPING polyclipping" "GLU glu" "FONTS freetype2 harfbuzz fontconfig" "PNG libpng16"
  "XML libxml-2.0" "QHULL qhull_r" "EPOXY epoxy" "EGL egl" "IMAGE_FORMATS libpng16 OpenEXR")
foreach(target IN LISTS strata_room_targets)
  get_target_property(links ${target} LINK_LIBRARIES)
  foreach(link IN LISTS links)
    if(link MATCHES "^PkgConfig::(.+)$")
      set(listed ${STRATA_PKG_CONFIG_TARGETS})
      list(FILTER listed INCLUDE REGEX "^${CMAKE_MATCH_1} ")
      if(NOT listed)
        message(FATAL_ERROR "${target} links ${link}: add its modules to STRATA_PKG_CONFIG_TARGETS (cmake/Install.cmake)")
      endif()
    endif()
  endforeach()
endforeach()
list(TRANSFORM STRATA_PKG_CONFIG_TARGETS PREPEND "\n  \"" OUTPUT_VARIABLE strata_pkg_lines)
list(TRANSFORM strata_pkg_lines APPEND "\"")
list(JOIN strata_pkg_lines "" STRATA_PKG_CONFIG_LINES)
# strata_contour runs its loops on OpenMP where the compiler has it (engine/contour).
find_package(OpenMP)
set(STRATA_OPENMP ${OpenMP_CXX_FOUND})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/strataConfig.cmake.in ${PROJECT_BINARY_DIR}/strataConfig.cmake
  INSTALL_DESTINATION ${STRATA_CMAKE_DIR})
# 0.x: a minor version may break the API, so only the same minor version is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/strataConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/strataConfig.cmake ${PROJECT_BINARY_DIR}/strataConfigVersion.cmake
  DESTINATION ${STRATA_CMAKE_DIR})

# strata.pc finds its prefix from where it lies (${pcfiledir}), so it is right
# under any prefix that `cmake --install --prefix` or the package chooses.
file(RELATIVE_PATH STRATA_PC_TO_PREFIX ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" STRATA_PC_TO_PREFIX "${STRATA_PC_TO_PREFIX}")
list(TRANSFORM strata_room_targets PREPEND -l OUTPUT_VARIABLE strata_pc_libs)
list(JOIN strata_pc_libs " " STRATA_PC_LIBS)
set(STRATA_PC_OPENMP "")
if(STRATA_OPENMP)
  set(STRATA_PC_OPENMP "${OpenMP_CXX_FLAGS} ")
endif()
configure_file(${PROJECT_SOURCE_DIR}/cmake/strata.pc.in ${PROJECT_BINARY_DIR}/strata.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/strata.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# The Debian package (cpack -G DEB in the build folder): all of the above
# under /usr. Its Depends are the shared libraries the programs load, as
# dpkg-shlibdeps reads them; building against the libraries needs the -dev
# packages of their dependencies, which it suggests.
set(CPACK_PACKAGE_NAME strata)
set(CPACK_PACKAGE_VENDOR "strata maintainers")
set(CPACK_PACKAGE_CONTACT "strata maintainers <noreply@example.org>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "CSG rendered in image space on the GPU: renderer, viewer and libraries")
set(CPACK_PACKAGE_DESCRIPTION "strata renders OpenSCAD's CSG trees on the GPU by depth peeling, \
headless through EGL or in a window: strata-render (OpenSCAD's command line, \
PNG/EXR images and mesh exports), strata-view (the interactive viewer), \
strata-bench, and the static libraries with their headers, CMake package and \
pkg-config file for embedding the renderer in a program.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# A GL driver for the EGL context (Mesa's llvmpipe runs everywhere), openscad
# for .scad input, and OpenSCAD's default font for text().
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libegl-mesa0, libgl1-mesa-dri, openscad, fonts-liberation2")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "pkg-config, libglm-dev, libepoxy-dev, libegl-dev, libglfw3-dev, \
libopenmesh-dev, libcgal-dev, libembree-dev, libpolyclipping-dev, libglu1-mesa-dev, libfreetype-dev, \
libharfbuzz-dev, libfontconfig-dev, libpng-dev, libxml2-dev, libqhull-dev, libopenexr-dev, lib3mf-dev")
include(CPack)
