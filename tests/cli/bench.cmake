# cacao-bench (BENCH) writes a JSON, CSV and plot that follow their schema (checked by bench_check,
# CHECK, which shares no code with the bench): on the embedded scene with two configurations,
# --repeat 2 --warmup 1, the JSON's timed frames are 1 and 2 (the warm-up frame 0 is not timed);
# on a scene folder with two ground truths the JSON's RMSE, MAE and p99 equal a recomputation from
# the AO images the bench saved. Bad flags get one line on stderr naming the flag, a non-zero exit
# and no file at all (nothing written before the last frame has run).
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)

function(bench_ok)
  execute_process(COMMAND ${BENCH} ${ARGN} WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT err STREQUAL "")
    message(FATAL_ERROR "cacao-bench ${ARGN}\nexited ${rc}\nstdout: ${out}\nstderr: ${err}")
  endif()
  message("${out}")
  set(bench_out "${out}" PARENT_SCOPE)
endfunction()

function(check)
  execute_process(COMMAND ${CHECK} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "bench_check ${ARGN}\n${out}${err}")
  endif()
  message("${out}")
endfunction()

# 1. The embedded scene (no ground truth): schema and the frames timed.
bench_ok(--configs lowest_native,lowest_downsampled --repeat 2 --warmup 1 --validate
         --json ${WORK}/embedded.json --csv ${WORK}/embedded.csv)
check(${WORK}/embedded.json ${WORK}/embedded.csv - 1 2)
foreach(config lowest_native lowest_downsampled)
  if(NOT bench_out MATCHES "\ndefault +${config} +[0-9]")
    message(FATAL_ERROR "the table has no row for default / ${config}:\n${bench_out}")
  endif()
endforeach()

# 2. A scene folder with both truths: errors recomputed from the saved AO, and the plots.
set(scene ${WORK}/room)
file(COPY ${ROOM}/ DESTINATION ${scene})
file(COPY_FILE ${PLANE}/depth.pfm ${scene}/ao_gt_falloff.pfm) # any 160x90 image in [0,1] serves as a truth
tool(ignored const ${scene}/ao_gt.pfm 160 90 0.9)
file(MAKE_DIRECTORY ${WORK}/ao)
bench_ok(--scene ${scene} --configs "low_native,medium_d*" --repeat 2 --warmup 1 --validate --save-ao ${WORK}/ao
         --json ${WORK}/room.json --csv ${WORK}/room.csv --plot ${WORK}/room.png)
check(${WORK}/room.json ${WORK}/room.csv ${WORK}/room.png 1 2 ${scene} ${WORK}/ao)
file(WRITE ${WORK}/amd.json [=[{"name": "AMD CACAO v1.2", "points": [{"scene": "room", "config": "amd low", "total_ms": 1.5, "rmse_ao_gt_falloff": 0.2}]}]=])
bench_ok(--scene ${scene} --configs low_native --repeat 1 --warmup 0 --reference ${WORK}/amd.json
         --json ${WORK}/svg.json --csv ${WORK}/svg.csv --plot ${WORK}/room.svg)
check(${WORK}/svg.json ${WORK}/svg.csv ${WORK}/room.svg 0 1)
file(READ ${WORK}/svg.json svg_json)
string(JSON ref_name GET "${svg_json}" reference name)
if(NOT ref_name STREQUAL "AMD CACAO v1.2")
  message(FATAL_ERROR "--reference points are not in the JSON: ${svg_json}")
endif()

# --plot-from re-plots a bench JSON (as tools/accuracy-report.py does with its merged runs).
bench_ok(--plot-from ${WORK}/room.json --reference ${WORK}/amd.json --plot ${WORK}/again.png)
check(${WORK}/room.json ${WORK}/room.csv ${WORK}/again.png 1 2)

# --pipeline-cache: per configuration, creation timed without, on an empty and on a warm cache;
# the same pipeline count as the results, a valid cache header, min <= median <= max.
bench_ok(--configs lowest_native,highest_downsampled --repeat 1 --warmup 0 --pipeline-cache 2
         --json ${WORK}/cache.json)
