# `cacao-inspect list --costs BENCH.json` puts beside each permutation the median of the per-pass
# median times a cacao-bench JSON recorded for it and the configurations it served (each once);
# a permutation the bench did not run shows "-". The JSON here is written by hand, so the expected
# median (of 3.0, 5.0 and 10.0: 5.000) is known without the bench. A missing file or one without
# "results" fails with one line naming it. Inputs: INSPECT, WORK.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(WRITE ${WORK}/bench.json [=[{"results": [
 {"scene": "a", "config": "high_native_blur4", "passes": [{"name": "generate.q2", "time_ms": 3.0}]},
 {"scene": "b", "config": "high_native", "passes": [{"name": "generate.q2", "time_ms": 10.0}]},
 {"scene": "a", "config": "high_native", "passes": [{"name": "generate.q2", "time_ms": 5.0},
                                                  {"name": "prepare_depths.mips.native", "time_ms": 1.25}]}]}]=])
execute_process(COMMAND ${INSPECT} list --costs ${WORK}/bench.json RESULT_VARIABLE rc OUTPUT_VARIABLE out
                ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "list --costs failed: ${err}")
endif()
foreach(row "generate.q2 +5.000 +3  high_native_blur4,high_native\n" "prepare_depths.mips.native +1.250 +1  high_native\n"
            "generate.q1 +- +0  ")
  if(NOT out MATCHES "${row}")
    message(FATAL_ERROR "list --costs: no row matching '${row}' in:\n${out}")
  endif()
endforeach()
execute_process(COMMAND ${INSPECT} list --costs ${WORK}/bench.json --json RESULT_VARIABLE rc OUTPUT_VARIABLE out)
string(JSON count LENGTH "${out}")
math(EXPR last "${count} - 1")
foreach(i RANGE ${last})
  string(JSON key GET "${out}" ${i} key)
  if(key STREQUAL "generate.q2")
    string(JSON ms GET "${out}" ${i} cost median_ms)
    string(JSON runs GET "${out}" ${i} cost runs)
    if(NOT ms EQUAL 5 OR NOT runs EQUAL 3)
      message(FATAL_ERROR "list --costs --json: generate.q2 cost ${ms} ms over ${runs} runs, expected 5 over 3")
    endif()
  endif()
endforeach()
file(WRITE ${WORK}/not_bench.json "{\"passes\": []}")
foreach(bad ${WORK}/missing.json ${WORK}/not_bench.json)
  execute_process(COMMAND ${INSPECT} list --costs ${bad} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(FIND "${err}" "${bad}" at)
  if(rc EQUAL 0 OR at LESS 0 OR NOT out STREQUAL "")
    message(FATAL_ERROR "list --costs ${bad}: exit ${rc}, stdout '${out}', stderr '${err}'")
  endif()
endforeach()
