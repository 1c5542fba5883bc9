# cacao-inspect's refusals are one line naming the argument and the problem, with a non-zero exit
# and nothing on stdout (issue 35, defect 9): extra arguments after `verify` or `stats` are named
# (not "unknown command" after the whole usage); `list --costs` on a truncated JSON gives the JSON
# error's line and column, not "not a cacao-bench JSON"; a "results" entry that is not an object,
# or a config name with control characters (which the table would print raw), is refused naming
# the entry; a missing value is "needs a value", not "unknown argument"; an unknown --pass is
# refused (it printed an empty table and exited 0); --size takes digits x digits in 1..16384 and
# nothing else: -1x5 (read as 4294967295x5), 99999999999x1 (wrapped), 10x10junk (accepted) and 0x0
# ("needs --size") each name the value. The control bytes of the costs file are written here, so
# the expected messages are known without the tool. Inputs: INSPECT (may be empty), WORK.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
if(NOT INSPECT)
  return()
endif()
function(expect_inspect_refused needle)
  expect_program_refused(${INSPECT} "${needle}" ${ARGN})
endfunction()

expect_inspect_refused("verify: takes no arguments (got 'extra')" verify extra)
expect_inspect_refused("stats: takes no arguments (got 'x')" stats x)
expect_inspect_refused("unknown command 'frobnicate' (see cacao-inspect --help)" frobnicate)

file(WRITE ${WORK}/cut.json "{\"results\": [{\"config\": \"high_native\", \"passes\": [{\"name\": \"gen")
expect_inspect_refused("--costs ${WORK}/cut.json: not valid JSON (error at line 1, column" list --costs ${WORK}/cut.json)
file(WRITE ${WORK}/numbers.json "{\"results\": [1, \"x\", null]}")
expect_inspect_refused("numbers.json: results[0]: not an object" list --costs ${WORK}/numbers.json)
file(WRITE ${WORK}/escape.json "{\"results\": [{\"config\": \"ok\", \"passes\": []}, {\"config\": \"red\\u001b[31m\", \"passes\": [{\"name\": \"generate.q2\", \"time_ms\": 1}]}]}")
expect_inspect_refused("escape.json: results[1].config: needs a string without control characters" list --costs
                       ${WORK}/escape.json)
file(WRITE ${WORK}/negative.json "{\"results\": [{\"config\": \"c\", \"passes\": [{\"name\": \"generate.q2\", \"time_ms\": -1}]}]}")
expect_inspect_refused("negative.json: results[0].passes[0]: needs a string \"name\" and a finite \"time_ms\""
                       list --costs ${WORK}/negative.json)

expect_inspect_refused("list: --costs needs a value" list --costs)
expect_inspect_refused("list: --pass needs a value" list --pass)
expect_inspect_refused("list: --pass nosuch: no such pass (one of prepare_depths," list --pass nosuch)
expect_inspect_refused("list: --quality ultra: no such level (one of lowest, low, medium, high, highest)" list
                       --quality ultra)

foreach(size -1x5 99999999999x1 10x10junk 0x0 16385x1 64 x64 " 64x64")
  expect_inspect_refused("--size ${size}: needs WxH, each a whole number from 1 to 16384" plan --size "${size}")
endforeach()
expect_inspect_refused("--size: needs a value (WxH)" plan --size)
execute_process(COMMAND ${INSPECT} plan --size 16384x1 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^plan: 16384x1,")
  message(FATAL_ERROR "plan --size 16384x1 (the largest size): exit ${rc}: ${out}${err}")
endif()