file(READ ${WORK}/cache.json cache_json)
string(JSON n LENGTH "${cache_json}" pipeline_cache configurations)
string(JSON trials GET "${cache_json}" pipeline_cache trials)
string(JSON scene_w GET "${cache_json}" scenes 0 width)
string(JSON scene_h GET "${cache_json}" scenes 0 height)
if(NOT n EQUAL 2 OR NOT trials EQUAL 2 OR NOT bench_out MATCHES "pipeline creation at ${scene_w}x${scene_h} ")
  message(FATAL_ERROR "--pipeline-cache 2: ${n} configurations, ${trials} trials\n${bench_out}")
endif()
foreach(i 0 1)
  string(JSON config GET "${cache_json}" pipeline_cache configurations ${i} config)
  string(JSON pipes GET "${cache_json}" pipeline_cache configurations ${i} pipeline_count)
  string(JSON result_pipes GET "${cache_json}" results ${i} pipeline_count)
  string(JSON bytes GET "${cache_json}" pipeline_cache configurations ${i} cache_bytes)
  string(JSON valid GET "${cache_json}" pipeline_cache configurations ${i} header_valid)
  if(NOT pipes EQUAL result_pipes OR bytes LESS 32 OR NOT valid)
    message(FATAL_ERROR "${config}: ${pipes} pipelines (results: ${result_pipes}), ${bytes} bytes, header ${valid}")
  endif()
  foreach(kind no_cache empty_cache warm_cache)
    string(JSON lo GET "${cache_json}" pipeline_cache configurations ${i} ${kind} min_ms)
    string(JSON mid GET "${cache_json}" pipeline_cache configurations ${i} ${kind} median_ms)
    string(JSON hi GET "${cache_json}" pipeline_cache configurations ${i} ${kind} max_ms)
    if(NOT lo GREATER 0 OR lo GREATER mid OR mid GREATER hi)
      message(FATAL_ERROR "${config} ${kind}: min ${lo} median ${mid} max ${hi}")
    endif()
  endforeach()
endforeach()

# 3. Bad flags: one line naming the flag, non-zero exit, no files.
set(BAD ${WORK}/bad)
function(expect_refused needle)
  file(REMOVE_RECURSE ${BAD})
  file(MAKE_DIRECTORY ${BAD})
  execute_process(COMMAND ${BENCH} ${ARGN} --json ${BAD}/r.json --csv ${BAD}/r.csv WORKING_DIRECTORY ${BAD}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REGEX REPLACE "\n$" "" message "${err}")
  if(rc EQUAL 0 OR NOT rc MATCHES "^[0-9]+$")
    message(FATAL_ERROR "cacao-bench ${ARGN}: exit '${rc}', expected a failure")
  endif()
  string(FIND "${message}" "${needle}" at)
  if(at LESS 0 OR message MATCHES "\n" OR NOT message MATCHES "^cacao-bench: ")
    message(FATAL_ERROR "cacao-bench ${ARGN}: expected one line naming '${needle}', got: ${err}")
  endif()
  file(GLOB leftovers ${BAD}/*)
  if(leftovers)
    message(FATAL_ERROR "cacao-bench ${ARGN}: left files behind: ${leftovers}")
  endif()
  message("refused as expected: ${message}")
endfunction()
expect_refused(--repeat --repeat 0)
expect_refused(--warmup --warmup -1)
expect_refused(--warmup --warmup)
expect_refused(--pipeline-cache --pipeline-cache 0)
expect_refused(--pipeline-cache --pipeline-cache)
expect_refused(--sweep --sweep half)
expect_refused(nonesuch --configs high_native,nonesuch)
expect_refused(--plot --scene ${scene} --configs low_native --plot ${BAD}/r.pdf)
expect_refused(--plot --configs low_native --plot ${BAD}/r.png) # the embedded scene has no truth to plot
expect_refused("-o: a flag of cacao" --configs low_native -o ${BAD}/x.png)
expect_refused(--bogus --bogus)
expect_refused(--strength --strength 9)
expect_refused(${WORK}/missing --scene ${WORK}/missing)
expect_refused(${WORK}/missing.json --reference ${WORK}/missing.json)
expect_refused(--save-ao --save-ao ${WORK}/missing)
expect_refused(--plot-from --plot-from ${WORK}/room.json --plot ${BAD}/p.png) # with --json/--csv: it runs nothing
