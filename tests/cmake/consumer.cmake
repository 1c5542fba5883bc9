# Engine integration, four ways, each building and running examples/headless.c (a real frame on
# the first Vulkan device): MODE=subdir (add_subdirectory), MODE=package (cmake --install of this
# build into a temporary prefix, then find_package), MODE=pkgconfig (pkg-config --cflags --libs
# cacao with the same prefix), MODE=volk (the example on volk with VK_NO_PROTOTYPES, no loader
# linked, against that prefix; its AO must equal example_headless's, REFERENCE). The library is the kind the build makes: LIBRARY (libcacao.a, or
# libcacao.so with -DBUILD_SHARED_LIBS=ON, which the subdir consumer then asks for too). Inputs:
# MODE, SOURCE_DIR, BUILD_DIR, WORK, GENERATOR, C_FLAGS, LIBRARY, SHARED, and RUN_ENV
# ("|"-separated VAR=value; the sanitizer build's preloads, see cacao_sanitizer_env).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}${err}")
  endif()
  set(last_output "${out}${err}" PARENT_SCOPE)
endfunction()
set(flags "-DCMAKE_C_FLAGS=${C_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${C_FLAGS}")
if(MODE STREQUAL "subdir")
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer/subdir -B ${WORK}/build -G ${GENERATOR}
      -DCACAO_SOURCE_DIR=${SOURCE_DIR} "-DBUILD_SHARED_LIBS=${SHARED}" ${flags})
  run(${CMAKE_COMMAND} --build ${WORK}/build)
  set(exe ${WORK}/build/headless)
else()
  run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK}/prefix)
  foreach(f include/cacao.h lib/${LIBRARY} lib/cmake/cacao/cacaoConfig.cmake lib/cmake/cacao/cacaoConfigVersion.cmake
          lib/pkgconfig/cacao.pc bin/cacao bin/cacao-inspect)
    if(NOT EXISTS ${WORK}/prefix/${f})
      message(FATAL_ERROR "cmake --install did not install ${f}")
    endif()
  endforeach()
  if(MODE STREQUAL "volk")
    # An engine on volk: headless.c built with -DCACAO_EXAMPLE_VOLK and volk.c, the loader not
    # linked (volk and cacao each open it at run time), against the installed static library.
    find_file(VOLK_C volk.c PATHS /usr/include NO_DEFAULT_PATH)
    if(NOT VOLK_C)
      message("CACAO_SKIP: volk.c not found (Debian package libvulkan-volk-dev)")
      return()
    endif()
    set(ENV{PKG_CONFIG_PATH} ${WORK}/prefix/lib/pkgconfig)
    find_program(PKG_CONFIG pkg-config REQUIRED)
    run(${PKG_CONFIG} --cflags --libs cacao)
    string(STRIP "${last_output}" pc_flags)
    separate_arguments(pc_list UNIX_COMMAND "${pc_flags}")
    separate_arguments(extra UNIX_COMMAND "${C_FLAGS}")
    run(cc -std=c11 ${extra} -DCACAO_EXAMPLE_VOLK ${SOURCE_DIR}/examples/headless.c ${VOLK_C} ${pc_list} -ldl -lm
        -Wl,-rpath,${WORK}/prefix/lib -o ${WORK}/headless)
    set(exe ${WORK}/headless)
    run(readelf -d ${exe})
    if(last_output MATCHES "libvulkan")
      message(FATAL_ERROR "the volk consumer links the Vulkan loader:\n${last_output}")
    endif()
  elseif(MODE STREQUAL "package")
    run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer/package -B ${WORK}/build -G ${GENERATOR}
        -DCACAO_SOURCE_DIR=${SOURCE_DIR} -DCMAKE_PREFIX_PATH=${WORK}/prefix ${flags})
    run(${CMAKE_COMMAND} --build ${WORK}/build)
    set(exe ${WORK}/build/headless)
  else()
    set(ENV{PKG_CONFIG_PATH} ${WORK}/prefix/lib/pkgconfig)
    find_program(PKG_CONFIG pkg-config REQUIRED)
    # cacao itself needs no loader (cacao.h); the example calls Vulkan, so it asks for vulkan too.
    # A static libcacao brings its private libraries (-lm -ldl) through --static.
    set(pc_static)
    if(NOT SHARED)
      set(pc_static --static)
    endif()
    run(${PKG_CONFIG} ${pc_static} --cflags --libs cacao vulkan)
    string(STRIP "${last_output}" pc_flags)
    separate_arguments(pc_list UNIX_COMMAND "${pc_flags}")
    separate_arguments(extra UNIX_COMMAND "${C_FLAGS}")
    message("pkg-config ${pc_static} --cflags --libs cacao vulkan: ${pc_flags}")
    run(cc -std=c11 ${extra} ${SOURCE_DIR}/examples/headless.c ${pc_list} -lm -Wl,-rpath,${WORK}/prefix/lib
        -o ${WORK}/headless)
    set(exe ${WORK}/headless)
  endif()
endif()
string(REPLACE "|" ";" run_env "${RUN_ENV}")
set(env_prefix)
if(run_env)
  set(env_prefix ${CMAKE_COMMAND} -E env ${run_env})
endif()
run(${env_prefix} ${exe} ${WORK}/ao.bin)
message("${MODE} consumer ran: ${last_output}")
# Same AO as the build's own example (REFERENCE: example_headless, which lets cacao find the
# loader itself), byte for byte: how cacao gets its entry points changes nothing it computes.
if(REFERENCE)
  run(${env_prefix} ${REFERENCE} ${WORK}/reference.bin)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/ao.bin ${WORK}/reference.bin RESULT_VARIABLE same)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "the ${MODE} consumer's AO differs from example_headless's")
  endif()
  message("${MODE} consumer: AO identical to example_headless's")
endif()
