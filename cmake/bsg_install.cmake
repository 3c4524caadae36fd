# `cmake --install BUILD [--prefix DIR]`: the `bsg` program, its configs, the
# libraries with their public headers, a CMake package and a pkg-config file.
#
#   <prefix>/bin/bsg
#   <prefix>/share/bsg/configs/            algorithms/, envs/, runs/, grids/
#   <prefix>/include/bsg/<folder>/*.h      included as "envs/env.h", "envs/physics/world.h", ...
#   <prefix>/lib/libbsg_<folder>.a         and one per room: libbsg_envs_physics.a, ...
#   <prefix>/lib/cmake/bsg/                find_package(bsg) -> bsg::envs, bsg::algos, ... (and the rooms)
#   <prefix>/lib/pkgconfig/bsg.pc          pkg-config --cflags --libs bsg
include(CMakePackageConfigHelpers)

# Every library, lowest first (the order the pkg-config file links in reverse).
set(BSG_INSTALLED_LIBRARIES bsg_common ${BSG_ENVS_ROOMS} bsg_envs ${BSG_ALGOS_ROOMS} bsg_algos)
if(TARGET bsg_experiments)
  list(APPEND BSG_INSTALLED_LIBRARIES bsg_experiments_statistics bsg_experiments)
endif()
set(BSG_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/bsg)

# A program that includes the headers must compile Eigen with the same
# instruction set and floating-point contraction as the libraries did.
target_compile_options(bsg_common INTERFACE "$<INSTALL_INTERFACE:${BSG_CODEGEN_OPTIONS}>")

install(TARGETS bsg RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/configs/ DESTINATION ${CMAKE_INSTALL_DATADIR}/bsg/configs)

install(TARGETS ${BSG_INSTALLED_LIBRARIES} EXPORT bsgTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
# The headers of each top folder, its rooms' subfolders included.
foreach(folder common envs algos experiments)
  if(folder STREQUAL "experiments" AND NOT TARGET bsg_experiments)
    continue()
  endif()
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/bsg/${folder}
          FILES_MATCHING PATTERN "*.h")
endforeach()

install(EXPORT bsgTargets NAMESPACE bsg:: DESTINATION ${BSG_INSTALL_CMAKEDIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/bsgConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/cmake/bsgConfig.cmake
                              INSTALL_DESTINATION ${BSG_INSTALL_CMAKEDIR})
# 0.x: a minor version may change the interface.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/bsgConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/bsgConfig.cmake ${CMAKE_BINARY_DIR}/cmake/bsgConfigVersion.cmake
        DESTINATION ${BSG_INSTALL_CMAKEDIR})

# pkg-config: libraries highest first, as a static link needs them.
set(BSG_PC_LIBS "")
foreach(library ${BSG_INSTALLED_LIBRARIES})
  get_target_property(type ${library} TYPE)
  if(NOT type STREQUAL "INTERFACE_LIBRARY")  # an umbrella with no archive of its own
    set(BSG_PC_LIBS "-l${library} ${BSG_PC_LIBS}")
  endif()
endforeach()
string(STRIP "${BSG_PC_LIBS}" BSG_PC_LIBS)
list(JOIN BSG_CODEGEN_OPTIONS " " BSG_PC_CFLAGS)
file(RELATIVE_PATH BSG_PC_PREFIX_FROM_PCFILEDIR ${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" BSG_PC_PREFIX_FROM_PCFILEDIR "${BSG_PC_PREFIX_FROM_PCFILEDIR}")
configure_file(${CMAKE_CURRENT_LIST_DIR}/bsg.pc.in ${CMAKE_BINARY_DIR}/cmake/bsg.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/cmake/bsg.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
