# `cmake --install` and the package: find_package(tuneray) gives tuneray::tuner (needs SQLite
# only) and tuneray::render with the libraries under it; pkg-config gives the tuner
# (tuneray-tuner.pc). Headers go to include/tuneray/<folder>/, so that consumers spell includes
# as the sources do ("tuner/hybrid_tuner.h") with include/tuneray on their include path.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(TUNERAY_INSTALL_INCLUDEDIR ${CMAKE_INSTALL_INCLUDEDIR}/tuneray)
set(TUNERAY_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/tuneray)

# One export set per component, so that a program using only the tuner never has to find the
# renderer's third-party packages.
function(tuneray_install_library target export_set folder)
  # The libraries give ${PROJECT_SOURCE_DIR}/src as their include directory, which an installed
  # package must not point at; rewriting it here keeps their CMakeLists free of install logic.
  get_target_property(dirs ${target} INTERFACE_INCLUDE_DIRECTORIES)
  set(rewritten)
  foreach(dir IN LISTS dirs)
    if(dir STREQUAL "${PROJECT_SOURCE_DIR}/src")
      list(APPEND rewritten "$<BUILD_INTERFACE:${dir}>")
    else()
      list(APPEND rewritten "${dir}")
    endif()
  endforeach()
  set_property(TARGET ${target} PROPERTY INTERFACE_INCLUDE_DIRECTORIES "${rewritten}")
  set_property(TARGET ${target} PROPERTY EXPORT_NAME ${folder})
  install(TARGETS ${target} EXPORT ${export_set}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${TUNERAY_INSTALL_INCLUDEDIR})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/${folder}/
    DESTINATION ${TUNERAY_INSTALL_INCLUDEDIR}/${folder}
    FILES_MATCHING PATTERN "*.h")
endfunction()

# Every library links tuneray_warnings privately; a static library's private link dependencies
# are still link dependencies of its users, so it is exported. In a sanitizer build its
# -fsanitize link options are exactly what a consumer of the instrumented archives needs.
# tuneray_math links it as an interface, so its compile options (warnings, AVX2) are made
# build-only, to keep them out of consumers' compilations.
get_target_property(options tuneray_warnings INTERFACE_COMPILE_OPTIONS)
list(TRANSFORM options PREPEND "$<BUILD_INTERFACE:")
list(TRANSFORM options APPEND ">")
set_property(TARGET tuneray_warnings PROPERTY INTERFACE_COMPILE_OPTIONS "${options}")
set_property(TARGET tuneray_warnings PROPERTY EXPORT_NAME build_options)
install(TARGETS tuneray_warnings EXPORT tunerayBuildTargets)
install(EXPORT tunerayBuildTargets NAMESPACE tuneray:: DESTINATION ${TUNERAY_INSTALL_CMAKEDIR})

tuneray_install_library(tuneray_tuner tunerayTunerTargets tuner)
install(EXPORT tunerayTunerTargets NAMESPACE tuneray:: DESTINATION ${TUNERAY_INSTALL_CMAKEDIR})

tuneray_install_library(tuneray_math tunerayRenderTargets math)
# The rendering headers use AVX2/FMA intrinsics inline; in the tree these flags come from
# tuneray_warnings, whose compile options are build-only (above).
target_compile_options(tuneray_math INTERFACE $<INSTALL_INTERFACE:-mavx2;-mfma;-mf16c>)
tuneray_install_library(tuneray_image tunerayRenderTargets image)
tuneray_install_library(tuneray_scene tunerayRenderTargets scene)
tuneray_install_library(tuneray_accel tunerayRenderTargets accel)
tuneray_install_library(tuneray_render tunerayRenderTargets render)
# Private to image, but its `stb` archive must be linked by whoever links image.
set_property(TARGET tuneray_stb PROPERTY EXPORT_NAME stb)
install(TARGETS tuneray_stb EXPORT tunerayRenderTargets)
install(EXPORT tunerayRenderTargets NAMESPACE tuneray:: DESTINATION ${TUNERAY_INSTALL_CMAKEDIR})

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/tunerayConfig.cmake.in
  ${PROJECT_BINARY_DIR}/package/tunerayConfig.cmake
  INSTALL_DESTINATION ${TUNERAY_INSTALL_CMAKEDIR})
# 0.x: a minor version may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/tunerayConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/package/tunerayConfig.cmake
  ${PROJECT_BINARY_DIR}/package/tunerayConfigVersion.cmake
  DESTINATION ${TUNERAY_INSTALL_CMAKEDIR})

# The .pc file locates the prefix from its own directory, so that it stays right when the tree
# is installed with `cmake --install --prefix` elsewhere than the configured prefix.
set(TUNERAY_PC_DIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
file(RELATIVE_PATH TUNERAY_PC_TO_PREFIX /prefix/${TUNERAY_PC_DIR} /prefix)
string(REGEX REPLACE "/$" "" TUNERAY_PC_TO_PREFIX "${TUNERAY_PC_TO_PREFIX}")
set(TUNERAY_PC_EXTRA_LIBS "")
if(TUNERAY_SANITIZE)
  set(TUNERAY_PC_EXTRA_LIBS " -fsanitize=address,undefined")
endif()
configure_file(${CMAKE_CURRENT_LIST_DIR}/tuneray-tuner.pc.in
  ${PROJECT_BINARY_DIR}/package/tuneray-tuner.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/package/tuneray-tuner.pc DESTINATION ${TUNERAY_PC_DIR})
