# The steps of tests/package (see CMakeLists.txt there), run with cmake -P -DSTEP=...
# install: a fresh prefix, so that a file no install rule provides cannot be left over.
# cmake: the consumer project through find_package(tuneray).
# pkgconfig: the tuner consumer compiled with `pkg-config --cflags --libs tuneray-tuner` only.
cmake_minimum_required(VERSION 3.25)
set(PREFIX ${WORK_DIR}/prefix)
# Consumers are compiled strictly, so that a warning in an installed header fails here.
set(CONSUMER_FLAGS -Wall -Wextra -Werror)

# Runs a command; fails the test with its output when it fails. OUTPUT receives stdout+stderr.
function(run what)
  cmake_parse_arguments(ARG "" "OUTPUT" "COMMAND" ${ARGN})
  execute_process(COMMAND ${ARG_COMMAND} RESULT_VARIABLE rc OUTPUT_VARIABLE out
    ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    list(JOIN ARG_COMMAND " " shown)
    message(FATAL_ERROR "${what} failed (${rc}): ${shown}\n${out}")
  endif()
  if(ARG_OUTPUT)
    set(${ARG_OUTPUT} "${out}" PARENT_SCOPE)
  endif()
endfunction()

# The consumer's answer: (x - 3)^2 + 1 is smallest at x = 3.
function(expect_best_x program)
  run("${program}" COMMAND ${program} OUTPUT out)
  message(STATUS "${program}: ${out}")
  if(NOT out MATCHES "best x = 3\n")
    message(FATAL_ERROR "${program} printed\n${out}\nexpected \"best x = 3\"")
  endif()
endfunction()

if(STEP STREQUAL "install")
  file(REMOVE_RECURSE ${PREFIX})
  run("cmake --install" COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})
  foreach(file ${LIBDIR}/cmake/tuneray/tunerayConfig.cmake ${LIBDIR}/cmake/tuneray/tunerayConfigVersion.cmake
      ${LIBDIR}/pkgconfig/tuneray-tuner.pc include/tuneray/tuner/hybrid_tuner.h
      include/tuneray/render/tile_renderer.h ${LIBDIR}/libtuneray_tuner.a ${LIBDIR}/libtuneray_render.a)
    if(NOT EXISTS ${PREFIX}/${file})
      message(FATAL_ERROR "cmake --install did not install ${file}")
    endif()
  endforeach()

elseif(STEP STREQUAL "cmake")
  # README's example is this consumer's main.cpp, less the two lines on the file's role here.
  file(READ ${SOURCE_DIR}/README.md readme)
  string(REGEX MATCH "## Use the tuner in your program.*" readme "${readme}")
  string(REGEX MATCH "```cpp\n([^`]*)```" readme "${readme}")
  set(readme_example "${CMAKE_MATCH_1}")
  file(READ ${CONSUMER_DIR}/main.cpp example)
  string(REGEX MATCH "^[^\n]*\n[^\n]*\n(.*)$" example "${example}")
  set(example "${CMAKE_MATCH_1}")
  if(NOT readme_example STREQUAL example)
    message(FATAL_ERROR "README.md's tuner example differs from ${CONSUMER_DIR}/main.cpp")
  endif()
  set(build ${WORK_DIR}/cmake-consumer)
  file(REMOVE_RECURSE ${build})
  list(JOIN CONSUMER_FLAGS " " flags)
  run("configuring the consumer" COMMAND ${CMAKE_COMMAND} -S ${CONSUMER_DIR} -B ${build}
    -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_CXX_FLAGS=${flags}
    -DCMAKE_PREFIX_PATH=${PREFIX})
  run("building the consumer" COMMAND ${CMAKE_COMMAND} --build ${build} -j 2)
  expect_best_x(${build}/tuner_consumer)
  run("render_consumer" COMMAND ${build}/render_consumer OUTPUT out)
  message(STATUS "render_consumer: ${out}")
  if(NOT out MATCHES "mean radiance = [0-9]*\\.[0-9]*[1-9]")
    message(FATAL_ERROR "render_consumer rendered nothing:\n${out}")
  endif()

elseif(STEP STREQUAL "pkgconfig")
  find_program(PKG_CONFIG pkg-config)
  if(NOT PKG_CONFIG)
    message("SKIPPED: pkg-config is not installed (scripts/install-deps installs it)")
    return()
  endif()
  set(ENV{PKG_CONFIG_PATH} ${PREFIX}/${LIBDIR}/pkgconfig)
  run("pkg-config" COMMAND ${PKG_CONFIG} --cflags --libs tuneray-tuner OUTPUT out)
  string(STRIP "${out}" out)
  message(STATUS "pkg-config --cflags --libs tuneray-tuner: ${out}")
  separate_arguments(pc_flags UNIX_COMMAND "${out}")
  set(program ${WORK_DIR}/pkgconfig-consumer)
  file(REMOVE ${program})
  run("compiling the consumer with the pkg-config flags" COMMAND ${CXX} -std=c++20
    ${CONSUMER_FLAGS} ${CONSUMER_DIR}/main.cpp -o ${program} ${pc_flags})
  expect_best_x(${program})

else()
  message(FATAL_ERROR "unknown STEP '${STEP}'")
endif()
