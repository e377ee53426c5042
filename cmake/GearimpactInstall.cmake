# `cmake --install BUILD --prefix P`: the library, its headers, the program with
# the paper's data, a CMake config package (find_package(gearimpact CONFIG)
# gives gearimpact::gearimpact) and gearimpact.pc. Everything is placed
# relative to P, so a prefix can be moved after installing.
include(CMakePackageConfigHelpers)

set(GEARIMPACT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/gearimpact)
set(GEARIMPACT_DATA_DIR ${CMAKE_INSTALL_DATADIR}/gearimpact)

set(gearimpact_installed_targets gearimpact)
if(TARGET gearimpact_cli)
  set_target_properties(gearimpact_cli PROPERTIES EXPORT_NAME cli)
  list(APPEND gearimpact_installed_targets gearimpact_cli)
endif()
install(TARGETS ${gearimpact_installed_targets} EXPORT gearimpactTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The program's own plumbing (the atomic writer, the scoring of the paper's
# statements) is not part of the installed interface; the same list is
# INTERNAL in verify/structure/check_layers.py, which keeps it out of the facade.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/lib/include/gearimpact DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  PATTERN "atomic_file.hpp" EXCLUDE PATTERN "scoring.hpp" EXCLUDE)
# The program looks for its data at <bin>/../share/gearimpact/paper_data
# (reference/data_location.cpp).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/paper_data/ DESTINATION ${GEARIMPACT_DATA_DIR}/paper_data)

install(EXPORT gearimpactTargets NAMESPACE gearimpact:: DESTINATION ${GEARIMPACT_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/gearimpactConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/gearimpactConfig.cmake
  INSTALL_DESTINATION ${GEARIMPACT_CMAKE_DIR}
  PATH_VARS GEARIMPACT_DATA_DIR)
# Before 1.0 a minor release may change the interface.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/gearimpactConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/gearimpactConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/gearimpactConfigVersion.cmake DESTINATION ${GEARIMPACT_CMAKE_DIR})

# pkg-config: the prefix relative to the .pc file (${pcfiledir}), so the file
# stays right wherever --prefix puts it.
set(GEARIMPACT_PC_DIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
if(IS_ABSOLUTE "${GEARIMPACT_PC_DIR}")
  set(GEARIMPACT_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  string(REGEX REPLACE "[^/]+" ".." pc_up "${GEARIMPACT_PC_DIR}")
  set(GEARIMPACT_PC_PREFIX "\${pcfiledir}/${pc_up}")
endif()
# libmatio, when this build links it (MATLAB v5 records).
if(GEARIMPACT_HAVE_MATIO)
  set(GEARIMPACT_PC_MATIO " matio")
else()
  set(GEARIMPACT_PC_MATIO "")
endif()
configure_file(${CMAKE_CURRENT_LIST_DIR}/gearimpact.pc.in ${CMAKE_CURRENT_BINARY_DIR}/gearimpact.pc
  @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/gearimpact.pc DESTINATION ${GEARIMPACT_PC_DIR})
