# The installed SDK, exactly as a user meets it; run with `cmake -P` by CTest (CMakeLists.txt).
#   STEP=install: install the build tree BUILD_DIR into a fresh PREFIX (BINDIR, INCLUDEDIR and
#                 LIBDIR are the GNUInstallDirs of the build).
#   STEP=plugin:  configure and build PROJECT_DIR (an out-of-tree plugin using
#                 find_package(filmback)) with CXX_COMPILER and GENERATOR, then check that the
#                 installed `filmback plugins` lists it and `filmback render` can use it.
cmake_minimum_required(VERSION 3.20)

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "failed (${status}): ${ARGN}\n--- stdout\n${out}\n--- stderr\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()

function(expect_contains text what context)
  string(FIND "${text}" "${what}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${context}: expected to find '${what}' in:\n${text}")
  endif()
endfunction()

if(STEP STREQUAL "install")
  file(REMOVE_RECURSE ${PREFIX})
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX})
  foreach(_file ${INCLUDEDIR}/filmback/plugin_abi.h ${INCLUDEDIR}/filmback/plugin_sdk.h
                ${LIBDIR}/cmake/filmback/filmbackConfig.cmake
                ${LIBDIR}/cmake/filmback/filmbackConfigVersion.cmake
                ${LIBDIR}/cmake/filmback/filmbackTargets.cmake ${BINDIR}/filmback)
    if(NOT EXISTS ${PREFIX}/${_file})
      message(FATAL_ERROR "install: ${PREFIX}/${_file} is missing")
    endif()
  endforeach()
  message(STATUS "installed into ${PREFIX}")
elseif(STEP STREQUAL "plugin")
  set(_build ${WORK_DIR}/${BUILD_NAME})
  file(REMOVE_RECURSE ${_build})
  # Only the install prefix may provide filmback: no package registry, no source tree.
  run(${CMAKE_COMMAND} -S ${PROJECT_DIR} -B ${_build} -G ${GENERATOR}
      -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
      -DCMAKE_PREFIX_PATH=${PREFIX} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
  file(STRINGS ${_build}/CMakeCache.txt _found REGEX "^filmback_DIR:")
  expect_contains("${_found}" "=${PREFIX}/${LIBDIR}/cmake/filmback" "find_package(filmback)")
  run(${CMAKE_COMMAND} --build ${_build})
  set(_plugin ${_build}/libfilmback_filter_outoftree.so)
  if(NOT EXISTS ${_plugin})
    message(FATAL_ERROR "the out-of-tree build made no ${_plugin}")
  endif()

  # The installed front end, with the out-of-tree build folder on the plugin path.
  set(ENV{FILMBACK_PLUGIN_PATH} ${_build})
  run(${PREFIX}/${BINDIR}/filmback plugins)
  expect_contains("${run_out}" "filter outoftree 1.0.0" "filmback plugins")
  expect_contains("${run_out}" "  file ${_plugin}\n" "filmback plugins")
  set(_image ${_build}/outoftree.exr)
  run(${PREFIX}/${BINDIR}/filmback render ${SCENE} -o ${_image} --res 32x18 --spp 1 -q
      --filter outoftree:radius=0.75)
  if(NOT EXISTS ${_image})
    message(FATAL_ERROR "filmback render --filter outoftree wrote no ${_image}")
  endif()
  # A camera model with a parameter of its own, which filmback learns from its schema alone: at
  # roll 0 its image is the perspective camera's, every pixel value equal (idiff with zero
  # tolerance); rolled, it is not.
  run(${PREFIX}/${BINDIR}/filmback plugins)
  expect_contains("${run_out}" "camera outoftree 1.0.0" "filmback plugins")
  expect_contains("${run_out}" "roll_deg" "filmback plugins")
  foreach(_camera perspective outoftree outoftree:roll_deg=180)
    string(MAKE_C_IDENTIFIER ${_camera} _id)
    run(${PREFIX}/${BINDIR}/filmback render ${SCENE} -o ${_build}/${_id}.exr --res 32x18 --spp 1
        -q --camera-model ${_camera})
  endforeach()
  execute_process(COMMAND idiff -fail 0 -warn 0 ${_build}/perspective.exr ${_build}/outoftree.exr
                  RESULT_VARIABLE _unrolled OUTPUT_VARIABLE _out)
  if(NOT _unrolled EQUAL 0)
    message(FATAL_ERROR "--camera-model outoftree (roll 0) differs from perspective:\n${_out}")
  endif()
  execute_process(COMMAND idiff -fail 0 -warn 0 ${_build}/outoftree.exr
                          ${_build}/outoftree_roll_deg_180.exr RESULT_VARIABLE _rolled
                  OUTPUT_QUIET)
  if(_rolled EQUAL 0)
    message(FATAL_ERROR "--camera-model outoftree:roll_deg=180 rendered the unrolled image")
  endif()
  message(STATUS "${_plugin}: built by ${CXX_COMPILER}, listed and used in a render by the installed filmback; so was the out-of-tree camera")
else()
  message(FATAL_ERROR "STEP must be install or plugin")
endif()
