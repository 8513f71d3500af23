# Install rules: headers, static and shared libraries, the CLI and the data it reads at run time,
# pkg-config file and CMake package (find_package(biref) -> biref::biref).
include(CMakePackageConfigHelpers)

set(BIREF_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/biref)
set(BIREF_INSTALL_TARGETS biref)
if(TARGET biref_shared)
  list(APPEND BIREF_INSTALL_TARGETS biref_shared)
else()
  set_target_properties(biref PROPERTIES EXPORT_NAME biref)
endif()
install(TARGETS ${BIREF_INSTALL_TARGETS} EXPORT birefTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/biref DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
if(TARGET biref_cli)
  install(TARGETS biref_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
# Example scenes (biref bench, biref figure) and example programs.
install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/examples/ DESTINATION ${BIREF_INSTALL_DATADIR}/examples
        PATTERN "build" EXCLUDE)

install(EXPORT birefTargets NAMESPACE biref:: DESTINATION ${BIREF_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_SOURCE_DIR}/cmake/birefConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/birefConfig.cmake INSTALL_DESTINATION ${BIREF_CMAKE_DIR})
# 0.x: a new minor version may change the API.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/birefConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/birefConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/birefConfigVersion.cmake
        DESTINATION ${BIREF_CMAKE_DIR})

# pkg-config: dynamic linking needs only -lbiref; --static adds the private dependencies.
# The prefix is written relative to the .pc file, so `cmake --install --prefix P` works too.
set(BIREF_PC_LIBS_PRIVATE "-lm ${OpenMP_C_FLAGS}")
file(RELATIVE_PATH BIREF_PC_TO_PREFIX /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" BIREF_PC_TO_PREFIX "${BIREF_PC_TO_PREFIX}")
configure_file(${CMAKE_CURRENT_SOURCE_DIR}/cmake/biref.pc.in ${CMAKE_CURRENT_BINARY_DIR}/biref.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/biref.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
