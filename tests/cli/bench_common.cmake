# Helpers of the cacao-bench test scripts. Besides cli_common.cmake's inputs they get BENCH (the
# binary). Runs are kept small: a 32x18 scene and one frame of one configuration (RUN1).
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
set(RUN1 --configs lowest_native --repeat 1 --warmup 0)

# tiny_scene(dir): the default scene at 32x18 as a scene folder, with an ao_gt.pfm truth (any image
# in [0,1] serves: these tests look at files and messages, not at the errors' values).
function(tiny_scene dir)
  file(MAKE_DIRECTORY ${dir})
  tool(ignored scene ${dir} 32 18)
  tool(ignored const ${dir}/ao_gt.pfm 32 18 0.9)
endfunction()

# Runs cacao-bench in WORK; sets <prefix>_rc, <prefix>_out, <prefix>_err. A run past 120 s fails.
function(bench_run prefix)
  execute_process(COMMAND ${BENCH} ${ARGN} WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err TIMEOUT 120)
  set(${prefix}_rc "${rc}" PARENT_SCOPE)
  set(${prefix}_out "${out}" PARENT_SCOPE)
  set(${prefix}_err "${err}" PARENT_SCOPE)
endfunction()

# Runs cacao-bench and fails the test unless it exits 0 with nothing on stderr.
function(bench_ok)
  bench_run(r ${ARGN})
  if(NOT r_rc EQUAL 0 OR NOT r_err STREQUAL "")
    message(FATAL_ERROR "cacao-bench ${ARGN}\nexited ${r_rc}\nstdout: ${r_out}\nstderr: ${r_err}")
  endif()
endfunction()

# expect_program_refused for cacao-bench.
function(expect_bench_refused needle)
  expect_program_refused(${BENCH} "${needle}" ${ARGN})
endfunction()

# Sets <var> to every file under dir (relative) with its SHA-256, so that a later snapshot shows
# whether anything there was created, removed or changed.
function(snapshot var dir)
  file(GLOB_RECURSE files RELATIVE ${dir} ${dir}/*)
  list(SORT files)
  set(listing "")
  foreach(f ${files})
    file(SHA256 ${dir}/${f} hash)
    string(APPEND listing "${f} ${hash}\n")
  endforeach()
  set(${var} "${listing}" PARENT_SCOPE)
endfunction()

# Fails unless dir holds exactly what snapshot <before> recorded.
function(expect_unchanged what dir before)
  snapshot(now ${dir})
  if(NOT now STREQUAL before)
    message(FATAL_ERROR "${what}: ${dir} changed.\nbefore:\n${before}\nafter:\n${now}")
  endif()
endfunction()
