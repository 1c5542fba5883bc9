# Helpers of the CLI test scripts. Every script gets CACAO (the binary), TOOL (cli_tool), WORK (its
# own scratch folder, emptied here) and SCENES (folders made by the setup test: room = the default
# scene at 160x90, plane = a camera-facing plane at 160x90).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(ROOM ${SCENES}/room)
set(PLANE ${SCENES}/plane)

# Runs cacao with the arguments in WORK; sets <prefix>_rc, <prefix>_out, <prefix>_err.
function(cacao_run prefix)
  execute_process(COMMAND ${CACAO} ${ARGN} WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  set(${prefix}_rc "${rc}" PARENT_SCOPE)
  set(${prefix}_out "${out}" PARENT_SCOPE)
  set(${prefix}_err "${err}" PARENT_SCOPE)
endfunction()

# Runs cacao and fails the test unless it exits 0 with nothing on stderr; sets <prefix>_out.
function(cacao_ok prefix)
  cacao_run(r ${ARGN})
  if(NOT r_rc EQUAL 0 OR NOT r_err STREQUAL "")
    message(FATAL_ERROR "cacao ${ARGN}\nexited ${r_rc}\nstdout: ${r_out}\nstderr: ${r_err}")
  endif()
  set(${prefix}_out "${r_out}" PARENT_SCOPE)
endfunction()

# Runs cli_tool and fails the test if it fails; sets <var> to its stdout (stripped).
function(tool var)
  execute_process(COMMAND ${TOOL} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "cli_tool ${ARGN} failed: ${err}")
  endif()
  set(${var} "${out}" PARENT_SCOPE)
endfunction()

# Fails unless lo <= value <= hi (if() compares numbers as C doubles).
function(expect_between what value lo hi)
  if(NOT value MATCHES "^-?[0-9]" OR value LESS lo OR value GREATER hi)
    message(FATAL_ERROR "${what}: got '${value}', expected a number in [${lo}, ${hi}]")
  endif()
  message("${what}: ${value} (expected ${lo} .. ${hi})")
endfunction()

# Fails the test when any file matches the globs (searched recursively); <what> names the case.
function(expect_no_files what)
  file(GLOB_RECURSE found ${ARGN})
  if(found)
    message(FATAL_ERROR "${what}: ${found}")
  endif()
endfunction()

# The mean absolute difference of two images (all pixels), via cli_tool.
function(mean_abs_diff var a b)
  tool(line diff ${a} ${b})
  string(REGEX MATCH "mean_abs ([0-9.e+-]+)" _ "${line}")
  set(${var} "${CMAKE_MATCH_1}" PARENT_SCOPE)
endfunction()

# Runs <program> (at most 60 s: a hang is a failure) and fails the test unless it exits non-zero
# with exactly one line on stderr that contains <needle> and carries no escape byte, and nothing
# on stdout (no partial output).
function(expect_program_refused program needle)
  execute_process(COMMAND ${program} ${ARGN} WORKING_DIRECTORY ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err TIMEOUT 60)
  get_filename_component(name "${program}" NAME)
  string(REGEX REPLACE "\n$" "" message "${err}")
  if(NOT rc MATCHES "^[1-9][0-9]*$")
    message(FATAL_ERROR "${name} ${ARGN}: expected a failure exit, got '${rc}': ${err}")
  endif()
  string(FIND "${message}" "${needle}" at)
  if(at LESS 0)
    message(FATAL_ERROR "${name} ${ARGN}: message does not name '${needle}': ${err}")
  endif()
  string(ASCII 27 esc)
  string(FIND "${message}" "${esc}" escape_at)
  if(message MATCHES "\n" OR NOT escape_at EQUAL -1)
    message(FATAL_ERROR "${name} ${ARGN}: message spans lines or carries an escape: ${err}")
  endif()
  if(NOT out STREQUAL "")
    message(FATAL_ERROR "${name} ${ARGN}: refused, but printed on stdout: ${out}")
  endif()
  message("refused as expected: ${message}")
endfunction()

# expect_program_refused for cacao.
function(expect_cacao_refused needle)
  expect_program_refused(${CACAO} "${needle}" ${ARGN})
endfunction()
